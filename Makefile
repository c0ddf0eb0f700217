# wovenff — build, run, test, bench.
#   make deps    install the Debian packages this project needs (root or sudo)
#   make         build the C core, the C tests and the FreeFEM module
#   make run     the paper's ballistic scene (SCENE=name for another, ARGS="-mesh fine ...");
#                installs what is missing (make deps), builds the module only (no test binary);
#                NP=N: one model over N MPI ranks (the MPI module; docs/distributed.md)
#   make test    C tests, .edp tests and physics checks; ends with "N passed, N failed";
#                installs what is missing (make deps) and builds everything first
#   make bench   benchmarks (not part of make test)

CC       ?= gcc
CXX      ?= g++
BUILD    := build
# -fno-math-errno lets gcc vectorise sqrt; never -ffast-math (it removes NaN checks).
OPT      ?= -O2 -fno-math-errno
# The per-element kernels (cells, membrane) are vectorised across blocks of
# elements (libmvec's atan/exp) and built once per kernel variant (see
# KERNEL_VARIANTS below): KERNEL_ARCH is the baseline's instruction set, the
# one every machine that loads wovenff.so must have. -fno-trapping-math (no
# floating-point traps: values and NaN checks unchanged) lets gcc if-convert
# the lane loops without AVX-512 masks, so the baseline and avx2 variants
# vectorise them too (libmvec's 2- and 4-lane atan/exp).
KERNEL_ARCH ?= -march=x86-64-v2
KERNEL_OPT  := -O3 -fopenmp-simd -fno-trapping-math
CFLAGS   := -std=gnu11 $(OPT) -fopenmp -Wall -Wextra -Werror -fPIC
# The binding: our warnings are errors; FreeFEM's headers are -isystem (their
# own warnings are not ours). -Wno-mismatched-new-delete: gcc 12 misreads
# FreeFEM's CodeAlloc (a class operator new/delete pair) in every
# `Global.Add(..., new OneOperatorN_<...>(f))` registration.
CXXFLAGS := -std=c++14 -O2 -fPIC -Wall -Wextra -Werror -Wno-mismatched-new-delete \
            -DBAMG_LONG_LONG -DNCHECKPTR -Wno-deprecated-declarations -DWFF_MODEL_OPAQUE \
            -isystem /usr/include/freefem++ -Iinclude
LDLIBS   := -fopenmp -lgsl -lgslcblas -lgmsh -lmvec -lm
# Include paths: the core sees its own headers only; test code also sees tests/c/lib.
CORE_INC := -Iinclude -Iplugin
TEST_INC := $(CORE_INC) -Itests/c/lib
# Header dependencies from the compiler: each object gets a .d file beside it.
DEPFLAGS := -MMD -MP

DEB_PACKAGES := freefem++ libfreefem++-dev gmsh libgmsh-dev libgsl-dev gnuplot-nox ghostscript \
                gcc g++ make
# What only tests need: a one-box Slurm for tests/sh/slurm_sweep.sh (the sweeps' -runner
# srun|slurm). make deps installs them too, but one that cannot be installed is a warning,
# never a failed build or `make run` (the test then skips its Slurm part, saying why).
DEB_TEST_PACKAGES := slurm-wlm munge
# MPI (docs/distributed.md): OpenMPI, the MPI FreeFEM's FreeFem++-mpi runs on. Installed by make
# deps like the test packages: without it the MPI module is not built and the distributed tests
# skip, saying why; the serial build and `make run` never need it.
DEB_MPI_PACKAGES := libopenmpi-dev openmpi-bin

CORE_SRC := $(sort $(wildcard plugin/*.c plugin/cells/*.c plugin/solids/*.c))
CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/%.o)
# The per-element kernels, built once per variant (docs/architecture.md, "Kernel
# variants"): build/kernel/VARIANT/plugin/... for -march KERNEL_ARCH_VARIANT
# and -DWFF_KERNEL_VARIANT=VARIANT, which names the variant's code in the
# source (include/wovenff/kernel_name.h: the entry points NAME__VARIANT, its
# cells in a section of their own), linked into one object
# build/kernel/VARIANT.o; plugin/kernel_dispatch.c picks one per model at run
# time (WOVENFF_KERNEL).
KERNEL_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(wildcard plugin/cells/*.c) plugin/membrane_forces.c \
                                         plugin/membrane_tri.c plugin/membrane_quad.c \
                                         plugin/membrane_centre.c)
KERNEL_VARIANTS := baseline avx2 avx512
KERNEL_ARCH_baseline = $(KERNEL_ARCH)
KERNEL_ARCH_avx2 := -march=x86-64-v3
KERNEL_ARCH_avx512 := -march=x86-64-v4
KERNEL_SRC := $(KERNEL_OBJ:$(BUILD)/%.o=%.c)
KERNEL_PART_OBJ := $(foreach v,$(KERNEL_VARIANTS),$(KERNEL_SRC:%.c=$(BUILD)/kernel/$(v)/%.o))
KERNEL_VARIANT_OBJ := $(KERNEL_VARIANTS:%=$(BUILD)/kernel/%.o)
CORE_OBJ := $(filter-out $(KERNEL_OBJ),$(CORE_OBJ)) $(KERNEL_VARIANT_OBJ)
CTEST_SRC := $(sort $(wildcard tests/c/test_*.c))
CTEST_BIN := $(CTEST_SRC:tests/c/%.c=$(BUILD)/tests/%)
TESTLIB_SRC := $(sort $(wildcard tests/c/lib/*.c))
TESTLIB_OBJ := $(TESTLIB_SRC:%.c=$(BUILD)/%.o)
MODULE   := $(BUILD)/wovenff.so
# The MPI module (docs/distributed.md): the same objects, comm.c built with OpenMPI's mpicc
# (-DWFF_MPI), for FreeFem++-mpi under mpirun (tools/ff.sh -np N, make run NP=N). Built with
# the rest when mpicc and mpi.h are there (MPI=1 to require it, MPI=0 to leave it out).
MPICC    ?= mpicc
MPI      ?= $(shell $(MPICC) --showme:incdirs >/dev/null 2>&1 && test -f "$$($(MPICC) --showme:incdirs | cut -d' ' -f1)/mpi.h" && echo 1 || echo 0)
MPI_MODULE := $(BUILD)/mpi/wovenff.so
MPI_CORE_OBJ = $(filter-out $(BUILD)/plugin/comm.o,$(CORE_OBJ)) $(BUILD)/mpi/plugin/comm.o
MODULE_SRC := $(sort $(wildcard plugin/ff/*.cpp))

MODULE_OBJ := $(MODULE_SRC:%.cpp=$(BUILD)/%.o)

SCENE ?= ballistic_impact
ARGS  ?=

# Every object depends on build/flags.txt, rewritten only when the compiler or
# a flag changes, so a changed flag (OPT=..., KERNEL_ARCH=...) rebuilds all.
FLAGS_FILE := $(BUILD)/flags.txt
FLAGS_NOW  := $(CC) $(CFLAGS) | $(KERNEL_OPT) $(foreach v,$(KERNEL_VARIANTS),$(v): \
              $(KERNEL_ARCH_$(v))) | $(CXX) $(CXXFLAGS) | $(LDLIBS)
$(shell mkdir -p $(BUILD) && [ "$$(cat $(FLAGS_FILE) 2>/dev/null)" = '$(FLAGS_NOW)' ] || \
        printf '%s\n' '$(FLAGS_NOW)' > $(FLAGS_FILE))

.PHONY: all deps run test bench clean print-core-objects
.SECONDARY:
all: $(CORE_OBJ) $(CTEST_BIN) $(MODULE) $(if $(filter 1,$(MPI)),$(MPI_MODULE))

$(BUILD)/plugin/%.o: plugin/%.c $(FLAGS_FILE)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(CORE_INC) $(DEPFLAGS) -c $< -o $@

# The per-element kernels, once per variant: compiled with the variant's name
# (WFF_KERNEL_VARIANT), linked (ld -r) into one object.
define KERNEL_VARIANT_RULE
$(BUILD)/kernel/$(1)/%.o: %.c $(FLAGS_FILE)
	@mkdir -p $$(dir $$@)
	$$(CC) $$(CFLAGS) $$(KERNEL_OPT) $$(KERNEL_ARCH_$(1)) -DWFF_KERNEL_VARIANT=$(1) \
	    $$(CORE_INC) $$(DEPFLAGS) -c $$< -o $$@
$(BUILD)/kernel/$(1).o: $(KERNEL_SRC:%.c=$(BUILD)/kernel/$(1)/%.o)
	$$(LD) -r -o $$@ $$^
endef
$(foreach v,$(KERNEL_VARIANTS),$(eval $(call KERNEL_VARIANT_RULE,$(v))))

$(BUILD)/tests/c/lib/%.o: tests/c/lib/%.c $(FLAGS_FILE)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(TEST_INC) $(DEPFLAGS) -c $< -o $@

$(BUILD)/tests/%: tests/c/%.c $(CORE_OBJ) $(TESTLIB_OBJ) $(FLAGS_FILE)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(TEST_INC) $(DEPFLAGS) -MF $@.d -MT $@ $< $(TESTLIB_OBJ) $(CORE_OBJ) \
	    $(LDLIBS) -o $@

$(BUILD)/plugin/ff/%.o: plugin/ff/%.cpp $(FLAGS_FILE)
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS) $(DEPFLAGS) -c $< -o $@

# (the link map says which variant each function of the library belongs to:
# tests/sh/portable_build.sh reads it)
$(MODULE): $(MODULE_OBJ) $(CORE_OBJ)
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS) -shared $(MODULE_OBJ) $(CORE_OBJ) $(LDLIBS) -Wl,-Map=$(BUILD)/wovenff.map \
	    -o $@

# gcc 12 misreads OpenMPI's MPI_UNWEIGHTED (-Wstringop-overread: a false warning, our -Werror)
$(BUILD)/mpi/plugin/comm.o: plugin/comm.c $(FLAGS_FILE)
	@mkdir -p $(dir $@)
	$(MPICC) $(CFLAGS) -DWFF_MPI -Wno-stringop-overread $(CORE_INC) $(DEPFLAGS) -c $< -o $@

$(MPI_MODULE): $(MODULE_OBJ) $(MPI_CORE_OBJ)
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS) -shared $(MODULE_OBJ) $(MPI_CORE_OBJ) $(LDLIBS) \
	    $(shell $(MPICC) --showme:link 2>/dev/null) -o $@

deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; \
	else echo "all Debian packages present"; fi; \
	missing=""; for p in $(DEB_TEST_PACKAGES) $(DEB_MPI_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing (for the tests):$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  { $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; } \
	    || echo "warning: could not install$$missing: tests/sh/slurm_sweep.sh (Slurm) or tests/sh/distributed.sh (MPI) will skip"; \
	fi

# A scene with a run lock refuses a folder holding an earlier run's results;
# `make run` into the scene's default folder starts afresh (-overwrite 1)
# unless ARGS names its own -out or -overwrite.
LOCKED_SCENES := ballistic_impact strip_tension explicit_loop unit_cell_explorer ballistic_limit
RUN_FRESH := $(if $(filter $(SCENE),$(LOCKED_SCENES)),$(if $(findstring -out,$(ARGS))$(findstring -overwrite,$(ARGS)),,-overwrite 1))
# (make deps first, then the build: a recursive make, so that -j cannot compile before the
# packages are there on a fresh machine)
NP ?=
run:
	@$(MAKE) --no-print-directory deps
	@$(MAKE) --no-print-directory $(if $(NP),$(MPI_MODULE),$(MODULE))
	@sh tools/ff.sh $(if $(NP),-np $(NP) )freefem_scripts/$(SCENE).edp $(RUN_FRESH) $(ARGS)

test:
	@$(MAKE) --no-print-directory deps
	@$(MAKE) --no-print-directory all
	@sh tests/run.sh

BENCH_BIN := $(BUILD)/bench/kernel_speed $(BUILD)/bench/compare
$(BUILD)/bench/%: bench/%.c $(CORE_OBJ) $(FLAGS_FILE)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(CORE_INC) $(DEPFLAGS) -MF $@.d -MT $@ $< $(CORE_OBJ) $(LDLIBS) -o $@

# make bench QUICK=1: the reduced set (small meshes, short runs; under a minute here)
QUICK ?= 0
bench: all $(BENCH_BIN)
	@BENCH_QUICK=$(QUICK) sh bench/run.sh

clean:
	rm -rf $(BUILD)

-include $(CORE_OBJ:.o=.d) $(KERNEL_PART_OBJ:.o=.d) $(TESTLIB_OBJ:.o=.d) $(CTEST_BIN:=.d) $(MODULE_OBJ:.o=.d) \
         $(BENCH_BIN:=.d)

# The objects wovenff.so is linked from (tests/sh/portable_build.sh scans them).
print-core-objects:
	@echo $(CORE_OBJ)

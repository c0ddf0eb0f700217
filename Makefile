# wovenff — build, run, test, bench.
#   make deps    install the Debian packages this project needs (root or sudo)
#   make         build the C core, the C tests and the FreeFEM module
#   make run     the paper's ballistic scene (SCENE=name for another, ARGS="-mesh fine ...")
#   make test    C tests, .edp tests and physics checks; ends with "N passed, N failed"
#   make bench   benchmarks (not part of make test)

CC       ?= gcc
CXX      ?= g++
BUILD    := build
# -fno-math-errno lets gcc vectorise sqrt; never -ffast-math (it removes NaN checks).
OPT      ?= -O2 -fno-math-errno
# The per-element kernels (cells, membrane) are built for this machine's vector
# unit and vectorised across blocks of elements (libmvec's atan/exp). For a
# build that runs on other x86-64 machines: make KERNEL_ARCH=-march=x86-64-v2
KERNEL_ARCH ?= -march=native
KERNEL_OPT  := -O3 $(KERNEL_ARCH) -fopenmp-simd
CFLAGS   := -std=gnu11 $(OPT) -fopenmp -Wall -Wextra -Werror -fPIC
# The binding: our warnings are errors; FreeFEM's headers are -isystem (their
# own warnings are not ours). -Wno-mismatched-new-delete: gcc 12 misreads
# FreeFEM's CodeAlloc (a class operator new/delete pair) in every
# `Global.Add(..., new OneOperatorN_<...>(f))` registration.
CXXFLAGS := -std=c++14 -O2 -fPIC -Wall -Wextra -Werror -Wno-mismatched-new-delete \
            -DBAMG_LONG_LONG -DNCHECKPTR -Wno-deprecated-declarations \
            -isystem /usr/include/freefem++ -Iinclude
LDLIBS   := -fopenmp -lgsl -lgslcblas -lgmsh -lmvec -lm
# Include paths: the core sees its own headers only; test code also sees tests/c/lib.
CORE_INC := -Iinclude -Iplugin
TEST_INC := $(CORE_INC) -Itests/c/lib
# Header dependencies from the compiler: each object gets a .d file beside it.
DEPFLAGS := -MMD -MP

DEB_PACKAGES := freefem++ libfreefem++-dev gmsh libgmsh-dev libgsl-dev gnuplot-nox ghostscript \
                gcc g++ make

CORE_SRC := $(sort $(wildcard plugin/*.c plugin/cells/*.c))
CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/%.o)
CTEST_SRC := $(sort $(wildcard tests/c/test_*.c))
CTEST_BIN := $(CTEST_SRC:tests/c/%.c=$(BUILD)/tests/%)
TESTLIB_SRC := $(sort $(wildcard tests/c/lib/*.c))
TESTLIB_OBJ := $(TESTLIB_SRC:%.c=$(BUILD)/%.o)
MODULE   := $(BUILD)/wovenff.so
MODULE_SRC := $(sort $(wildcard plugin/ff/*.cpp))

MODULE_OBJ := $(MODULE_SRC:%.cpp=$(BUILD)/%.o)

SCENE ?= ballistic_impact
ARGS  ?=

# Every object depends on build/flags.txt, rewritten only when the compiler or
# a flag changes, so a changed flag (OPT=..., KERNEL_ARCH=...) rebuilds all.
FLAGS_FILE := $(BUILD)/flags.txt
FLAGS_NOW  := $(CC) $(CFLAGS) | $(KERNEL_OPT) | $(CXX) $(CXXFLAGS) | $(LDLIBS)
$(shell mkdir -p $(BUILD) && [ "$$(cat $(FLAGS_FILE) 2>/dev/null)" = '$(FLAGS_NOW)' ] || \
        printf '%s\n' '$(FLAGS_NOW)' > $(FLAGS_FILE))

.PHONY: all deps run test bench clean
.SECONDARY:
all: $(CORE_OBJ) $(CTEST_BIN) $(MODULE)

$(BUILD)/plugin/%.o: plugin/%.c $(FLAGS_FILE)
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) $(CORE_INC) $(DEPFLAGS) -c $< -o $@

# The per-element kernels: built for this machine's vector unit (see KERNEL_ARCH).
KERNEL_OBJ := $(patsubst %.c,$(BUILD)/%.o,$(wildcard plugin/cells/*.c) plugin/membrane.c \
                                         plugin/membrane_quad.c)
$(KERNEL_OBJ): CFLAGS += $(KERNEL_OPT)

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

$(MODULE): $(MODULE_OBJ) $(CORE_OBJ)
	@mkdir -p $(dir $@)
	$(CXX) $(CXXFLAGS) -shared $(MODULE_OBJ) $(CORE_OBJ) $(LDLIBS) -o $@

deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing; \
	else echo "all Debian packages present"; fi

# A scene with a run lock refuses a folder holding an earlier run's results;
# `make run` into the scene's default folder starts afresh (-overwrite 1)
# unless ARGS names its own -out or -overwrite.
LOCKED_SCENES := ballistic_impact strip_tension explicit_loop unit_cell_explorer
RUN_FRESH := $(if $(filter $(SCENE),$(LOCKED_SCENES)),$(if $(findstring -out,$(ARGS))$(findstring -overwrite,$(ARGS)),,-overwrite 1))
run: all
	@sh tools/ff.sh freefem_scripts/$(SCENE).edp $(RUN_FRESH) $(ARGS)

test: all
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

-include $(CORE_OBJ:.o=.d) $(TESTLIB_OBJ:.o=.d) $(CTEST_BIN:=.d) $(MODULE_OBJ:.o=.d) \
         $(BENCH_BIN:=.d)

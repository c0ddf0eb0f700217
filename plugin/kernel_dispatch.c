/* kernel_dispatch.c: the kernel variants (include/wovenff/kernel.h) — which
 * ones this CPU runs, which one a request names, each variant's build of a
 * cell, and the membrane entry points wff_elements_forces and
 * wff_elements_stable_step, which run the variant of their material's cell.
 *
 * The Makefile compiles every kernel source once per variant with
 * -DWFF_KERNEL_VARIANT=VARIANT, and the sources name their copies
 * (include/wovenff/kernel_name.h): the entry points are defined as
 * WFF_KERNEL_NAME(wff_elements_forces), i.e. wff_elements_forces__baseline,
 * __avx2, __avx512 (declared below), each variant's cells register in their
 * own linker section wff_cells__avx2, ... (the baseline's in "wff_cells", the
 * registry of registry.c). Constant tables only; knows no cell and no model,
 * only the entry points' types. */
#include "wovenff/kernel.h"
#include "wovenff/membrane.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The environment variable a model reads when it is created. */
#define KERNEL_ENV "WOVENFF_KERNEL"

/* Each variant's copies of the entry points (same types as membrane.h's). */
#define VARIANT_ENTRIES(v)                                                              \
    extern __typeof__(wff_elements_forces) wff_elements_forces__##v;                   \
    extern __typeof__(wff_elements_stable_step) wff_elements_stable_step__##v;         \
    extern const wff_cell_type *const __start_wff_cells__##v[] __attribute__((weak));  \
    extern const wff_cell_type *const __stop_wff_cells__##v[] __attribute__((weak))
VARIANT_ENTRIES(baseline);
VARIANT_ENTRIES(avx2);
VARIANT_ENTRIES(avx512);
/* the baseline's cells are the registry's (registry.c) */
extern const wff_cell_type *const __start_wff_cells[] __attribute__((weak));
extern const wff_cell_type *const __stop_wff_cells[] __attribute__((weak));

struct wff_kernel {
    const char *name;
    const char *isa;                       /* what it needs, for listings and messages */
    const char *cpu_feature;               /* __builtin_cpu_supports' name for that level */
    const wff_cell_type *const *cells_start, *const *cells_stop; /* its cells' tables */
    __typeof__(wff_elements_forces) *forces;
    __typeof__(wff_elements_stable_step) *stable_step;
};

static const wff_kernel kernels[] = {
    {"baseline", "x86-64-v2 (SSE4.2)", "x86-64-v2", __start_wff_cells, __stop_wff_cells,
     wff_elements_forces__baseline, wff_elements_stable_step__baseline},
    {"avx2", "x86-64-v3 (AVX2, FMA)", "x86-64-v3", __start_wff_cells__avx2,
     __stop_wff_cells__avx2, wff_elements_forces__avx2, wff_elements_stable_step__avx2},
    {"avx512", "x86-64-v4 (AVX-512)", "x86-64-v4", __start_wff_cells__avx512,
     __stop_wff_cells__avx512, wff_elements_forces__avx512, wff_elements_stable_step__avx512},
};
#define N_KERNELS ((int)(sizeof kernels / sizeof kernels[0]))

int wff_kernel_count(void) { return N_KERNELS; }

const wff_kernel *wff_kernel_at(int index)
{
    return index >= 0 && index < N_KERNELS ? &kernels[index] : NULL;
}

const char *wff_kernel_name(const wff_kernel *k) { return k->name; }
const char *wff_kernel_isa(const wff_kernel *k) { return k->isa; }

int wff_kernel_runs_here(const wff_kernel *k)
{
    __builtin_cpu_init(); /* libgcc's CPU model (set once by its constructor; idempotent) */
    /* __builtin_cpu_supports needs a literal name */
    if (strcmp(k->cpu_feature, "x86-64-v2") == 0)
        return __builtin_cpu_supports("x86-64-v2") != 0;
    if (strcmp(k->cpu_feature, "x86-64-v3") == 0)
        return __builtin_cpu_supports("x86-64-v3") != 0;
    if (strcmp(k->cpu_feature, "x86-64-v4") == 0)
        return __builtin_cpu_supports("x86-64-v4") != 0;
    return 0;
}

/* "baseline avx2 avx512" (or only those this CPU runs) into buf. */
static const char *kernel_names(int runnable_only, char *buf, size_t size)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < N_KERNELS; i++)
        if (!runnable_only || wff_kernel_runs_here(&kernels[i])) {
            int n = snprintf(buf + used, size - used, "%s%s", used ? " " : "", kernels[i].name);
            if (n < 0 || (size_t)n >= size - used)
                break;
            used += (size_t)n;
        }
    return used ? buf : "none";
}

int wff_kernel_select(const char *request, const wff_kernel **out, wff_error *err)
{
    char names[64];
    *out = NULL;
    if (!request || !*request || strcmp(request, "auto") == 0) {
        for (int i = N_KERNELS - 1; i >= 0; i--)
            if (wff_kernel_runs_here(&kernels[i])) {
                *out = &kernels[i];
                return 0;
            }
        return wff_fail(err, "kernel: this CPU runs none of the kernel variants (the "
                        "baseline needs %s)", kernels[0].isa);
    }
    for (int i = 0; i < N_KERNELS; i++)
        if (strcmp(request, kernels[i].name) == 0) {
            if (!wff_kernel_runs_here(&kernels[i]))
                return wff_fail(err, "kernel '%s' needs %s, which this CPU lacks (it runs: %s)",
                                request, kernels[i].isa, kernel_names(1, names, sizeof names));
            *out = &kernels[i];
            return 0;
        }
    return wff_fail(err, "kernel '%s': unknown kernel variant (known: auto %s)", request,
                    kernel_names(0, names, sizeof names));
}

const wff_cell_type *wff_kernel_cell(const wff_kernel *k, const wff_cell_type *cell)
{
    /* only a built cell has builds: a table made at run time may share its name */
    if (!k->cells_start || !k->cells_stop || !cell || !wff_kernel_of_cell(cell))
        return NULL;
    for (const wff_cell_type *const *c = k->cells_start; c < k->cells_stop; c++)
        if (strcmp(wff_cell_name((*c)), wff_cell_name(cell)) == 0)
            return *c;
    return NULL;
}

const wff_kernel *wff_kernel_of_cell(const wff_cell_type *cell)
{
    for (int i = 0; i < N_KERNELS; i++) {
        const wff_kernel *k = &kernels[i];
        if (k->cells_start && k->cells_stop)
            for (const wff_cell_type *const *c = k->cells_start; c < k->cells_stop; c++)
                if (*c == cell)
                    return k;
    }
    return NULL;
}

const char *wff_material_kernel(const wff_material *mat)
{
    const wff_kernel *k = wff_kernel_of_cell(mat->cell);
    return (k ? k : &kernels[0])->name;
}

int wff_kernel_apply(wff_material *mat, const char *request, wff_error *err)
{
    const char *asked = request ? request : getenv(KERNEL_ENV);
    const wff_kernel *k;
    if (wff_kernel_select(asked, &k, err)) {
        if (!request && err) { /* say where the request came from */
            char why[sizeof err->message];
            snprintf(why, sizeof why, "%s", err->message);
            return wff_fail(err, "environment variable %s: %s", KERNEL_ENV, why);
        }
        return -1;
    }
    const wff_cell_type *cell = wff_kernel_cell(k, mat->cell);
    if (!cell) {
        if (!asked || !*asked || strcmp(asked, "auto") == 0)
            return 0; /* a cell built into no variant (made at run time) runs as it is */
        return wff_fail(err, "kernel '%s': cell '%s' has no build for it", k->name,
                        mat->cell ? wff_cell_name(mat->cell) : "(none)");
    }
    mat->cell = cell;
    return 0;
}

/* The membrane entry points: the variant of the material's cell (baseline for
 * a cell in none). A look-up of a few pointers per pass. */
static const wff_kernel *kernel_of(const wff_element_material *em)
{
    const wff_kernel *k = wff_kernel_of_cell(em->mat->cell);
    return k ? k : &kernels[0];
}

void wff_elements_forces(const wff_elements *el, const wff_element_material *em, const double *X,
                         const double *u, double *state, double dt, double *f,
                         wff_force_totals *totals)
{
    kernel_of(em)->forces(el, em, X, u, state, dt, f, totals);
}

double wff_elements_stable_step(const wff_elements *el, const wff_element_material *em,
                                const double *X, const double *u, int *worst)
{
    return kernel_of(em)->stable_step(el, em, X, u, worst);
}

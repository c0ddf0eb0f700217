/* wovenff — kernel variants: the per-element kernels built for several
 * x86-64 instruction sets, one chosen per model at run time.
 *
 * The per-element kernels — every cell (plugin/cells/: evaluate,
 * evaluate_shared, evaluate_tri_block, wave_speeds, ...) and the membrane
 * passes wff_elements_forces and wff_elements_stable_step (plugin/membrane*.c)
 * — are compiled once per variant by the Makefile, each copy named in the
 * source by the variant it is (wovenff/kernel_name.h: WFF_KERNEL_NAME):
 *
 *   baseline   -march=x86-64-v2 (SSE4.2): any x86-64 machine since ~2009
 *   avx2       -march=x86-64-v3 (AVX2, FMA, BMI2)
 *   avx512     -march=x86-64-v4 (AVX-512 F/BW/CD/DQ/VL)
 *
 * Everything else in wovenff.so is built for the compiler's default x86-64,
 * so the library loads and runs anywhere; tests/sh/portable_build.sh checks the
 * disassembly for that.
 *
 * A model's choice is its material's cell: wff_kernel_apply points mat->cell
 * at that variant's build of the same cell (same name, same parameters), and
 * the membrane passes run the variant their material's cell belongs to. No
 * global state: the choice lives in the material, the tables are constant.
 * A model reads the environment variable WOVENFF_KERNEL once, when it is
 * created (auto when unset: the widest variant this CPU runs). */
#ifndef WOVENFF_KERNEL_H
#define WOVENFF_KERNEL_H

#include "wovenff/cell.h"
#include "wovenff/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wff_kernel wff_kernel;

/* The variants built into this library, baseline first, widest last. */
int wff_kernel_count(void);
const wff_kernel *wff_kernel_at(int index);    /* NULL outside 0 .. count − 1 */
const char *wff_kernel_name(const wff_kernel *k); /* "baseline", "avx2", "avx512" */
const char *wff_kernel_isa(const wff_kernel *k);  /* what it needs, e.g. "x86-64-v4 (AVX-512)" */
int wff_kernel_runs_here(const wff_kernel *k);    /* 1 if this CPU (and its OS) runs it */

/* The variant a request names: "baseline", "avx2", "avx512", or "auto" (or
 * NULL or ""): the widest this CPU runs. -1 with err naming the request and
 * the known names when it is unknown or this CPU cannot run it. */
int wff_kernel_select(const char *request, const wff_kernel **out, wff_error *err);

/* Variant k's build of cell (found by name), or NULL when k has none (a cell
 * table made at run time, e.g. by a test). */
const wff_cell_type *wff_kernel_cell(const wff_kernel *k, const wff_cell_type *cell);

/* The variant whose build cell is, or NULL for a cell in none of them. */
const wff_kernel *wff_kernel_of_cell(const wff_cell_type *cell);

/* The name of the variant mat runs ("baseline" for a cell in none). */
const char *wff_material_kernel(const wff_material *mat);

/* Run mat on the variant request names (as wff_kernel_select; NULL: the
 * environment variable WOVENFF_KERNEL, auto when unset or empty): mat->cell
 * becomes that variant's build of its cell. -1 with err set (mat unchanged)
 * for a bad request, or a variant that has no build of the cell (only an
 * explicit request; auto then keeps the cell as it is). */
int wff_kernel_apply(wff_material *mat, const char *request, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

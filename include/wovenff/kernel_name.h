/* wovenff — names of the kernel variants' code (include/wovenff/kernel.h).
 *
 * The Makefile compiles each kernel source (KERNEL_OBJ: the cells and the
 * membrane passes) once per variant with -DWFF_KERNEL_VARIANT=baseline, avx2
 * or avx512; everything else is compiled once, without it. In a kernel
 * source:
 *
 *   WFF_KERNEL_NAME(wff_elements_forces)   an entry point, or a function one
 *       kernel file calls in another: wff_elements_forces__avx2 in the avx2
 *       build (kernel_dispatch.c calls each variant's by that name; outside
 *       a variant build the plain name);
 *   WFF_KERNEL_PRIMARY                     1 in the baseline build (and
 *       outside a variant build), 0 in the others: a function the rest of the
 *       library calls by its plain name is defined under #if WFF_KERNEL_PRIMARY,
 *       once, by the baseline build;
 *   WFF_CELLS_SECTION                      the linker section a cell registers
 *       in (cell.h's WFF_REGISTER_CELL): "wff_cells" (the registry's, the
 *       baseline's and any cell outside the kernels) or "wff_cells__avx2", ...
 *
 * Static functions need nothing: each build's are its own. */
#ifndef WOVENFF_KERNEL_NAME_H
#define WOVENFF_KERNEL_NAME_H

#define WFF_KERNEL_STR_(x) #x
#define WFF_KERNEL_STR(x) WFF_KERNEL_STR_(x)
#define WFF_KERNEL_CAT_(a, b) a##__##b
#define WFF_KERNEL_CAT(a, b) WFF_KERNEL_CAT_(a, b)
/* (an identifier that is not a macro is 0 in #if: 1 only for baseline) */
#define WFF_KERNEL_IS_PRIMARY_baseline 1
#define WFF_KERNEL_IS_PRIMARY_(v) WFF_KERNEL_IS_PRIMARY_##v
#define WFF_KERNEL_IS_PRIMARY(v) WFF_KERNEL_IS_PRIMARY_(v)

#ifdef WFF_KERNEL_VARIANT
#define WFF_KERNEL_NAME(name) WFF_KERNEL_CAT(name, WFF_KERNEL_VARIANT)
#if WFF_KERNEL_IS_PRIMARY(WFF_KERNEL_VARIANT)
#define WFF_KERNEL_PRIMARY 1
#define WFF_CELLS_SECTION "wff_cells"
#else
#define WFF_KERNEL_PRIMARY 0
#define WFF_CELLS_SECTION "wff_cells__" WFF_KERNEL_STR(WFF_KERNEL_VARIANT)
#endif
#else
#define WFF_KERNEL_NAME(name) name
#define WFF_KERNEL_PRIMARY 1
#define WFF_CELLS_SECTION "wff_cells"
#endif

#endif

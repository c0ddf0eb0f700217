/* The blocked quad4 force pass (plugin/membrane_quad.c), internal to the
 * membrane code (the kernels): wff_elements_forces calls it and falls back to
 * its plain per-point loop when it declines; and the two halves of the pass. */
#ifndef WOVENFF_MEMBRANE_QUAD_H
#define WOVENFF_MEMBRANE_QUAD_H

#include "wovenff/membrane.h"

#include <stddef.h>

/* Internal forces of every quad through the cell's evaluate_point_block,
 * written into its slots (el->slot); the state of the quads' points (mat->n_state each) updated
 * with step dt. Adds Σ w W, Σ w × dissipation, Σ w × failure dissipation and Σ w × slip dissipation
 * (w = Gauss weight × det J) / J_pre into totals->sums (order-free,
 * fixed_sum.h), and notes the first bad point (lowest quad, then
 * lowest point) in totals if totals has none. Threads: el->n_threads on large
 * meshes, the same bits for a given count. Returns 0, or −1 with nothing done
 * when the fast path does not apply (no evaluate_point_block, the reference
 * path asked for, static amplitudes, or the cell declines its parameters). */
int WFF_KERNEL_NAME(wff_quad_block_forces)(const wff_elements *el,
                                           const wff_element_material *em, const double *X,
                                           const double *u, double *state, double dt,
                                           wff_force_totals *totals);

/* The two halves of the force pass wff_elements_forces (membrane_forces.c), each
 * writing its elements' forces into their slots (el->slot), adding Σ A W, Σ A × dissipation, Σ A ×
 * failure dissipation and Σ A × slip dissipation / J_pre into totals->sums (each block's, order-free),
 * its Newton iterations and first bad point into totals: the
 * triangles (membrane_tri.c; the first bad one wins over the quads'), then
 * the quads (membrane_quad.c: wff_quad_block_forces, else point by point). */
void WFF_KERNEL_NAME(wff_tri_forces)(const wff_elements *el, const wff_element_material *em,
                                     const double *X, const double *u, double *state,
                                     double dt, wff_force_totals *totals);
void WFF_KERNEL_NAME(wff_quad_forces)(const wff_elements *el, const wff_element_material *em,
                                      const double *X, const double *u, double *state,
                                      double dt, wff_force_totals *totals);

/* The entry points as this build of the kernels defines them (kernel_name.h:
 * wff_elements_forces__avx2, ...); kernel_dispatch.c's wff_elements_forces
 * and wff_elements_stable_step call the variant of the material's cell. */
__typeof__(wff_elements_forces) WFF_KERNEL_NAME(wff_elements_forces);
__typeof__(wff_elements_stable_step) WFF_KERNEL_NAME(wff_elements_stable_step);

#endif

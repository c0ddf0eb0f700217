/* The blocked quad4 force pass (plugin/membrane_quad.c) and the thread-buffer
 * reduction both passes share, internal to the membrane code (the kernels):
 * wff_elements_forces calls it and falls back to its plain per-point loop
 * when it declines. */
#ifndef WOVENFF_MEMBRANE_QUAD_H
#define WOVENFF_MEMBRANE_QUAD_H

#include "wovenff/membrane.h"

#include <stddef.h>

/* Internal forces of every quad through the cell's evaluate_point_block,
 * added into f; the state of the quads' points (mat->n_state each) updated
 * with step dt. Adds Σ w W, Σ w × dissipation and Σ w × failure dissipation
 * (w = Gauss weight × det J, not yet divided by J_pre) into *energy,
 * *dissipated and *failure, and notes the first bad point (lowest quad, then
 * lowest point) in totals if totals has none. Threads: el->n_threads on large
 * meshes, the same bits for a given count. Returns 0, or −1 with nothing done
 * when the fast path does not apply (no evaluate_point_block, the reference
 * path asked for, static amplitudes, or the cell declines its parameters). */
int WFF_KERNEL_NAME(wff_quad_block_forces)(const wff_elements *el,
                                           const wff_element_material *em, const double *X,
                                           const double *u, double *state, double dt,
                                           double *f, double *energy, double *dissipated,
                                           double *failure, wff_force_totals *totals);

/* The two halves of the force pass wff_elements_forces (membrane_forces.c), each
 * adding its elements' forces into f, Σ A W, Σ A × dissipation and Σ A ×
 * failure dissipation (not yet divided by J_pre) into *energy, *dissipated,
 * *failure, its Newton iterations and first bad point into totals: the
 * triangles (membrane_tri.c; the first bad one wins over the quads'), then
 * the quads (membrane_quad.c: wff_quad_block_forces, else point by point). */
void WFF_KERNEL_NAME(wff_tri_forces)(const wff_elements *el, const wff_element_material *em,
                                     const double *X, const double *u, double *state,
                                     double dt, double *f, double *energy, double *dissipated,
                                     double *failure, wff_force_totals *totals);
void WFF_KERNEL_NAME(wff_quad_forces)(const wff_elements *el, const wff_element_material *em,
                                      const double *X, const double *u, double *state,
                                      double dt, double *f, double *energy, double *dissipated,
                                      double *failure, wff_force_totals *totals);

/* The entry points as this build of the kernels defines them (kernel_name.h:
 * wff_elements_forces__avx2, ...); kernel_dispatch.c's wff_elements_forces
 * and wff_elements_stable_step call the variant of the material's cell. */
__typeof__(wff_elements_forces) WFF_KERNEL_NAME(wff_elements_forces);
__typeof__(wff_elements_stable_step) WFF_KERNEL_NAME(wff_elements_stable_step);

/* Inside a force pass's parallel region, past its element loop's barrier: the
 * extra threads' buffers (el->thread_f) added into f, each thread a slice of
 * the DOFs, buffers in thread order (the same bits for a given count), each
 * cleared as it is read — no pass zeroes them, every pass relies on finding
 * them zero. The region's end is the barrier after it. */
static inline void wff_thread_buffers_reduce(const wff_elements *el, double *f, int team)
{
    if (team <= 1)
        return;
    const size_t n_dofs = (size_t)el->n_dofs;
#pragma omp for schedule(static) nowait
    for (size_t i = 0; i < n_dofs; i++) {
        double extra = 0;
        for (int k = 1; k < team; k++) {
            double *b = el->thread_f + (size_t)(k - 1) * n_dofs + i;
            extra += *b;
            *b = 0;
        }
        f[i] += extra;
    }
}

#endif

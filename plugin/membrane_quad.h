/* The blocked quad4 force pass (plugin/membrane_quad.c), internal to the
 * membrane code: wff_elements_forces calls it and falls back to its plain
 * per-point loop when it declines. */
#ifndef WOVENFF_MEMBRANE_QUAD_H
#define WOVENFF_MEMBRANE_QUAD_H

#include "wovenff/membrane.h"

/* Internal forces of every quad through the cell's evaluate_point_block,
 * added into f; γᶠ of the quads' points updated with step dt. Adds Σ w W and
 * Σ w × dissipation (w = Gauss weight × det J, not yet divided by J_pre) into
 * *energy and *dissipated, and notes the first bad point (lowest quad, then
 * lowest point) in totals if totals has none. Threads: el->n_threads on large
 * meshes, the same bits for a given count. Returns 0, or −1 with nothing done
 * when the fast path does not apply (no evaluate_point_block, the reference
 * path asked for, static amplitudes, or the cell declines its parameters). */
int wff_quad_block_forces(const wff_elements *el, const wff_element_material *em,
                          const double *X, const double *u, double *gamma_f, double dt,
                          double *f, double *energy, double *dissipated,
                          wff_force_totals *totals);

#endif

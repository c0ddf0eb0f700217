/* Membrane elements: the internal-force pass wff_elements_forces (a kernel,
 * built once per variant: docs/architecture.md, "Kernel variants"): the
 * triangles (membrane_tri.c), then the quads (membrane_quad.c), their sums
 * in that order. The set-up (reference geometry, threads, static amplitudes)
 * is membrane_setup.c, the stable step membrane_centre.c. See
 * include/wovenff/membrane.h for the formulas. */
#include "wovenff/membrane.h"
#include "membrane_quad.h"

void WFF_KERNEL_NAME(wff_elements_forces)(const wff_elements *el, const wff_element_material *em,
                                          const double *X, const double *u, double *state,
                                          double dt, double *f, wff_force_totals *totals)
{
    totals->internal_energy = totals->dissipated = totals->failure_dissipated = 0;
    totals->bad_element = -1;
    totals->bad_point = -1;
    totals->bad_status = 0;
    totals->bad_residual = 0;
    totals->bad_iterations = 0;
    totals->amplitude_iterations = 0;
    double energy = 0, dissipated = 0, failure = 0;

    WFF_KERNEL_NAME(wff_tri_forces)(el, em, X, u, state, dt, f, &energy, &dissipated, &failure,
                                    totals);
    WFF_KERNEL_NAME(wff_quad_forces)(el, em, X, u, state, dt, f, &energy, &dissipated, &failure,
                                     totals);
    totals->internal_energy = energy / em->J_pre;
    totals->dissipated = dissipated / em->J_pre;
    totals->failure_dissipated = failure / em->J_pre;
}

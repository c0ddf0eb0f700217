/* Membrane elements: the internal-force pass wff_elements_forces (a kernel,
 * built once per variant: docs/architecture.md, "Kernel variants"): the
 * triangles (membrane_tri.c), then the quads (membrane_quad.c), each element
 * writing its force on its nodes into its slots, then every node adding its
 * slots into f in element order (wff_elements_gather), their energies in
 * block order. The set-up (reference geometry, threads, static amplitudes)
 * is membrane_setup.c, the stable step membrane_centre.c. See
 * include/wovenff/membrane.h for the formulas. */
#include "wovenff/membrane.h"
#include "membrane_quad.h"

#define D WFF_DOFS_PER_NODE

/* Every node the elements reference adds its slots, in ascending element order,
 * into f: s = ((0 + s₁) + s₂) + …, f += s. A node's sum depends on no thread or
 * rank that computed its elements: the same bits for any. Threads over the
 * nodes (each node one thread's). */
static void elements_gather(const wff_elements *el, double *f)
{
    const int threads = wff_elements_team(el);
    /* (over ranks: this rank's own nodes, plugin/distribute.c) */
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
    for (int k = el->gather_begin; k < el->gather_end; k++) {
        const int *slot = el->node_slot + el->node_slot_start[k];
        const int count = el->node_slot_start[k + 1] - el->node_slot_start[k];
        double sum[D] = {0, 0, 0, 0, 0};
        for (int i = 0; i < count; i++) {
            const double *s = el->slot + D * (size_t)slot[i];
            for (int c = 0; c < D; c++)
                sum[c] += s[c];
        }
        double *fn = f + D * (size_t)el->node_list[k];
        for (int c = 0; c < D; c++)
            fn[c] += sum[c];
    }
}

void WFF_KERNEL_NAME(wff_elements_forces)(const wff_elements *el, const wff_element_material *em,
                                          const double *X, const double *u, double *state,
                                          double dt, double *f, wff_force_totals *totals)
{
    totals->bad_element = -1;
    totals->bad_point = -1;
    totals->bad_status = 0;
    totals->bad_residual = 0;
    totals->bad_iterations = 0;
    totals->amplitude_iterations = 0;
    for (int k = 0; k < WFF_BLOCK_SUMS; k++)
        totals->sums[k] = wff_fixed_zero();
    WFF_KERNEL_NAME(wff_tri_forces)(el, em, X, u, state, dt, totals);
    WFF_KERNEL_NAME(wff_quad_forces)(el, em, X, u, state, dt, totals);
    elements_gather(el, f);
    totals->internal_energy = wff_fixed_value(&totals->sums[0]);
    totals->dissipated = wff_fixed_value(&totals->sums[1]);
    totals->failure_dissipated = wff_fixed_value(&totals->sums[2]);
    totals->slip_dissipated = wff_fixed_value(&totals->sums[3]);
}

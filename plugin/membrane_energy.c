/* Membrane elements: the stored energy per mechanism summed over the mesh and
 * the lumped masses (include/wovenff/membrane.h), and one element's stored
 * energy (erosion's measure of what an eroded element held) — sums for output,
 * set-up and erosion,
 * not on the per-step path (the force pass and the stable step are in
 * membrane_tri.c, membrane_quad.c and membrane_centre.c). */
#include "wovenff/membrane.h"
#include "membrane_geometry.h"
#include "solver_internal.h" /* D, the DOFs per node */

#include <math.h>
#include <string.h>

void wff_elements_energy_split(const wff_elements *el, const wff_element_material *em,
                               const double *X, const double *u, const double *state,
                               double *mech)
{
    const wff_cell_type *cell = em->mat->cell;
    const int ns = em->mat->n_state;
    for (int k = 0; k < wff_cell_n_mech(cell); k++)
        mech[k] = 0;
    if (!wff_cell_has_energy_split(cell))
        return;
    double point[WFF_MECH_MAX];
    for (int e = 0; e < el->n_tris; e++) {
        const int *node = el->tri + 3 * e;
        if (wff_element_eroded(el, e)) /* no stored energy */
            continue;
        double F[6], Fe[6];
        tri_deformation(el, em, X, u, e, F, Fe);
        double w = el->tri_area[e] / 3 / em->J_pre;
        for (int q = 0; q < WFF_TRI_POINTS; q++) {
            double dA[2] = {u[D * node[q] + 3], u[D * node[q] + 4]};
            if (em->static_amplitudes) /* the point's own balanced amplitudes */
                memcpy(dA, el->point_dA + 6 * e + 2 * q, sizeof dA);
            wff_cell_energy_split(em->mat, Fe, dA, state + ns * (3 * e + q), point);
            for (int k = 0; k < wff_cell_n_mech(cell); k++)
                mech[k] += w * point[k];
        }
    }
    for (int e = 0; e < el->n_quads; e++) {
        if (wff_element_eroded(el, el->n_tris + e))
            continue;
        for (int q = 0; q < WFF_QUAD_POINTS; q++) {
            double N[4], dA[2], F[6], Fe[6];
            quad_point_kinematics(el, em, X, u, e, q, N, dA, F, Fe);
            wff_cell_energy_split(em->mat, Fe, dA,
                               state + ns * (3 * el->n_tris + 4 * e + q), point);
            double w = el->quad_weight[4 * e + q] / em->J_pre;
            for (int k = 0; k < wff_cell_n_mech(cell); k++)
                mech[k] += w * point[k];
        }
    }
}

void wff_elements_masses(const wff_elements *el, const wff_element_material *em, int n_nodes,
                         double *mass)
{
    double amplitude_factor = em->amplitude_mass_factor > 0 ? em->amplitude_mass_factor : 1;
    memset(mass, 0, sizeof(double) * D * (size_t)n_nodes);
    double density = em->mat->areal_density / em->J_pre;
    for (int e = 0; e < el->n_tris; e++)
        for (int a = 0; a < 3; a++)
            mass[D * el->tri[3 * e + a]] += density * el->tri_area[e] / 3;
    for (int e = 0; e < el->n_quads; e++) {
        double area = 0;
        for (int q = 0; q < 4; q++)
            area += el->quad_weight[4 * e + q];
        for (int a = 0; a < 4; a++)
            mass[D * el->quad[4 * e + a]] += density * area / 4;
    }
    for (int n = 0; n < n_nodes; n++) {
        double m = mass[D * n];
        mass[D * n + 1] = mass[D * n + 2] = m;
        mass[D * n + 3] = mass[D * n + 4] = m / 6 * amplitude_factor; /* eq. 12 */
    }
}

double wff_element_stored_energy(const wff_elements *el, const wff_element_material *em,
                                 const double *X, const double *u, const double *state,
                                 int n_state, int e)
{
    const wff_material *mat = em->mat;
    const double *s = state + (size_t)n_state * wff_element_first_point(el->n_tris, e);
    double F[6], Fe[6], energy = 0;
    wff_point_result r;
    if (e < el->n_tris) {
        const int *node = el->tri + 3 * e;
        tri_deformation(el, em, X, u, e, F, Fe);
        double W = 0;
        for (int q = 0; q < WFF_TRI_POINTS; q++) {
            double dA[2] = {u[D * node[q] + 3], u[D * node[q] + 4]};
            if (em->static_amplitudes)
                memcpy(dA, el->point_dA + 6 * e + 2 * q, sizeof dA);
            if (wff_material_evaluate(mat, Fe, dA, s + n_state * q, 0, &r) ==
                    WFF_POINT_OK && isfinite(r.energy))
                W += r.energy / 3;
        }
        energy = el->tri_area[e] * W;
    } else {
        int qe = e - el->n_tris;
        for (int q = 0; q < WFF_QUAD_POINTS; q++) {
            double N[4], dA[2];
            quad_point_kinematics(el, em, X, u, qe, q, N, dA, F, Fe);
            if (wff_material_evaluate(mat, Fe, dA, s + n_state * q, 0, &r) ==
                    WFF_POINT_OK && isfinite(r.energy))
                energy += el->quad_weight[4 * qe + q] * r.energy;
        }
    }
    return energy / em->J_pre;
}

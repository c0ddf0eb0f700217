/* fields.c: output of a model's state: per-node fields by name (DOFs,
 * the cell's diagnostics, the shear angle, the stored energy; element values
 * averaged to nodes by area) and the stored energy split by mechanism. Reads
 * the state; changes nothing. Knows cells only through their names tables;
 * nothing of the integrator, contact or FreeFEM. */
#include "solver_internal.h"
#include "zones.h"
#include "pack.h"
#include "wovenff/state.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const dof_names[D] = {"ux", "uy", "uz", "dA1", "dA2"};

int wff_model_nodal_field(const wff_model *m, const char *name, double *out, wff_error *err)
{
    if (strcmp(name, "ply") == 0) { /* a pack's ply of each node, 0-based (pack.h) */
        for (int n = 0; n < m->n_nodes; n++)
            out[wff_model_user_node(m, n)] = wff_pack_node_ply(m, n);
        return 0;
    }
    for (int c = 0; c < D; c++)
        if (strcmp(name, dof_names[c]) == 0) {
            for (int n = 0; n < m->n_nodes; n++)
                out[wff_model_user_node(m, n)] = m->u[D * n + c];
            return 0;
        }
    for (int c = 0; c < 3; c++)
        if (strcmp(name, c == 0 ? "vx" : c == 1 ? "vy" : "vz") == 0) {
            for (int n = 0; n < m->n_nodes; n++)
                out[wff_model_user_node(m, n)] = m->v[D * n + c];
            return 0;
        }
    for (int k = 0; k < 2; k++) /* absolute amplitudes A_k = A_k0 + dA_k (state.c) */
        if (strcmp(name, k ? "A2" : "A1") == 0)
            return wff_model_amplitude(m, k, out, err);
    const wff_cell_type *cell = m->mat.cell;
    int diag = -1;
    for (int d = 0; d < wff_cell_n_diag(cell); d++)
        if (strcmp(name, wff_cell_diag_name(cell, d)) == 0)
            diag = d;
    /* generic names for the yarn tensions, whatever the cell calls them */
    for (int k = 0; k < 2; k++)
        if (strcmp(name, k ? "yarn_tension2" : "yarn_tension1") == 0)
            diag = wff_cell_yarn_tension_diag(cell, k);
    /* damage and erosion: the element values (erosion.c), whatever a cell's
     * diagnostics are called */
    if (strcmp(name, "damage1") == 0 || strcmp(name, "damage2") == 0 ||
        strcmp(name, "eroded") == 0)
        diag = -1;
    int shear = strcmp(name, "gamma") == 0, energy = strcmp(name, "W") == 0;
    double *element = NULL; /* another element field (state.h), averaged the same way */
    if (diag < 0 && !shear && !energy) {
        wff_error why;
        element = malloc(sizeof(double) * (size_t)(m->el.n_tris + m->el.n_quads + 1));
        if (!element)
            return wff_fail(err, "out of memory");
        if (wff_model_element_values_model(m, name, element, &why)) {
            free(element);
            if (strncmp(why.message, "unknown element field", 21) != 0)
                return wff_fail(err, "%s", why.message);
            const char *known = strstr(why.message, "(known: ");
            return wff_fail(err, "unknown field '%s' (known: ux uy uz dA1 dA2 vx vy vz A1 A2 "
                            "gamma yarn_tension1 yarn_tension2 %s", name,
                            known ? known + 8 : ")");
        }
    }
    double *weight = calloc((size_t)m->n_nodes, sizeof(double));
    if (!weight) {
        free(element);
        return wff_fail(err, "out of memory");
    }
    memset(out, 0, sizeof(double) * (size_t)m->n_nodes);
    int n_el = m->el.n_tris + m->el.n_quads;
    /* an eroded element carries nothing: left out of the averages of what the cell
     * evaluates (a node with no live element reads 0 there) */
    const int live_only = m->el.eroded && (diag >= 0 || energy ||
                                           (element && wff_element_field_evaluated(m, name)));
    for (int e = 0; e < n_el; e++) {
        double value;
        if (live_only && m->el.eroded[e])
            continue;
        if (element) {
            value = element[e];
        } else if (shear) {
            double F[6], dA[2];
            wff_element_center_state(&m->el, m->mesh.xy, m->u, e, F, dA);
            const double *Fp = m->em.F_pre;
            double g1[3], g2[3];
            for (int i = 0; i < 3; i++) {
                g1[i] = F[2 * i] * Fp[0] + F[2 * i + 1] * Fp[2];
                g2[i] = F[2 * i] * Fp[1] + F[2 * i + 1] * Fp[3];
            }
            double dot = g1[0] * g2[0] + g1[1] * g2[1] + g1[2] * g2[2];
            double cx = g1[1] * g2[2] - g1[2] * g2[1], cy = g1[2] * g2[0] - g1[0] * g2[2],
                   cz = g1[0] * g2[1] - g1[1] * g2[0];
            value = M_PI_2 - atan2(sqrt(cx * cx + cy * cy + cz * cz), dot);
        } else {
            wff_point_result r;
            wff_model_element_center_eval(m, m->u, e, &r);
            int d = wff_model_element_diag(m, e, diag); /* a zone's cell may lack it: 0 there */
            value = energy ? r.energy : d >= 0 ? r.diag[d] : 0;
        }
        const int *node, nn = wff_element_nodes(&m->el, e, &node);
        const double area = wff_element_area(&m->el, e);
        for (int a = 0; a < nn; a++) {
            out[node[a]] += area * value;
            weight[node[a]] += area;
        }
    }
    for (int n = 0; n < m->n_nodes; n++)
        out[n] = weight[n] > 0 ? out[n] / weight[n] : 0;
    free(weight);
    free(element);
    return wff_model_nodes_to_user_in_place(m, out, 1, err); /* (the user's numbering) */
}

int wff_model_energy_split(const wff_model *m, double *out)
{
    const wff_cell_type *cell = m->mat.cell;
    int n = wff_cell_n_mech(cell) < WFF_MECH_MAX ? wff_cell_n_mech(cell) : WFF_MECH_MAX;
    double mech[WFF_MECH_MAX] = {0};
    if (n > 0)
        wff_zones_energy_split(m, m->u, m->state, mech);
    for (int k = 0; k < n; k++)
        out[k] = m->symmetry_factor * mech[k];
    return n;
}

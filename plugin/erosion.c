/* erosion.c: element erosion (plugin/erosion.h): the setting, the scan after
 * a force pass that marks elements whose yarns have ruptured and moves their
 * stored energy to the eroded energy, and the damage the output and the mesh
 * transfer read. The element kernels (membrane.c, membrane_quad.c,
 * membrane_centre.c) only skip what el->eroded marks. Knows the model's
 * arrays and the cells through their tables (damage_state); nothing of the
 * integrator's step, contact, output files or FreeFEM. */
#include "erosion.h"
#include "membrane_geometry.h"
#include "zones.h"
#include "pack.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Index in mat's points of family k's damage, or −1 when they carry none. */
static int damage_index(const wff_material *mat, int k)
{
    int i = wff_cell_damage_state(mat->cell, k);
    return i >= 0 && i < mat->n_state ? i : -1;
}

/* Whether some material of the model carries both damage states; the first
 * cell without yarn failure into *lacking (NULL if none). */
static int materials_damage(const wff_model *m, const wff_cell_type **lacking)
{
    int carry = 0;
    *lacking = NULL;
    for (int z = 0; z < wff_model_zone_count(m); z++) {
        const wff_material *mat = wff_model_zone_material(m, z);
        if (!mat || (z > 0 && wff_model_zone_size(m, z) == 0))
            continue;
        if (wff_cell_damage_state(mat->cell, 0) < 0 || wff_cell_damage_state(mat->cell, 1) < 0) {
            if (!*lacking)
                *lacking = mat->cell;
            continue;
        }
        carry |= damage_index(mat, 0) >= 0 && damage_index(mat, 1) >= 0;
    }
    return carry;
}

static int flags_on(wff_model *m, int rule, wff_error *err)
{
    int n_el = m->el.n_tris + m->el.n_quads;
    if (!m->el.eroded) {
        m->el.eroded = calloc((size_t)(n_el ? n_el : 1), 1);
        if (!m->el.eroded)
            return wff_fail(err, "erosion: out of memory for %d elements' flags", n_el);
    }
    m->el.erosion = rule;
    return wff_zones_erosion_changed(m, err);
}

int wff_erosion_set(wff_model *m, double value, wff_error *err)
{
    if (!(value == 0 || value == 1 || value == 2))
        return wff_fail(err, "erosion = %g: must be 0 (off), 1 (an element goes when both "
                        "yarn families have ruptured at every point) or 2 (either family)",
                        value);
    int rule = (int)value;
    if (rule == WFF_EROSION_OFF) {
        if (m->n_eroded > 0)
            return wff_fail(err, "erosion = 0: %d elements have eroded already (an eroded "
                            "element does not come back)", m->n_eroded);
        free(m->el.eroded);
        m->el.eroded = NULL;
        m->el.erosion = WFF_EROSION_OFF;
        return wff_zones_erosion_changed(m, err);
    }
    const wff_cell_type *lacking;
    int carry = materials_damage(m, &lacking);
    if (lacking)
        return wff_fail(err, "erosion = %d: cell '%s' has no yarn failure (no damage "
                        "state): its elements could never erode; use a cell with failure "
                        "or erosion = 0", rule, wff_cell_name(lacking));
    if (!carry)
        return wff_fail(err, "erosion = %d: the material (%s, cell '%s') has yarn failure "
                        "off (failure = 0): its points carry no damage; set failure = 1 in "
                        "the material file", rule, m->mat.source, wff_cell_name(m->mat.cell));
    return flags_on(m, rule, err);
}

int wff_erosion_default(wff_model *m, wff_error *err)
{
    if (damage_index(&m->mat, 0) < 0 || damage_index(&m->mat, 1) < 0)
        return 0;
    return flags_on(m, WFF_EROSION_BOTH, err);
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
        deformation_gradient(X, u, node, 3, el->tri_grad + 6 * e, F);
        preload_apply(em, F, Fe);
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

/* Whether element e's points have ruptured as the rule asks. */
static int ruptured(const wff_model *m, const wff_material *mat, const double *s, int n_points,
                    int rule)
{
    const int ns = m->n_state;
    int k0 = damage_index(mat, 0), k1 = damage_index(mat, 1);
    int all[2] = {k0 >= 0, k1 >= 0};
    for (int q = 0; q < n_points && (all[0] || all[1]); q++) {
        if (all[0] && !(s[ns * q + k0] >= 1))
            all[0] = 0;
        if (all[1] && !(s[ns * q + k1] >= 1))
            all[1] = 0;
    }
    return rule == WFF_EROSION_BOTH ? all[0] && all[1] : all[0] || all[1];
}

double wff_erosion_scan(wff_model *m, const double *u, const double *state)
{
    unsigned char *eroded = m->el.eroded;
    if (!eroded || m->el.erosion == WFF_EROSION_OFF)
        return 0;
    const int nt = m->el.n_tris, n_el = nt + m->el.n_quads;
    double removed = 0;
    int any = 0;
    for (int e = 0; e < n_el; e++) {
        if (eroded[e])
            continue;
        wff_element_material scratch;
        const wff_element_material *em = wff_zones_element_material(m, e, &scratch);
        const double *s = state + (size_t)m->n_state * wff_element_first_point(m->el.n_tris, e);
        if (!ruptured(m, em->mat, s, e < nt ? WFF_TRI_POINTS : WFF_QUAD_POINTS,
                      m->el.erosion))
            continue;
        double stored = wff_element_stored_energy(&m->el, em, m->mesh.xy, u, state, m->n_state, e);
        removed += stored;
        wff_pack_eroded(m, e, stored); /* the ply's share (pack.h) */
        eroded[e] = 1;
        m->n_eroded++;
        any = 1;
    }
    if (any)
        m->eroded_energy += removed;
    return removed;
}

double wff_element_damage(const wff_model *m, int e, int k)
{
    wff_element_material scratch;
    const wff_material *mat = wff_zones_element_material(m, e, &scratch)->mat;
    int i = damage_index(mat, k);
    if (i < 0)
        return 0;
    const int n = e < m->el.n_tris ? WFF_TRI_POINTS : WFF_QUAD_POINTS;
    const double *s = m->state + (size_t)m->n_state * wff_element_first_point(m->el.n_tris, e);
    double mean = 0;
    for (int q = 0; q < n; q++)
        mean += s[m->n_state * q + i] / n;
    return mean;
}

int wff_model_damaged(const wff_model *m)
{
    if (m->n_eroded > 0)
        return 1;
    const int n_el = m->el.n_tris + m->el.n_quads;
    for (int e = 0; e < n_el; e++)
        for (int k = 0; k < 2; k++)
            if (wff_element_damage(m, e, k) > 0)
                return 1;
    return 0;
}

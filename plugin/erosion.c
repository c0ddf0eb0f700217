/* erosion.c: element erosion (plugin/erosion.h), a part of the step
 * (part.h): the setting, the scan after a force pass that marks elements
 * whose yarns have ruptured and moves their stored energy (the element
 * layer's wff_element_stored_energy) to the eroded energy, the mesh-transfer
 * refusal and carry, and the damage the output and the mesh transfer read.
 * The element kernels (membrane_tri.c, membrane_quad.c, membrane_centre.c)
 * only skip what el->eroded marks. Knows the model's arrays and the cells
 * through their wrappers (cell_ops.h: damage_state); nothing of the
 * integrator's step, contact, output files or FreeFEM. */
#include "erosion.h"
#include "zones.h"
#include "distribute.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
        carry |= wff_material_damage_state(mat, 0) >= 0 && wff_material_damage_state(mat, 1) >= 0;
    }
    return carry;
}

/* The part's allocations: the list of a pass's eroded elements. */
static void erosion_free(wff_model *m)
{
    free(m->eroded_now);
    free(m->eroded_now_energy);
    m->eroded_now = NULL;
    m->eroded_now_energy = NULL;
    m->n_eroded_now = 0;
}

int wff_erosion_on(wff_model *m, int rule, wff_error *err)
{
    int n_el = m->el.n_tris + m->el.n_quads;
    if (!m->el.eroded) {
        m->el.eroded = calloc((size_t)(n_el ? n_el : 1), 1);
        if (!m->el.eroded)
            return wff_fail(err, "erosion: out of memory for %d elements' flags", n_el);
    }
    if (!m->eroded_now) { /* the list of a pass's eroded elements (at most all of them) */
        m->eroded_now = malloc(sizeof(int) * (size_t)(n_el ? n_el : 1));
        m->eroded_now_energy = malloc(sizeof(double) * (size_t)(n_el ? n_el : 1));
        if (!m->eroded_now || !m->eroded_now_energy)
            return wff_fail(err, "erosion: out of memory for %d elements' list", n_el);
    }
    m->n_eroded_now = 0;
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
        erosion_free(m);
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
    return wff_erosion_on(m, rule, err);
}

int wff_erosion_default(wff_model *m, wff_error *err)
{
    if (wff_material_damage_state(&m->mat, 0) < 0 || wff_material_damage_state(&m->mat, 1) < 0)
        return 0;
    return wff_erosion_on(m, WFF_EROSION_BOTH, err);
}

/* Whether element e's points have ruptured as the rule asks. */
static int ruptured(const wff_model *m, const wff_material *mat, const double *s, int n_points,
                    int rule)
{
    const int ns = m->n_state;
    int k0 = wff_material_damage_state(mat, 0), k1 = wff_material_damage_state(mat, 1);
    int all[2] = {k0 >= 0, k1 >= 0};
    for (int q = 0; q < n_points && (all[0] || all[1]); q++) {
        if (all[0] && !(s[ns * q + k0] >= 1))
            all[0] = 0;
        if (all[1] && !(s[ns * q + k1] >= 1))
            all[1] = 0;
    }
    return rule == WFF_EROSION_BOTH ? all[0] && all[1] : all[0] || all[1];
}

/* After an accumulating force pass that advanced the states (dt_flow > 0):
 * the elements whose yarns have ruptured go (the part's after_forces). */
static double erosion_after_forces(wff_model *m, const double *u, const double *state,
                                   double dt_flow)
{
    unsigned char *eroded = m->el.eroded;
    if (!eroded)
        return 0;
    m->n_eroded_now = 0;
    if (!(dt_flow > 0) || m->el.erosion == WFF_EROSION_OFF)
        return 0;
    const int nt = m->el.n_tris, n_el = nt + m->el.n_quads;
    /* the elements whose yarns have ruptured, in element order (over ranks:
     * each rank's own, plugin/distribute.c) ... */
    for (int e = 0; e < n_el; e++) {
        if (eroded[e] || !wff_dist_owns_element(m, e))
            continue;
        wff_element_material scratch;
        const wff_element_material *em = wff_zones_element_material(m, e, &scratch);
        const double *s = state + (size_t)m->n_state * wff_element_first_point(m->el.n_tris, e);
        if (!ruptured(m, em->mat, s, e < nt ? WFF_TRI_POINTS : WFF_QUAD_POINTS,
                      m->el.erosion))
            continue;
        double stored = wff_element_stored_energy(&m->el, em, m->mesh.xy, u, state, m->n_state, e);
        m->eroded_now[m->n_eroded_now] = e; /* (a pack's ply accounts read them) */
        m->eroded_now_energy[m->n_eroded_now++] = stored;
    }
    /* ... (over ranks: every rank's, in element order) taken out */
    m->n_eroded_now = wff_dist_eroded_gather(m, m->n_eroded_now);
    double removed = 0;
    for (int i = 0; i < m->n_eroded_now; i++) {
        removed += m->eroded_now_energy[i];
        eroded[m->eroded_now[i]] = 1;
        m->n_eroded++;
    }
    if (m->n_eroded_now > 0)
        m->eroded_energy += removed;
    return removed;
}

double wff_element_damage(const wff_model *m, int e, int k)
{
    wff_element_material scratch;
    const wff_material *mat = wff_zones_element_material(m, e, &scratch)->mat;
    int i = wff_material_damage_state(mat, k);
    if (i < 0)
        return 0;
    const int n = e < m->el.n_tris ? WFF_TRI_POINTS : WFF_QUAD_POINTS;
    const double *s = m->state + (size_t)m->n_state * wff_element_first_point(m->el.n_tris, e);
    double mean = 0;
    for (int q = 0; q < n; q++)
        mean += s[m->n_state * q + i] / n;
    return mean;
}

int wff_element_torn(const wff_model *m, int e)
{
    if (wff_element_eroded(&m->el, e))
        return 1;
    wff_element_material scratch;
    const wff_material *mat = wff_zones_element_material(m, e, &scratch)->mat;
    const int n = e < m->el.n_tris ? WFF_TRI_POINTS : WFF_QUAD_POINTS;
    const double *s = m->state + (size_t)m->n_state * wff_element_first_point(m->el.n_tris, e);
    for (int k = 0; k < 2; k++) {
        int i = wff_material_damage_state(mat, k);
        for (int q = 0; i >= 0 && q < n; q++)
            if (s[m->n_state * q + i] >= 1)
                return 1;
    }
    return 0;
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

/* The setting erosion (wff_erosion_set checks it). */
static int erosion_apply(wff_model *m, double value, wff_error *err)
{
    return wff_erosion_set(m, value, err);
}

static const wff_setting erosion_settings[] = {
    {"erosion", NULL, erosion_apply},
    {NULL, NULL, NULL},
};

/* A mesh transfer carries neither erosion nor yarn damage: refused once
 * elements have eroded, or with erosion on and damage anywhere (erosion off,
 * the damage states transfer as any state). */
static int erosion_refuses_remesh(const wff_model *m, char *why, size_t size)
{
    if (!(m->n_eroded > 0 || (m->el.eroded && wff_model_damaged(m))))
        return 0;
    snprintf(why, size, "the model has %s (%d elements eroded): a mesh transfer does not "
             "carry yarn damage or erosion: run without -adapt or without failure",
             m->n_eroded ? "eroded elements" : "yarn damage", m->n_eroded);
    return 1;
}

/* Onto a new mesh (nothing eroded, no damage: refused otherwise): erosion
 * stays on with its rule. */
static int erosion_carry(const wff_model *from, wff_model *to, wff_error *err)
{
    return from->el.eroded ? wff_erosion_on(to, from->el.erosion, err) : 0;
}

const wff_part_ops wff_erosion_part = {
    .name = "erosion",
    .after_forces = erosion_after_forces,
    .settings = erosion_settings,
    .refuses_remesh = erosion_refuses_remesh,
    .carry = erosion_carry,
    .free = erosion_free,
};

/* zones.c: per-region materials. A model may give sets of its elements
 * materials of their own (zones); zone 0 is the model's material. The zones
 * are kept as one wff_elements set per zone (the zone's elements copied out of
 * the mesh at assignment, node numbers the model's), so the element kernels
 * run unchanged on each; the model's own m->el stays the whole mesh (geometry
 * and output). The force pass, masses, stable step and energy split loop over
 * the zones; the points' internal state is gathered from the model's array
 * (m->n_state per point) into a zone's (its material's n_state per point: a
 * prefix of the model's, the same names) and scattered back around each pass. A zone's cell may see its own diagonal preload,
 * matched to the model cell's membrane forces at the model's preload
 * (docs/model.md "Zonal materials"); every zone takes the model's orientation
 * (its preload, a material-frame state, turned the same way). Knows the model, elements and cells
 * through their tables; nothing of the integrator's step, contact, output
 * files or FreeFEM. Without zones (m->zones NULL) every function is the plain
 * call the model made before zones existed. */
#include "zones.h"
#include "distribute.h"
#include "wovenff/cell_ops.h"
#include "plies.h"
#include "wovenff/balance.h"
#include "wovenff/kernel.h"
#include "wovenff/material.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct wff_zone {
    wff_material mat;         /* zone 0: unused (the model's m->mat) */
    int preload;              /* WFF_ZONE_PRELOAD_* */
    double F_pre[4];          /* matched: the zone cell's own preload */
    int n_elements, n_tris;   /* built: elements (model numbering, ascending: tris first) */
    int *element;
    int *tri, *quad;          /* connectivity copies the zone's wff_elements points into */
    wff_elements el;
    double *state;            /* the zone's points' states (3 points per tri, then 4 per
                                 quad; the zone material's n_state each) */
    int consecutive;          /* built: its elements consecutive in the model's numbering
                                 (a pack's ply): its points' states a run of the model's */
    int ply;                  /* the ply of a pack its elements are all in (pack.h: a
                                 pack's zones are split by ply), 0 outside a pack */
    wff_force_totals pass;    /* the zone's totals at the last force pass (per-ply sums) */
} wff_zone;

struct wff_zones {
    int n;                    /* zones, zone 0 included */
    int n_el;                 /* elements of the model */
    int *element_zone;        /* per element: its zone */
    double *mass;             /* one zone's masses (5 per node) */
    int cap;                  /* zones allocated */
    wff_zone *zone;
};

static void zone_unbuild(wff_zone *z)
{
    free(z->element);
    free(z->tri);
    free(z->quad);
    free(z->state);
    wff_elements_free(&z->el);
    z->element = z->tri = z->quad = NULL;
    z->state = NULL;
    z->n_elements = z->n_tris = z->consecutive = 0;
}

void wff_zones_free(wff_model *m)
{
    struct wff_zones *Z = m->zones;
    if (!Z)
        return;
    for (int k = 0; k < Z->n; k++)
        zone_unbuild(&Z->zone[k]);
    free(Z->element_zone);
    free(Z->mass);
    free(Z->zone);
    free(Z);
    m->zones = NULL;
}

/* What zone k's elements see: the model's settings, the zone's material and,
 * when matched, its preload. */
static void zone_material(const wff_model *m, int k, wff_element_material *em)
{
    const wff_zone *z = &m->zones->zone[k];
    *em = m->em;
    if (m->pack && wff_pack_plies(m) > 1) { /* a pack's ply has its own warp direction */
        em->orientation = wff_pack_orientation(m, z->ply);
        wff_orientation_map(em->orientation, m->preload, em->F_pre);
    }
    if (k == 0)
        return;
    em->mat = &z->mat;
    if (z->preload == WFF_ZONE_PRELOAD_MATCHED) { /* (material frame, turned as the ply's) */
        wff_orientation_map(em->orientation, z->F_pre, em->F_pre);
        em->J_pre = z->F_pre[0] * z->F_pre[3] - z->F_pre[1] * z->F_pre[2];
    }
}

/* The material of zone k (zone 0: the model's). */
static const wff_material *zone_mat(const wff_model *m, int k)
{
    return k == 0 ? &m->mat : &m->zones->zone[k].mat;
}

int wff_zones_in_place(const wff_model *m, int k)
{
    const wff_zone *z = m->zones && k >= 0 && k < m->zones->n ? &m->zones->zone[k] : NULL;
    return z && z->n_elements > 0 && z->consecutive && zone_mat(m, k)->n_state == m->n_state;
}

/* The states of zone k's points from (to_model 0) or into (1) the model's
 * array state (m->n_state per point): the zone's n_state first of each. */
static void zone_state(const wff_model *m, int k, double *state, int to_model)
{
    wff_zone *z = &m->zones->zone[k];
    const int nt = m->el.n_tris, ns = m->n_state, nz = zone_mat(m, k)->n_state;
    if (nz == 0 || wff_zones_in_place(m, k))
        return; /* nothing to copy: the pass works on the model's (zone_points) */
    for (int i = 0; i < z->n_elements; i++) {
        int e = z->element[i];
        int np = e < nt ? WFF_TRI_POINTS : WFF_QUAD_POINTS;
        double *global = state + (size_t)ns * wff_element_first_point(nt, e);
        double *local = z->state + (size_t)nz * wff_element_first_point(z->n_tris, i);
        for (int q = 0; q < np; q++)
            for (int j = 0; j < nz; j++) {
                if (to_model)
                    global[ns * q + j] = local[nz * q + j];
                else
                    local[nz * q + j] = global[ns * q + j];
            }
    }
}

/* The states zone k's element pass works on: the model's array itself where
 * the zone's points are a run of it in its layout (wff_zones_in_place), else
 * z->state (zone_state copies it in and out; the same numbers either way). */
static double *zone_points(const wff_model *m, int k, double *state)
{
    const wff_zone *z = &m->zones->zone[k];
    return wff_zones_in_place(m, k) ? state + (size_t)m->n_state * wff_element_first_point(
                                                  m->el.n_tris, z->element[0])
                                    : z->state;
}

/* The material whose state_names name the model's states: the one with the
 * most states (the model's own without zones or on a tie). */
static const wff_material *state_material(const wff_model *m)
{
    const wff_material *best = &m->mat;
    for (int k = 1; m->zones && k < m->zones->n; k++)
        if (zone_mat(m, k)->n_state > best->n_state)
            best = zone_mat(m, k);
    return best;
}

const char *wff_model_state_name(const wff_model *m, int i)
{
    const wff_material *mat = state_material(m);
    return i >= 0 && i < mat->n_state ? wff_cell_state_name(mat->cell, i) : "";
}

/* A zone of material mat: its states must be a prefix of the model's (the
 * same names) or the model's a prefix of its; in the second case the model's
 * points take its layout (m->state re-laid with the larger stride, each
 * point's values kept, the new states 0). -1 (err set) otherwise. */
static int zone_states_fit(wff_model *m, const wff_material *mat, const char *path,
                           wff_error *err)
{
    const wff_material *have = state_material(m);
    int common = mat->n_state < have->n_state ? mat->n_state : have->n_state;
    for (int i = 0; i < common; i++)
        if (strcmp(wff_cell_state_name(mat->cell, i), wff_cell_state_name(have->cell, i)) != 0)
            return wff_fail(err, "zone material '%s': cell '%s' carries state %d '%s' where "
                            "the model's points carry '%s' (cell '%s'): a zone's states must "
                            "be a prefix of the model's or extend them", path,
                            wff_cell_name(mat->cell), i + 1, wff_cell_state_name(mat->cell, i),
                            wff_cell_state_name(have->cell, i), wff_cell_name(have->cell));
    if (mat->n_state <= m->n_state)
        return 0;
    size_t np = wff_elements_point_count(&m->el);
    size_t ns = (size_t)mat->n_state;
    double *wide = calloc(np * ns > 0 ? np * ns : 1, sizeof(double));
    if (!wide)
        return wff_fail(err, "zone material '%s': out of memory for %zu points' states", path,
                        np);
    for (size_t p = 0; p < np; p++)
        for (int j = 0; j < m->n_state; j++)
            wide[ns * p + (size_t)j] = m->state[(size_t)m->n_state * p + (size_t)j];
    free(m->state);
    m->state = wide;
    m->n_state = mat->n_state;
    free(m->operator_scratch); /* sized for the old layout: operators.c allocates anew */
    m->operator_scratch = NULL;
    return 0;
}

/* The zones' element sets from element_zone. */
static int build(wff_model *m, wff_error *err)
{
    struct wff_zones *Z = m->zones;
    int nt = m->el.n_tris;
    for (int k = 0; k < Z->n; k++) {
        wff_zone *z = &Z->zone[k];
        zone_unbuild(z);
        int count = 0, tris = 0;
        for (int e = 0; e < Z->n_el; e++)
            if (Z->element_zone[e] == k) {
                count++;
                tris += e < nt;
            }
        if (count == 0)
            continue;
        int quads = count - tris;
        z->element = malloc(sizeof(int) * (size_t)count);
        z->tri = malloc(sizeof(int) * 3 * (size_t)(tris ? tris : 1));
        z->quad = malloc(sizeof(int) * 4 * (size_t)(quads ? quads : 1));
        z->state = malloc(sizeof(double) *
                          ((size_t)zone_mat(m, k)->n_state * wff_element_first_point(tris, count) + 1));
        if (!z->element || !z->tri || !z->quad || !z->state) {
            zone_unbuild(z);
            return wff_fail(err, "zones: out of memory for zone %d (%d elements)", k, count);
        }
        int i = 0;
        for (int e = 0; e < Z->n_el; e++) {
            if (Z->element_zone[e] != k)
                continue;
            if (e < nt)
                memcpy(z->tri + 3 * i, m->mesh.tri + 3 * e, 3 * sizeof(int));
            else
                memcpy(z->quad + 4 * (i - tris), m->mesh.quad + 4 * (e - nt), 4 * sizeof(int));
            z->element[i++] = e;
        }
        z->n_elements = count;
        z->n_tris = tris;
        z->consecutive = z->element[count - 1] - z->element[0] == count - 1; /* (ascending) */
        if (wff_elements_init(&z->el, m->mesh.xy, tris, z->tri, quads, z->quad, err)) {
            zone_unbuild(z);
            return -1;
        }
    }
    return wff_zones_erosion_changed(m, err);
}

int wff_zones_erosion_changed(wff_model *m, wff_error *err)
{
    struct wff_zones *Z = m->zones;
    for (int k = 0; Z && k < Z->n; k++) {
        wff_zone *z = &Z->zone[k];
        z->el.erosion = m->el.erosion;
        if (!m->el.eroded) {
            free(z->el.eroded);
            z->el.eroded = NULL;
        } else if (z->n_elements > 0 && !z->el.eroded) {
            z->el.eroded = calloc((size_t)z->n_elements, 1);
            if (!z->el.eroded)
                return wff_fail(err, "zones: out of memory for zone %d's erosion flags", k);
        }
    }
    return 0;
}

/* The model's erosion flags into the zones' (element by element: a byte each). */
static void zones_eroded_copy(const wff_model *m)
{
    const struct wff_zones *Z = m->zones;
    if (!Z || !m->el.eroded)
        return;
    for (int k = 0; k < Z->n; k++) {
        wff_zone *z = (wff_zone *)&Z->zone[k]; /* its flags only */
        if (z->el.eroded)
            for (int i = 0; i < z->n_elements; i++)
                z->el.eroded[i] = m->el.eroded[z->element[i]];
    }
}

/* Zone k's diagonal preload whose membrane forces are the model cell's at the
 * model's preload (balance.c's wff_preload_matched). */
static int match_preload(wff_model *m, int k, wff_error *err)
{
    wff_zone *z = &m->zones->zone[k];
    const double *Fp = m->preload; /* (material frame: the orientation does not enter) */
    if (Fp[1] != 0 || Fp[2] != 0)
        return wff_fail(err, "zone %d (%s): a matched preload needs a diagonal model preload "
                        "(F_pre = [%g %g; %g %g])", k, z->mat.source, Fp[0], Fp[1], Fp[2], Fp[3]);
    const double a_model[2] = {Fp[0], Fp[3]};
    const double dA0[2] = {m->n_nodes ? m->u[3] : 0, m->n_nodes ? m->u[4] : 0};
    double target[2], a[2];
    if (wff_preload_forces(&m->mat, a_model, dA0, target))
        return wff_fail(err, "zone %d: the model's cell fails at its preload", k);
    if (wff_preload_matched(&z->mat, target, a_model, a) == 0) {
        z->F_pre[0] = a[0], z->F_pre[1] = z->F_pre[2] = 0, z->F_pre[3] = a[1];
        return 0;
    }
    return wff_fail(err, "zone %d (%s): no diagonal preload of cell '%s' gives the model's "
                    "preload membrane forces %g, %g N/m (cell '%s' at stretch %g, %g)", k,
                    z->mat.source, wff_cell_name(z->mat.cell), target[0], target[1], wff_cell_name(m->mat.cell),
                    a_model[0], a_model[1]);
}

int wff_zones_preload_changed(wff_model *m, wff_error *err)
{
    struct wff_zones *Z = m->zones;
    if (!Z)
        return 0;
    for (int k = 1; k < Z->n; k++)
        if (Z->zone[k].preload == WFF_ZONE_PRELOAD_MATCHED && match_preload(m, k, err))
            return -1;
    return 0;
}

/* The zone table of a model without one: zone 0 (the model's material) holding
 * every element; -1 (err set) if out of memory. */
static int zones_create(wff_model *m, const char *what, wff_error *err)
{
    int n_el = m->el.n_tris + m->el.n_quads;
    struct wff_zones *Z = calloc(1, sizeof *Z);
    if (Z) {
        Z->element_zone = calloc((size_t)(n_el ? n_el : 1), sizeof(int));
        Z->mass = malloc(sizeof(double) * (size_t)m->n_dofs);
        Z->cap = 1 + (m->pack ? wff_pack_plies(m) : 0) + 8;
        Z->zone = calloc((size_t)Z->cap, sizeof *Z->zone);
    }
    if (!Z || !Z->element_zone || !Z->mass || !Z->zone) {
        if (Z)
            free(Z->element_zone), free(Z->mass), free(Z->zone);
        free(Z);
        return wff_fail(err, "%s: out of memory", what);
    }
    Z->n = 1;
    Z->n_el = n_el;
    m->zones = Z;
    return 0;
}

/* A new zone of material mat for ply `ply` (its elements given later); its index, or -1
 * (err set) if the table is full or out of memory. */
static int zone_add(wff_model *m, const wff_material *mat, int preload, int ply,
                    const char *what, wff_error *err)
{
    struct wff_zones *Z = m->zones;
    if (Z->n >= WFF_ZONES_MAX)
        return wff_fail(err, "zone material '%s': %d zones already, the most a model has (a "
                        "pack's zone is split into one per ply)", what, WFF_ZONES_MAX);
    if (Z->n >= Z->cap) {
        int cap = 2 * Z->cap < WFF_ZONES_MAX ? 2 * Z->cap : WFF_ZONES_MAX;
        wff_zone *grown = realloc(Z->zone, sizeof *grown * (size_t)cap);
        if (!grown)
            return wff_fail(err, "zone material '%s': out of memory", what);
        memset(grown + Z->cap, 0, sizeof *grown * (size_t)(cap - Z->cap));
        Z->zone = grown;
        Z->cap = cap;
    }
    int k = Z->n++;
    wff_zone *z = &Z->zone[k];
    memset(z, 0, sizeof *z);
    z->mat = *mat;
    z->preload = preload;
    z->ply = ply;
    return k;
}

/* wff_model_zone_elements' zones with the selection in the model's own element
 * order (zones.h): in a pack of several plies one zone per ply it touches. */
int wff_zones_select(wff_model *m, const unsigned char *selected,
                               const char *material_path, int preload, wff_error *err)
{
    if (m->step > 0 || m->v_half_valid)
        return wff_fail(err, "zone material '%s': the run has started (step %ld); give the "
                        "zones their materials before the first step", material_path, m->step);
    if (m->em.static_amplitudes)
        return wff_fail(err, "zone material '%s': static amplitudes are on; zones keep the "
                        "amplitudes dynamic (set static_amplitudes 0)", material_path);
    if (preload != WFF_ZONE_PRELOAD_SHARED && preload != WFF_ZONE_PRELOAD_MATCHED)
        return wff_fail(err, "zone material '%s': preload mode %d: must be 0 (shared) or 1 "
                        "(matched)", material_path, preload);
    int n_el = m->el.n_tris + m->el.n_quads;
    wff_material mat;
    /* on the model's kernel variant (kernel.h), like the model's own material */
    if (wff_material_load(material_path, &mat, err) ||
        wff_kernel_apply(&mat, wff_material_kernel(&m->mat), err))
        return -1;
    if (wff_cell_amplitudes(mat.cell) > 0 && wff_cell_amplitudes(m->mat.cell) == 0)
        return wff_fail(err, "zone material '%s': cell '%s' has crimp amplitudes and the "
                        "model's cell '%s' has none (its amplitude DOFs are fixed): give "
                        "the model the cell with amplitudes and the zones the others",
                        material_path, wff_cell_name(mat.cell), wff_cell_name(m->mat.cell));
    if (preload == WFF_ZONE_PRELOAD_MATCHED && wff_cell_amplitudes(mat.cell) > 0)
        return wff_fail(err, "zone material '%s': a matched preload is for a cell without "
                        "amplitudes (cell '%s' has them: use the shared preload)",
                        material_path, wff_cell_name(mat.cell));
    int plies = m->pack ? wff_pack_plies(m) : 1;
    int used[WFF_PLIES_MAX] = {0}, needed = 0;
    for (int e = 0; e < n_el; e++)
        if (selected[e])
            used[plies > 1 ? wff_pack_element_ply(m, e) : 0] = 1;
    for (int p = 0; p < plies; p++)
        needed += used[p];
    if (needed == 0) { /* an empty zone is allowed: one zone (of ply 0) */
        used[0] = 1;
        needed = 1;
    }
    if (m->zones && m->zones->n + needed > WFF_ZONES_MAX)
        return wff_fail(err, "zone material '%s': %d zones already, the most a model has is "
                        "%d (a pack's zone is split into one per ply: this one needs %d)",
                        material_path, m->zones->n, WFF_ZONES_MAX, needed);
    if (zone_states_fit(m, &mat, material_path, err))
        return -1;
    int fresh = m->zones == NULL;
    if (fresh && zones_create(m, material_path, err))
        return -1;
    struct wff_zones *Z = m->zones;
    int first = Z->n, count = 0;
    for (int p = 0; p < plies; p++) {
        if (!used[p])
            continue;
        int k = zone_add(m, &mat, preload, p, material_path, err);
        if (k < 0 || (preload == WFF_ZONE_PRELOAD_MATCHED && match_preload(m, k, err))) {
            Z->n = first;
            if (fresh)
                wff_zones_free(m);
            return -1;
        }
    }
    for (int e = 0; e < n_el; e++)
        if (selected[e]) {
            int p = plies > 1 ? wff_pack_element_ply(m, e) : 0, k = first;
            while (k < Z->n - 1 && Z->zone[k].ply != p)
                k++;
            Z->element_zone[e] = k;
            count++;
        }
    if (build(m, err))
        return -1;
    return count;
}

int wff_zones_pack(wff_model *m, wff_error *err)
{
    if (m->zones)
        return wff_fail(err, "plies: the model has zonal materials already; give the plies "
                        "first, then the zones");
    if (zones_create(m, "plies", err))
        return -1;
    struct wff_zones *Z = m->zones;
    for (int p = 0; p < wff_pack_plies(m); p++)
        if (zone_add(m, &m->mat, WFF_ZONE_PRELOAD_SHARED, p, m->mat.source, err) < 0) {
            wff_zones_free(m);
            return -1;
        }
    for (int e = 0; e < Z->n_el; e++)
        Z->element_zone[e] = 1 + wff_pack_element_ply(m, e);
    if (build(m, err)) {
        wff_zones_free(m);
        return -1;
    }
    return 0;
}

void wff_zones_ply_totals(const wff_model *m, double *stored, double *shear, double *failure,
                          double *slip)
{
    const struct wff_zones *Z = m->zones;
    int plies = m->pack ? wff_pack_plies(m) : 1;
    for (int p = 0; p < plies; p++)
        stored[p] = shear[p] = failure[p] = slip[p] = 0;
    if (!Z)
        return;
    for (int k = 0; k < Z->n; k++) {
        const wff_zone *z = &Z->zone[k];
        if (z->n_elements == 0)
            continue;
        int p = z->ply >= 0 && z->ply < plies ? z->ply : 0;
        stored[p] += z->pass.internal_energy;
        shear[p] += z->pass.dissipated;
        failure[p] += z->pass.failure_dissipated;
        slip[p] += z->pass.slip_dissipated;
    }
}

int wff_model_zone_count(const wff_model *m)
{
    return m->zones ? m->zones->n : 1;
}

int wff_model_zone_size(const wff_model *m, int zone)
{
    if (!m->zones)
        return zone == 0 ? m->el.n_tris + m->el.n_quads : 0;
    return zone >= 0 && zone < m->zones->n ? m->zones->zone[zone].n_elements : 0;
}

const wff_material *wff_model_zone_material(const wff_model *m, int zone)
{
    if (zone == 0)
        return &m->mat;
    return m->zones && zone > 0 && zone < m->zones->n ? &m->zones->zone[zone].mat : NULL;
}

void wff_zones_forces(wff_model *m, const double *u, double *state, double dt, double *f,
                      wff_force_totals *totals)
{
    struct wff_zones *Z = m->zones;
    if (!Z) {
        wff_dist_prepare(m, &m->el, NULL);
        wff_elements_forces(&m->el, &m->em, m->mesh.xy, u, state, dt, f, totals);
        wff_dist_forces(m, f, totals, NULL, 0); /* (over ranks: plugin/distribute.c) */
        return;
    }
    zones_eroded_copy(m);
    totals->internal_energy = totals->dissipated = totals->failure_dissipated = 0;
    totals->slip_dissipated = 0;
    for (int s = 0; s < WFF_BLOCK_SUMS; s++)
        totals->sums[s] = wff_fixed_zero();
    totals->bad_element = -1;
    totals->bad_point = 0;
    totals->bad_status = WFF_POINT_OK;
    totals->bad_residual = 0;
    totals->bad_iterations = 0;
    totals->amplitude_iterations = 0;
    /* a pack's plies share no node: with threads, plies at once (each ply's zones in
     * order, one thread each), the totals summed in zone order below: the same bits */
    const int plies = m->pack ? wff_pack_plies(m) : 1;
    const int by_ply = plies > 1 && m->el.n_threads > 1;
    for (int k = 0; k < Z->n; k++) /* (over ranks: each zone's masks, before the threads) */
        if (Z->zone[k].n_elements > 0)
            wff_dist_prepare(m, &Z->zone[k].el, Z->zone[k].element);
#pragma omp parallel for schedule(dynamic, 1) num_threads(m->el.n_threads) if (by_ply)
    for (int p = 0; p < (by_ply ? plies : 1); p++)
        for (int k = 0; k < Z->n; k++) {
            wff_zone *z = &Z->zone[k];
            if (z->n_elements == 0 || (by_ply && z->ply != p))
                continue;
            wff_element_material em;
            zone_material(m, k, &em);
            z->el.n_threads = by_ply ? 1
                              : m->el.n_threads <= z->el.max_threads ? m->el.n_threads : 1;
            zone_state(m, k, state, 0);
            wff_elements_forces(&z->el, &em, m->mesh.xy, u, zone_points(m, k, state), dt, f,
                                &z->pass);
            zone_state(m, k, state, 1);
        }
    for (int k = 0; k < Z->n; k++) {
        const wff_zone *z = &Z->zone[k];
        if (z->n_elements == 0)
            continue;
        const wff_force_totals t = z->pass;
        for (int s = 0; s < WFF_BLOCK_SUMS; s++) /* (order-free: the zones' sums are one sum) */
            wff_fixed_merge(&totals->sums[s], &t.sums[s]);
        totals->amplitude_iterations += t.amplitude_iterations;
        if (t.bad_element >= 0 && totals->bad_element < 0) {
            totals->bad_element = z->element[t.bad_element];
            totals->bad_point = t.bad_point;
            totals->bad_status = t.bad_status;
            totals->bad_residual = t.bad_residual;
            totals->bad_iterations = t.bad_iterations;
        }
    }
    totals->internal_energy = wff_fixed_value(&totals->sums[0]);
    totals->dissipated = wff_fixed_value(&totals->sums[1]);
    totals->failure_dissipated = wff_fixed_value(&totals->sums[2]);
    totals->slip_dissipated = wff_fixed_value(&totals->sums[3]);
    const int ns = WFF_BLOCK_SUMS;
    wff_fixed *zone_sums = wff_dist_fixed_scratch(m, ns * Z->n); /* (NULL on one rank) */
    if (!zone_sums)
        return;
    /* over ranks: the forces, the pass's sums and each zone's (a pack's per-ply
     * accounts) in one exchange (plugin/distribute.c) */
    for (int k = 0; k < Z->n; k++)
        for (int s = 0; s < ns; s++)
            zone_sums[ns * k + s] = Z->zone[k].n_elements ? Z->zone[k].pass.sums[s] : wff_fixed_zero();
    wff_dist_forces(m, f, totals, zone_sums, ns * Z->n);
    for (int k = 0; k < Z->n; k++) {
        wff_zone *z = &Z->zone[k];
        if (z->n_elements == 0)
            continue;
        for (int s = 0; s < ns; s++)
            z->pass.sums[s] = zone_sums[ns * k + s];
        z->pass.internal_energy = wff_fixed_value(&z->pass.sums[0]);
        z->pass.dissipated = wff_fixed_value(&z->pass.sums[1]);
        z->pass.failure_dissipated = wff_fixed_value(&z->pass.sums[2]);
        z->pass.slip_dissipated = wff_fixed_value(&z->pass.sums[3]);
    }
}

void wff_zones_masses(wff_model *m)
{
    struct wff_zones *Z = m->zones;
    if (!Z) {
        wff_elements_masses(&m->el, &m->em, m->n_nodes, m->mass);
        return;
    }
    memset(m->mass, 0, sizeof(double) * (size_t)m->n_dofs);
    for (int k = 0; k < Z->n; k++) {
        wff_zone *z = &Z->zone[k];
        if (z->n_elements == 0)
            continue;
        wff_element_material em = m->em; /* ρ_A of the zone over J_pre of the model */
        em.mat = k == 0 ? &m->mat : &z->mat;
        wff_elements_masses(&z->el, &em, m->n_nodes, Z->mass);
        for (int i = 0; i < m->n_dofs; i++)
            m->mass[i] += Z->mass[i];
    }
}

double wff_zones_stable_step(const wff_model *m, const double *u, int *worst)
{
    const struct wff_zones *Z = m->zones;
    if (!Z)
        return wff_elements_stable_step(&m->el, &m->em, m->mesh.xy, u, worst);
    zones_eroded_copy(m);
    double dt = INFINITY;
    *worst = -1;
    for (int k = 0; k < Z->n; k++) {
        const wff_zone *z = &Z->zone[k];
        if (z->n_elements == 0)
            continue;
        wff_element_material em;
        zone_material(m, k, &em);
        int w = -1;
        double dz = wff_elements_stable_step(&z->el, &em, m->mesh.xy, u, &w);
        if (!(dz >= dt) || *worst < 0) { /* a NaN wins: it is reported */
            dt = dz;
            *worst = w >= 0 && w < z->n_elements ? z->element[w] : -1;
        }
    }
    return dt;
}

double wff_zones_amplitude_length(const wff_model *m)
{
    const struct wff_zones *Z = m->zones;
    double length = wff_cell_amplitude_length(&m->mat);
    for (int k = 1; Z && k < Z->n; k++)
        if (Z->zone[k].n_elements > 0)
            length = fmin(length, wff_cell_amplitude_length(&Z->zone[k].mat));
    return length;
}

void wff_zones_energy_split(const wff_model *m, const double *u, const double *state,
                            double *mech)
{
    const struct wff_zones *Z = m->zones;
    if (!Z) {
        wff_elements_energy_split(&m->el, &m->em, m->mesh.xy, u, state, mech);
        return;
    }
    zones_eroded_copy(m);
    const wff_cell_type *base = m->mat.cell;
    for (int j = 0; j < wff_cell_n_mech(base) && j < WFF_MECH_MAX; j++)
        mech[j] = 0;
    for (int k = 0; k < Z->n; k++) {
        wff_zone *z = (wff_zone *)&Z->zone[k]; /* its state scratch only */
        if (z->n_elements == 0)
            continue;
        wff_element_material em;
        zone_material(m, k, &em);
        zone_state(m, k, (double *)state, 0);
        double part[WFF_MECH_MAX] = {0};
        wff_elements_energy_split(&z->el, &em, m->mesh.xy, u, zone_points(m, k, (double *)state),
                                  part);
        const wff_cell_type *cell = em.mat->cell;
        for (int i = 0; i < wff_cell_n_mech(cell) && i < WFF_MECH_MAX; i++)
            for (int j = 0; j < wff_cell_n_mech(base) && j < WFF_MECH_MAX; j++)
                if (strcmp(wff_cell_mech_name(cell, i), wff_cell_mech_name(base, j)) == 0)
                    mech[j] += part[i];
    }
}

const wff_element_material *wff_zones_element_material(const wff_model *m, int e,
                                                       wff_element_material *scratch)
{
    if (!m->zones || e < 0 || e >= m->zones->n_el || m->zones->element_zone[e] == 0)
        return &m->em;
    zone_material(m, m->zones->element_zone[e], scratch);
    return scratch;
}

uint64_t wff_zones_fingerprint(const wff_model *m, uint64_t g)
{
    const struct wff_zones *Z = m->zones;
    if (!Z)
        return g;
    g = wff_fnv1a(g, &Z->n, sizeof Z->n);
    g = wff_fnv1a(g, Z->element_zone, sizeof(int) * (size_t)Z->n_el);
    for (int k = 1; k < Z->n; k++) {
        const wff_zone *z = &Z->zone[k];
        g = wff_fnv1a(g, wff_cell_name(z->mat.cell), strlen(wff_cell_name(z->mat.cell)));
        g = wff_fnv1a(g, &z->mat.areal_density, sizeof(double));
        g = wff_fnv1a(g, z->mat.params, sizeof z->mat.params);
        g = wff_fnv1a(g, &z->preload, sizeof(int));
        if (z->preload == WFF_ZONE_PRELOAD_MATCHED)
            g = wff_fnv1a(g, z->F_pre, sizeof z->F_pre);
    }
    return g;
}

/* pack_build.c: a model made a multi-ply pack (include/wovenff/pack.h:
 * wff_model_set_plies, a ply's material and orientation). A pack of N plies
 * is the model's specimen mesh copied N times, in the model's order ply by
 * ply (the specimen's renumbering kept within each ply), ply p's mid-plane at
 * u_z = p·gap; the model is rebuilt from that mesh with its material and
 * settings, and each ply gets a zone (zones.c) with its own material and
 * orientation. The pack's per-step part is pack.c's. One ply: the model as
 * it was (no mesh, zone or step change). */
#include "pack.h"
#include "erosion.h"
#include "zones.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Why the model can no longer become a pack ("" if it can). */
static const char *too_late(const wff_model *m)
{
    if (m->pack)
        return "the plies are set already (once per model)";
    if (m->step > 0 || m->v_half_valid || m->time != 0)
        return "the run has started (or a checkpoint was loaded)";
    if (m->n_bc > 0 || m->clamp.n > 0)
        return "boundary conditions are set";
    if (m->projectile.active)
        return "the projectile is set";
    if (m->zones)
        return "zonal materials are set";
    if (m->em.static_amplitudes)
        return "static amplitudes are on";
    if (m->preload[0] != 1 || m->preload[1] != 0 || m->preload[2] != 0 || m->preload[3] != 1)
        return "a preload is set";
    for (int i = 0; i < m->n_dofs; i++)
        if (m->u[i] != 0 || m->v[i] != 0)
            return "a preload or initial state is set";
    return "";
}

/* The N-copy mesh of m's mesh (model order, ply by ply) into *out. */
static int stack_mesh(const wff_model *m, int N, wff_mesh *out, wff_error *err)
{
    const wff_mesh *s = &m->mesh;
    const size_t nn = (size_t)s->n_nodes, nt = (size_t)s->n_tris, nq = (size_t)s->n_quads,
                 ne = (size_t)s->n_edges, n = (size_t)N;
    memset(out, 0, sizeof *out);
    out->n_nodes = (int)(n * nn);
    out->n_tris = (int)(n * nt);
    out->n_quads = (int)(n * nq);
    out->n_edges = (int)(n * ne);
    out->n_groups = s->n_groups;
    out->xy = malloc(sizeof(double) * 2 * (n * nn + 1));
    out->tri = malloc(sizeof(int) * 3 * (n * nt + 1));
    out->tri_region = malloc(sizeof(int) * (n * nt + 1));
    out->quad = malloc(sizeof(int) * 4 * (n * nq + 1));
    out->quad_region = malloc(sizeof(int) * (n * nq + 1));
    out->edge = malloc(sizeof(int) * 2 * (n * ne + 1));
    out->edge_label = malloc(sizeof(int) * (n * ne + 1));
    out->groups = malloc(sizeof(wff_mesh_group) * ((size_t)s->n_groups + 1));
    if (!out->xy || !out->tri || !out->tri_region || !out->quad || !out->quad_region ||
        !out->edge || !out->edge_label || !out->groups) {
        wff_mesh_free(out);
        return wff_fail(err, "plies: out of memory for %d plies of %zu nodes", N, nn);
    }
    if (s->n_groups)
        memcpy(out->groups, s->groups, sizeof(wff_mesh_group) * (size_t)s->n_groups);
    for (size_t p = 0; p < n; p++) {
        const int shift = (int)(p * nn);
        memcpy(out->xy + 2 * p * nn, s->xy, sizeof(double) * 2 * nn);
        for (size_t i = 0; i < 3 * nt; i++)
            out->tri[3 * p * nt + i] = s->tri[i] + shift;
        for (size_t i = 0; i < 4 * nq; i++)
            out->quad[4 * p * nq + i] = s->quad[i] + shift;
        for (size_t i = 0; i < 2 * ne; i++)
            out->edge[2 * p * ne + i] = s->edge[i] + shift;
        if (nt)
            memcpy(out->tri_region + p * nt, s->tri_region, sizeof(int) * nt);
        if (nq)
            memcpy(out->quad_region + p * nq, s->quad_region, sizeof(int) * nq);
        if (ne)
            memcpy(out->edge_label + p * ne, s->edge_label, sizeof(int) * ne);
    }
    return 0;
}

/* The pack's user numbering from the specimen's (m's order arrays; none: none). */
static int stack_order(const wff_model *m, int N, wff_model *pk, wff_error *err)
{
    if (!m->node_user)
        return 0;
    const int nn = m->mesh.n_nodes, nt = m->mesh.n_tris, nq = m->mesh.n_quads;
    const size_t tn = (size_t)N * (size_t)nn, te = (size_t)N * (size_t)(nt + nq);
    pk->node_user = malloc(sizeof(int) * (tn + 1));
    pk->node_model = malloc(sizeof(int) * (tn + 1));
    pk->element_user = malloc(sizeof(int) * (te + 1));
    pk->element_model = malloc(sizeof(int) * (te + 1));
    if (!pk->node_user || !pk->node_model || !pk->element_user || !pk->element_model)
        return wff_fail(err, "plies: out of memory for the node order");
    for (int p = 0; p < N; p++) {
        for (int i = 0; i < nn; i++)
            pk->node_user[p * nn + i] = p * nn + m->node_user[i];
        for (int t = 0; t < nt; t++)
            pk->element_user[p * nt + t] = p * nt + m->element_user[t];
        for (int q = 0; q < nq; q++)
            pk->element_user[N * nt + p * nq + q] = N * nt + p * nq + (m->element_user[nt + q] - nt);
    }
    for (size_t i = 0; i < tn; i++)
        pk->node_model[pk->node_user[i]] = (int)i;
    for (size_t e = 0; e < te; e++)
        pk->element_model[pk->element_user[e]] = (int)e;
    return 0;
}

/* The settings made on m before the plies, onto the pack's model. */
static int copy_settings(const wff_model *m, wff_model *pk, wff_error *err)
{
    pk->dt_factor = m->dt_factor;
    pk->dt_interval = m->dt_interval;
    pk->t_stop = m->t_stop;
    pk->symmetry_factor = m->symmetry_factor;
    pk->em.reference_path = m->em.reference_path;
    pk->em.amplitude_mass_factor = m->em.amplitude_mass_factor;
    pk->projectile.search_all = m->projectile.search_all;
    pk->el.team_min_tris = m->el.team_min_tris;
    if (m->el.n_threads != pk->el.n_threads &&
        wff_elements_set_threads(&pk->el, m->el.n_threads, err))
        return -1;
    if (m->el.erosion != pk->el.erosion && wff_erosion_set(pk, m->el.erosion, err))
        return -1;
    return wff_model_set_orientation(pk, m->em.orientation, err);
}

int wff_model_set_plies(wff_model *m, int n_plies, double gap, wff_error *err)
{
    if (n_plies < 1 || n_plies > WFF_PLIES_MAX)
        return wff_fail(err, "plies = %d: must be 1 to %d", n_plies, WFF_PLIES_MAX);
    if (!(gap >= 0) || !isfinite(gap))
        return wff_fail(err, "ply gap = %g m: must be a finite spacing >= 0 (0: plies touching)",
                        gap);
    const char *late = too_late(m);
    if (late[0])
        return wff_fail(err, "plies: %s; give the plies right after the model is created "
                        "(before the preload, boundary conditions, projectile, zones and "
                        "checkpoint loads)", late);
    struct wff_pack *P = calloc(1, sizeof *P);
    if (!P)
        return wff_fail(err, "plies: out of memory");
    P->n = n_plies;
    P->gap = gap;
    P->nodes = m->mesh.n_nodes;
    P->tris = m->mesh.n_tris;
    P->quads = m->mesh.n_quads;
    P->mu = WFF_PLY_MU_DEFAULT;
    for (int p = 0; p < n_plies; p++) {
        P->orientation[p] = m->em.orientation;
        P->first_damage_time[p] = -1; /* intact */
    }
    if (n_plies == 1) { /* the model as it is */
        m->pack = P;
        return 0;
    }
    wff_model pk;
    memset(&pk, 0, sizeof pk);
    if (stack_mesh(m, n_plies, &pk.mesh, err)) {
        free(P);
        return -1;
    }
    pk.mat = m->mat;
    if (stack_order(m, n_plies, &pk, err) ||
        wff_elements_init(&pk.el, pk.mesh.xy, pk.mesh.n_tris, pk.mesh.tri, pk.mesh.n_quads,
                          pk.mesh.quad, err)) {
        wff_model_order_free(&pk);
        wff_mesh_free(&pk.mesh);
        free(P);
        return -1;
    }
    if (wff_model_setup(&pk, err)) { /* (pk freed) */
        free(P);
        return -1;
    }
    pk.pack = P;
    if (copy_settings(m, &pk, err) || wff_zones_pack(&pk, err)) {
        wff_model_free(&pk);
        return -1;
    }
    for (int n = 0; n < pk.n_nodes; n++) /* ply p's mid-plane at z = p gap */
        pk.u[D * n + WFF_UZ] = wff_pack_node_ply(&pk, n) * gap;
    if (wff_model_masses_changed(&pk, err)) {
        wff_model_free(&pk);
        return -1;
    }
    wff_model_set_element_lengths(&pk); /* (each ply's zone: the model's material) */
    wff_model_free(m); /* (the pack has its own communicator over the same ranks) */
    *m = pk;
    return 0;
}

int wff_model_ply_material(wff_model *m, int ply, const char *material_path, wff_error *err)
{
    if (wff_pack_check_ply(m, ply, "ply material", err))
        return -1;
    int n_el = m->el.n_tris + m->el.n_quads;
    unsigned char *sel = malloc((size_t)(n_el ? n_el : 1));
    if (!sel)
        return wff_fail(err, "out of memory");
    for (int e = 0; e < n_el; e++) /* (in the user's order, as wff_model_zone_elements takes) */
        sel[e] = wff_pack_element_ply(m, wff_model_element_of_user(m, e)) == ply;
    int n = wff_model_zone_elements(m, sel, material_path, WFF_ZONE_PRELOAD_SHARED, err);
    free(sel);
    if (n < 0) {
        char why[WFF_ERROR_MAX];
        snprintf(why, sizeof why, "%s", err->message);
        return wff_fail(err, "ply %d material: %s", ply, why);
    }
    return n;
}

int wff_model_ply_orientation(wff_model *m, int ply, double theta, wff_error *err)
{
    if (wff_pack_check_ply(m, ply, "ply orientation", err))
        return -1;
    if (!isfinite(theta))
        return wff_fail(err, "ply %d orientation = %g rad: must be a finite angle", ply, theta);
    if (fabs(theta) > WFF_ANGLE_MAX_DEG * (M_PI / 180))
        return wff_fail(err, "ply %d orientation = %g rad (%g deg): an angle beyond +-1e6 "
                        "degrees is refused (give it modulo 360)", ply, theta,
                        theta * 180 / M_PI);
    if (wff_pack_plies(m) == 1)
        return wff_model_set_orientation(m, theta, err);
    struct wff_pack *P = m->pack;
    if ((m->step > 0 || m->v_half_valid) && theta != P->orientation[ply])
        return wff_fail(err, "ply %d orientation = %g deg: the run has started (t = %g s, "
                        "step %ld); set it before the first step", ply, theta * 180 / M_PI,
                        m->time, m->step);
    P->orientation[ply] = theta;
    return wff_model_masses_changed(m, err); /* (masses unchanged: the stored energy) */
}


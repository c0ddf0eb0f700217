/* pack.c: multi-ply packs (include/wovenff/pack.h). A pack of N plies is the
 * model's specimen mesh copied N times, in the model's order ply by ply (the
 * specimen's renumbering kept within each ply), ply p's mid-plane at u_z =
 * p·gap; the model is rebuilt from that mesh with its material and settings,
 * and each ply gets a zone (zones.c) with its own material and orientation.
 * Per-ply values come from the zones' per-pass totals. The ply-to-ply contact
 * is ply_contact.c's. Knows the model, zones and mesh arrays; nothing of
 * FreeFEM. One ply: the model as it was (no mesh, zone or step change). */
#include "pack.h"
#include "erosion.h"
#include "zones.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void wff_pack_free(wff_model *m)
{
    if (!m->pack)
        return;
    wff_ply_contact_free(m->pack);
    free(m->pack);
    m->pack = NULL;
}

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
    for (int p = 0; p < n_plies; p++)
        P->orientation[p] = m->em.orientation;
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
    wff_model_free(m);
    *m = pk;
    return 0;
}

int wff_model_ply_count(const wff_model *m)
{
    return wff_pack_plies(m);
}

static int check_ply(const wff_model *m, int ply, const char *what, wff_error *err)
{
    if (ply < 0 || ply >= wff_pack_plies(m))
        return wff_fail(err, "%s: ply %d: the pack has plies 0 to %d", what, ply,
                        wff_pack_plies(m) - 1);
    return 0;
}

int wff_model_ply_material(wff_model *m, int ply, const char *material_path, wff_error *err)
{
    if (check_ply(m, ply, "ply material", err))
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
    if (check_ply(m, ply, "ply orientation", err))
        return -1;
    if (!isfinite(theta))
        return wff_fail(err, "ply %d orientation = %g rad: must be a finite angle", ply, theta);
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

void wff_pack_orientation_all(wff_model *m, double theta)
{
    if (m->pack)
        for (int p = 0; p < m->pack->n; p++)
            m->pack->orientation[p] = theta;
}

int wff_model_node_ply(const wff_model *m, int user_node)
{
    if (user_node < 0 || user_node >= m->n_nodes)
        return -1;
    return wff_pack_node_ply(m, wff_model_node_of_user(m, user_node));
}

int wff_model_element_ply(const wff_model *m, int user_element)
{
    if (user_element < 0 || user_element >= m->el.n_tris + m->el.n_quads)
        return -1;
    return wff_pack_element_ply(m, wff_model_element_of_user(m, user_element));
}

void wff_pack_accumulate(wff_model *m)
{
    struct wff_pack *P = m->pack;
    if (!P || P->n == 1)
        return;
    double stored[WFF_PLIES_MAX], shear[WFF_PLIES_MAX], failure[WFF_PLIES_MAX];
    wff_zones_ply_totals(m, stored, shear, failure);
    for (int p = 0; p < P->n; p++) {
        P->stored[p] = stored[p] - P->removed[p];
        P->shear[p] += shear[p];
        P->failure[p] += failure[p];
        P->eroded[p] += P->removed[p];
        P->removed[p] = 0;
    }
}

void wff_pack_eroded(wff_model *m, int e, double energy)
{
    if (m->pack && m->pack->n > 1)
        m->pack->removed[wff_pack_element_ply(m, e)] += energy;
}

static double effective_thickness(const wff_model *m)
{
    if (m->pack && m->pack->thickness > 0)
        return m->pack->thickness;
    return m->mat.areal_density / (WFF_PLY_FIBRE_DENSITY * WFF_PLY_FIBRE_FRACTION);
}

double wff_pack_contact_distance(const wff_model *m)
{
    double t = effective_thickness(m), gap = m->pack ? m->pack->gap : t;
    return t < gap ? t : gap;
}

int wff_pack_set_option(wff_model *m, const char *key, double value, int *rc, wff_error *err)
{
    int mu = strcmp(key, "ply_mu") == 0, th = strcmp(key, "ply_thickness") == 0;
    if (!mu && !th)
        return 0;
    *rc = 0;
    if (!m->pack) {
        *rc = wff_fail(err, "%s: the model is not a pack (give the plies first)", key);
    } else if (mu) {
        if (!(value >= 0) || !isfinite(value))
            *rc = wff_fail(err, "ply_mu = %g: must be a friction coefficient >= 0", value);
        else
            m->pack->mu = value;
    } else {
        if (!(value > 0) || !isfinite(value))
            *rc = wff_fail(err, "ply_thickness = %g m: must be > 0", value);
        else if (m->step > 0 || m->v_half_valid)
            *rc = wff_fail(err, "ply_thickness: the run has started (step %ld); set it before "
                           "the first step", m->step);
        else
            m->pack->thickness = value;
    }
    return 1;
}

/* Ply p's node range in the model's order. */
static void ply_nodes(const wff_model *m, int p, int *first, int *end)
{
    int per = wff_pack_plies(m) > 1 ? m->pack->nodes : m->n_nodes;
    *first = wff_pack_plies(m) > 1 ? p * per : 0;
    *end = *first + per;
}

/* Ply p's element e's nodes (k of them) into c. */
static int element_nodes(const wff_model *m, int e, const int **c)
{
    const int nt = m->el.n_tris;
    *c = e < nt ? m->el.tri + 3 * e : m->el.quad + 4 * (e - nt);
    return e < nt ? 3 : 4;
}

/* The largest u_z − base over the nodes reached from a node whose u_z is held
 * (an edge, the clamp) through ply p's elements not eroded; -1 if it cannot
 * tell (no such node, out of memory). */
static int attached_apex(const wff_model *m, int p, int first, int end, double base, double *apex)
{
    const int nt = m->el.n_tris, n_el = nt + m->el.n_quads, nn = end - first;
    const unsigned char *eroded = m->el.eroded;
    int *offset = calloc((size_t)nn + 1, sizeof(int)), *queue = malloc(sizeof(int) * (size_t)nn);
    unsigned char *seen = calloc((size_t)nn, 1);
    int *incident = NULL, rc = -1;
    if (!offset || !queue || !seen)
        goto done;
    for (int e = 0; e < n_el; e++) { /* node -> live elements (CSR) */
        if (eroded[e] || wff_pack_element_ply(m, e) != p)
            continue;
        const int *c;
        for (int j = 0, k = element_nodes(m, e, &c); j < k; j++)
            offset[c[j] - first + 1]++;
    }
    for (int i = 0; i < nn; i++)
        offset[i + 1] += offset[i];
    incident = malloc(sizeof(int) * (size_t)(offset[nn] > 0 ? offset[nn] : 1));
    int *fill = queue; /* (the queue's room, as fill counters first) */
    if (!incident)
        goto done;
    memcpy(fill, offset, sizeof(int) * (size_t)nn);
    for (int e = 0; e < n_el; e++) {
        if (eroded[e] || wff_pack_element_ply(m, e) != p)
            continue;
        const int *c;
        for (int j = 0, k = element_nodes(m, e, &c); j < k; j++)
            incident[fill[c[j] - first]++] = e;
    }
    int head = 0, tail = 0;
    for (int i = 0; i < nn; i++)
        if (offset[i + 1] > offset[i] && m->dof_kind[D * (first + i) + WFF_UZ] != WFF_DOF_FREE)
            seen[i] = 1, queue[tail++] = i;
    if (tail == 0)
        goto done; /* nothing held: every element not eroded counts */
    double top = -INFINITY;
    while (head < tail) {
        const int i = queue[head++];
        top = fmax(top, m->u[D * (first + i) + WFF_UZ] - base);
        for (int k = offset[i]; k < offset[i + 1]; k++) {
            const int *c;
            for (int j = 0, kn = element_nodes(m, incident[k], &c); j < kn; j++)
                if (!seen[c[j] - first])
                    seen[c[j] - first] = 1, queue[tail++] = c[j] - first;
        }
    }
    *apex = top;
    rc = 0;
done:
    free(offset);
    free(queue);
    free(seen);
    free(incident);
    return rc;
}

/* Ply p's largest u_z (less its plane's p gap). Once elements have eroded,
 * over the part of the ply still attached: the nodes reached from the held
 * edge through elements not eroded (or, with no held node, of any element not
 * eroded). A fragment (a node whose elements have all eroded, or a piece torn
 * off whole) flies on with the projectile or away from it and is not the ply's
 * deflection. */
static double ply_apex(const wff_model *m, int p)
{
    int first, end;
    ply_nodes(m, p, &first, &end);
    double base = m->pack && m->pack->n > 1 ? p * m->pack->gap : 0, apex = -INFINITY;
    const unsigned char *eroded = m->el.eroded;
    if (!eroded || m->n_eroded == 0) {
        for (int n = first; n < end; n++)
            apex = fmax(apex, m->u[D * n + WFF_UZ] - base);
        return apex;
    }
    if (attached_apex(m, p, first, end, base, &apex) == 0)
        return apex;
    apex = 0; /* (every element eroded: 0) */
    const int n_el = m->el.n_tris + m->el.n_quads;
    int any = 0;
    for (int e = 0; e < n_el; e++) {
        if (eroded[e] || wff_pack_element_ply(m, e) != p)
            continue;
        const int *c;
        for (int j = 0, k = element_nodes(m, e, &c); j < k; j++)
            apex = any++ ? fmax(apex, m->u[D * c[j] + WFF_UZ] - base) : m->u[D * c[j] + WFF_UZ] - base;
    }
    return apex;
}

int wff_model_ply_value(const wff_model *m, int ply, const char *key, double *value,
                        wff_error *err)
{
    if (check_ply(m, ply, "ply value", err))
        return -1;
    const double s = m->symmetry_factor;
    const int single = wff_pack_plies(m) == 1;
    const struct wff_pack *P = m->pack;
    int stored_k = strcmp(key, "stored") == 0, kin_k = strcmp(key, "kinetic") == 0;
    int diss_k = strcmp(key, "dissipated") == 0, abs_k = strcmp(key, "absorbed") == 0;
    double stored = 0, kinetic = 0, dissipated = 0;
    if (stored_k || abs_k) {
        if (single) {
            stored = m->internal_energy;
        } else if (m->step == 0 && !m->v_half_valid) { /* before the run: the set-up's pass */
            double st[WFF_PLIES_MAX], sh[WFF_PLIES_MAX], fa[WFF_PLIES_MAX];
            wff_zones_ply_totals(m, st, sh, fa);
            stored = st[ply];
        } else {
            stored = P->stored[ply];
        }
    }
    if (diss_k || abs_k)
        dissipated = single ? m->dissipated_shear + m->dissipated_failure + m->eroded_energy
                            : P->shear[ply] + P->failure[ply] + P->eroded[ply];
    if (kin_k || abs_k) {
        int first, end;
        ply_nodes(m, ply, &first, &end);
        const double half = m->v_half_valid ? 0.5 * m->dt : 0;
        for (int i = D * first; i < D * end; i++)
            if (m->dof_kind[i] == WFF_DOF_FREE) {
                double vn = m->v[i] - half * m->f[i] / m->mass[i];
                kinetic += 0.5 * m->mass[i] * vn * vn;
            }
    }
    if (strcmp(key, "apex") == 0) {
        *value = ply_apex(m, ply);
    } else if (stored_k) {
        *value = s * stored;
    } else if (kin_k) {
        *value = s * kinetic;
    } else if (diss_k) {
        *value = s * dissipated;
    } else if (abs_k) {
        *value = s * (kinetic + stored + dissipated);
    } else if (strcmp(key, "failed") == 0 || strcmp(key, "eroded") == 0) {
        int failed = key[0] == 'f', count = 0, n_el = m->el.n_tris + m->el.n_quads;
        for (int e = 0; e < n_el; e++) {
            if (wff_pack_element_ply(m, e) != ply)
                continue;
            if (failed)
                count += wff_element_damage(m, e, 0) > 0 || wff_element_damage(m, e, 1) > 0;
            else
                count += wff_element_eroded(&m->el, e);
        }
        *value = count;
    } else {
        return wff_fail(err, "ply %d: unknown key '%s' (known: apex, kinetic, stored, "
                        "dissipated, absorbed, failed, eroded)", ply, key);
    }
    return 0;
}

/* The largest in-plane displacement of a node relative to its partner in the next
 * ply (the ply contact pairs node i with node i: this must stay small against the
 * element size), m. */
static double ply_slip(const wff_model *m)
{
    const struct wff_pack *P = m->pack;
    double slip = 0;
    for (int p = 0; P && p + 1 < P->n; p++)
        for (int i = 0; i < P->nodes; i++) {
            const double *a = m->u + D * (p * P->nodes + i), *b = a + D * P->nodes;
            slip = fmax(slip, hypot(b[0] - a[0], b[1] - a[1]));
        }
    return slip;
}

int wff_model_pack_value(const wff_model *m, const char *key, double *value, wff_error *err)
{
    const struct wff_pack *P = m->pack;
    if (strcmp(key, "plies") == 0)
        *value = wff_pack_plies(m);
    else if (strcmp(key, "back_face") == 0)
        *value = ply_apex(m, wff_pack_plies(m) - 1);
    else if (strcmp(key, "ply_contact_dissipated") == 0)
        *value = P ? m->symmetry_factor * P->dissipated : 0;
    else if (strcmp(key, "ply_penetration") == 0)
        *value = P ? P->penetration : 0;
    else if (strcmp(key, "ply_contacts") == 0)
        *value = P ? P->contacts : 0;
    else if (strcmp(key, "ply_mu") == 0)
        *value = P ? P->mu : WFF_PLY_MU_DEFAULT;
    else if (strcmp(key, "ply_thickness") == 0)
        *value = effective_thickness(m);
    else if (strcmp(key, "ply_gap") == 0)
        *value = P ? P->gap : 0;
    else if (strcmp(key, "ply_slip") == 0)
        *value = ply_slip(m);
    else if (strcmp(key, "ply_contact_seconds") == 0)
        *value = P ? P->seconds : 0;
    else if (strcmp(key, "ply_left_out") == 0)
        *value = P ? P->left_out : 0;
    else if (strcmp(key, "ply_penetration_bound") == 0)
        *value = wff_ply_penetration_bound(m);
    else
        return wff_fail(err, "unknown pack value '%s' (known: plies, back_face, "
                        "ply_contact_dissipated, ply_penetration, ply_contacts, ply_mu, "
                        "ply_thickness, ply_gap, ply_slip, ply_contact_seconds, ply_left_out, "
                        "ply_penetration_bound)",
                        key);
    return 0;
}

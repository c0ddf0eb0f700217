/* pack.c: a multi-ply pack's part of the step (part.h, pack.h): the per-ply
 * energies after each force pass (from the zones' per-pass totals and the
 * elements erosion took), the settings ply_mu and ply_thickness, every ply
 * following the model-wide orientation, its state and settings for checkpoints,
 * and the per-ply and pack values (include/wovenff/pack.h). The stacked model is built by
 * pack_build.c, the ply-to-ply contact is ply_contact.c's. Knows the model's
 * arrays, zones and erosion; nothing of FreeFEM. */
#include "pack.h"
#include "erosion.h"
#include "perforation.h"
#include "ply_contact.h"
#include "zones.h"
#include "wovenff/renumber.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int wff_model_ply_count(const wff_model *m)
{
    return wff_pack_plies(m);
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

int wff_pack_check_ply(const wff_model *m, int ply, const char *what, wff_error *err)
{
    if (ply < 0 || ply >= wff_pack_plies(m))
        return wff_fail(err, "%s: ply %d: the pack has plies 0 to %d", what, ply,
                        wff_pack_plies(m) - 1);
    return 0;
}

static void pack_free(wff_model *m)
{
    if (!m->pack)
        return;
    wff_ply_contact_free(m->pack);
    free(m->pack);
    m->pack = NULL;
}

/* The model-wide orientation set (wff_model_set_orientation): every ply's. */
static void pack_follow(wff_model *m, const char *what, double theta)
{
    if (m->pack && strcmp(what, "orientation") == 0)
        for (int p = 0; p < m->pack->n; p++)
            m->pack->orientation[p] = theta;
}

/* A pack of one ply (no zones' per-ply totals): its first damaged point after
 * each advancing pass (wff_model_damaged, erosion.c), until one is found; no
 * scan where its one material's yarns cannot fail (with a ply material, a zone,
 * the scan reads each element's). */
static void first_damage_scan(wff_model *m)
{
    struct wff_pack *P = m->pack;
    if (P->first_damage_time[0] >= 0 || (!m->zones && wff_material_damage_state(&m->mat, 0) < 0))
        return;
    if (wff_model_damaged(m))
        P->first_damage_time[0] = m->time;
}

/* After an accumulating force pass: the pass's per-ply energies; the elements
 * erosion took in it (erosion.h, before this part in the list) go from their
 * ply's stored energy to its eroded energy. */
static double pack_after_forces(wff_model *m, const double *u, const double *state,
                                double dt_flow)
{
    (void)u, (void)state;
    struct wff_pack *P = m->pack;
    if (!P)
        return 0;
    if (P->n == 1) {
        if (dt_flow > 0)
            first_damage_scan(m);
        return 0;
    }
    for (int i = 0; i < m->n_eroded_now; i++) /* (in element order, as erosion took them) */
        P->removed[wff_pack_element_ply(m, m->eroded_now[i])] += m->eroded_now_energy[i];
    double stored[WFF_PLIES_MAX], shear[WFF_PLIES_MAX], failure[WFF_PLIES_MAX];
    double slip[WFF_PLIES_MAX];
    wff_zones_ply_totals(m, stored, shear, failure, slip);
    for (int p = 0; p < P->n; p++) {
        P->stored[p] = stored[p] - P->removed[p];
        P->shear[p] += shear[p];
        P->failure[p] += failure[p];
        P->slip[p] += slip[p];
        P->eroded[p] += P->removed[p];
        P->removed[p] = 0;
        /* a damage grows only where its yarn is stretched (yarn_failure.h), releasing
         * Δd W⁺ > 0: the pass's failure energy is positive exactly when a point of
         * the ply was damaged in it */
        if (P->first_damage_time[p] < 0 && dt_flow > 0 && failure[p] > 0)
            P->first_damage_time[p] = m->time;
    }
    return 0;
}


/* The settings ply_mu and ply_thickness. */
static int check_pack(const char *name, const wff_model *m, wff_error *err)
{
    if (!m->pack)
        return wff_fail(err, "%s: the model is not a pack (give the plies first)", name);
    return 0;
}

static int check_ply_mu(const wff_model *m, double value, wff_error *err)
{
    if (check_pack("ply_mu", m, err))
        return -1;
    if (!(value >= 0) || !isfinite(value))
        return wff_fail(err, "ply_mu = %g: must be a friction coefficient >= 0", value);
    return 0;
}

static int apply_ply_mu(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->pack->mu = value;
    return 0;
}

static int check_ply_thickness(const wff_model *m, double value, wff_error *err)
{
    if (check_pack("ply_thickness", m, err))
        return -1;
    if (!(value > 0) || !isfinite(value))
        return wff_fail(err, "ply_thickness = %g m: must be > 0", value);
    if (m->step > 0 || m->v_half_valid)
        return wff_fail(err, "ply_thickness: the run has started (step %ld); set it before "
                        "the first step", m->step);
    return 0;
}

static int apply_ply_thickness(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->pack->thickness = value;
    return 0;
}

static const wff_setting pack_settings[] = {
    {"ply_mu", check_ply_mu, apply_ply_mu},
    {"ply_thickness", check_ply_thickness, apply_ply_thickness},
    {NULL, NULL, NULL},
};

/* Ply p's largest u_z (less its plane's p gap). Once a yarn has ruptured in
 * the ply (an element eroded, or a family at damage 1 at a point), over the
 * part of the ply still held by intact yarns: the nodes reached from the held
 * edge (the clamp) through elements not eroded with no yarn ruptured
 * (perforation.h, WFF_HELD_INTACT; with no held node, every node of such an
 * element). A node held so is joined to the clamp by yarns strained at most
 * to their rupture strain, so the apex cannot exceed what the clamp allows;
 * a flap of torn fabric (however it hangs on), a fragment and a node left
 * with no element are not the ply's deflection. 0 when no intact element is
 * left (or out of memory). */
static double ply_apex(const wff_model *m, int p)
{
    int first, end;
    wff_ply_node_range(m, p, &first, &end);
    double base = m->pack && m->pack->n > 1 ? p * m->pack->gap : 0, apex = -INFINITY;
    const int n_el = m->el.n_tris + m->el.n_quads;
    int torn = 0;
    for (int e = 0; e < n_el && !torn; e++)
        torn = wff_pack_element_ply(m, e) == p && wff_element_torn(m, e);
    if (!torn) {
        for (int n = first; n < end; n++)
            apex = fmax(apex, m->u[D * n + WFF_UZ] - base);
        return apex;
    }
    unsigned char *held = malloc((size_t)(end - first));
    int count = held ? wff_ply_held_nodes(m, p, WFF_HELD_INTACT, held) : -1;
    for (int n = first; count > 0 && n < end; n++)
        if (held[n - first])
            apex = fmax(apex, m->u[D * n + WFF_UZ] - base);
    free(held);
    return count > 0 ? apex : 0;
}

int wff_model_ply_value(const wff_model *m, int ply, const char *key, double *value,
                        wff_error *err)
{
    if (wff_pack_check_ply(m, ply, "ply value", err))
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
            double st[WFF_PLIES_MAX], sh[WFF_PLIES_MAX], fa[WFF_PLIES_MAX], sl[WFF_PLIES_MAX];
            wff_zones_ply_totals(m, st, sh, fa, sl);
            stored = st[ply];
        } else {
            stored = P->stored[ply];
        }
    }
    if (diss_k || abs_k)
        dissipated = single ? m->dissipated_shear + m->dissipated_failure + m->eroded_energy +
                                  m->dissipated_slip
                            : P->shear[ply] + P->failure[ply] + P->eroded[ply] + P->slip[ply];
    if (kin_k || abs_k) {
        int first, end;
        wff_ply_node_range(m, ply, &first, &end);
        const double half = m->v_half_valid ? 0.5 * m->dt : 0;
        for (int i = D * first; i < D * end; i++)
            if (m->dof_kind[i] == WFF_DOF_FREE) {
                double vn = m->v[i] - half * m->f[i] / m->mass[i];
                kinetic += 0.5 * m->mass[i] * vn * vn;
            }
    }
    if (strcmp(key, "apex") == 0) {
        *value = ply_apex(m, ply);
    } else if (strcmp(key, "holed") == 0 || strcmp(key, "through") == 0) {
        wff_perforation verdict;
        if (wff_model_perforation(m, &verdict, err))
            return -1;
        *value = key[0] == 'h' ? verdict.holed[ply] : verdict.through[ply];
    } else if (stored_k) {
        *value = s * stored;
    } else if (kin_k) {
        *value = s * kinetic;
    } else if (diss_k) {
        *value = s * dissipated;
    } else if (abs_k) {
        *value = s * (kinetic + stored + dissipated);
    } else if (strcmp(key, "first_damage_time") == 0) {
        *value = P ? P->first_damage_time[ply] : -1;
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
                        "dissipated, absorbed, failed, eroded, holed, through, first_damage_time)",
                        ply, key);
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
        *value = wff_ply_thickness(m);
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

/* Its state for checkpoints and the adaptive step: each ply's energy
 * accounts (the stored energy too: a value read before the first pass after a
 * load is the checkpointed one). The ply contact's are its own part's. */
static int pack_state_fields(wff_model *m, wff_state_field *f)
{
    struct wff_pack *P = m->pack;
    if (!P || P->n < 2)
        return 0;
    const size_t n = (size_t)P->n;
    f[0] = (wff_state_field){P->stored, sizeof(double), n};
    f[1] = (wff_state_field){P->shear, sizeof(double), n};
    f[2] = (wff_state_field){P->failure, sizeof(double), n};
    f[3] = (wff_state_field){P->slip, sizeof(double), n};
    f[4] = (wff_state_field){P->eroded, sizeof(double), n};
    f[5] = (wff_state_field){P->first_damage_time, sizeof(double), n};
    return 6;
}

/* What a checkpoint of a pack must match beyond the stacked mesh: the plies'
 * spacing, each ply's warp direction, the contact's friction and thickness. */
static uint64_t pack_fingerprint(const wff_model *m, uint64_t g)
{
    const struct wff_pack *P = m->pack;
    if (!P || P->n < 2)
        return g;
    g = wff_fnv1a(g, &P->n, sizeof P->n);
    g = wff_fnv1a(g, &P->gap, sizeof P->gap);
    g = wff_fnv1a(g, P->orientation, sizeof(double) * (size_t)P->n);
    g = wff_fnv1a(g, &P->mu, sizeof P->mu);
    return wff_fnv1a(g, &P->thickness, sizeof P->thickness);
}

/* The pack's values by name, in wovenffState's order (include/wovenff/pack.h). */
static const char *const pack_value_names[] = {
    "plies", "back_face", "ply_contact_dissipated", "ply_penetration", "ply_contacts",
    "ply_slip", "ply_mu", "ply_thickness", "ply_gap", "ply_contact_seconds", "ply_left_out",
    "ply_penetration_bound", NULL};

static void pack_value(const wff_model *m, const char *key, double *value)
{
    wff_error ignored; /* (every name above is known) */
    *value = 0;
    wff_model_pack_value(m, key, value, &ignored);
}

const wff_part_ops wff_pack_part = {
    .name = "pack",
    .after_forces = pack_after_forces,
    .follow = pack_follow,
    .settings = pack_settings,
    .value_names = pack_value_names,
    .value = pack_value,
    .state_fields = pack_state_fields,
    .fingerprint = pack_fingerprint,
    .free = pack_free,
};

/* Zonal materials (plugin/zones.c) through the C API:
 *   1. a model whose two zones have the same material (King inside a disc and
 *      outside it) runs as the one-material model to round-off (displacements,
 *      energies, masses, the stable step), triangles and quadrilaterals;
 *   2. a matched preload: the far zone's cell (linear yarns) carries the King
 *      cell's preload membrane forces, so a preloaded, clamped square stays at
 *      rest (the shared preload does not: its linear yarns pull much harder);
 *   3. King inside, linear yarns outside, struck by a projectile: the energy
 *      balance closes within 0.5 % of the reference at every block end;
 *   4. refusals that name what is wrong: zones after the first step, static
 *      amplitudes, an amplitude cell over a cell without amplitudes, a mesh
 *      transfer, a checkpoint loaded into a model without the zones. */
#include "check.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"
#include "wovenff/state.h"
#include "zones.h" /* wff_zones_in_place */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define LINEAR "freefem_scripts/materials/kevlar_linear.txt"
#define D WFF_DOFS_PER_NODE

/* The King cell's preload of 1 N per yarn (F_pre, dA⁰). */
static int king_preload(check_state *st, double F[4], double dA[2])
{
    wff_material mat;
    wff_error err;
    wff_biaxial_state s;
    memset(&s, 0, sizeof s);
    s.stretch[0] = s.stretch[1] = 1;
    if (wff_material_load(KEVLAR, &mat, &err) || wff_preload_equal_force(&mat, 1.0, &s, &err)) {
        CHECK(st, 0, "%s", err.message);
        return -1;
    }
    F[0] = s.stretch[0], F[1] = F[2] = 0, F[3] = s.stretch[1];
    dA[0] = s.dA[0], dA[1] = s.dA[1];
    return 0;
}

/* A clamped (edges fixed) preloaded square; zone_material NULL: no zones; else
 * the elements farther than 1 cm from the centre get it. */
static int make(check_state *st, wff_model *m, int type, const char *zone_material, int preload,
                int projectile)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, 16, 16, type, 1, 0.2, 5};
    wff_error err;
    double F[4], dA[2];
    if (king_preload(st, F, dA))
        return -1;
    if (test_model_rect(m, &r, KEVLAR, &err) || wff_model_set_preload(m, F, dA, &err)) {
        CHECK(st, 0, "%s", err.message);
        return -1;
    }
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int g = 0; g < 4; g++)
        for (int c = WFF_UX; c <= WFF_UZ; c++)
            if (wff_model_fix_group(m, edges[g], c, &err) < 0) {
                CHECK(st, 0, "%s", err.message);
                return -1;
            }
    if (zone_material) {
        int n = wff_model_zone_disc(m, 0, 0, 0.01, 1, zone_material, preload, &err);
        int n_el = m->el.n_tris + m->el.n_quads;
        CHECK(st, n > 0 && n < n_el, "zone disc: %d of %d elements (%s)", n,
              n_el, n < 0 ? err.message : "");
        if (n < 0)
            return -1;
        CHECK(st, wff_model_zone_count(m) == 2 &&
                  wff_model_zone_size(m, 0) + wff_model_zone_size(m, 1) == n_el &&
                  wff_model_zone_size(m, 1) == n,
              "zone sizes %d + %d of %d", wff_model_zone_size(m, 0), wff_model_zone_size(m, 1),
              n_el);
    }
    if (projectile && wff_model_set_projectile(m, 6.35e-3, 0.002, 20, 0.3, &err)) {
        CHECK(st, 0, "%s", err.message);
        return -1;
    }
    return 0;
}

static double max_abs(const double *a, int n)
{
    double x = 0;
    for (int i = 0; i < n; i++)
        x = fmax(x, fabs(a[i]));
    return x;
}

/* Model b's zone 1 of KEVLAR: the first half of its elements in the model's
 * numbering (both zones consecutive: their passes work on the model's states
 * in place, zones.c), checked to be so; -1 if it fails. */
static int zone_halves(check_state *st, wff_model *b, const char *what)
{
    wff_error err;
    const int n_el = b->el.n_tris + b->el.n_quads;
    unsigned char *sel = calloc((size_t)n_el, 1);
    if (!sel)
        return -1;
    for (int e = 0; e < n_el / 2; e++)
        sel[b->element_user ? b->element_user[e] : e] = 1; /* (NULL: the caller's order) */
    int n = wff_model_zone_elements(b, sel, KEVLAR, WFF_ZONE_PRELOAD_SHARED, &err);
    free(sel);
    CHECK(st, n == n_el / 2, "%s: zone of the first %d elements: %d (%s)", what, n_el / 2, n,
          n < 0 ? err.message : "");
    CHECK(st, wff_zones_in_place(b, 0) && wff_zones_in_place(b, 1),
          "%s: both halves work in place (%d, %d)", what, wff_zones_in_place(b, 0),
          wff_zones_in_place(b, 1));
    return n == n_el / 2 ? 0 : -1;
}

/* 1. The one-material model against the same material in two zones: a disc
 * (halves 0; its states copied in and out of the zone, zones.c's plain path)
 * or the two halves of the element numbering (halves 1: in place). */
static void same_material(check_state *st, int type, int halves, const char *what)
{
    wff_model a, b;
    if (make(st, &a, type, NULL, 0, 1))
        return;
    if (make(st, &b, type, halves ? NULL : KEVLAR, WFF_ZONE_PRELOAD_SHARED, 1) ||
        (halves && zone_halves(st, &b, what))) {
        wff_model_free(&a);
        return;
    }
    if (!halves)
        CHECK(st, !wff_zones_in_place(&b, 1), "%s: the disc zone works on a copy", what);
    wff_error err;
    int nd = a.n_dofs;
    double mass_diff = 0;
    for (int i = 0; i < nd; i++)
        mass_diff = fmax(mass_diff, fabs(a.mass[i] - b.mass[i]) / a.mass[i]);
    CHECK(st, mass_diff < 1e-14, "%s: masses agree (%.2g)", what, mass_diff);
    double dta, dtb;
    int wa, wb;
    CHECK(st, wff_model_stable_step(&a, NULL, &dta, &wa, &err) == 0 &&
                  wff_model_stable_step(&b, NULL, &dtb, &wb, &err) == 0 && dta == dtb && wa == wb,
          "%s: stable step %.17g (element %d) and %.17g (element %d)", what, dta, wa, dtb, wb);
    int rc = wff_model_advance(&a, 0.1e-3, 100000, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    rc = wff_model_advance(&b, 0.1e-3, 100000, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    double du = 0, scale = max_abs(a.u, nd), dg = 0;
    for (int i = 0; i < nd; i++)
        du = fmax(du, fabs(a.u[i] - b.u[i]));
    int nq = (3 * a.el.n_tris + 4 * a.el.n_quads) * a.n_state; /* every state of every point */
    CHECK(st, a.n_state == b.n_state, "%s: %d and %d states per point", what, a.n_state,
          b.n_state);
    for (int q = 0; q < nq; q++)
        dg = fmax(dg, fabs(a.state[q] - b.state[q]));
    wff_energies ea, eb;
    wff_model_energies(&a, &ea);
    wff_model_energies(&b, &eb);
    double split_a[WFF_MECH_MAX], split_b[WFF_MECH_MAX];
    int na = wff_model_energy_split(&a, split_a), nb = wff_model_energy_split(&b, split_b);
    double dsplit = 0;
    for (int k = 0; k < na && na == nb; k++)
        dsplit = fmax(dsplit, fabs(split_a[k] - split_b[k]) / fabs(ea.internal));
    printf("  same material, %s: %ld steps, max |u| %.3g m, |du| %.2g m, |dgamma_f| %.2g, "
           "internal %.10g / %.10g J\n", what, a.step, scale, du, dg, ea.internal, eb.internal);
    CHECK(st, a.step == b.step && a.step > 50, "%s: steps %ld and %ld", what, a.step, b.step);
    CHECK(st, scale > 1e-4 && du < 1e-10 * scale, "%s: displacements agree to round-off: "
          "%.3g of %.3g m", what, du, scale);
    CHECK(st, dg < 1e-10, "%s: γᶠ agrees: %.3g", what, dg);
    CHECK(st, fabs(ea.internal - eb.internal) < 1e-10 * fabs(ea.internal) &&
                  fabs(ea.kinetic_transverse - eb.kinetic_transverse) <
                      1e-10 * ea.kinetic_transverse &&
                  fabs(ea.dissipated_shear - eb.dissipated_shear) <=
                      1e-10 * fabs(ea.dissipated_shear) + 1e-20,
          "%s: energies agree (internal %.17g / %.17g J)", what, ea.internal, eb.internal);
    CHECK(st, na == nb && na > 0 && dsplit < 1e-10, "%s: energy split agrees (%d, %d; %.2g)",
          what, na, nb, dsplit);
    double *fa = malloc(sizeof(double) * (size_t)a.n_nodes),
           *fb = malloc(sizeof(double) * (size_t)a.n_nodes);
    if (fa && fb) {
        const char *fields[] = {"T1", "W", "F_I"};
        for (int k = 0; k < 3; k++) {
            CHECK(st, wff_model_nodal_field(&a, fields[k], fa, &err) == 0 &&
                          wff_model_nodal_field(&b, fields[k], fb, &err) == 0, "%s", err.message);
            double d = 0, s = max_abs(fa, a.n_nodes);
            for (int n = 0; n < a.n_nodes; n++)
                d = fmax(d, fabs(fa[n] - fb[n]));
            CHECK(st, d <= 1e-9 * s, "%s: field %s agrees (%.3g of %.3g)", what, fields[k], d, s);
        }
    }
    free(fa);
    free(fb);
    wff_model_free(&a);
    wff_model_free(&b);
}

/* 2. The fastest fabric speed after 0.05 ms of rest, m/s. */
static double speed_at_rest(check_state *st, int preload)
{
    wff_model m;
    if (make(st, &m, TEST_MESH_TRI, LINEAR, preload, 0))
        return NAN;
    wff_error err;
    if (wff_model_advance(&m, 0.05e-3, 100000, &err)) {
        CHECK(st, 0, "%s", err.message);
        wff_model_free(&m);
        return NAN;
    }
    double v = 0;
    for (int n = 0; n < m.n_nodes; n++)
        v = fmax(v, hypot(m.v[D * n], m.v[D * n + 1]));
    wff_model_free(&m);
    return v;
}

static void matched_preload(check_state *st)
{
    double matched = speed_at_rest(st, WFF_ZONE_PRELOAD_MATCHED);
    double shared = speed_at_rest(st, WFF_ZONE_PRELOAD_SHARED);
    printf("  at rest, King inside linear yarns: in-plane speed %.3g m/s with the matched "
           "preload, %.3g m/s with the shared one\n", matched, shared);
    CHECK(st, matched < 1e-6, "matched preload: the zones are in equilibrium (%.3g m/s)",
          matched);
    CHECK(st, shared > 1e3 * matched && shared > 1e-3,
          "shared preload: the zones are not in equilibrium (%.3g m/s)", shared);
    /* the forces per mesh width match: σ11 = P11/λ2 of both cells */
    wff_model m;
    if (make(st, &m, TEST_MESH_TRI, LINEAR, WFF_ZONE_PRELOAD_MATCHED, 0))
        return;
    double fa = 0, fb = 0, fa22 = 0;
    double *T = malloc(sizeof(double) * (size_t)(m.el.n_tris + m.el.n_quads));
    wff_error err;
    if (T && wff_model_element_values(&m, "P22", T, &err) == 0)
        fa22 = T[0];
    if (T && wff_model_element_values(&m, "P11", T, &err) == 0) {
        fa = T[0]; /* a corner triangle: linear yarns; the centre: King */
        int centre = -1;
        for (int e = 0; e < m.el.n_tris && centre < 0; e++) {
            const int *t = m.mesh.tri + 3 * e;
            double cx = (m.mesh.xy[2 * t[0]] + m.mesh.xy[2 * t[1]] + m.mesh.xy[2 * t[2]]) / 3;
            double cy = (m.mesh.xy[2 * t[0] + 1] + m.mesh.xy[2 * t[1] + 1] +
                         m.mesh.xy[2 * t[2] + 1]) / 3;
            if (hypot(cx, cy) < 0.005)
                centre = e;
        }
        fb = centre >= 0 ? T[centre] : NAN;
    }
    const wff_material *far = wff_model_zone_material(&m, 1);
    CHECK(st, far && strcmp(far->cell->name, "linear_yarns") == 0 && wff_model_zone_material(
              &m, 2) == NULL, "zone 1's material is the linear yarns");
    /* P11 per unstretched width; per mesh width σ11 = P11 / λ2: the linear yarns' λ2 is
     * 1 + P22 / S_2 (S_2 = 5.15e6 N/m in LINEAR) */
    double F[4], dA[2];
    king_preload(st, F, dA);
    double sigma_far = fa / (1 + fa22 / 5.15e6), sigma_king = fb / F[3];
    printf("  preload force per mesh width: linear yarns %.9g N/m, King %.9g N/m\n", sigma_far,
           sigma_king);
    CHECK(st, fa > 0 && fabs(sigma_far - sigma_king) < 1e-6 * sigma_king,
          "preload forces of the zones per mesh width: %.9g, %.9g N/m", sigma_far, sigma_king);
    free(T);
    wff_model_free(&m);
}

/* 3. */
static void two_materials_energy(check_state *st)
{
    wff_model m;
    if (make(st, &m, TEST_MESH_TRI, LINEAR, WFF_ZONE_PRELOAD_MATCHED, 1))
        return;
    wff_error err;
    wff_energies e;
    double worst = 0, fabric = 0;
    for (int block = 1; block <= 8; block++) {
        if (wff_model_advance(&m, block * 0.02e-3, 1000000, &err)) {
            CHECK(st, 0, "%s", err.message);
            break;
        }
        wff_model_energies(&m, &e);
        worst = fmax(worst, fabs(e.error));
        CHECK(st, fabs(e.error) < 0.005, "two materials: energy error %.3g at t = %g s", e.error,
              m.time);
        fabric = e.kinetic_inplane + e.kinetic_transverse + e.internal;
    }
    printf("  two materials: %ld steps, max |energy error| %.2e, fabric %.3g J of %.3g J\n",
           m.step, worst, fabric - (m.initial_total - m.initial_kinetic) * m.symmetry_factor,
           0.5 * 0.002 * 20 * 20);
    CHECK(st, m.projectile.velocity < 20, "the projectile is slowed: %g m/s",
          m.projectile.velocity);
    wff_model_free(&m);
}

/* 4. */
static void refusals(check_state *st)
{
    wff_model m;
    wff_error err;
    if (make(st, &m, TEST_MESH_TRI, NULL, 0, 0))
        return;
    unsigned char *none = calloc((size_t)(m.el.n_tris + 1), 1);
    CHECK(st, wff_model_set_option(&m, "static_amplitudes", 1, &err) == 0, "%s", err.message);
    CHECK(st, wff_model_zone_elements(&m, none, LINEAR, 0, &err) == -1 &&
              strstr(err.message, "static amplitudes"), "zones with static amplitudes: %s",
          err.message);
    CHECK(st, wff_model_set_option(&m, "static_amplitudes", 0, &err) == 0, "%s", err.message);
    CHECK(st, wff_model_zone_elements(&m, none, LINEAR, 7, &err) == -1 &&
              strstr(err.message, "preload mode 7"), "bad preload mode: %s", err.message);
    CHECK(st, wff_model_zone_disc(&m, 0, 0, -1, 1, LINEAR, 0, &err) == -1 &&
              strstr(err.message, "radius -1"), "negative radius: %s", err.message);
    CHECK(st, wff_model_zone_region(&m, "nowhere", 0, LINEAR, 0, &err) == -1 &&
              strstr(err.message, "nowhere"), "unknown group: %s", err.message);
    CHECK(st, wff_model_zone_region(&m, "fabric", 0, KEVLAR, WFF_ZONE_PRELOAD_MATCHED, &err) ==
                  -1 && strstr(err.message, "amplitudes"),
          "matched preload of an amplitude cell: %s", err.message);
    CHECK(st, wff_model_zone_region(&m, "fabric", 0, "no/such.txt", 0, &err) == -1 &&
              strstr(err.message, "no/such.txt"), "missing file: %s", err.message);
    int n = wff_model_zone_region(&m, NULL, TEST_FABRIC, LINEAR, WFF_ZONE_PRELOAD_MATCHED, &err);
    CHECK(st, n == m.el.n_tris, "the whole fabric by its region tag: %d (%s)", n,
          n < 0 ? err.message : "");
    CHECK(st, wff_model_set_option(&m, "static_amplitudes", 1, &err) == -1 &&
              strstr(err.message, "zonal"), "static amplitudes with zones: %s", err.message);
    wff_mesh copy;
    test_rect r = {-0.03, 0.03, -0.03, 0.03, 16, 16, TEST_MESH_TRI, 1, 0.2, 5};
    if (test_mesh_rect(&r, &copy) == 0)
        CHECK(st, wff_model_remesh(&m, &copy, NULL, &err) == -1 &&
                  strstr(err.message, "zonal materials"), "remesh with zones: %s", err.message);
    /* a checkpoint of the zonal model does not load into the model without zones */
    char dir[256], path[300];
    wff_model plain;
    if (test_tmp_dir("zones", dir, sizeof dir) == 0 && make(st, &plain, TEST_MESH_TRI, NULL, 0, 0) == 0) {
        test_tmp_path(dir, "zonal.state", path, sizeof path);
        CHECK(st, wff_model_advance(&m, 1e-6, 1000, &err) == 0, "%s", err.message);
        CHECK(st, wff_model_save(&m, path, &err) == 0, "%s", err.message);
        CHECK(st, wff_model_load_state(&plain, path, &err) == -1 && strstr(err.message, "material"),
              "checkpoint into a model without the zones: %s", err.message);
        CHECK(st, wff_model_zone_elements(&m, none, LINEAR, 0, &err) == -1 &&
                  strstr(err.message, "has started"), "zones after the start: %s", err.message);
        wff_model_free(&plain);
        test_tmp_remove(dir);
    }
    wff_model_free(&m);
    /* an amplitude cell in a zone of a model without amplitudes */
    test_rect r2 = {0, 0.01, 0, 0.01, 2, 2, TEST_MESH_TRI, 1, 0, 0};
    if (test_model_rect(&m, &r2, LINEAR, &err) == 0) {
        CHECK(st, wff_model_zone_region(&m, "fabric", 0, KEVLAR, 0, &err) == -1 &&
                  strstr(err.message, "has crimp amplitudes"), "amplitudes over none: %s",
              err.message);
        wff_model_free(&m);
    }
    free(none);
}

int main(void)
{
    check_state st = {0, 0};
    same_material(&st, TEST_MESH_TRI, 0, "triangles");
    same_material(&st, TEST_MESH_QUAD, 0, "quadrilaterals");
    same_material(&st, TEST_MESH_TRI, 1, "triangles, halves in place");
    same_material(&st, TEST_MESH_QUAD, 1, "quadrilaterals, halves in place");
    matched_preload(&st);
    two_materials_energy(&st);
    refusals(&st);
    return check_summary(&st, "test_zones");
}

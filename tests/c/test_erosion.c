/* Element erosion (plugin/erosion.c) with a cell registered in this test
 * binary only ("test_erosion": linear yarns whose stiffness falls with a
 * damage per family, d_k = clamp((ε_k,max − ε_f)/(ε_r − ε_f), 0, 1), never
 * decreasing; W = Σ ½ S_k (1 − d_k) ε_k² + ½ G γ²), and King's plain weave
 * (eroded by setting the flags, for its blocked kernels):
 *   1. eroded elements give exactly no force: with every element eroded the
 *      forces and the stored energy are 0; the forces of a model with a set S
 *      eroded plus those of the same model with the rest eroded are the
 *      forces of the model with none eroded, to round-off (plain, blocked tri
 *      and quad kernels, static amplitudes, the reference path, a zone); the
 *      forces of the eroded model are −dE/du (central differences);
 *   2. the eroded energy is the stored energy the elements had;
 *   3. the stable step ignores eroded elements (a sliver that sets it, once
 *      eroded, does not; the blocked scan agrees with the scalar one);
 *   4. a struck square perforates: elements erode and the energy balance
 *      closes across the erosion events;
 *   5. a node with no live element is a free mass the projectile still pushes;
 *   6. checkpoint and restart carry the flags and accumulators, bit for bit;
 *      another erosion rule is refused;
 *   7. the rules: both families (default) and either family;
 *   8. refusals: a cell without yarn failure (named), failure = 0, a bad rule,
 *      erosion 0 after elements eroded, a mesh transfer with damage;
 *   9. the fields damage1 damage2 eroded;
 *  10. King with failure struck at 600 m/s (held edges): elements erode, the
 *      energy balance within 1 %, and momentum along z balances at every step
 *      through the erosions (the projectile's lost momentum = the fabric's
 *      gained + the impulse the held edges took, from their reactions, within
 *      1e-9 of M v0: the scheme conserves it exactly but for round-off). */
#include "check.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "rng.h"
#include "wovenff/cell.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"
#include "wovenff/state.h"
#include "test_cells_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define EROSION "tests/data/erosion_cell.txt"
#define EROSION_OFF "tests/data/erosion_cell_off.txt"
#define NODAMAGE "tests/data/erosion_nodamage.txt"
#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

/* ---- the test cell ------------------------------------------------------ */

typedef struct ero_params {
    tcell_params yarns; /* S_k, G, ε_f, ε_r */
    double failure;     /* 0: no damage states */
} ero_params;

static const char *const ero_state_names[] = {"damage1", "damage2"};
static const char *const ero_state_units[] = {"-", "-"};

/* With failure, d_k = max(d_k, clamp((ε_k − ε_f)/(ε_r − ε_f), 0, 1)) when dt > 0
 * (held at dt = 0); N_k = S_k (1 − d_k) ε_k, W_yarn = Σ ½ S_k (1 − d_k) ε_k²; the
 * failure dissipation is the stored energy released, Σ ½ S_k ε_k² (d_k' − d_k). */
static void ero_law(const void *params, const double *state, double dt, tcell_yarns *y,
                    wff_point_result *out)
{
    const ero_params *c = params;
    double damage[2], released = 0;
    y->energy_yarn = 0;
    for (int f = 0; f < 2; f++) {
        double old = c->failure ? state[f] : 0, d = old;
        if (c->failure && dt > 0) {
            double reached = tcell_damage_reached(&c->yarns, y->strain[f]);
            d = reached > old ? reached : old;
        }
        damage[f] = d;
        double half = 0.5 * c->yarns.stiffness[f] * y->strain[f] * y->strain[f];
        y->force[f] = c->yarns.stiffness[f] * (1 - d) * y->strain[f];
        y->energy_yarn += (1 - d) * half;
        released += (d - old) * half;
    }
    if (out) {
        out->state[0] = damage[0];
        out->state[1] = damage[1];
        out->dissipated = 0;
        out->failure_dissipated = released;
    }
}
TCELL_OPS(ero)

static int ero_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    ero_params *c = (ero_params *)mat->params;
    if (tcell_parse(kv, mat, sizeof *c, err) || wff_kv_number(kv, "failure", &c->failure, err))
        return -1;
    if (!(c->yarns.rupture_strain > c->yarns.fail_strain))
        return wff_kv_reject(kv, "rupture_strain", err, "rupture > fail strain");
    mat->yarn_spacing[0] = mat->yarn_spacing[1] = 1e-3;
    mat->n_state = c->failure != 0 ? 2 : 0; /* failure = 0: no damage states */
    return 0;
}

static const wff_cell_type test_erosion =
    TCELL_TABLE("test_erosion", ero, ero_parse,
                .summary = "test only: linear yarns with a damage per family",
                .n_state_max = 2, .damage_state = {0, 1});
WFF_REGISTER_CELL(test_erosion);

/* The same cell declaring no yarn failure (damage_state −1): erosion refused. */
static int nodamage_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    int rc = ero_parse(kv, mat, err);
    ((ero_params *)mat->params)->failure = 0;
    mat->n_state = 0;
    return rc;
}
static const wff_cell_type test_erosion_nodamage =
    TCELL_TABLE("test_erosion_nodamage", ero, nodamage_parse,
                .summary = "test only: linear yarns, no failure",
                .n_state_max = 0, .damage_state = {-1, -1});
WFF_REGISTER_CELL(test_erosion_nodamage);

/* ---- helpers -------------------------------------------------------------- */

static int n_elements(const wff_model *m) { return m->el.n_tris + m->el.n_quads; }

static int n_points_of(const wff_model *m, int e) { return e < m->el.n_tris ? 3 : 4; }

static double *point_state(wff_model *m, int e, int q)
{
    size_t base = e < m->el.n_tris ? 3 * (size_t)e
                                   : 3 * (size_t)m->el.n_tris + 4 * (size_t)(e - m->el.n_tris);
    return m->state + (size_t)m->n_state * (base + (size_t)q);
}

static void set_damage(wff_model *m, int e, double d1, double d2)
{
    for (int q = 0; q < n_points_of(m, e); q++) {
        point_state(m, e, q)[0] = d1;
        point_state(m, e, q)[1] = d2;
    }
}

/* Forces R and stored energy (whole) at U; dt > 0 advances the states (and erodes). */
static int forces(check_state *st, wff_model *m, const double *U, double *R, double dt,
                  double *E)
{
    wff_error err;
    int rc = wff_model_forces(m, U, R, dt, E, &err);
    CHECK(st, rc == 0, "forces: %s", err.message);
    return rc;
}

/* Erosion flags set directly (King has no damage): on for the elements sel selects. */
static void flags(wff_model *m, int (*sel)(int), int want)
{
    if (!m->el.eroded)
        m->el.eroded = calloc((size_t)n_elements(m), 1);
    m->el.erosion = 1;
    for (int e = 0; e < n_elements(m); e++)
        if (sel(e) == want)
            m->el.eroded[e] = 1;
}

static int every_third(int e) { return e % 3 == 0; }

static double max_abs(const double *a, int n)
{
    double b = 0;
    for (int i = 0; i < n; i++)
        b = fmax(b, fabs(a[i]));
    return b;
}

static void random_u(const wff_model *m, double *U, double amp, int amplitudes, uint64_t seed)
{
    wff_rng rng = {seed};
    for (int i = 0; i < m->n_dofs; i++) {
        int c = i % D;
        U[i] = c < 3 ? wff_rng_uniform(&rng, -amp, amp)
                     : amplitudes ? wff_rng_uniform(&rng, -1e-7, 1e-7) : 0;
    }
}

/* ---- 1, 2, 9: forces, energy, fields with the test cell ------------------- */

static void check_forces_test_cell(check_state *st, int type)
{
    const test_rect r = {0, 0.01, 0, 0.01, 4, 4, type, 1, 0.2, 5};
    const char *kind = type == TEST_MESH_TRI ? "triangles" : "quads";
    wff_model a0, a1, full, all;
    wff_error err;
    if (test_model_rect(&a0, &r, EROSION, &err) || test_model_rect(&a1, &r, EROSION, &err) ||
        test_model_rect(&full, &r, EROSION, &err) || test_model_rect(&all, &r, EROSION, &err)) {
        CHECK(st, 0, "models: %s", err.message);
        return;
    }
    CHECK(st, a0.el.eroded != NULL && a0.el.erosion == WFF_EROSION_BOTH,
          "%s: erosion on (both) by default for a material with failure", kind);
    int n = a0.n_dofs, ne = n_elements(&a0), n_s = 0;
    double *U = malloc(sizeof(double) * (size_t)n), *R0 = malloc(sizeof(double) * (size_t)n);
    double *R1 = malloc(sizeof(double) * (size_t)n), *Rf = malloc(sizeof(double) * (size_t)n);
    double *R2 = malloc(sizeof(double) * (size_t)n);
    random_u(&a0, U, 2e-6, 0, 17 + (uint64_t)type); /* strains ~1e-3, below fail_strain */
    /* full: S damaged but not eroded (erosion off); a1: S damaged and eroded by a pass */
    wff_model_set_option(&full, "erosion", 0, &err);
    for (int e = 0; e < ne; e++)
        if (every_third(e)) {
            set_damage(&full, e, 1, 1);
            set_damage(&a1, e, 1, 1);
            n_s++;
        }
    double E0, E1, Ef, E2, Ea, dummy;
    if (forces(st, &a1, U, R1, 1e-9, &dummy)) /* the pass that erodes */
        goto done;
    CHECK(st, a1.n_eroded == n_s, "%s: the %d damaged elements eroded (%d)", kind, n_s,
          a1.n_eroded);
    int flags_ok = 1;
    for (int e = 0; e < ne; e++)
        flags_ok &= a1.el.eroded[e] == every_third(e);
    CHECK(st, flags_ok, "%s: exactly the damaged elements eroded", kind);
    forces(st, &a0, U, R0, 0, &E0);
    forces(st, &a1, U, R1, 0, &E1);
    forces(st, &full, U, Rf, 0, &Ef);
    /* 2: eroded energy = the stored energy the eroded elements had */
    double eroded = a1.eroded_energy * a1.symmetry_factor;
    printf("  %s: %d of %d eroded; stored energy %.6e J undamaged, %.6e J damaged, %.6e J "
           "after erosion, eroded %.6e J\n", kind, n_s, ne, E0, Ef, E1, eroded);
    CHECK(st, eroded > 0 && fabs(eroded - (Ef - E1)) <= 1e-12 * Ef,
          "%s: eroded energy %.9e J = the elements' stored energy %.9e J", kind, eroded,
          Ef - E1);
    /* the rest eroded, S live (damaged): the two add up to `full` */
    wff_model a2;
    if (test_model_rect(&a2, &r, EROSION, &err) == 0) {
        for (int e = 0; e < ne; e++)
            if (every_third(e))
                set_damage(&a2, e, 1, 1);
        flags(&a2, every_third, 0);
        forces(st, &a2, U, R2, 0, &E2);
        double worst = 0;
        for (int i = 0; i < n; i++)
            worst = fmax(worst, fabs(R1[i] + R2[i] - Rf[i]));
        CHECK(st, worst <= 1e-12 * max_abs(Rf, n) && fabs(E1 + E2 - Ef) <= 1e-12 * Ef,
              "%s: forces of S eroded + of the rest eroded = forces of none eroded (%.2e of "
              "%.2e N; energy %.3e + %.3e = %.3e J)", kind, worst, max_abs(Rf, n), E1, E2, Ef);
        wff_model_free(&a2);
    }
    /* every element eroded: exactly no force, no energy, no energy split */
    for (int e = 0; e < ne; e++)
        set_damage(&all, e, 1, 1);
    forces(st, &all, U, R2, 1e-9, &dummy);
    forces(st, &all, U, R2, 0, &Ea);
    double split[WFF_MECH_MAX];
    int nm = wff_model_energy_split(&all, split);
    CHECK(st, all.n_eroded == ne && max_abs(R2, n) == 0 && Ea == 0 && nm == 2 &&
                  split[0] == 0 && split[1] == 0,
          "%s: every element eroded: forces %g N, energy %g J, split %g %g (all exactly 0)",
          kind, max_abs(R2, n), Ea, split[0], split[1]);
    /* the eroded model's forces are −dE/du (central differences) */
    {
        double h = 1e-10, worst = 0, scale = max_abs(R1, n);
        int checked = 0;
        for (int i = 0; i < n; i += 7) {
            if (i % D >= 3)
                continue;
            double save = U[i], Ep, Em;
            U[i] = save + h;
            forces(st, &a1, U, R2, 0, &Ep);
            U[i] = save - h;
            forces(st, &a1, U, R2, 0, &Em);
            U[i] = save;
            worst = fmax(worst, fabs(-(Ep - Em) / (2 * h) - R1[i]));
            checked++;
        }
        CHECK(st, worst <= 1e-5 * scale, "%s: eroded model's forces = -dE/du at %d DOFs "
              "(worst %.2e of %.2e N)", kind, checked, worst, scale);
    }
    /* 9: fields */
    {
        double *v = malloc(sizeof(double) * (size_t)ne), *nodal = malloc(sizeof(double) *
                                                                            (size_t)a1.n_nodes);
        int ok = wff_model_element_values(&a1, "eroded", v, &err) == 0;
        int good = ok;
        for (int e = 0; ok && e < ne; e++)
            good &= v[e] == (every_third(e) ? 1 : 0);
        CHECK(st, good, "%s: element field eroded is 1 on the eroded elements: %s", kind,
              ok ? "" : err.message);
        ok = wff_model_element_values(&a1, "damage2", v, &err) == 0;
        good = ok;
        for (int e = 0; ok && e < ne; e++)
            good &= v[e] == (every_third(e) ? 1 : 0);
        CHECK(st, good, "%s: element field damage2 is the points' mean", kind);
        ok = wff_model_element_values(&a1, "T1", v, &err) == 0;
        good = ok;
        for (int e = 0; ok && e < ne; e++)
            good &= every_third(e) ? v[e] == 0 : 1;
        CHECK(st, good, "%s: an eroded element's tension is 0", kind);
        ok = wff_model_nodal_field(&a1, "eroded", nodal, &err) == 0;
        double lo = 1, hi = 0;
        for (int i = 0; ok && i < a1.n_nodes; i++)
            lo = fmin(lo, nodal[i]), hi = fmax(hi, nodal[i]);
        CHECK(st, ok && lo >= 0 && hi <= 1 && hi > 0, "%s: nodal eroded field in [%g, %g]",
              kind, lo, hi);
        wff_model off;
        if (test_model_rect(&off, &r, EROSION_OFF, &err) == 0) {
            ok = wff_model_element_values(&off, "damage1", v, &err) == 0 &&
                 max_abs(v, ne) == 0;
            CHECK(st, ok, "%s: damage1 is 0 for a material without damage states", kind);
            wff_model_free(&off);
        }
        free(v);
        free(nodal);
    }
done:
    free(U), free(R0), free(R1), free(Rf), free(R2);
    wff_model_free(&a0), wff_model_free(&a1), wff_model_free(&full), wff_model_free(&all);
}

/* ---- 1 (blocked kernels): King, flags set directly ------------------------ */

static int king_variant(check_state *st, const test_rect *r, int reference, int stat,
                        int erode_sel, double *R, double *E)
{
    wff_model m;
    wff_error err;
    if (test_model_rect(&m, r, KEVLAR, &err)) {
        CHECK(st, 0, "King: %s", err.message);
        return -1;
    }
    int rc = 0;
    if (reference)
        rc = wff_model_set_option(&m, "reference_path", 1, &err);
    if (!rc && stat)
        rc = wff_model_set_option(&m, "static_amplitudes", 1, &err);
    CHECK(st, rc == 0, "%s", err.message);
    if (erode_sel >= 0)
        flags(&m, every_third, erode_sel);
    double *U = malloc(sizeof(double) * (size_t)m.n_dofs);
    random_u(&m, U, 5e-6, 1, 99);
    rc = forces(st, &m, U, R, 0, E);
    free(U);
    wff_model_free(&m);
    return rc;
}

static void check_king_paths(check_state *st, int type)
{
    const test_rect r = {0, 0.006, 0, 0.006, 6, 5, type, 1, 0.2, 9};
    const char *kind = type == TEST_MESH_TRI ? "triangles" : "quads";
    wff_model probe;
    wff_error err;
    if (test_model_rect(&probe, &r, KEVLAR, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    int n = probe.n_dofs;
    CHECK(st, probe.el.eroded == NULL, "King without failure: erosion off (no flags)");
    wff_model_free(&probe);
    double *R0 = malloc(sizeof(double) * (size_t)n), *R1 = malloc(sizeof(double) * (size_t)n);
    double *R2 = malloc(sizeof(double) * (size_t)n), *Rr = malloc(sizeof(double) * (size_t)n);
    static const char *const path[] = {"blocked", "reference path", "static amplitudes"};
    for (int p = 0; p < 3; p++) {
        double E0, E1, E2, Er;
        int reference = p == 1, stat = p == 2;
        if (king_variant(st, &r, reference, stat, -1, R0, &E0) ||
            king_variant(st, &r, reference, stat, 1, R1, &E1) ||
            king_variant(st, &r, reference, stat, 0, R2, &E2))
            continue;
        double worst = 0;
        for (int i = 0; i < n; i++)
            worst = fmax(worst, fabs(R1[i] + R2[i] - R0[i]));
        CHECK(st, worst <= 1e-10 * max_abs(R0, n) && fabs(E1 + E2 - E0) <= 1e-10 * fabs(E0),
              "King %s, %s: forces of S eroded + the rest eroded = none eroded (%.2e of %.2e "
              "N), energies %.4e + %.4e = %.4e J", kind, path[p], worst, max_abs(R0, n), E1,
              E2, E0);
        if (p == 0) { /* blocked and reference paths agree with elements eroded */
            if (king_variant(st, &r, 1, 0, 1, Rr, &Er) == 0) {
                double d = 0;
                for (int i = 0; i < n; i++)
                    d = fmax(d, fabs(Rr[i] - R1[i]));
                CHECK(st, d <= 1e-10 * max_abs(R1, n) && fabs(Er - E1) <= 1e-10 * fabs(E1),
                      "King %s: blocked = reference path with S eroded (%.2e N)", kind, d);
            }
        }
    }
    free(R0), free(R1), free(R2), free(Rr);
}

/* ---- 3: the stable step --------------------------------------------------- */

static int around_node(const wff_model *m, int e, int node)
{
    int nn = e < m->el.n_tris ? 3 : 4;
    const int *c = e < m->el.n_tris ? m->el.tri + 3 * e : m->el.quad + 4 * (e - m->el.n_tris);
    for (int a = 0; a < nn; a++)
        if (c[a] == node)
            return 1;
    return 0;
}

static void check_stable_step(check_state *st, const char *material, int by_damage)
{
    const test_rect r = {0, 0.01, 0, 0.01, 6, 6, TEST_MESH_TRI, 1, 0, 1};
    wff_mesh mesh;
    wff_model m[2];
    wff_error err;
    int node = 3 * 7 + 3; /* interior node (3, 3), moved near (4, 3): slivers around it */
    for (int k = 0; k < 2; k++) {
        if (test_mesh_rect(&r, &mesh)) {
            CHECK(st, 0, "mesh");
            return;
        }
        mesh.xy[2 * node] += 0.9 * 0.01 / 6;
        if (wff_model_create_from_mesh(&m[k], &mesh, material, &err)) {
            CHECK(st, 0, "%s", err.message);
            return;
        }
        if (k == 1)
            wff_model_set_option(&m[k], "reference_path", 1, &err);
    }
    double dt0, dt1, dt1r;
    int w0, w1, w1r;
    wff_model_stable_step(&m[0], NULL, &dt0, &w0, &err);
    CHECK(st, around_node(&m[0], w0, node), "%s: the sliver sets the step (element %d)",
          material, w0 + 1);
    int ne = n_elements(&m[0]), n_around = 0;
    for (int k = 0; k < 2; k++) {
        for (int e = 0; e < ne; e++) {
            if (!around_node(&m[k], e, node))
                continue;
            n_around += k == 0;
            if (by_damage)
                set_damage(&m[k], e, 1, 1);
            else {
                if (!m[k].el.eroded)
                    m[k].el.eroded = calloc((size_t)ne, 1);
                m[k].el.erosion = 1;
                m[k].el.eroded[e] = 1;
            }
        }
        if (by_damage) {
            double *R = malloc(sizeof(double) * (size_t)m[k].n_dofs), E;
            double *U = calloc((size_t)m[k].n_dofs, sizeof(double));
            forces(st, &m[k], U, R, 1e-9, &E);
            CHECK(st, m[k].n_eroded == n_around, "%d elements around the node eroded (%d)",
                  n_around, m[k].n_eroded);
            free(R), free(U);
        }
    }
    wff_model_stable_step(&m[0], NULL, &dt1, &w1, &err);
    wff_model_stable_step(&m[1], NULL, &dt1r, &w1r, &err);
    printf("  %s: stable step %.4g s (sliver %d) -> %.4g s (element %d) with the %d elements "
           "around the moved node eroded; the plain scan %.4g s\n", material, dt0, w0 + 1, dt1,
           w1 + 1, n_around, dt1r);
    CHECK(st, dt1 > 2 * dt0 && !around_node(&m[0], w1, node) && !m[0].el.eroded[w1],
          "%s: eroded slivers set no step (%.3g s -> %.3g s)", material, dt0, dt1);
    CHECK(st, fabs(dt1r - dt1) <= 1e-12 * dt1 && w1r == w1,
          "%s: the blocked and the plain scan agree with elements eroded", material);
    wff_model_free(&m[0]), wff_model_free(&m[1]);
}

/* ---- 4, 6: a struck square perforates; checkpoint ------------------------- */

static const test_rect square = {-0.03, 0.03, -0.03, 0.03, 14, 14, TEST_MESH_TRI, 1, 0.2, 11};

/* The square of EROSION with a 10 g projectile at velocity (m/s). */
static int struck(check_state *st, wff_model *m, double velocity)
{
    return tcell_struck(st, m, &square, EROSION, 0.01, velocity);
}

static void check_perforation(check_state *st)
{
    wff_model a, b;
    wff_error err;
    if (struck(st, &a, 200))
        return;
    double worst = 0;
    int rc = 0, first_eroded_step = -1;
    for (int k = 0; k < 60 && rc == 0; k++) {
        rc = wff_model_advance(&a, 1, 100, &err);
        wff_energies e;
        wff_model_energies(&a, &e);
        worst = fmax(worst, fabs(e.error));
        if (a.n_eroded > 0 && first_eroded_step < 0)
            first_eroded_step = (int)a.step;
    }
    CHECK(st, rc == 0, "struck square: %s", err.message);
    wff_energies e;
    wff_model_energies(&a, &e);
    printf("  struck square at 200 m/s, %ld steps (%.3g ms): %d of %d elements eroded (first "
           "by step %d), projectile %.4g m/s, failure energy %.4g J, eroded energy %.4g J, "
           "initial kinetic %.4g J, largest energy error %.2e\n", a.step, a.time * 1e3,
           a.n_eroded, n_elements(&a), first_eroded_step, a.projectile.velocity,
           e.dissipated_failure, e.eroded, 0.5 * 0.01 * 200 * 200, worst);
    CHECK(st, a.n_eroded > 0 && e.eroded > 0 && e.dissipated_failure > 0,
          "elements erode (%d), failure and eroded energies %g J, %g J", a.n_eroded,
          e.dissipated_failure, e.eroded);
    CHECK(st, worst < 1e-3, "the energy balance closes across the erosion events: largest "
          "error %.2e of the reference", worst);

    /* 6: checkpoint round trip */
    char dir[400], path[512];
    if (test_tmp_dir("test_erosion", dir, sizeof dir)) {
        CHECK(st, 0, "no temporary folder");
        wff_model_free(&a);
        return;
    }
    test_tmp_path(dir, "eroded.ckpt", path, sizeof path);
    rc = wff_model_save(&a, path, &err);
    CHECK(st, rc == 0, "save: %s", err.message);
    if (struck(st, &b, 200) == 0) {
        rc = wff_model_load_state(&b, path, &err);
        CHECK(st, rc == 0, "load: %s", err.message);
        int ne = n_elements(&a);
        CHECK(st, rc == 0 && memcmp(a.el.eroded, b.el.eroded, (size_t)ne) == 0 &&
                      a.n_eroded == b.n_eroded && a.eroded_energy == b.eroded_energy &&
                      a.dissipated_failure == b.dissipated_failure,
              "checkpoint: eroded flags, count, eroded and failure energies restored");
        rc = wff_model_advance(&a, 1, 300, &err) || wff_model_advance(&b, 1, 300, &err);
        CHECK(st, rc == 0, "%s", err.message);
        CHECK(st, memcmp(a.u, b.u, sizeof(double) * (size_t)a.n_dofs) == 0 &&
                      memcmp(a.el.eroded, b.el.eroded, (size_t)ne) == 0 &&
                      a.n_eroded == b.n_eroded && a.eroded_energy == b.eroded_energy &&
                      a.dissipated_failure == b.dissipated_failure,
              "the restarted run continues bit for bit (u, flags, energies; %d eroded)",
              b.n_eroded);
        wff_model_free(&b);
    }
    if (struck(st, &b, 200) == 0) {
        wff_model_set_option(&b, "erosion", 2, &err);
        rc = wff_model_load_state(&b, path, &err);
        CHECK(st, rc != 0 && strstr(err.message, "erosion"),
              "a checkpoint of another erosion rule is refused: %s",
              rc ? err.message : "loaded");
        wff_model_free(&b);
    }
    /* a mesh transfer with damage is refused */
    wff_mesh same;
    if (test_mesh_rect(&square, &same) == 0) {
        rc = wff_model_remesh(&a, &same, NULL, &err);
        CHECK(st, rc != 0 && strstr(err.message, "eroded"),
              "a mesh transfer of an eroded model is refused: %s", rc ? err.message : "done");
    }
    test_tmp_remove(dir);
    wff_model_free(&a);
}

/* ---- 5: a free node is pushed -------------------------------------------- */

static void check_free_node(check_state *st)
{
    wff_model m;
    wff_error err;
    const test_rect r = {-0.01, 0.01, -0.01, 0.01, 4, 4, TEST_MESH_TRI, 1, 0, 1};
    if (test_model_rect(&m, &r, EROSION, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    int ne = n_elements(&m), centre = wff_model_nearest_node(&m, 0, 0), n_around = 0;
    for (int e = 0; e < ne; e++)
        if (around_node(&m, e, centre)) {
            set_damage(&m, e, 1, 1);
            n_around++;
        }
    double *R = malloc(sizeof(double) * (size_t)m.n_dofs), *U = calloc((size_t)m.n_dofs, 8), E;
    forces(st, &m, U, R, 1e-9, &E);
    int rc = wff_model_set_projectile(&m, 2e-3, 0.01, 10, 0, &err);
    if (!rc)
        rc = wff_model_place_projectile(&m, -1e-5, &err);
    CHECK(st, rc == 0 && m.n_eroded == n_around, "the %d elements around the centre eroded "
          "(%d): %s", n_around, m.n_eroded, rc ? err.message : "");
    rc = wff_model_advance(&m, 1e-4, 100000, &err);
    CHECK(st, rc == 0, "free masses struck: %s", err.message);
    wff_energies e;
    wff_model_energies(&m, &e);
    double uz = m.u[D * centre + 2], vz = m.v[D * centre + 2];
    printf("  the elements around the centre eroded, projectile at 10 m/s: centre node uz %.4g mm, vz %.4g m/s, "
           "projectile %.4g m/s, energy error %.2e\n", uz * 1e3, vz, m.projectile.velocity,
           e.error);
    CHECK(st, uz > 0.5e-3 && vz > 9 && m.projectile.velocity < 10,
          "a node with no live element is pushed by the projectile (uz %g m, vz %g m/s)", uz,
          vz);
    CHECK(st, fabs(e.error) < 1e-6, "the balance holds with a free mass (%.2e)", e.error);
    free(R), free(U);
    wff_model_free(&m);
}

/* ---- 7, 8: rules and refusals -------------------------------------------- */

static void check_rules(check_state *st)
{
    const test_rect r = {0, 0.01, 0, 0.01, 3, 3, TEST_MESH_TRI, 1, 0, 1};
    wff_model m;
    wff_error err;
    if (test_model_rect(&m, &r, EROSION, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    double *R = malloc(sizeof(double) * (size_t)m.n_dofs), *U = calloc((size_t)m.n_dofs, 8), E;
    set_damage(&m, 0, 1, 0);         /* family 1 ruptured everywhere */
    set_damage(&m, 1, 1, 0);         /* family 1 at two points, family 2 at the third */
    point_state(&m, 1, 2)[0] = 0.5;
    point_state(&m, 1, 2)[1] = 1;
    set_damage(&m, 2, 1, 0.999);     /* not quite both */
    forces(st, &m, U, R, 1e-9, &E);
    CHECK(st, m.n_eroded == 0, "rule both: one family ruptured erodes nothing (%d)",
          m.n_eroded);
    int rc = wff_model_set_option(&m, "erosion", 2, &err);
    CHECK(st, rc == 0, "erosion = 2: %s", err.message);
    forces(st, &m, U, R, 1e-9, &E);
    CHECK(st, m.n_eroded == 2 && m.el.eroded[0] && !m.el.eroded[1] && m.el.eroded[2],
          "rule either: elements with one family ruptured at every point erode (%d: %d %d %d)",
          m.n_eroded, m.el.eroded[0], m.el.eroded[1], m.el.eroded[2]);
    rc = wff_model_set_option(&m, "erosion", 0, &err);
    CHECK(st, rc != 0 && strstr(err.message, "eroded"), "erosion 0 after erosion refused: %s",
          rc ? err.message : "accepted");
    rc = wff_model_set_option(&m, "erosion", 3, &err);
    CHECK(st, rc != 0 && strstr(err.message, "erosion = 3"), "erosion 3 refused: %s",
          rc ? err.message : "accepted");
    free(R), free(U);
    wff_model_free(&m);

    if (test_model_rect(&m, &r, EROSION, &err) == 0) { /* damage, none eroded yet */
        set_damage(&m, 1, 0.5, 0);
        wff_mesh same;
        if (test_mesh_rect(&r, &same) == 0) {
            rc = wff_model_remesh(&m, &same, NULL, &err);
            CHECK(st, rc != 0 && strstr(err.message, "yarn damage"),
                  "a mesh transfer with erosion on and yarn damage is refused: %s",
                  rc ? err.message : "done");
        }
        wff_model_free(&m);
    }
    if (test_model_rect(&m, &r, NODAMAGE, &err) == 0) {
        CHECK(st, m.el.eroded == NULL, "a cell without failure: erosion off by default");
        rc = wff_model_set_option(&m, "erosion", 1, &err);
        printf("  %s\n", rc ? err.message : "accepted");
        CHECK(st, rc != 0 && strstr(err.message, "test_erosion_nodamage"),
              "erosion refused for a cell without yarn failure, naming it: %s",
              rc ? err.message : "accepted");
        wff_model_free(&m);
    }
    if (test_model_rect(&m, &r, EROSION_OFF, &err) == 0) {
        CHECK(st, m.el.eroded == NULL, "failure = 0: erosion off by default");
        rc = wff_model_set_option(&m, "erosion", 1, &err);
        CHECK(st, rc != 0 && strstr(err.message, "failure = 0"),
              "erosion refused for a material with failure off: %s",
              rc ? err.message : "accepted");
        wff_model_free(&m);
    }
    /* a zone: the zone's elements erode too, and give no force */
    if (test_model_rect(&m, &r, EROSION, &err) == 0) {
        rc = wff_model_zone_disc(&m, 0, 0, 0.004, 0, EROSION, WFF_ZONE_PRELOAD_SHARED, &err);
        CHECK(st, rc > 0, "zone: %s", rc > 0 ? "" : err.message);
        int ne = n_elements(&m);
        double *R2 = malloc(sizeof(double) * (size_t)m.n_dofs);
        double *U2 = malloc(sizeof(double) * (size_t)m.n_dofs);
        random_u(&m, U2, 2e-6, 0, 3);
        for (int e = 0; e < ne; e++)
            set_damage(&m, e, 1, 1);
        forces(st, &m, U2, R2, 1e-9, &E);
        forces(st, &m, U2, R2, 0, &E);
        CHECK(st, m.n_eroded == ne && max_abs(R2, m.n_dofs) == 0 && E == 0,
              "with a zone: every element eroded (%d of %d), forces %g N, energy %g J",
              m.n_eroded, ne, max_abs(R2, m.n_dofs), E);
        free(R2), free(U2);
        wff_model_free(&m);
    }
}

/* ---- King with failure: a fast impact erodes, the balance closes --------- */

static void check_king_impact(check_state *st)
{
    char dir[400], path[512];
    if (test_tmp_dir("test_erosion_king", dir, sizeof dir)) {
        CHECK(st, 0, "no temporary folder");
        return;
    }
    test_tmp_path(dir, "kevlar_failure.txt", path, sizeof path);
    int switched = test_tmp_copy_replacing(KEVLAR, path, "failure = 0", "failure = 1\n") == 1;
    CHECK(st, switched, "%s has a line 'failure = 0'", KEVLAR);
    wff_model m;
    wff_error err;
    int rc = test_model_rect(&m, &square, path, &err);
    CHECK(st, rc == 0, "King with failure: %s", err.message);
    if (rc) {
        test_tmp_remove(dir);
        return;
    }
    CHECK(st, m.el.eroded && m.el.erosion == WFF_EROSION_BOTH,
          "King with failure = 1: erosion on (both) by default");
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int g = 0; g < 4 && rc >= 0; g++)
        for (int c = WFF_UX; c <= WFF_UZ && rc >= 0; c++)
            rc = wff_model_fix_group(&m, edges[g], c, &err);
    const double v0 = 600, mass = 0.002;
    if (rc >= 0)
        rc = wff_model_set_projectile(&m, 2.5e-3, mass, v0, 0.2, &err);
    if (rc >= 0)
        rc = wff_model_set_option(&m, "dtfactor", 0.5, &err);
    /* momentum along z: the projectile's and the free nodes' (half-step velocities)
     * change by the impulse the held edges put in, sum_k h_k sum R_z (R = -f_int on
     * held DOFs: the support's force on the node), h_k = (dt_k + dt_k+1) / 2 the
     * velocity update's interval; internal forces sum to zero over all nodes (eroded
     * elements have none), the contact impulses are internal to the pair. So the
     * projectile's lost momentum = the fabric's gained + what the edges took out
     * (taken = -sum h R) */
    double edge_taken = 0, worst = 0, worst_momentum = 0;
    for (int k = 0; k < 40 * 250 && rc >= 0; k++) {
        double dt_used = m.dt;
        rc = wff_model_advance(&m, 1, 1, &err);
        double r_z = 0, fabric = 0;
        for (int n = 0; n < m.n_nodes; n++) {
            if (m.dof_kind[WFF_DOFS_PER_NODE * n + WFF_UZ] != WFF_DOF_FREE)
                r_z += m.reaction[WFF_DOFS_PER_NODE * n + WFF_UZ];
            else
                fabric += m.mass[WFF_DOFS_PER_NODE * n + WFF_UZ] * m.v[WFF_DOFS_PER_NODE * n + WFF_UZ];
        }
        edge_taken -= 0.5 * (dt_used + m.dt) * r_z;
        double lost = m.projectile.mass * (v0 - m.projectile.velocity);
        worst_momentum = fmax(worst_momentum, fabs(lost - (fabric + edge_taken)));
        if (k % 250 == 249) {
            wff_energies e;
            wff_model_energies(&m, &e);
            worst = fmax(worst, fabs(e.error));
        }
    }
    CHECK(st, rc == 0, "King impact with failure: %s", err.message);
    {
        double fabric = 0;
        for (int n = 0; n < m.n_nodes; n++)
            if (m.dof_kind[WFF_DOFS_PER_NODE * n + WFF_UZ] == WFF_DOF_FREE)
                fabric += m.mass[WFF_DOFS_PER_NODE * n + WFF_UZ] * m.v[WFF_DOFS_PER_NODE * n + WFF_UZ];
        double lost = m.projectile.mass * (v0 - m.projectile.velocity);
        printf("  momentum along z: projectile lost %.6g N s, fabric gained %.6g N s, taken "
               "out by the held edges %.6g N s; largest imbalance over the run %.2e N s = %.2e of M v0\n",
               lost, fabric, edge_taken, worst_momentum, worst_momentum / (mass * v0));
        CHECK(st, worst_momentum <= 1e-9 * mass * v0,
              "projectile's lost momentum = fabric's gained + the edges' share at every step "
              "(largest imbalance %.2e of M v0, through %d erosions)", worst_momentum / (mass * v0),
              m.n_eroded);
        CHECK(st, fabs(edge_taken) > 1e-3 * mass * v0,
              "the edges take a share of the momentum (%.3g of M v0)", edge_taken / (mass * v0));
    }
    wff_energies e;
    wff_model_energies(&m, &e);
    printf("  King, failure on, %.0f m/s, %.0f g: %ld steps (%.3g ms), %d of %d elements "
           "eroded, projectile %.4g m/s, failure %.4g J, eroded %.4g J of %.4g J, largest "
           "energy error %.2e\n", v0, mass * 1e3, m.step, m.time * 1e3, m.n_eroded,
           n_elements(&m), m.projectile.velocity, e.dissipated_failure, e.eroded,
           0.5 * mass * v0 * v0, worst);
    CHECK(st, m.n_eroded > 0 && e.dissipated_failure > 0,
          "a fast King impact with failure erodes elements (%d)", m.n_eroded);
    CHECK(st, worst < 1e-2, "and the energy balance closes within 1 %% (largest %.2e)", worst);
    wff_model_free(&m);
    test_tmp_remove(dir);
}

int main(void)
{
    check_state st = {0, 0};
    check_forces_test_cell(&st, TEST_MESH_TRI);
    check_forces_test_cell(&st, TEST_MESH_QUAD);
    check_king_paths(&st, TEST_MESH_TRI);
    check_king_paths(&st, TEST_MESH_QUAD);
    /* the test cell's materials have a woven fabric's scales (wff_material_scales) */
    const char *const tree[] = {EROSION, NODAMAGE, "tests/data/erosion_cell_off.txt"};
    for (int i = 0; i < 3; i++) {
        wff_error e = {{0}};
        int rc = wff_material_scales(tree[i], &e);
        CHECK(&st, rc == 0, "%s: scales check %d: %s", tree[i], rc, e.message);
    }
    check_stable_step(&st, EROSION, 1);
    check_stable_step(&st, KEVLAR, 0);
    check_perforation(&st);
    check_free_node(&st);
    check_rules(&st);
    check_king_impact(&st);
    return check_summary(&st, "test_erosion");
}

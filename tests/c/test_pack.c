/* Multi-ply packs (plugin/pack.c, include/wovenff/pack.h) through the C API:
 *   1. one ply through the pack code is the plain model bit for bit (u, v,
 *      states, energies) under a projectile impact;
 *   2. three plies far apart: the struck ply is the plain model to round-off,
 *      the others stay where they were; groups hold every ply's nodes;
 *   3. ply 0 at 30 deg through its zone is the plain model at 30 deg to round-off;
 *      threads (the plies' force passes at once) give the same bits;
 *      free flight keeps the plies' offsets; per-ply energies sum to the model's;
 *      the "ply" fields;
 *   4. bad input: plies <= 0, > 40, gap < 0, after boundary conditions, a ply
 *      index out of range, a ply material that cannot be read; a checkpoint of
 *      the pack written and loaded back. */
#include "check.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "wovenff/pack.h"
#include "wovenff/renumber.h"
#include "wovenff/state.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

/* A 6 cm square of triangles, renumbered (as the binding's models are). */
static int square(check_state *st, wff_model *m, int n)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, n, n, TEST_MESH_TRI, 1, 0.2, 7};
    wff_mesh mesh;
    wff_error err;
    if (test_mesh_rect(&r, &mesh) || wff_model_create_ordered(m, &mesh, KEVLAR, 1, &err)) {
        CHECK(st, 0, "model: %s", err.message);
        return -1;
    }
    return 0;
}

/* Edges fixed, a projectile at 60 m/s; plies (0: none) at gap (test_meshes.h). */
static int impact(check_state *st, wff_model *m, int plies, double gap)
{
    wff_error err;
    if (test_model_struck(m, 12, KEVLAR, plies, gap, &err)) {
        CHECK(st, 0, "struck square, %d plies: %s", plies, err.message);
        return -1;
    }
    return 0;
}

static void same_model(check_state *st)
{
    wff_model a, b;
    wff_error err;
    if (impact(st, &a, 0, 0) || impact(st, &b, 1, 1e-3))
        return;
    int ra = wff_model_advance(&a, 4e-5, 100000, &err);
    int rb = wff_model_advance(&b, 4e-5, 100000, &err);
    CHECK(st, ra == 0 && rb == 0 && a.step == b.step && a.step > 20, "advance %d %d, steps %ld %ld",
          ra, rb, a.step, b.step);
    size_t nd = sizeof(double) * (size_t)a.n_dofs;
    CHECK(st, memcmp(a.u, b.u, nd) == 0 && memcmp(a.v, b.v, nd) == 0 && memcmp(a.f, b.f, nd) == 0,
          "one ply: u, v, f differ from the plain model");
    size_t ns = sizeof(double) * (size_t)a.n_state * wff_elements_point_count(&a.el);
    CHECK(st, memcmp(a.state, b.state, ns) == 0, "one ply: states differ");
    wff_energies ea, eb;
    wff_model_energies(&a, &ea);
    wff_model_energies(&b, &eb);
    CHECK(st, memcmp(&ea, &eb, sizeof ea) == 0, "one ply: energies differ (error %g, %g)",
          ea.error, eb.error);
    double apex, back;
    CHECK(st, wff_model_ply_value(&b, 0, "apex", &apex, &err) == 0 &&
              wff_model_pack_value(&b, "back_face", &back, &err) == 0 && apex == back && apex > 0,
          "one ply: apex %g back face %g", apex, back);
    wff_model_free(&a);
    wff_model_free(&b);
}

static void far_plies(check_state *st)
{
    wff_model a, b;
    wff_error err;
    const double gap = 0.05; /* beyond the projectile's reach in this time */
    if (impact(st, &a, 0, 0) || impact(st, &b, 3, gap))
        return;
    /* the stable step of the start kept (the plies at rest would otherwise set it) */
    wff_model_set_option(&a, "dtinterval", 1e6, &err);
    wff_model_set_option(&b, "dtinterval", 1e6, &err);
    int fixed_plain = wff_model_fix_group(&a, "left", WFF_UX, &err);
    int fixed_pack = wff_model_fix_group(&b, "left", WFF_UX, &err);
    CHECK(st, fixed_pack == 3 * fixed_plain && fixed_plain > 0, "group nodes %d of %d",
          fixed_pack, fixed_plain);
    CHECK(st, b.n_nodes == 3 * a.n_nodes && wff_model_ply_count(&b) == 3, "nodes %d, %d",
          b.n_nodes, a.n_nodes);
    int ra = wff_model_advance(&a, 4e-5, 100000, &err);
    int rb = wff_model_advance(&b, 4e-5, 100000, &err);
    CHECK(st, ra == 0 && rb == 0, "advance: %s", err.message);
    double big = 0, worst = 0, moved = 0;
    for (int k = 0; k < a.n_nodes; k++) { /* user node k of the plain = ply 0's node k */
        int na = wff_model_node_of_user(&a, k), nb = wff_model_node_of_user(&b, k);
        for (int c = 0; c < 3; c++) {
            big = fmax(big, fabs(a.u[D * na + c]));
            worst = fmax(worst, fabs(a.u[D * na + c] - b.u[D * nb + c]));
        }
        for (int p = 1; p < 3; p++) {
            int n = wff_model_node_of_user(&b, p * a.n_nodes + k);
            moved = fmax(moved, fabs(b.u[D * n] ) + fabs(b.u[D * n + 1]) +
                                    fabs(b.u[D * n + 2] - p * gap));
            CHECK(st, wff_model_node_ply(&b, p * a.n_nodes + k) == p, "node ply");
        }
    }
    CHECK(st, big > 1e-4 && worst <= 1e-9 * big, "ply 0 against the plain model: %g of %g",
          worst, big);
    CHECK(st, moved <= 1e-14 * gap, "plies 1, 2 moved by %g m", moved); /* (Σ ∇N_a = 0 to
                                                            round-off under u_z = p gap) */
    /* per-ply energies add up to the model's */
    wff_energies e;
    wff_model_energies(&b, &e);
    double kin = 0, stored = 0, diss = 0, v;
    for (int p = 0; p < 3; p++) {
        wff_model_ply_value(&b, p, "kinetic", &v, &err), kin += v;
        wff_model_ply_value(&b, p, "stored", &v, &err), stored += v;
        wff_model_ply_value(&b, p, "dissipated", &v, &err), diss += v;
    }
    CHECK_CLOSE(st, kin, e.kinetic_inplane + e.kinetic_transverse + e.kinetic_amplitude, 1e-12,
                1e-30, "kinetic sum");
    CHECK_CLOSE(st, stored, e.internal, 1e-12, 1e-30, "stored sum");
    CHECK_CLOSE(st, diss, e.dissipated_shear + e.dissipated_failure + e.eroded, 1e-12, 1e-30,
                "dissipated sum");
    CHECK(st, kin > 0 && stored > 0, "ply energies %g %g", kin, stored);
    wff_model_free(&a);
    wff_model_free(&b);
}

/* Ply 0 of a pack at 30 deg (its zone's own orientation) against a plain model at
 * 30 deg, the other ply far away: the same run to round-off. */
static void rotated_ply(check_state *st)
{
    wff_model a, b;
    wff_error err;
    const double theta = 30 * (M_PI / 180); /* as the setting "orientation" maps 30 */
    if (impact(st, &a, 0, 0) || impact(st, &b, 2, 0.05))
        return;
    int rc = wff_model_set_option(&a, "orientation", 30, &err) ||
             wff_model_ply_orientation(&b, 0, theta, &err) ||
             wff_model_set_option(&a, "dtinterval", 1e6, &err) ||
             wff_model_set_option(&b, "dtinterval", 1e6, &err);
    CHECK(st, rc == 0, "orientation: %s", err.message);
    if (rc == 0 && (wff_model_advance(&a, 4e-5, 100000, &err) ||
                    wff_model_advance(&b, 4e-5, 100000, &err)))
        CHECK(st, 0, "advance: %s", err.message);
    double big = 0, worst = 0;
    for (int k = 0; k < a.n_nodes; k++) {
        int na = wff_model_node_of_user(&a, k), nb = wff_model_node_of_user(&b, k);
        for (int c = 0; c < D; c++) {
            big = fmax(big, fabs(a.u[D * na + c]));
            worst = fmax(worst, fabs(a.u[D * na + c] - b.u[D * nb + c]));
        }
    }
    CHECK(st, big > 1e-4 && worst <= 1e-9 * big, "ply 0 at 30 deg against the plain model: %g "
          "of %g", worst, big);
    wff_model_free(&a);
    wff_model_free(&b);
}

/* The force pass of a pack with threads runs its plies at once: the same bits. */
static void threaded_plies(check_state *st)
{
    wff_model a, b;
    wff_error err;
    if (impact(st, &a, 4, 0.2e-3) || impact(st, &b, 4, 0.2e-3))
        return;
    int rc = wff_model_set_option(&b, "threads", 2, &err);
    CHECK(st, rc == 0, "threads: %s", err.message);
    if (rc == 0 && (wff_model_advance(&a, 3e-5, 100000, &err) ||
                    wff_model_advance(&b, 3e-5, 100000, &err)))
        CHECK(st, 0, "advance: %s", err.message);
    size_t nd = sizeof(double) * (size_t)a.n_dofs;
    CHECK(st, a.step == b.step && a.step > 10 && memcmp(a.u, b.u, nd) == 0 &&
              memcmp(a.v, b.v, nd) == 0,
          "4 plies, 1 and 2 threads: u, v differ (steps %ld %ld)", a.step, b.step);
    wff_model_free(&a);
    wff_model_free(&b);
}

static void free_flight(check_state *st)
{
    wff_model m;
    wff_error err;
    const double gap = 1e-3, vz = 5;
    if (square(st, &m, 6))
        return;
    if (wff_model_set_plies(&m, 4, gap, &err)) {
        CHECK(st, 0, "plies: %s", err.message);
        return;
    }
    for (int n = 0; n < m.n_nodes; n++)
        m.v[D * n + WFF_UZ] = vz;
    CHECK(st, wff_model_advance(&m, 1e-4, 100000, &err) == 0, "advance: %s", err.message);
    double worst = 0;
    for (int n = 0; n < m.n_nodes; n++) {
        int p = n / (m.n_nodes / 4);
        worst = fmax(worst, fabs(m.u[D * n + WFF_UZ] - p * gap - vz * m.time));
    }
    CHECK(st, worst <= 1e-12, "free flight: offsets off by %g m", worst);
    double *ply = malloc(sizeof(double) * (size_t)m.n_nodes);
    double *eply = malloc(sizeof(double) * (size_t)(m.el.n_tris + m.el.n_quads));
    int bad = 0;
    if (ply && eply && wff_model_nodal_field(&m, "ply", ply, &err) == 0 &&
        wff_model_element_values(&m, "ply", eply, &err) == 0) {
        for (int k = 0; k < m.n_nodes; k++)
            bad += ply[k] != k / (m.n_nodes / 4);
        int per = m.el.n_tris / 4;
        for (int e = 0; e < m.el.n_tris; e++)
            bad += eply[e] != e / per;
    } else {
        bad = -1;
    }
    CHECK(st, bad == 0, "ply fields: %d wrong", bad);
    free(ply);
    free(eply);
    wff_model_free(&m);
}

static void expect_fail(check_state *st, int rc, const wff_error *err, const char *word)
{
    CHECK(st, rc < 0 && strstr(err->message, word), "want an error naming '%s': rc %d, '%s'",
          word, rc, rc < 0 ? err->message : "");
}

static void bad_input(check_state *st)
{
    wff_model m;
    wff_error err;
    if (square(st, &m, 4))
        return;
    expect_fail(st, wff_model_set_plies(&m, 0, 1e-3, &err), &err, "1 to 40");
    expect_fail(st, wff_model_set_plies(&m, 41, 1e-3, &err), &err, "1 to 40");
    expect_fail(st, wff_model_set_plies(&m, 2, -1e-3, &err), &err, ">= 0");
    expect_fail(st, wff_model_set_plies(&m, 2, NAN, &err), &err, "gap");
    CHECK(st, wff_model_fix_group(&m, "left", WFF_UX, &err) > 0, "fix");
    expect_fail(st, wff_model_set_plies(&m, 2, 1e-3, &err), &err, "boundary conditions");
    wff_model_free(&m);
    if (square(st, &m, 4))
        return;
    CHECK(st, wff_model_set_plies(&m, 3, 1e-3, &err) == 0, "plies: %s", err.message);
    expect_fail(st, wff_model_set_plies(&m, 3, 1e-3, &err), &err, "once");
    expect_fail(st, wff_model_ply_material(&m, 3, KEVLAR, &err), &err, "plies 0 to 2");
    expect_fail(st, wff_model_ply_material(&m, -1, KEVLAR, &err), &err, "ply -1");
    expect_fail(st, wff_model_ply_material(&m, 1, "no/such/material.txt", &err), &err,
                "no/such/material.txt");
    expect_fail(st, wff_model_ply_orientation(&m, 5, 0.1, &err), &err, "ply 5");
    double v;
    expect_fail(st, wff_model_ply_value(&m, 7, "apex", &v, &err), &err, "ply 7");
    expect_fail(st, wff_model_ply_value(&m, 0, "apexx", &v, &err), &err, "apexx");
    expect_fail(st, wff_model_set_option(&m, "ply_mu", -1, &err), &err, "ply_mu");
    expect_fail(st, wff_model_set_option(&m, "ply_thickness", 0, &err), &err, "ply_thickness");
    CHECK(st, wff_model_ply_material(&m, 1, KEVLAR, &err) > 0, "ply material: %s", err.message);
    char dir[512], path[600];
    if (test_tmp_dir("pack", dir, sizeof dir) == 0) {
        test_tmp_path(dir, "pack.ckpt", path, sizeof path);
        /* a pack checkpoints (its parts' state fields) and loads back */
        CHECK(st, wff_model_save(&m, path, &err) == 0, "the pack's checkpoint: %s", err.message);
        CHECK(st, wff_model_load_state(&m, path, &err) == 0, "the pack's checkpoint loaded: %s",
              err.message);
        test_tmp_remove(dir);
    }
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    same_model(&st);
    far_plies(&st);
    rotated_ply(&st);
    threaded_plies(&st);
    free_flight(&st);
    bad_input(&st);
    return check_summary(&st, "test_pack");
}

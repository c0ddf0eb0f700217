/* The generic per-point internal state (cell.h) with a cell that carries two
 * states, registered in this test binary only ("test_two_states"):
 *   1. the cell suite runs on it (n_state 2: every state held at dt = 0,
 *      every fast-path comparison over both states);
 *   2. a struck square advances its states (both move), the failure
 *      dissipation enters the energy balance;
 *   3. checkpoint and restart carry every state: a model loaded from the
 *      checkpoint holds the same states and continues bit for bit; a
 *      checkpoint of another state layout (King: gamma_f) is refused naming
 *      both layouts;
 *   4. a mesh transfer carries every state: onto the same mesh unchanged,
 *      onto a finer mesh the flow strain within the old range, the damage the
 *      largest of the old points' values (one of them, never a mean).
 *
 * The cell: straight yarns along E1, E2 and an in-plane shear stiffness
 * (linear_yarns' laws, p_k⁰ = 1), with on family 1 a relaxing "flow" strain p
 * (state 0, a Maxwell element: ṗ = (ε₁ − p)/τ, backward Euler) and a damage d
 * (state 1, d = clamp((ε₁,max − ε_f)/(ε_r − ε_f), 0, 1), never decreasing):
 *   W = ½ S₁ (1 − d)(ε₁ − p)² + ½ S₂ ε₂² + ½ G γ²,  ε_k = λ_k − 1.
 * Dissipation: S₁ (1 − d)(ε₁ − p')(p' − p) (flow), ½ S₁ (ε₁ − p')² (d' − d)
 * (failure: the stored energy released at fixed strain). */
#include "check.h"
#include "cell_suite.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "wovenff/cell.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"
#include "wovenff/state.h"
#include "test_cells_fixture.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TWO_STATES "tests/data/two_states.txt"
#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

/* ---- the test cell ------------------------------------------------------ */

typedef struct two_params {
    tcell_params yarns;     /* S_k, G, ε_f, ε_r */
    double relax_time;      /* τ, s */
} two_params;

static const char *const two_state_names[] = {"flow_strain", "damage1"};
static const char *const two_state_units[] = {"-", "-"};
enum { S_FLOW, S_DAMAGE, S_COUNT };

/* The point's yarn forces with its states updated by dt (held when dt = 0). */
static void two_law(const void *params, const double *state, double dt, tcell_yarns *y,
                    wff_point_result *out)
{
    const two_params *c = params;
    const double *stiffness = c->yarns.stiffness;
    double r = dt / c->relax_time;
    double flow = (state[S_FLOW] + r * y->strain[0]) / (1 + r);
    double reached = tcell_damage_reached(&c->yarns, y->strain[0]);
    double damage = dt > 0 && reached > state[S_DAMAGE] ? reached : state[S_DAMAGE];
    double elastic1 = y->strain[0] - flow, stiffness1 = stiffness[0] * (1 - damage);
    y->force[0] = stiffness1 * elastic1;
    y->force[1] = stiffness[1] * y->strain[1];
    y->energy_yarn = 0.5 * stiffness1 * elastic1 * elastic1 +
                     0.5 * stiffness[1] * y->strain[1] * y->strain[1];
    if (!out)
        return;
    out->state[S_FLOW] = flow;
    out->state[S_DAMAGE] = damage;
    out->dissipated = stiffness[0] * (1 - state[S_DAMAGE]) * elastic1 * (flow - state[S_FLOW]);
    out->failure_dissipated =
        0.5 * stiffness[0] * elastic1 * elastic1 * (damage - state[S_DAMAGE]);
}
TCELL_OPS(two)

static int two_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    two_params *c = (two_params *)mat->params;
    if (tcell_parse(kv, mat, sizeof *c, err) ||
        wff_kv_number(kv, "relax_time", &c->relax_time, err))
        return -1;
    if (!(c->relax_time > 0) || !(c->yarns.rupture_strain > c->yarns.fail_strain))
        return wff_kv_reject(kv, "relax_time", err, "relax_time > 0, rupture > fail strain");
    mat->yarn_spacing[0] = mat->yarn_spacing[1] = 1e-3;
    mat->n_state = S_COUNT;
    return 0;
}

static const wff_cell_type test_two_states =
    TCELL_TABLE("test_two_states", two, two_parse,
                .summary = "test only: linear yarns with a relaxing flow strain and a damage on "
                           "family 1",
                .n_state_max = S_COUNT, .damage_state = {S_DAMAGE, -1});
WFF_REGISTER_CELL(test_two_states);

/* ---- the model tests ---------------------------------------------------- */

/* A square with fixed edges struck by a light projectile (2 g at 20 m/s). */
static int struck(check_state *st, wff_model *m, const test_rect *r, const char *material)
{
    return tcell_struck(st, m, r, material, 0.002, 20);
}

static size_t n_values(const wff_model *m)
{
    return (size_t)(3 * m->el.n_tris + 4 * m->el.n_quads) * (size_t)m->n_state;
}

/* Range of state j over the model's points. */
static void state_range(const wff_model *m, int j, double *lo, double *hi)
{
    size_t np = n_values(m) / (size_t)m->n_state;
    *lo = INFINITY, *hi = -INFINITY;
    for (size_t p = 0; p < np; p++) {
        double v = m->state[(size_t)m->n_state * p + (size_t)j];
        *lo = fmin(*lo, v), *hi = fmax(*hi, v);
    }
}

static const test_rect square = {-0.03, 0.03, -0.03, 0.03, 14, 14, TEST_MESH_TRI, 1, 0.2, 11};

static void check_run_and_checkpoint(check_state *st)
{
    wff_model a, b;
    wff_error err;
    if (struck(st, &a, &square, TWO_STATES))
        return;
    CHECK(st, a.n_state == 2 && strcmp(wff_model_state_name(&a, 0), "flow_strain") == 0 &&
                  strcmp(wff_model_state_name(&a, 1), "damage1") == 0,
          "the model's points carry the cell's two states: %d", a.n_state);
    int rc = wff_model_advance(&a, 1, 300, &err);
    CHECK(st, rc == 0, "%s", err.message);
    double flow_lo, flow_hi, dmg_lo, dmg_hi;
    state_range(&a, S_FLOW, &flow_lo, &flow_hi);
    state_range(&a, S_DAMAGE, &dmg_lo, &dmg_hi);
    wff_energies e;
    wff_model_energies(&a, &e);
    printf("  struck square, 300 steps: flow strain %.3g .. %.3g, damage %.3g .. %.3g, failure "
           "dissipation %.3g J, shear %.3g J, energy error %.2e\n", flow_lo, flow_hi, dmg_lo,
           dmg_hi, e.dissipated_failure, e.dissipated_shear, e.error);
    CHECK(st, flow_hi > 1e-4 && dmg_hi > 0.01 && dmg_lo == 0,
          "both states moved (flow up to %g, damage up to %g)", flow_hi, dmg_hi);
    CHECK(st, e.dissipated_failure > 0 && e.dissipated_shear > 0,
          "failure %g J and flow %g J dissipate", e.dissipated_failure, e.dissipated_shear);
    CHECK(st, fabs(e.error) < 1e-3, "energy balance with the failure term: error %g", e.error);
    /* the element field of each state is the mean of its points */
    int n_el = a.el.n_tris + a.el.n_quads;
    double *field = malloc(sizeof(double) * (size_t)n_el);
    for (int j = 0; j < 2 && field; j++) {
        rc = wff_model_element_values(&a, wff_model_state_name(&a, j), field, &err);
        CHECK(st, rc == 0, "element field %s: %s", wff_model_state_name(&a, j), err.message);
        double biggest = 0, lo, hi;
        for (int i = 0; rc == 0 && i < n_el; i++)
            biggest = fmax(biggest, fabs(field[i]));
        state_range(&a, j, &lo, &hi);
        CHECK(st, rc == 0 && biggest > 0 && biggest <= fmax(fabs(lo), fabs(hi)),
              "element field %s: largest %g within the points' %g .. %g",
              wff_model_state_name(&a, j), biggest, lo, hi);
    }
    free(field);

    char dir[400], path[512], kpath[512];
    if (test_tmp_dir("test_state", dir, sizeof dir)) {
        CHECK(st, 0, "no temporary folder");
        wff_model_free(&a);
        return;
    }
    test_tmp_path(dir, "two_states.ckpt", path, sizeof path);
    test_tmp_path(dir, "king.ckpt", kpath, sizeof kpath);
    rc = wff_model_save(&a, path, &err);
    CHECK(st, rc == 0, "save: %s", err.message);
    size_t n = n_values(&a);
    double *saved = malloc(sizeof(double) * n);
    memcpy(saved, a.state, sizeof(double) * n);
    if (struck(st, &b, &square, TWO_STATES) == 0) {
        rc = wff_model_load_state(&b, path, &err);
        CHECK(st, rc == 0, "load: %s", err.message);
        CHECK(st, rc == 0 && memcmp(b.state, saved, sizeof(double) * n) == 0,
              "every state of every point restored");
        CHECK(st, b.dissipated_failure == a.dissipated_failure, "failure dissipation restored");
        rc = wff_model_advance(&a, 1, 200, &err) || wff_model_advance(&b, 1, 200, &err);
        CHECK(st, rc == 0, "%s", err.message);
        CHECK(st, memcmp(a.state, b.state, sizeof(double) * n) == 0 &&
                      memcmp(a.u, b.u, sizeof(double) * (size_t)a.n_dofs) == 0 &&
                      a.dissipated_failure == b.dissipated_failure,
              "the restarted run continues bit for bit (states, u, failure dissipation)");
        wff_model_free(&b);
    }
    /* another layout: King's one state (gamma_f), same mesh */
    wff_model king;
    if (struck(st, &king, &square, KEVLAR) == 0) {
        rc = wff_model_save(&king, kpath, &err);
        CHECK(st, rc == 0, "save King: %s", err.message);
        rc = wff_model_load_state(&a, kpath, &err);
        printf("  a King checkpoint into the two-state model: %s\n", rc ? err.message : "loaded");
        CHECK(st, rc != 0 && strstr(err.message, "gamma_f") &&
                      strstr(err.message, "flow_strain damage1"),
              "refused, naming both layouts: %s", rc ? err.message : "loaded");
        wff_model_free(&king);
    }
    test_tmp_remove(dir);
    free(saved);
    wff_model_free(&a);
}

static void check_remesh(check_state *st)
{
    wff_model m;
    wff_error err;
    if (struck(st, &m, &square, TWO_STATES))
        return;
    int rc = wff_model_advance(&m, 1, 300, &err);
    CHECK(st, rc == 0, "%s", err.message);
    size_t n = n_values(&m);
    double *before = malloc(sizeof(double) * n);
    memcpy(before, m.state, sizeof(double) * n);
    double lo[2], hi[2];
    for (int j = 0; j < 2; j++)
        state_range(&m, j, &lo[j], &hi[j]);
    /* the same mesh: every state as it was */
    wff_mesh same;
    wff_remesh_report rep;
    CHECK(st, test_mesh_rect(&square, &same) == 0, "mesh");
    rc = wff_model_remesh(&m, &same, &rep, &err);
    CHECK(st, rc == 0, "same mesh: %s", err.message);
    CHECK(st, rc == 0 && n_values(&m) == n && memcmp(m.state, before, sizeof(double) * n) == 0,
          "same mesh: every state of every point unchanged");
    /* a finer mesh (no jitter): the flow strain interpolated within its range,
     * the damage the largest of the old points' (its peak kept) */
    test_rect fine = square;
    fine.nx = fine.ny = 28;
    fine.jitter = 0;
    wff_mesh finer;
    CHECK(st, test_mesh_rect(&fine, &finer) == 0, "mesh");
    rc = wff_model_remesh(&m, &finer, &rep, &err);
    CHECK(st, rc == 0, "finer mesh: %s", err.message);
    if (rc == 0) {
        double nlo[2], nhi[2];
        for (int j = 0; j < 2; j++)
            state_range(&m, j, &nlo[j], &nhi[j]);
        printf("  finer mesh (%d triangles): flow %.4g .. %.4g (was %.4g .. %.4g), damage "
               "%.4g .. %.4g (was %.4g .. %.4g)\n", m.el.n_tris, nlo[0], nhi[0], lo[0], hi[0],
               nlo[1], nhi[1], lo[1], hi[1]);
        CHECK(st, m.n_state == 2 && nlo[0] >= lo[0] - 1e-15 && nhi[0] <= hi[0] + 1e-15 &&
                      nhi[0] > 0,
              "flow strain transferred within its old range");
        /* the largest of the old points' values, not a mean: each new damage is one of
         * the old values, none above the old peak */
        size_t np_old = n / 2, np_new = n_values(&m) / 2, foreign = 0;
        for (size_t p = 0; p < np_new; p++) {
            double d = m.state[2 * p + S_DAMAGE];
            int found = 0;
            for (size_t q = 0; q < np_old && !found; q++)
                found = before[2 * q + S_DAMAGE] == d;
            foreign += !found;
        }
        CHECK(st, nlo[1] >= lo[1] && nhi[1] <= hi[1] && nhi[1] > 0 && foreign == 0,
              "damage transferred as the largest old value: peak %g (was %g), %zu of %zu new "
              "values not an old point's", nhi[1], hi[1], foreign, np_new);
        /* and the run goes on */
        rc = wff_model_advance(&m, 1, 50, &err);
        CHECK(st, rc == 0, "after the transfer: %s", err.message);
    }
    free(before);
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    {   /* the test cell's material has a woven fabric's scales (wff_material_scales) */
        wff_error e = {{0}};
        int rc = wff_material_scales(TWO_STATES, &e);
        CHECK(&st, rc == 0, "%s: scales check %d: %s", TWO_STATES, rc, e.message);
    }
    const cell_case two = {TWO_STATES, NULL, 0, 1};
    cell_suite_run(&st, &two);
    check_run_and_checkpoint(&st);
    check_remesh(&st);
    return check_summary(&st, "test_state");
}

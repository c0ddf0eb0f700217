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
#include "cells/cell_laws.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TWO_STATES "tests/data/two_states.txt"
#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

/* ---- the test cell ------------------------------------------------------ */

typedef struct two_params {
    double stiffness[2];     /* S_k, N/m */
    double shear_stiffness;  /* G, N/m */
    double relax_time;       /* τ, s */
    double fail_strain;      /* ε_f */
    double rupture_strain;   /* ε_r */
} two_params;

static const char *const two_diag_names[] = {"T1", "T2"};
static const char *const two_diag_units[] = {"N", "N"};
static const char *const two_mech_names[] = {"yarn_stretch", "shear"};
static const char *const two_state_names[] = {"flow_strain", "damage1"};
static const char *const two_state_units[] = {"-", "-"};
enum { S_FLOW, S_DAMAGE, S_COUNT };

typedef struct two_point {
    wff_yarn_frame fr;
    double strain[2], elastic1, stiffness1, force[2], flow, damage, energy_yarn, energy_shear;
} two_point;

/* The point with its states updated by dt (held when dt = 0). */
static int two_point_at(const two_params *c, const double F[6], const double *state, double dt,
                        two_point *pt)
{
    static const double unit[2] = {1, 1};
    if (wff_yarn_kinematics(unit, F, &pt->fr) != WFF_POINT_OK)
        return WFF_POINT_DEGENERATE;
    for (int f = 0; f < 2; f++)
        pt->strain[f] = pt->fr.p[f] - 1;
    double r = dt / c->relax_time;
    pt->flow = (state[S_FLOW] + r * pt->strain[0]) / (1 + r);
    double reached = (pt->strain[0] - c->fail_strain) / (c->rupture_strain - c->fail_strain);
    reached = reached < 0 ? 0 : reached > 1 ? 1 : reached;
    pt->damage = dt > 0 && reached > state[S_DAMAGE] ? reached : state[S_DAMAGE];
    pt->elastic1 = pt->strain[0] - pt->flow;
    pt->stiffness1 = c->stiffness[0] * (1 - pt->damage);
    pt->force[0] = pt->stiffness1 * pt->elastic1;
    pt->force[1] = c->stiffness[1] * pt->strain[1];
    pt->energy_yarn = 0.5 * pt->stiffness1 * pt->elastic1 * pt->elastic1 +
                      0.5 * c->stiffness[1] * pt->strain[1] * pt->strain[1];
    pt->energy_shear = 0.5 * c->shear_stiffness * pt->fr.gamma * pt->fr.gamma;
    return WFF_POINT_OK;
}

static int two_evaluate(const void *params, const double F[6], const double dA[2],
                        const double *state, double dt, wff_point_result *out)
{
    (void)dA;
    const two_params *c = params;
    two_point pt;
    if (two_point_at(c, F, state, dt, &pt) != WFF_POINT_OK) {
        wff_point_result_nan(out, 2);
        return WFF_POINT_DEGENERATE;
    }
    static const double no_spars[2] = {0, 0}, unit_scale[2] = {1, 1};
    double q[2][2];
    for (int f = 0; f < 2; f++)
        wff_q_coefficients(&pt.fr, f, pt.force[f], c->shear_stiffness * pt.fr.gamma, no_spars,
                           &q[f][f], &q[f][1 - f]);
    wff_stress_from_q(&pt.fr, q, unit_scale, out->stress);
    out->residual[0] = out->residual[1] = 0;
    out->energy = pt.energy_yarn + pt.energy_shear;
    out->state[S_FLOW] = pt.flow;
    out->state[S_DAMAGE] = pt.damage;
    out->dissipated = c->stiffness[0] * (1 - state[S_DAMAGE]) * pt.elastic1 *
                      (pt.flow - state[S_FLOW]);
    out->failure_dissipated =
        0.5 * c->stiffness[0] * pt.elastic1 * pt.elastic1 * (pt.damage - state[S_DAMAGE]);
    out->diag[0] = pt.force[0] * 1e-3; /* a yarn every mm */
    out->diag[1] = pt.force[1] * 1e-3;
    return WFF_POINT_OK;
}

static void two_energy_split(const void *params, const double F[6], const double dA[2],
                             const double *state, double *mech)
{
    (void)dA;
    two_point pt;
    if (two_point_at(params, F, state, 0, &pt) != WFF_POINT_OK) {
        mech[0] = mech[1] = NAN;
        return;
    }
    mech[0] = pt.energy_yarn;
    mech[1] = pt.energy_shear;
}

/* linear_yarns' bound (its stiffnesses are upper bounds of the damaged ones). */
static void two_wave_speeds(const void *params, double areal_density, const double F[6],
                            const double dA[2], double *membrane_speed, double *amplitude_omega)
{
    (void)dA;
    const two_params *c = params;
    two_point pt;
    *amplitude_omega = 0;
    if (two_point_at(c, F, wff_rest_state, 0, &pt) != WFF_POINT_OK) {
        *membrane_speed = INFINITY;
        return;
    }
    double sn = fmax(pt.fr.sin_t, 0.05), stretch_min = fmin(pt.fr.p[0], pt.fr.p[1]);
    double shear = 2 * c->shear_stiffness * (1 + fabs(pt.fr.gamma) * (1 + 1 / sn)) /
                   (stretch_min * stretch_min);
    double membrane = 0;
    for (int f = 0; f < 2; f++) {
        /* |N| with the flow strain at its extremes (0 and the strain) */
        double s_f = c->stiffness[f] + c->stiffness[f] * fabs(pt.strain[f]) / pt.fr.p[f] + shear;
        membrane = fmax(membrane, s_f);
    }
    *membrane_speed = sqrt(membrane / areal_density);
}

static int two_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    two_params *c = (two_params *)mat->params;
    memset(c, 0, sizeof *c);
    if (wff_kv_number(kv, "S_1", &c->stiffness[0], err) ||
        wff_kv_number(kv, "S_2", &c->stiffness[1], err) ||
        wff_kv_number(kv, "G", &c->shear_stiffness, err) ||
        wff_kv_number(kv, "relax_time", &c->relax_time, err) ||
        wff_kv_number(kv, "fail_strain", &c->fail_strain, err) ||
        wff_kv_number(kv, "rupture_strain", &c->rupture_strain, err))
        return -1;
    if (!(c->relax_time > 0) || !(c->rupture_strain > c->fail_strain))
        return wff_kv_reject(kv, "relax_time", err, "relax_time > 0, rupture > fail strain");
    mat->yarn_spacing[0] = mat->yarn_spacing[1] = 1e-3;
    mat->n_state = S_COUNT;
    return 0;
}

static const wff_cell_type test_two_states = {
    .name = "test_two_states",
    .summary = "test only: linear yarns with a relaxing flow strain and a damage on family 1",
    .n_amplitudes = 0,
    .n_diag = 2,
    .diag_names = two_diag_names,
    .diag_units = two_diag_units,
    .yarn_tension_diag = {0, 1},
    .n_mech = 2,
    .mech_names = two_mech_names,
    .n_state_max = S_COUNT,
    .state_names = two_state_names,
    .state_units = two_state_units,
    .damage_state = {S_DAMAGE, -1},
    .parse = two_parse,
    .evaluate = two_evaluate,
    .wave_speeds = two_wave_speeds,
    .energy_split = two_energy_split,
};
WFF_REGISTER_CELL(test_two_states);

/* ---- the model tests ---------------------------------------------------- */

/* A square with fixed edges struck by a light projectile. */
static int struck(check_state *st, wff_model *m, const test_rect *r, const char *material)
{
    wff_error err;
    int rc = test_model_rect(m, r, material, &err);
    CHECK(st, rc == 0, "%s: %s", material, err.message);
    if (rc)
        return -1;
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int g = 0; g < 4 && rc >= 0; g++)
        for (int c = WFF_UX; c <= WFF_UZ && rc >= 0; c++)
            rc = wff_model_fix_group(m, edges[g], c, &err);
    if (rc >= 0)
        rc = wff_model_set_projectile(m, 6.35e-3, 0.002, 20, 0.2, &err);
    CHECK(st, rc >= 0, "%s", err.message);
    if (rc < 0)
        wff_model_free(m);
    return rc < 0 ? -1 : 0;
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
    const cell_case two = {TWO_STATES, NULL, 0, 1};
    cell_suite_run(&st, &two);
    check_run_and_checkpoint(&st);
    check_remesh(&st);
    return check_summary(&st, "test_state");
}

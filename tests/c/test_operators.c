/* The loop operators of plugin/operators.c through the C API: a force pass
 * without dt has no side effect even with static amplitudes (γᶠ, the
 * points' amplitudes and the accumulators unchanged, the same R twice); with
 * dt it advances γᶠ, the dissipation and the element-step count; the stable
 * step of a NaN state and a contact without a projectile are errors that say
 * so; wff_model_step equals wff_model_advance by one step. */
#include "check.h"
#include "test_meshes.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

static const test_rect kRect = {0, 0.02, 0, 0.015, 6, 5, TEST_MESH_TRI, 1, 0.2, 7};

/* A sheared, bulged state (m). */
static void state(const wff_model *m, double *U)
{
    for (int n = 0; n < m->n_nodes; n++) {
        double x = m->mesh.xy[2 * n] / 0.02, y = m->mesh.xy[2 * n + 1] / 0.015;
        U[D * n] = 4e-5 * y;
        U[D * n + 1] = 2e-5 * x;
        U[D * n + 2] = 4e-4 * sin(M_PI * x) * sin(M_PI * y);
        U[D * n + 3] = -2e-6;
        U[D * n + 4] = -1e-6;
    }
}

static void no_side_effect(check_state *st, int static_amplitudes)
{
    wff_model m;
    wff_error err;
    if (test_model_rect(&m, &kRect, KEVLAR, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    if (static_amplitudes) {
        CHECK(st, wff_model_set_option(&m, "static_amplitudes", 1, &err) == 0, "%s", err.message);
    }
    size_t nd = (size_t)m.n_dofs, nq = (size_t)(3 * m.el.n_tris);
    double *U = calloc(nd, sizeof(double)), *R1 = calloc(nd, sizeof(double));
    double *R2 = calloc(nd, sizeof(double)), *g0 = calloc(nq, sizeof(double));
    double *dA0 = calloc(2 * nq, sizeof(double));
    state(&m, U);
    for (size_t q = 0; q < nq; q++) m.state[q] = 1e-3 * (double)(q % 7); /* a flowed state */
    memcpy(g0, m.state, nq * sizeof(double));
    if (m.el.point_dA) memcpy(dA0, m.el.point_dA, 2 * nq * sizeof(double));
    double e1 = 0, e2 = 0, internal = m.internal_energy, shear = m.dissipated_shear;
    long steps = m.element_steps;
    CHECK(st, wff_model_forces(&m, U, R1, 0, &e1, &err) == 0, "%s", err.message);
    CHECK(st, wff_model_forces(&m, U, R2, 0, &e2, &err) == 0, "%s", err.message);
    CHECK(st, memcmp(R1, R2, nd * sizeof(double)) == 0 && e1 == e2 && e1 > 0,
          "static %d: the same R and energy twice (%g, %g J)", static_amplitudes, e1, e2);
    CHECK(st, memcmp(g0, m.state, nq * sizeof(double)) == 0, "static %d: γᶠ held",
          static_amplitudes);
    CHECK(st, !m.el.point_dA || memcmp(dA0, m.el.point_dA, 2 * nq * sizeof(double)) == 0,
          "static %d: the points' static amplitudes unchanged", static_amplitudes);
    CHECK(st, m.internal_energy == internal && m.dissipated_shear == shear &&
              m.element_steps == steps, "static %d: accumulators unchanged", static_amplitudes);
    /* with dt: γᶠ flows, the dissipation and the count advance, R is the step's */
    CHECK(st, wff_model_forces(&m, U, R2, 1e-6, &e2, &err) == 0, "%s", err.message);
    int moved = memcmp(g0, m.state, nq * sizeof(double)) != 0;
    CHECK(st, moved && m.dissipated_shear > shear, "static %d: γᶠ flowed (%d), dissipated %g J",
          static_amplitudes, moved, m.dissipated_shear - shear);
    CHECK(st, m.element_steps == steps + m.el.n_tris && m.internal_energy == e2,
          "static %d: element steps %ld, stored energy %g J of the pass %g J", static_amplitudes,
          m.element_steps - steps, m.internal_energy, e2);
    CHECK(st, wff_model_forces(&m, U, R2, -1, &e2, &err) == -1 && strstr(err.message, "dt"),
          "negative dt refused: %s", err.message);
    free(U); free(R1); free(R2); free(g0); free(dA0);
    wff_model_free(&m);
}

static void errors_and_step(check_state *st)
{
    wff_model a, b;
    wff_error err;
    if (test_model_rect(&a, &kRect, KEVLAR, &err) || test_model_rect(&b, &kRect, KEVLAR, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    size_t nd = (size_t)a.n_dofs;
    double *U = calloc(nd, sizeof(double)), *V = calloc(nd, sizeof(double));
    double *R = calloc(nd, sizeof(double)), dt, tip[2] = {0, 10}, lost = 0;
    U[D * 7 + 2] = NAN;
    CHECK(st, wff_model_stable_step(&a, U, &dt, NULL, &err) == -1 &&
              strstr(err.message, "not positive") && strstr(err.message, "element"),
          "a NaN state: %s", err.message);
    CHECK(st, wff_model_contact(&a, U, V, R, tip, 1e-7, 1e-7, &lost, &err) == -1 &&
              strstr(err.message, "no projectile"), "no projectile: %s", err.message);
    for (int k = 0; k < 2; k++) {
        wff_model *m = k ? &b : &a;
        CHECK(st, wff_model_fix_group(m, "left", 2, &err) > 0, "%s", err.message);
        CHECK(st, wff_model_prescribe_group(m, "right", 2, 1.5, &err) > 0, "%s", err.message);
        CHECK(st, wff_model_set_option(m, "dtinterval", 2, &err) == 0, "%s", err.message);
    }
    for (int s = 1; s <= 5; s++) {
        double t0 = a.time;
        CHECK(st, wff_model_step(&a, &dt, &err) == 0, "%s", err.message);
        CHECK(st, wff_model_advance(&b, a.time, 1000, &err) == 0, "%s", err.message);
        CHECK(st, a.step == s && b.step == s && a.time == t0 + dt && b.time == a.time,
              "step %d: steps %ld %ld, times %g %g", s, a.step, b.step, a.time, b.time);
        CHECK(st, memcmp(a.u, b.u, nd * sizeof(double)) == 0 &&
                  memcmp(a.v, b.v, nd * sizeof(double)) == 0, "step %d: the same state", s);
    }
    free(U); free(V); free(R);
    wff_model_free(&a);
    wff_model_free(&b);
}

int main(void)
{
    check_state st = {0, 0};
    no_side_effect(&st, 0);
    no_side_effect(&st, 1);
    errors_and_step(&st);
    return check_summary(&st, "test_operators");
}

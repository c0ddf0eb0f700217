/* The stable-step scan's blocked path (triangles through the cell's
 * wave_speeds_block, docs/architecture.md "The stable-step scan on blocks")
 * gives the reference path's step (the scalar wave_speeds element by
 * element) and the same worst element: on random states, with the worst
 * element in the last, partly filled block, with two threads, and at every
 * step of a solver run. A table whose blocked wave speeds are 0.1 % off is
 * caught, so the comparison can fail. */
#include "check.h"
#include "rng.h"
#include "test_meshes.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE
/* the step of the two paths may differ by round-off only (libmvec's atan in
 * the blocked path, libm's in the scalar one) */
#define STEP_TOL 1e-13

/* king_plain's blocked wave speeds, 0.1 % too fast. */
static int fast_wave_speeds_block(const void *params, double areal_density, wff_wave_block *b)
{
    int rc = wff_cell_find("king_plain")->wave_speeds_block(params, areal_density, b);
    for (int j = 0; j < WFF_BLOCK; j++) {
        b->membrane_speed[j] *= 1.001;
        b->amplitude_omega[j] *= 1.001;
    }
    return rc;
}

/* A bumpy, sheared, compacted state; with hot >= 0 the nodes of triangle hot
 * compacted far more (the stiffest element: the worst step). */
static void random_state(wff_model *m, uint64_t seed, int hot)
{
    wff_rng g = {seed};
    for (int n = 0; n < m->n_nodes; n++) {
        double *u = m->u + D * n, x = m->mesh.xy[2 * n], y = m->mesh.xy[2 * n + 1];
        u[0] = 0.03 * y + wff_rng_uniform(&g, -1, 1) * 2e-5;
        u[1] = wff_rng_uniform(&g, -1, 1) * 2e-5;
        u[2] = 2e-3 * sin(100 * x) * cos(80 * y) + wff_rng_uniform(&g, -1, 1) * 2e-4;
        u[3] += wff_rng_uniform(&g, -3, 1) * 5e-6;
        u[4] += wff_rng_uniform(&g, -3, 1) * 5e-6;
    }
    if (hot >= 0)
        for (int a = 0; a < 3; a++) {
            int n = m->el.tri[3 * hot + a];
            m->u[D * n + 3] -= 40e-6;
            m->u[D * n + 4] -= 40e-6;
        }
}

/* The step and worst element by the blocked path (reference_path 0) and the
 * scalar one (reference_path 1); returns the relative difference of the steps
 * (INFINITY if the worst elements differ). */
static double both_paths(wff_model *m, double *dt_ref, int *worst_ref)
{
    int worst_blk;
    m->em.reference_path = 1;
    *dt_ref = wff_elements_stable_step(&m->el, &m->em, m->mesh.xy, m->u, worst_ref);
    m->em.reference_path = 0;
    double dt_blk = wff_elements_stable_step(&m->el, &m->em, m->mesh.xy, m->u, &worst_blk);
    if (worst_blk != *worst_ref)
        return INFINITY;
    return fabs(dt_blk - *dt_ref) / *dt_ref;
}

static int make(check_state *st, wff_model *m, int nx, int ny, uint64_t seed)
{
    test_rect r = {0, 0.04, 0, 0.03, nx, ny, TEST_MESH_TRI, 1, 0.2, seed};
    wff_error err;
    int rc = test_model_rect(m, &r, KEVLAR, &err);
    CHECK(st, rc == 0, "model: %s", rc ? err.message : "");
    if (rc)
        return -1;
    const double F_pre[4] = {1.00396, 0, 0, 1.0135}, dA0[2] = {-9.3e-6, -23.8e-6};
    rc = wff_model_set_preload(m, F_pre, dA0, &err);
    CHECK(st, rc == 0, "preload: %s", rc ? err.message : "");
    return rc;
}

/* Random states on a mesh of 2 nx ny triangles (not a whole number of blocks
 * when nx ny is odd), the worst element anywhere or in the last block. */
static void random_states(check_state *st, int nx, int ny, int threads)
{
    wff_model m;
    if (make(st, &m, nx, ny, 77))
        return;
    wff_error err;
    if (threads > m.el.max_threads) {
        printf("  stable step, %d threads: skipped (OpenMP allows %d)\n", threads,
               m.el.max_threads);
        wff_model_free(&m);
        return;
    }
    CHECK(st, wff_elements_set_threads(&m.el, threads, &err) == 0, "threads: %s", err.message);
    m.el.team_min_tris = 0; /* a team on this small mesh too: the threaded scan is under test */
    double worst = 0;
    int last_block_worst = 0, n = m.el.n_tris;
    for (int s = 0; s < 12; s++) {
        int hot = s % 3 == 0 ? -1 : s % 3 == 1 ? n - 1 - s % 2 : (int)(s * 7919L % n);
        memset(m.u, 0, sizeof(double) * (size_t)m.n_dofs);
        for (int k = 0; k < m.n_nodes; k++) { /* the preload's amplitudes */
            m.u[D * k + 3] = -9.3e-6;
            m.u[D * k + 4] = -23.8e-6;
        }
        random_state(&m, 1000 + (uint64_t)s, hot);
        double dt_ref;
        int worst_ref;
        double e = both_paths(&m, &dt_ref, &worst_ref);
        CHECK(st, e <= STEP_TOL, "%d x %d, %d threads, state %d: blocked step differs from the "
              "reference by %.3g (worst element %d)", nx, ny, threads, s, e, worst_ref + 1);
        CHECK(st, dt_ref > 0 && isfinite(dt_ref), "state %d: step %g", s, dt_ref);
        if (hot >= 0)
            CHECK(st, worst_ref == hot, "state %d: the compacted element %d sets the step, not %d",
                  s, hot + 1, worst_ref + 1);
        last_block_worst += worst_ref >= n - n % WFF_BLOCK && n % WFF_BLOCK;
        worst = fmax(worst, e);
    }
    CHECK(st, n % WFF_BLOCK == 0 || last_block_worst > 0,
          "no state had its worst element in the last, partly filled block");
    printf("  stable step, %d triangles, %d thread%s: blocked vs reference %.1e\n", n, threads,
           threads > 1 ? "s" : "", worst);
    wff_model_free(&m);
}

/* Blocked wave speeds 0.1 % too fast: the comparison above catches them. */
static void wrong_block_caught(check_state *st)
{
    wff_model m;
    if (make(st, &m, 7, 5, 78))
        return;
    random_state(&m, 5, -1);
    wff_cell_type wrong = *m.mat.cell;
    wrong.wave_speeds_block = fast_wave_speeds_block;
    m.mat.cell = &wrong;
    double dt_ref;
    int worst_ref;
    double e = both_paths(&m, &dt_ref, &worst_ref);
    CHECK(st, e > 1e-4, "blocked wave speeds 0.1%% off pass unnoticed (difference %.3g)", e);
    m.mat.cell = wff_cell_find("king_plain");
    wff_model_free(&m);
}

/* A solver run re-estimating every step: the step it takes is dtfactor times
 * the reference estimate at the state it was estimated at, every step. */
static void solver_steps(check_state *st)
{
    wff_model m;
    if (make(st, &m, 9, 7, 79))
        return;
    wff_error err;
    wff_rng g = {31};
    for (int n = 0; n < m.n_nodes; n++) { /* small random displacements and velocities */
        double *u = m.u + D * n, *v = m.v + D * n;
        for (int i = 0; i < 3; i++) {
            u[i] = wff_rng_uniform(&g, -1, 1) * (i < 2 ? 2e-5 : 2e-4);
            v[i] = wff_rng_uniform(&g, -1, 1);
        }
        u[3] += wff_rng_uniform(&g, -3, 1) * 1e-6;
        u[4] += wff_rng_uniform(&g, -3, 1) * 1e-6;
        v[3] = wff_rng_uniform(&g, -1, 1) * 0.01;
        v[4] = wff_rng_uniform(&g, -1, 1) * 0.01;
    }
    CHECK(st, wff_model_set_option(&m, "dtinterval", 1, &err) == 0, "%s", err.message);
    double worst = 0;
    int steps = 0;
    for (int s = 0; s < 150; s++) {
        if (wff_model_advance(&m, 1e9, 1, &err)) {
            CHECK(st, 0, "step %d: %s", s, err.message);
            break;
        }
        /* the step estimated at this u (advance estimates right after moving u) */
        int worst_ref;
        m.em.reference_path = 1;
        double dt_ref = wff_elements_stable_step(&m.el, &m.em, m.mesh.xy, m.u, &worst_ref);
        m.em.reference_path = 0;
        double e = fabs(m.dt - m.dt_factor * dt_ref) / (m.dt_factor * dt_ref);
        worst = fmax(worst, m.dt_worst_element == worst_ref ? e : INFINITY);
        steps++;
    }
    CHECK(st, worst <= STEP_TOL, "solver run: a step differs from dtfactor x the reference "
          "estimate by %.3g", worst);
    printf("  stable step, solver run of %d steps re-estimating each: step vs reference %.1e\n",
           steps, worst);
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    random_states(&st, 7, 5, 1);   /* 70 triangles: 8 blocks, the last of 6 */
    random_states(&st, 23, 25, 2); /* 1150: enough for a thread team */
    wrong_block_caught(&st);
    solver_steps(&st);
    return check_summary(&st, "test_stable_step");
}

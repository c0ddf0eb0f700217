/* The blocked quad4 force pass (plugin/membrane_quad.c) against the plain
 * per-point path (reference_path = 1) on random states of a jittered quad
 * mesh with an odd number of quads (a part-filled last block): forces,
 * stored energy, dissipation and the γᶠ update to round-off; 2 threads
 * against 1 to round-off, and the same bits twice; a NaN or a collapsed quad
 * reported at the same element and point as the plain path. */
#include "check.h"
#include "test_meshes.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

static double uniform(uint64_t *s) /* in [−1, 1) */
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 4503599627370496.0 - 1;
}

/* A random sheared, stretched, wrinkled, compacted state and random γᶠ. */
static void random_state(wff_model *m, uint64_t seed)
{
    for (int n = 0; n < m->n_nodes; n++) {
        double x = m->mesh.xy[2 * n], y = m->mesh.xy[2 * n + 1];
        m->u[D * n] = 0.01 * x + 0.03 * y + 2e-5 * uniform(&seed);
        m->u[D * n + 1] = 0.005 * y + 2e-5 * uniform(&seed);
        m->u[D * n + 2] = 1e-3 * sin(90 * x) * cos(70 * y) + 1e-4 * uniform(&seed);
        m->u[D * n + 3] = -9e-6 + 8e-6 * uniform(&seed);
        m->u[D * n + 4] = -24e-6 + 8e-6 * uniform(&seed);
    }
    for (int q = 0; q < 4 * m->el.n_quads; q++)
        m->state[q] = 0.02 * uniform(&seed);
}

typedef struct pass {
    double *f, *gamma_f;
    wff_force_totals t;
} pass;

static pass run_pass(wff_model *m, int reference, int threads, double dt)
{
    wff_error err;
    pass p;
    size_t nq = (size_t)(4 * m->el.n_quads);
    p.f = calloc((size_t)m->n_dofs, sizeof(double));
    p.gamma_f = malloc(nq * sizeof(double));
    memcpy(p.gamma_f, m->state, nq * sizeof(double));
    m->em.reference_path = reference;
    wff_elements_set_threads(&m->el, threads, &err);
    m->el.team_min_tris = 0; /* a team on this small mesh too: the threaded pass is under test */
    wff_elements_forces(&m->el, &m->em, m->mesh.xy, m->u, p.gamma_f, dt, p.f, &p.t);
    m->em.reference_path = 0;
    wff_elements_set_threads(&m->el, 1, &err);
    return p;
}

static void pass_free(pass *p)
{
    free(p->f);
    free(p->gamma_f);
}

/* Largest differences of b from a: forces over the largest force, γᶠ (over
 * max(|γᶠ|, 1e-3)), energy and dissipation over the energy. */
static double pass_difference(const wff_model *m, const pass *a, const pass *b)
{
    double scale = 0, df = 0, dg = 0;
    for (int i = 0; i < m->n_dofs; i++) {
        scale = fmax(scale, fabs(a->f[i]));
        df = fmax(df, fabs(b->f[i] - a->f[i]));
    }
    for (int q = 0; q < 4 * m->el.n_quads; q++)
        dg = fmax(dg, fabs(b->gamma_f[q] - a->gamma_f[q]) / fmax(fabs(a->gamma_f[q]), 1e-3));
    double W = fabs(a->t.internal_energy);
    double de = fabs(b->t.internal_energy - a->t.internal_energy) / W;
    double dd = fabs(b->t.dissipated - a->t.dissipated) / W;
    return fmax(fmax(df / scale, dg), fmax(de, dd));
}

static int make_model(check_state *st, wff_model *m)
{
    /* 23 × 13 = 299 quads: an odd count (the last block half full) and enough
     * for the threaded pass */
    test_rect r = {0, 0.23, 0, 0.13, 23, 13, TEST_MESH_QUAD, 0, 0.25, 777};
    wff_error err;
    int rc = test_model_rect(m, &r, KEVLAR, &err);
    CHECK(st, rc == 0, "%s", err.message);
    if (rc)
        return -1;
    const double F_pre[4] = {1.00396, 0.001, -0.002, 1.0135}, dA0[2] = {-9.3e-6, -23.8e-6};
    rc = wff_model_set_preload(m, F_pre, dA0, &err);
    CHECK(st, rc == 0, "preload: %s", rc ? err.message : "");
    CHECK(st, m->el.n_quads == 299 && m->el.n_tris == 0, "%d quads", m->el.n_quads);
    CHECK(st, m->mat.cell->evaluate_point_block != NULL,
          "the King cell offers evaluate_point_block (else this test compares plain to plain)");
    return rc ? -1 : 0;
}

/* 1. Blocked = plain on random states, with γᶠ held (dt = 0) and advanced. */
static void check_blocked_vs_plain(check_state *st)
{
    wff_model m;
    if (make_model(st, &m))
        return;
    double worst = 0, dissipated = 0;
    for (int s = 0; s < 6; s++) {
        random_state(&m, 1000 + (uint64_t)s);
        double dt = s % 2 ? 2e-7 : 0;
        pass ref = run_pass(&m, 1, 1, dt), fast = run_pass(&m, 0, 1, dt);
        CHECK(st, ref.t.bad_element < 0 && fast.t.bad_element < 0,
              "state %d: no bad point (plain %d, blocked %d)", s, ref.t.bad_element,
              fast.t.bad_element);
        double d = pass_difference(&m, &ref, &fast);
        worst = fmax(worst, d);
        if (dt > 0)
            dissipated = fmax(dissipated, ref.t.dissipated);
        int moved = 0;
        for (int q = 0; q < 4 * m.el.n_quads; q++)
            moved += ref.gamma_f[q] != m.state[q];
        CHECK(st, dt == 0 ? moved == 0 : moved > 0, "state %d: %d points' gamma_f moved", s,
              moved);
        pass_free(&ref);
        pass_free(&fast);
    }
    printf("  blocked vs plain quads: largest relative difference %.2e (dissipation up to %.3g J)\n",
           worst, dissipated);
    CHECK(st, worst <= 1e-12, "blocked quad path = plain path to round-off: %.3g", worst);
    CHECK(st, dissipated > 0, "the states with dt > 0 dissipate (the flow rule is exercised)");
    wff_model_free(&m);
}

/* 2. Threads: 2 = 1 to round-off, γᶠ the same bits, 2 threads the same bits twice. */
static void check_threads(check_state *st)
{
    wff_model m;
    if (make_model(st, &m))
        return;
    if (m.el.max_threads < 2) {
        printf("  threads: OpenMP offers 1 thread here; the 2-thread check is skipped\n");
        wff_model_free(&m);
        return;
    }
    random_state(&m, 4242);
    pass one = run_pass(&m, 0, 1, 1e-7), two = run_pass(&m, 0, 2, 1e-7);
    pass again = run_pass(&m, 0, 2, 1e-7);
    double d = pass_difference(&m, &one, &two);
    printf("  threads: 2 vs 1 thread, quads, differ by %.2e\n", d);
    CHECK(st, d <= 1e-12, "2 threads = 1 thread to round-off: %.3g", d);
    CHECK(st, memcmp(one.gamma_f, two.gamma_f, sizeof(double) * 4 * (size_t)m.el.n_quads) == 0,
          "gamma_f updated identically by 1 and 2 threads");
    CHECK(st, memcmp(two.f, again.f, sizeof(double) * (size_t)m.n_dofs) == 0 &&
                  two.t.internal_energy == again.t.internal_energy &&
                  two.t.dissipated == again.t.dissipated,
          "2 threads give the same bits twice");
    pass_free(&one);
    pass_free(&two);
    pass_free(&again);
    wff_model_free(&m);
}

/* 3. A NaN displacement and a collapsed quad: the same first bad element,
 * point and status as the plain path, 1 and 2 threads. */
static void check_bad_points(check_state *st)
{
    for (int c = 0; c < 2; c++) {
        wff_model m;
        if (make_model(st, &m))
            return;
        random_state(&m, 99);
        /* NaN: a quad in the middle; collapse: a quad of the bottom row, every node
         * onto the line y = 0, z = 0 (exact zeros: the yarns exactly parallel) */
        int e = c ? 11 : 150;
        const int *node = m.el.quad + 4 * e;
        if (c == 0)
            m.u[D * node[2] + 1] = NAN;
        else
            for (int a = 0; a < 4; a++) {
                m.u[D * node[a] + 1] = -m.mesh.xy[2 * node[a] + 1];
                m.u[D * node[a] + 2] = 0;
            }
        int threads = m.el.max_threads >= 2 ? 2 : 1;
        pass ref = run_pass(&m, 1, 1, 0), fast = run_pass(&m, 0, threads, 0);
        printf("  %s: plain path element %d point %d status %d, blocked %d %d %d\n",
               c ? "collapsed quad" : "NaN", ref.t.bad_element, ref.t.bad_point,
               ref.t.bad_status, fast.t.bad_element, fast.t.bad_point, fast.t.bad_status);
        CHECK(st, ref.t.bad_element >= 0, "%s found by the plain path", c ? "collapse" : "NaN");
        CHECK(st, ref.t.bad_element == fast.t.bad_element && ref.t.bad_point == fast.t.bad_point &&
                      ref.t.bad_status == fast.t.bad_status,
              "%s: blocked path reports what the plain path reports", c ? "collapse" : "NaN");
        CHECK(st, fast.t.bad_status == (c ? WFF_POINT_DEGENERATE : WFF_POINT_NONFINITE),
              "status %d", fast.t.bad_status);
        pass_free(&ref);
        pass_free(&fast);
        wff_model_free(&m);
    }
}

int main(void)
{
    check_state st = {0, 0};
    check_blocked_vs_plain(&st);
    check_threads(&st);
    check_bad_points(&st);
    return check_summary(&st, "test_quad_block");
}

/* Stability at the edges of the explicit scheme (docs/limits.md):
 *   1. a clamped square struck by a light projectile stays bounded, energy
 *      balanced, at 0.8, 0.9 and 0.99 of the stable step;
 *   2. forced past it (dtfactor 1.2, 1.5, 2) the run is stopped by the
 *      instability detector, before any NaN, with a message naming the time,
 *      the step, the element that sets the stable step, a suggested step and
 *      a suggested -dtfactor;
 *   3. long run: a preloaded, clamped elastic square set vibrating (in-plane,
 *      transverse and crimp amplitudes) for ~1000 in-plane periods keeps its
 *      energy: the balance error stays small and does not grow;
 *   4. the start from a state out of equilibrium (a clamped 10 cm square of
 *      Kevlar released at rest from a 3 mm bump, its amplitudes not balanced):
 *      the energy error after one step converges as dt² (the half-step start,
 *      the integer-step kinetic energy and the balance's reference are
 *      second order). */
#include "check.h"
#include "test_meshes.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"
#include "wovenff/renumber.h"
#include "wovenff/state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define ELASTIC "tests/data/king_elastic.txt"
#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

static int clamped_square(check_state *st, wff_model *m, const char *material, int n,
                          double dtfactor)
{
    test_rect r = {-0.05, 0.05, -0.05, 0.05, n, n, TEST_MESH_TRI, 1, 0.2, 11};
    wff_error err;
    if (test_model_rect(m, &r, material, &err)) {
        CHECK(st, 0, "%s", err.message);
        return -1;
    }
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    int rc = 0;
    for (int g = 0; g < 4 && rc == 0; g++)
        for (int c = 0; c < 3 && rc == 0; c++)
            rc = wff_model_fix_group(m, edges[g], c, &err) < 0;
    if (rc == 0)
        rc = wff_model_set_option(m, "dtfactor", dtfactor, &err);
    CHECK(st, rc == 0, "setup: %s", err.message);
    if (rc)
        wff_model_free(m);
    return rc ? -1 : 0;
}

/* 1. and 2.: returns 0 if the run completed, 1 if it stopped (message in err). */
static int impact_adaptive(check_state *st, double dtfactor, int travel, int adaptive,
                           double *worst, long *steps, long *travel_steps, long *cuts,
                           wff_error *err);

static int impact(check_state *st, double dtfactor, int travel, double *worst, long *steps,
                  long *travel_steps, wff_error *err)
{
    long cuts;
    return impact_adaptive(st, dtfactor, travel, 0, worst, steps, travel_steps, &cuts, err);
}

static int impact_adaptive(check_state *st, double dtfactor, int travel, int adaptive,
                           double *worst, long *steps, long *travel_steps, long *cuts,
                           wff_error *err)
{
    wff_model m;
    *worst = 0;
    *steps = 0;
    if (clamped_square(st, &m, ELASTIC, 20, dtfactor))
        return -1;
    int rc = wff_model_set_option(&m, "travel_limit", travel, err) ||
             wff_model_set_option(&m, "adaptive_step", adaptive, err) ||
             wff_model_set_projectile(&m, 6.35e-3, 0.0005, 20, 0, err);
    CHECK(st, rc == 0, "%s", err->message);
    for (int block = 1; block <= 20 && rc == 0; block++) {
        rc = wff_model_advance(&m, block * 0.01e-3, 1000000, err);
        if (rc)
            break;
        wff_energies e;
        wff_model_energies(&m, &e);
        *worst = fmax(*worst, fabs(e.error));
    }
    *steps = m.step;
    *travel_steps = m.travel_steps;
    *cuts = m.step_cuts;
    wff_model_free(&m);
    return rc ? 1 : 0;
}

static void check_step_ladder(check_state *st)
{
    static const double below[] = {0.8, 0.9, 0.99};
    for (int i = 0; i < 3; i++) {
        double worst;
        long steps, travel_steps;
        wff_error err;
        int rc = impact(st, below[i], 1, &worst, &steps, &travel_steps, &err);
        printf("  dtfactor %.2f: %ld steps to 0.2 ms (%ld shortened by the travel limit), max "
               "|energy error| %.2e\n", below[i], steps, travel_steps, worst);
        CHECK(st, rc == 0, "dtfactor %g: %s", below[i], rc ? err.message : "");
        CHECK(st, worst < 2e-3, "dtfactor %g: energy error %g", below[i], worst);
    }
    /* Past the stable step. The estimate combines the membrane and amplitude
     * limits as a bound for the coupled system (1/dt² = 1/dt_m² + 1/dt_A²) and
     * is conservative by about 25 % here: 1.2 × it still runs (not asserted
     * either way), 1.5 × and 2 × it are past the true limit and must be caught
     * (the travel limit off: it shortens the steps where the growing mode, the
     * amplitudes, speeds up, and so holds these runs; checked below). */
    static const double above[] = {1.5, 2.0};
    for (int i = 0; i < 2; i++) {
        double worst;
        long steps, travel_steps;
        wff_error err;
        err.message[0] = 0;
        int held = impact(st, above[i], 1, &worst, &steps, &travel_steps, &err);
        printf("  dtfactor %.2f, travel limit on: %s after %ld steps (%ld shortened), max |energy "
               "error| %.2e\n", above[i], held ? "stopped" : "ran to the end", steps,
               travel_steps, worst);
        /* held by the travel limit, not accurate: 1.2e-2 at 1.5, 7.0e-2 at 2 (measured;
         * docs/limits.md "Time step"), below the detector's 50 % */
        CHECK(st, held == 1 || (travel_steps > 0 && worst < 0.5),
              "dtfactor %g with the travel limit: neither stopped nor held (error %g, %ld "
              "shortened steps)", above[i], worst, travel_steps);
        err.message[0] = 0;
        int rc = impact(st, above[i], 0, &worst, &steps, &travel_steps, &err);
        printf("  dtfactor %.2f: stopped after %ld steps: %s\n", above[i], steps, err.message);
        CHECK(st, rc == 1, "dtfactor %g: the run must stop as unstable", above[i]);
        static const char *const want[] = {"unstable", "t = ", "(step ", "triangle ",
                                           "suggested step ", "suggested -dtfactor 0.8"};
        for (int k = 0; k < 6; k++)
            CHECK(st, strstr(err.message, want[k]) != NULL, "dtfactor %g: message lacks '%s': %s",
                  above[i], want[k], err.message);
        CHECK(st, strstr(err.message, "NaN") == NULL, "caught before NaN: %s", err.message);
    }
    /* the adaptive step: the same runs past the bound, the travel limit off, go
     * back to the last good state with dtfactor halved and finish */
    for (int i = 0; i < 2; i++) {
        double worst;
        long steps, travel_steps, cuts;
        wff_error err;
        int rc = impact_adaptive(st, above[i], 0, 1, &worst, &steps, &travel_steps, &cuts, &err);
        printf("  dtfactor %.2f, travel limit off, adaptive step: %s after %ld steps, %ld cuts, "
               "max |energy error| %.2e\n", above[i], rc ? "stopped" : "ran to the end", steps,
               cuts, worst);
        CHECK(st, rc == 0, "adaptive step at dtfactor %g: %s", above[i], rc ? err.message : "");
        CHECK(st, cuts >= 1 && cuts <= 3, "adaptive step at dtfactor %g: %ld cuts", above[i], cuts);
        CHECK(st, worst < 2e-3, "adaptive step at dtfactor %g: energy error %g", above[i], worst);
    }
}

/* 3. Long run. Preload 1 N per yarn (the membrane then has transverse
 * stiffness), a smooth initial velocity in every DOF family, fixed edges. */
static void check_long_run(check_state *st)
{
    wff_material mat;
    wff_error err;
    wff_biaxial_state pre = {.stretch = {1, 1}};
    if (wff_material_load(ELASTIC, &mat, &err) || wff_preload_equal_force(&mat, 1.0, &pre, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    wff_model m;
    test_rect r = {0, 0.02, 0, 0.02, 6, 6, TEST_MESH_TRI, 1, 0.15, 3};
    if (test_model_rect(&m, &r, ELASTIC, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    double F[4] = {pre.stretch[0], 0, 0, pre.stretch[1]};
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    int rc = wff_model_set_preload(&m, F, pre.dA, &err);
    for (int g = 0; g < 4 && rc == 0; g++)
        for (int c = 0; c < 3 && rc == 0; c++)
            rc = wff_model_fix_group(&m, edges[g], c, &err) < 0;
    CHECK(st, rc == 0, "%s", err.message);
    if (rc) {
        wff_model_free(&m);
        return;
    }
    for (int n = 0; n < m.n_nodes; n++) {
        double x = m.mesh.xy[2 * n] / 0.02, y = m.mesh.xy[2 * n + 1] / 0.02;
        double s = sin(M_PI * x) * sin(M_PI * y);
        double *v = m.v + D * n;
        v[0] = 0.5 * s * cos(M_PI * y);
        v[1] = -0.3 * s * cos(M_PI * x);
        v[2] = 2.0 * s;
        v[3] = 0.02 * s;
        v[4] = -0.01 * s;
        for (int c = 0; c < 3; c++)
            if (m.dof_kind[D * n + c] != WFF_DOF_FREE)
                v[c] = 0;
    }
    /* in-plane period ~ 2L/c, c ~ 5 km/s: 8 µs; transverse ~ 0.3 ms */
    const int blocks = 40;
    const double t_end = 8e-3;
    double worst = 0, early = 0, late = 0;
    for (int b = 1; b <= blocks && rc == 0; b++) {
        rc = wff_model_advance(&m, b * t_end / blocks, 100000000, &err);
        CHECK(st, rc == 0, "long run: %s", rc ? err.message : "");
        wff_energies e;
        wff_model_energies(&m, &e);
        worst = fmax(worst, fabs(e.error));
        if (b <= blocks / 4)
            early = fmax(early, fabs(e.error));
        if (b > 3 * blocks / 4)
            late = fmax(late, fabs(e.error));
    }
    wff_energies e;
    wff_model_energies(&m, &e);
    printf("  long run: %d triangles, %ld steps to %.0f ms (~%.0f in-plane periods, ~%.0f "
           "transverse), max |energy error| %.2e (first quarter %.2e, last quarter %.2e); "
           "kinetic %.3e J, internal %.3e J\n", m.el.n_tris, m.step, 1e3 * m.time, m.time / 8e-6,
           m.time / 0.3e-3, worst, early, late,
           e.kinetic_inplane + e.kinetic_transverse + e.kinetic_amplitude, e.internal);
    CHECK(st, worst < 1e-3, "long run energy error %g", worst);
    CHECK(st, late < 3 * early + 1e-5, "no drift: first quarter %g, last quarter %g", early, late);
    wff_model_free(&m);
}


/* The bumped square of the issue "Stable from any state" (a clamped 10 cm
 * square of Kevlar, 12 x 12 x 2 triangles, released at rest from a 3 mm bump
 * with in-plane and amplitude parts of its shape) into m at dtfactor:
 * preload 0 none, 1 the 1 N preload with its amplitudes overwritten by the
 * bump's, 2 the preload's amplitudes kept and the bump's added. 0, or -1 with
 * err set (m freed). */
static int bump_model(wff_model *m, double dtfactor, int preload, wff_error *err)
{
    test_rect r = {0, 0.1, 0, 0.1, 12, 12, TEST_MESH_TRI, 0, 0, 1};
    if (test_model_rect(m, &r, KEVLAR, err))
        return -1;
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    int rc = 0;
    for (int g = 0; g < 4 && rc == 0; g++)
        for (int c = 0; c < 3 && rc == 0; c++)
            rc = wff_model_fix_group(m, edges[g], c, err) < 0;
    if (rc == 0)
        rc = wff_model_set_option(m, "dtfactor", dtfactor, err);
    double dA0[2] = {0, 0};
    if (rc == 0 && preload) {
        wff_biaxial_state bs;
        memset(&bs, 0, sizeof bs);
        bs.stretch[0] = bs.stretch[1] = 1;
        rc = wff_preload_equal_force(&m->mat, 1.0, &bs, err);
        double Fp[4] = {bs.stretch[0], 0, 0, bs.stretch[1]};
        dA0[0] = bs.dA[0];
        dA0[1] = bs.dA[1];
        if (rc == 0)
            rc = wff_model_set_preload(m, Fp, dA0, err);
    }
    double *u = calloc((size_t)m->n_dofs, sizeof(double));
    for (int n = 0; n < m->n_nodes && rc == 0; n++) {
        double x = m->mesh.xy[2 * n], y = m->mesh.xy[2 * n + 1];
        double s = 16 * x * (0.1 - x) * y * (0.1 - y) / 1e-4;
        double bump[D] = {1e-5 * s, 1e-5 * s, 3e-3 * s, -5e-6 * s, -5e-6 * s};
        if (preload == 2) {
            bump[3] += dA0[0];
            bump[4] += dA0[1];
        }
        memcpy(u + D * wff_model_user_node(m, n), bump, sizeof bump); /* (the set's order) */
    }
    if (rc == 0)
        rc = wff_model_set_vector(m, "u", u, err);
    free(u);
    if (rc)
        wff_model_free(m);
    return rc ? -1 : 0;
}

/* 4. The bumped square released at rest: error after the first step at dtfactor
 * 0.1, 0.05, 0.025. With the integer-step kinetic energy alone it was −(ωΔt)²/4
 * of the amplitude oscillation the release excites (0.74 % at 0.1), falling as
 * Δt²; the balance's kinetic energy ½ m v^{n−½}·v^{n+½} (docs/model.md §14)
 * leaves the scheme's own error: at least second order, and below 1e-4 at 0.1. */
static double bump_one_step(check_state *st, double dtfactor)
{
    wff_model m;
    wff_error err;
    if (bump_model(&m, dtfactor, 0, &err)) {
        CHECK(st, 0, "bumped square, dtfactor %g: %s", dtfactor, err.message);
        return NAN;
    }
    int rc = wff_model_advance(&m, 1e9, 1, &err);
    CHECK(st, rc == 0, "bumped square, dtfactor %g: %s", dtfactor, rc ? err.message : "");
    wff_energies e;
    wff_model_energies(&m, &e);
    wff_model_free(&m);
    return rc ? NAN : e.error;
}

static void check_bump_start(check_state *st)
{
    double e1 = bump_one_step(st, 0.1), e2 = bump_one_step(st, 0.05),
           e3 = bump_one_step(st, 0.025);
    printf("  bumped square from rest, energy error after one step: %.4e (0.1), %.4e (0.05), "
           "%.4e (0.025): ratios %.3f, %.3f\n", e1, e2, e3, e1 / e2, e2 / e3);
    CHECK(st, fabs(e1 / e2) > 3.8 && fabs(e2 / e3) > 3.8,
          "one-step energy error not second order: ratios %g, %g", e1 / e2, e2 / e3);
    CHECK(st, fabs(e1) < 1e-4, "one-step energy error at 0.1 of the estimate: %g", e1);
}

/* 5. The bumped square of the issue "Stable from any state", released at rest
 * (no preload; the 1 N preload with its amplitudes overwritten by the bump's,
 * each yarn ~50 N out of balance; the preload's amplitudes kept and the bump's
 * added): 10,000 built-in steps at dtfactor 0.8 and 0.9, the energy error below
 * 1e-3. Without the travel limit these stopped as unstable at steps 108, 10 and
 * 214 (0.8): the released amplitudes swing through several lengths 1/a of the
 * compaction exponential in one step; with it at 0.625 of 1/a they ran with
 * errors of 7.3e-3-2.6e-2, the scheme's on the swing (docs/model.md §12). */
static void check_bump_long(check_state *st)
{
    static const double factors[] = {0.8, 0.9};
    for (int f = 0; f < 2; f++)
        for (int preload = 0; preload < 3; preload++) {
            wff_model m;
            wff_error err;
            if (bump_model(&m, factors[f], preload, &err)) {
                CHECK(st, 0, "bumped square, preload %d: %s", preload, err.message);
                return;
            }
            int rc = 0;
            double worst = 0;
            for (long k = 0; k < 10000 && rc == 0; k++) {
                rc = wff_model_advance(&m, 1e9, 1, &err);
                wff_energies e;
                wff_model_energies(&m, &e);
                worst = fmax(worst, fabs(e.error));
            }
            static const char *const what[] = {"no preload", "preload, amplitudes overwritten",
                                               "preload, amplitudes kept"};
            printf("  bumped square, %s, dtfactor %.1f: %ld steps to %.4g ms (%ld shortened by the "
                   "travel limit), max |energy error| %.3g\n", what[preload], factors[f], m.step,
                   1e3 * m.time, m.travel_steps, worst);
            CHECK(st, rc == 0 && m.step == 10000, "bumped square, %s, dtfactor %g: %s",
                  what[preload], factors[f], rc ? err.message : "");
            CHECK(st, worst < 1e-3, "bumped square, %s, dtfactor %g: energy error %g",
                  what[preload], factors[f], worst);
            wff_model_free(&m);
        }
}

/* 6. Steps that change. A clamped square of the elastic cell moving at 1e-4 m/s
 * (strains ~1e-8), the stable step re-estimated every step, run 3000 steps
 * twice: at dtfactor 0.9 throughout, and with it set between advances to 0.3 ...
 * 0.9 every 50 steps. With the stagger's shift (docs/model.md §14) the changes
 * add nothing to the balance's error beyond the state's own (its nonlinearity,
 * the same in both); with the shift taken out they put it off by the moves of
 * (Δt²/8) Σ f²/m. *worst: the balance's, *unshifted: without the shift. */
static int run_step_changes(int vary, double *worst, double *unshifted, wff_error *err)
{
    wff_model m;
    test_rect r = {0, 0.02, 0, 0.02, 6, 6, TEST_MESH_TRI, 1, 0.15, 3};
    if (test_model_rect(&m, &r, ELASTIC, err))
        return -1;
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    int rc = wff_model_set_option(&m, "dtinterval", 1, err);
    for (int g = 0; g < 4 && rc == 0; g++)
        for (int c = 0; c < 3 && rc == 0; c++)
            rc = wff_model_fix_group(&m, edges[g], c, err) < 0;
    for (int n = 0; n < m.n_nodes; n++) {
        double x = m.mesh.xy[2 * n] / 0.02, y = m.mesh.xy[2 * n + 1] / 0.02;
        double s = sin(M_PI * x) * sin(M_PI * y), *v = m.v + D * n;
        v[0] = 1e-4 * s * cos(M_PI * y);
        v[1] = -0.6e-4 * s * cos(M_PI * x);
        v[3] = 1e-6 * s;
        for (int c = 0; c < 3; c++)
            if (m.dof_kind[D * n + c] != WFF_DOF_FREE)
                v[c] = 0;
    }
    static const double factors[] = {0.9, 0.3, 0.7, 0.45, 0.85, 0.6};
    *worst = *unshifted = 0;
    if (rc == 0)
        rc = wff_model_set_option(&m, "dtfactor", 0.9, err);
    for (int block = 0; block < 60 && rc == 0; block++) {
        if (vary && block > 0)
            rc = wff_model_set_option(&m, "dtfactor", factors[block % 6], err);
        for (int k = 0; k < 50 && rc == 0; k++) {
            rc = wff_model_advance(&m, 1e9, 1, err);
            wff_energies e;
            wff_model_energies(&m, &e);
            *worst = fmax(*worst, fabs(e.error));
            *unshifted = fmax(*unshifted, fabs(e.error - m.stagger_shift * m.symmetry_factor / e.reference));
        }
    }
    wff_model_free(&m);
    return rc ? -1 : 0;
}

static void check_step_changes(check_state *st)
{
    wff_error err;
    double held, held_unshifted, varied, varied_unshifted;
    if (run_step_changes(0, &held, &held_unshifted, &err) ||
        run_step_changes(1, &varied, &varied_unshifted, &err)) {
        CHECK(st, 0, "steps that change: %s", err.message);
        return;
    }
    printf("  steps that change (3000 steps, the stable step re-estimated every step): max |energy "
           "error| at dtfactor 0.9 %.2e (without the stagger's shift %.2e); dtfactor set to 0.3-0.9 "
           "every 50 steps %.2e (without the shift %.2e)\n", held, held_unshifted, varied,
           varied_unshifted);
    CHECK(st, varied < 2 * held, "steps that change: energy error %g, at a held dtfactor %g",
          varied, held);
    CHECK(st, varied_unshifted > 1e3 * varied, "steps that change: without the shift %g (the "
          "changes did not move the stagger: the check checks nothing)", varied_unshifted);
}

/* 7. Impulses at steps that change. The small-strain square of 6 (the elastic
 * cell at strains ~1e-8: a linear system to the balance's digits), struck at
 * its centre by a light projectile at 2e-4 m/s with friction (the contact's
 * normal and friction impulses every step it touches), its left edge held by
 * the friction clamp instead of fixed (the clamp's impulses), the stable step
 * re-estimated every step and dtfactor set to 0.3-0.9 every 50 steps. The
 * impulses' work booked at the trapezoidal rule's measure after every
 * correction, and the contact forces out of the balance's stagger
 * (impulse_stagger, docs/model.md §14), keep the balance to the state's own
 * error; *worst: the balance's, *unbooked: without the impulses' share of the
 * stagger (what the measure read before), *dissipated: the contacts' and
 * friction's, J. */
static int run_impulses(int vary, double *worst, double *unbooked, double *dissipated,
                        long *touching, wff_error *err)
{
    wff_model m;
    test_rect r = {0, 0.02, 0, 0.02, 6, 6, TEST_MESH_TRI, 1, 0, 3}; /* (a node at the centre) */
    if (test_model_rect(&m, &r, ELASTIC, err))
        return -1;
    static const char *const edges[] = {"right", "bottom", "top"};
    int rc = wff_model_set_option(&m, "dtinterval", 1, err);
    for (int g = 0; g < 3 && rc == 0; g++)
        for (int c = 0; c < 3 && rc == 0; c++)
            rc = wff_model_fix_group(&m, edges[g], c, err) < 0;
    if (rc == 0)
        rc = wff_model_clamp_friction(&m, "left", 1e-4, 0.3, err) < 0;
    if (rc == 0)
        rc = wff_model_set_projectile(&m, 0.004, 1e-3, 2e-4, 0.3, err);
    if (rc == 0)
        rc = wff_model_set_impact_point(&m, 0.01, 0.01, err);
    for (int n = 0; n < m.n_nodes && rc == 0; n++) {
        double x = m.mesh.xy[2 * n] / 0.02, y = m.mesh.xy[2 * n + 1] / 0.02;
        double s = sin(M_PI * x) * sin(M_PI * y), *v = m.v + D * n;
        v[0] = 1e-4 * s * cos(M_PI * y);
        v[1] = -0.6e-4 * s * cos(M_PI * x);
        for (int c = 0; c < 3; c++)
            if (m.dof_kind[D * n + c] != WFF_DOF_FREE)
                v[c] = 0;
    }
    static const double factors[] = {0.9, 0.3, 0.7, 0.45, 0.85, 0.6};
    *worst = *unbooked = 0;
    *touching = 0;
    if (rc == 0)
        rc = wff_model_set_option(&m, "dtfactor", 0.9, err);
    for (int block = 0; block < 60 && rc == 0; block++) {
        if (vary && block > 0)
            rc = wff_model_set_option(&m, "dtfactor", factors[block % 6], err);
        for (int k = 0; k < 50 && rc == 0; k++) {
            rc = wff_model_advance(&m, 1e9, 1, err);
            wff_energies e;
            wff_model_energies(&m, &e);
            *worst = fmax(*worst, fabs(e.error));
            *unbooked = fmax(*unbooked, fabs(e.error - e.impulse_stagger / e.reference));
            *touching += m.projectile.n_contact > 0;
        }
    }
    wff_energies e;
    wff_model_energies(&m, &e);
    *dissipated = e.dissipated_friction;
    wff_model_free(&m);
    return rc ? -1 : 0;
}

static void check_impulses(check_state *st)
{
    wff_error err;
    double held, held_unbooked, held_d, varied, varied_unbooked, varied_d;
    long held_touch, varied_touch;
    if (run_impulses(0, &held, &held_unbooked, &held_d, &held_touch, &err) ||
        run_impulses(1, &varied, &varied_unbooked, &varied_d, &varied_touch, &err)) {
        CHECK(st, 0, "impulses at steps that change: %s", err.message);
        return;
    }
    printf("  impulses (projectile contact and friction clamp on the small-strain square, 3000 "
           "steps): max |energy error| at dtfactor 0.9 %.2e (without the impulses' stagger "
           "%.2e), %ld steps in contact, dissipated %.3e J; dtfactor set to 0.3-0.9 every 50 "
           "steps %.2e (without %.2e), %ld in contact, dissipated %.3e J\n", held, held_unbooked,
           held_touch, held_d, varied, varied_unbooked, varied_touch, varied_d);
    CHECK(st, held_touch > 100 && varied_touch > 100,
          "impulses: the projectile touched the square on %ld and %ld steps only", held_touch,
          varied_touch);
    CHECK(st, held_d > 0 && varied_d > 0, "impulses: dissipation %g, %g J not positive", held_d,
          varied_d);
    CHECK(st, held < 1e-6 && varied < 1e-6, "impulses: energy error %g (held), %g (varied)",
          held, varied);
    CHECK(st, held_unbooked > 100 * held, "impulses: without the impulses' share of the "
          "stagger %g against %g (the contact gave nothing to check)", held_unbooked, held);
}

int main(void)
{
    check_state st = {0, 0};
    check_step_ladder(&st);
    check_long_run(&st);
    check_bump_start(&st);
    check_bump_long(&st);
    check_step_changes(&st);
    check_impulses(&st);
    return check_summary(&st, "test_stability");
}

/* The Lambert–Jonas fit (plugin/limit_fit.c):
 *  - the law itself: 0 at and below V_bl, a (V^p − V_bl^p)^(1/p) above;
 *  - noiseless data from a known law (stopped runs below it, perforating
 *    ones above) gives V_bl, a, p back to 1e-6, for several laws;
 *  - with Gaussian noise on V_r (seeded), over 400 seeds the truth lies
 *    within 2 reported standard errors of the estimate in at least 88 % of
 *    them for each parameter (t with 8 degrees of freedom: 92 % nominal, a
 *    binomial sd of 1.4 %; they give 93.5, 91.8 and 95.3 % for V_bl, a, p,
 *    the first 100 seeds alone 91, 85 and 92 %), and the residual
 *    standard deviation is the noise's (within 40 %);
 *  - the check can fail: the same data admit V_bl 10 % off the truth within
 *    2 standard errors in at most 3 % of the seeds, and a wrong law (convex
 *    in V_s, not of the family) leaves a residual standard deviation more
 *    than twice the noise;
 *  - V50 from the bracket: mid-point and half gap;
 *  - bad input refused with a message naming what: fewer than 3 perforating
 *    runs, non-finite values, negative speeds. */
#include "check.h"
#include "rng.h"
#include "wovenff/limit.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define N_RUNS 14
#ifndef SEEDS
#define SEEDS 400
#endif

/* Runs at n speeds from lo to hi (even spacing), residual from the law plus
 * noise (m/s; a noisy residual below 0 is a stopped run: 0). */
static void make_runs(double vbl, double a, double p, double lo, double hi, int n, double noise,
                      wff_rng *rng, double *vs, double *vr)
{
    for (int i = 0; i < n; i++) {
        vs[i] = lo + (hi - lo) * i / (n - 1);
        double r = wff_lambert_jonas(vs[i], vbl, a, p);
        if (r > 0 && noise > 0)
            r = fmax(r + noise * wff_rng_normal(rng), 0);
        vr[i] = r;
    }
}

static void test_law(check_state *st)
{
    CHECK(st, wff_lambert_jonas(100, 100, 0.9, 2) == 0, "at V_bl");
    CHECK(st, wff_lambert_jonas(50, 100, 0.9, 2) == 0, "below V_bl");
    CHECK_CLOSE(st, wff_lambert_jonas(200, 100, 0.9, 2), 0.9 * sqrt(30000.0), 1e-14, 0, "p = 2");
    CHECK_CLOSE(st, wff_lambert_jonas(200, 100, 0.8, 1), 80, 1e-14, 0, "p = 1");
}

static void test_noiseless(check_state *st)
{
    /* V_bl, a, p, the runs' speeds from lo to hi x V_bl (450, 1.2, 6: the law
     * passes the striking speed above 482 m/s; its runs stop at 475 m/s, as
     * no projectile leaves faster than it struck and the fit refuses that) */
    static const double laws[][5] = {{120, 0.9, 2.0, 0.6, 2.2}, {300, 1.0, 1.5, 0.6, 2.2},
                                     {80, 0.7, 3.5, 0.6, 2.2}, {450, 1.2, 6.0, 0.9, 1.055}};
    for (size_t k = 0; k < sizeof laws / sizeof *laws; k++) {
        double vs[N_RUNS], vr[N_RUNS];
        double vbl = laws[k][0], a = laws[k][1], p = laws[k][2];
        make_runs(vbl, a, p, laws[k][3] * vbl, laws[k][4] * vbl, N_RUNS, 0, NULL, vs, vr);
        wff_limit_fit f;
        wff_error err;
        int rc = wff_limit_fit_run(vs, vr, N_RUNS, &f, &err);
        CHECK(st, rc == 0, "law %zu: %s", k, rc ? err.message : "");
        if (rc)
            continue;
        CHECK_CLOSE(st, f.value[WFF_LIMIT_VBL], vbl, 1e-6, 0, "noiseless V_bl");
        CHECK_CLOSE(st, f.value[WFF_LIMIT_A], a, 1e-6, 0, "noiseless a");
        CHECK_CLOSE(st, f.value[WFF_LIMIT_P], p, 1e-6, 0, "noiseless p");
        CHECK(st, f.residual_sd < 1e-6 * vbl, "law %zu: residual sd %g m/s", k, f.residual_sd);
        CHECK(st, f.n_perforated + f.n_stopped == N_RUNS && f.n_mixed == 0, "counts");
        CHECK(st, f.bracket_low < vbl && vbl < f.bracket_high, "bracket [%g, %g] holds %g",
              f.bracket_low, f.bracket_high, vbl);
        /* V50 from the bracket: the runs' mid-point and half gap */
        CHECK_CLOSE(st, f.v50_bracket, 0.5 * (f.highest_stopped + f.lowest_perforated), 1e-15, 0,
                    "V50 bracket");
        CHECK(st, fabs(f.v50_bracket - vbl) <= f.v50_bracket_half_gap, "V50 bracket %g +- %g vs %g",
              f.v50_bracket, f.v50_bracket_half_gap, vbl);
    }
}

static void test_noise(check_state *st)
{
    const double vbl = 150, a = 0.85, p = 2.2, noise = 3; /* m/s */
    int inside[3] = {0, 0, 0}, seeds = SEEDS, fitted = 0, off_inside = 0;
    double sd_sum = 0, se_sum = 0;
    for (int seed = 1; seed <= seeds; seed++) {
        wff_rng rng = {0x9E3779B97F4A7C15ULL * (uint64_t)seed};
        double vs[N_RUNS], vr[N_RUNS];
        make_runs(vbl, a, p, 0.7 * vbl, 2.0 * vbl, N_RUNS, noise, &rng, vs, vr);
        wff_limit_fit f;
        wff_error err;
        if (wff_limit_fit_run(vs, vr, N_RUNS, &f, &err)) {
            CHECK(st, 0, "seed %d: %s", seed, err.message);
            continue;
        }
        fitted++;
        double truth[3] = {vbl, a, p};
        for (int j = 0; j < 3; j++)
            inside[j] += fabs(f.value[j] - truth[j]) <= 2 * f.std_error[j];
        off_inside += fabs(f.value[WFF_LIMIT_VBL] - 1.1 * vbl) <= 2 * f.std_error[WFF_LIMIT_VBL];
        sd_sum += f.residual_sd;
        se_sum += f.std_error[WFF_LIMIT_VBL];
        CHECK(st, f.std_error[WFF_LIMIT_VBL] > 0, "seed %d: se(V_bl) %g m/s", seed,
              f.std_error[WFF_LIMIT_VBL]);
    }
    CHECK(st, fitted == seeds, "fitted %d of %d", fitted, seeds);
    static const char *const names[3] = {"V_bl", "a", "p"};
    for (int j = 0; j < 3; j++) {
        printf("noise %g m/s: truth of %s within 2 SE in %d of %d seeds\n", noise, names[j],
               inside[j], seeds);
        CHECK(st, inside[j] >= 88 * seeds / 100, "%s inside 2 SE in only %d of %d", names[j], inside[j],
              seeds);
    }
    printf("V_bl 10 %% off within 2 SE in %d of %d seeds; mean residual sd %g m/s (noise %g)\n",
           off_inside, seeds, sd_sum / seeds, noise);
    CHECK(st, off_inside <= 3 * seeds / 100, "a wrong V_bl admitted in %d seeds", off_inside);
    CHECK_CLOSE(st, sd_sum / seeds, noise, 0.4, 0, "mean residual sd vs noise");
    printf("mean se(V_bl) %g m/s (V_bl %g m/s)\n", se_sum / seeds, vbl);
    CHECK(st, se_sum / seeds < 0.03 * vbl, "mean se(V_bl) %g m/s", se_sum / seeds);

    /* a law not of the family: V_r = 0.6 (V − V_bl)² / V_bl above V_bl, convex
     * in V where every a (V^p − V_bl^p)^(1/p) with p >= 1 is concave */
    wff_rng rng = {12345};
    double vs[N_RUNS], vr[N_RUNS];
    for (int i = 0; i < N_RUNS; i++) {
        vs[i] = vbl * (0.7 + 1.3 * i / (N_RUNS - 1));
        vr[i] = vs[i] > vbl ? 0.6 * (vs[i] - vbl) * (vs[i] - vbl) / vbl + noise * wff_rng_normal(&rng) : 0;
        vr[i] = fmax(vr[i], 0);
    }
    wff_limit_fit f;
    wff_error err;
    int rc = wff_limit_fit_run(vs, vr, N_RUNS, &f, &err);
    CHECK(st, rc == 0, "wrong law: %s", rc ? err.message : "");
    printf("wrong law: residual sd %g m/s (noise %g)\n", f.residual_sd, noise);
    CHECK(st, rc || f.residual_sd > 2 * noise, "wrong law fitted with residual sd %g m/s",
          f.residual_sd);
}

static void test_bad_input(check_state *st)
{
    double vs[5] = {100, 120, 140, 160, 180}, vr[5] = {0, 0, 0, 30, 50};
    wff_limit_fit f;
    wff_error err;
    CHECK(st, wff_limit_fit_run(vs, vr, 5, &f, &err) != 0, "2 perforating runs accepted");
    CHECK(st, strstr(err.message, "2 perforating runs") && strstr(err.message, "at least 3"),
          "message: %s", err.message);
    vr[2] = 10;
    CHECK(st, wff_limit_fit_run(vs, vr, 5, &f, &err) == 0, "3 perforating runs: %s", err.message);
    CHECK(st, isnan(f.std_error[0]), "3 points: no residual variance, se %g", f.std_error[0]);
    vr[1] = NAN;
    CHECK(st, wff_limit_fit_run(vs, vr, 5, &f, &err) != 0, "NaN accepted");
    CHECK(st, strstr(err.message, "run 2") && strstr(err.message, "not a finite number"),
          "message: %s", err.message);
    vr[1] = 0;
    vs[4] = INFINITY;
    CHECK(st, wff_limit_fit_run(vs, vr, 5, &f, &err) != 0, "inf accepted");
    CHECK(st, strstr(err.message, "run 5"), "message: %s", err.message);
    vs[4] = 180;
    vr[0] = -1;
    CHECK(st, wff_limit_fit_run(vs, vr, 5, &f, &err) != 0, "negative residual accepted");
    CHECK(st, strstr(err.message, "run 1") && strstr(err.message, ">= 0"), "message: %s",
          err.message);
    vr[0] = 0;
    vr[3] = vs[3] * 1.01; /* a residual above its striking speed: no projectile does that */
    CHECK(st, wff_limit_fit_run(vs, vr, 5, &f, &err) != 0, "residual above striking accepted");
    CHECK(st, strstr(err.message, "run 4") && strstr(err.message, "above the striking speed"),
          "message: %s", err.message);
    vr[3] = vs[3]; /* equal: allowed (nothing lost) */
    CHECK(st, wff_limit_fit_run(vs, vr, 5, &f, &err) == 0, "residual = striking refused: %s",
          err.message);
    double v50, gap;
    double bs[3] = {100, 110, 130}, br[3] = {0, 0, 20};
    CHECK(st, wff_limit_bracket(bs, br, 3, &v50, &gap) == 0 && v50 == 120 && gap == 10,
          "bracket %g +- %g", v50, gap);
    br[0] = br[1] = 5;
    CHECK(st, wff_limit_bracket(bs, br, 3, &v50, &gap) != 0 && isnan(v50), "no stopped run");
}

int main(void)
{
    check_state st = {0, 0};
    test_law(&st);
    test_noiseless(&st);
    test_noise(&st);
    test_bad_input(&st);
    return check_summary(&st, "test_limit_fit");
}

/* The MIL-STD-662F sequence and V50 (plugin/mil662.c), on synthetic shooters:
 *  - a deterministic shooter (complete above a threshold T = 16.3 m/s), first
 *    shot 20 m/s, steps 16 then 8 m/s, one shot a round: the documented
 *    sequence, worked by hand from the rule in include/wovenff/mil662.h:
 *      20 C, 4 P (reversal: step 8), 12 P, 20 fired -> step 4: 16 P,
 *      20 fired -> step 2: 18 C, 16 fired -> step 1: 17 C
 *    after which the three highest partial (16, 12, 4) and three lowest
 *    complete (17, 18, 20) lie within 16 m/s <= 38.1: V50 87/6 = 14.5 m/s,
 *    sample sd sqrt(167.5/5); with a 6 m/s largest spread the sequence goes
 *    on, 16.5 C, 16.25 P: after 8 shots the six (16.25, 16, 12; 16.5, 17, 18)
 *    span 6 m/s, V50 95.75/6; with 3 m/s and a budget of 8 shots, not met;
 *  - two shots a round: the round's extra a step (or a half step) beside the
 *    sequence's shot, every speed new; the rule met after 6 shots in 3
 *    rounds (8 in 4 with a 14 m/s spread), the six by hand;
 *  - an extra not within a quarter of its offset of a shot fired (a shot
 *    0.28 m/s from one fired would only repeat it);
 *  - the V50 from a list: ties (equal speeds: the earlier shot), shots
 *    neither partial nor complete left out, too few, too wide;
 *  - a shot neither partial nor complete: steers as a partial, not counted;
 *  - no speed left at the resolution; bad input named. */
#include "check.h"
#include "wovenff/mil662.h"

#include <math.h>
#include <string.h>

#define MAX_SHOTS 64

typedef struct shooter {
    double threshold; /* m/s: complete above it */
    double speed[MAX_SHOTS];
    int outcome[MAX_SHOTS];
    int n, rounds;
} shooter;

/* Fire rounds of `jobs` until the rule is met within spread_max or `budget`
 * shots; returns the final status. */
static int run_sequence(check_state *st, shooter *sh, const wff_mil662_params *p, int jobs,
                        int budget, double spread_max, wff_mil662_result *r)
{
    wff_error err;
    sh->n = sh->rounds = 0;
    for (;;) {
        int rc = wff_mil662_v50(sh->speed, sh->outcome, sh->n, spread_max, r, &err);
        CHECK(st, rc == 0, "v50: %s", rc ? err.message : "");
        if (r->status == WFF_MIL662_MET || sh->n >= budget)
            return r->status;
        double next[WFF_MIL662_JOBS_MAX];
        int want = jobs < budget - sh->n ? jobs : budget - sh->n;
        int m = wff_mil662_next(sh->speed, sh->outcome, sh->n, p, want, next, NULL, &err);
        CHECK(st, m >= 1, "next: %d %s", m, m < 0 ? err.message : "");
        if (m < 1)
            return -1;
        sh->rounds++;
        for (int k = 0; k < m; k++) {
            sh->speed[sh->n] = next[k];
            sh->outcome[sh->n] = next[k] > sh->threshold ? WFF_MIL662_COMPLETE : WFF_MIL662_PARTIAL;
            sh->n++;
        }
    }
}

static void check_speeds(check_state *st, const shooter *sh, const double *want, int n,
                         const char *what)
{
    CHECK(st, sh->n == n, "%s: %d shots, want %d", what, sh->n, n);
    for (int i = 0; i < n && i < sh->n; i++)
        CHECK(st, fabs(sh->speed[i] - want[i]) < 1e-9, "%s: shot %d at %.10g m/s, want %g", what,
              i + 1, sh->speed[i], want[i]);
}

static wff_mil662_params test_params(void)
{
    wff_mil662_params p = wff_mil662_defaults(20);
    p.step = 16;
    p.step_after = 8;
    return p;
}

static void test_textbook(check_state *st)
{
    wff_mil662_params p = test_params();
    shooter sh = {.threshold = 16.3};
    wff_mil662_result r;
    int status = run_sequence(st, &sh, &p, 1, 14, WFF_MIL662_SPREAD, &r);
    static const double seq[] = {20, 4, 12, 16, 18, 17};
    check_speeds(st, &sh, seq, 6, "one a round");
    CHECK(st, status == WFF_MIL662_MET && sh.rounds == 6, "status %d after %d rounds", status, sh.rounds);
    CHECK_CLOSE(st, r.v50, 87.0 / 6, 1e-14, 0, "V50 of 4 12 16 | 17 18 20");
    CHECK_CLOSE(st, r.spread, 16, 1e-14, 0, "spread");
    CHECK_CLOSE(st, r.std_dev, sqrt(167.5 / 5), 1e-14, 0, "sample sd");
    CHECK(st, r.n_partial == 3 && r.n_complete == 3 && r.n_none == 0, "counts %d %d %d", r.n_partial,
          r.n_complete, r.n_none);
    static const int chosen[6] = {3, 2, 1, 5, 4, 0}; /* 16 12 4 | 17 18 20 */
    for (int k = 0; k < 6; k++)
        CHECK(st, r.chosen[k] == chosen[k], "chosen[%d] = %d, want %d", k, r.chosen[k], chosen[k]);
    CHECK(st, r.highest_partial == 16 && r.lowest_complete == 17, "bracket %g %g", r.highest_partial,
          r.lowest_complete);

    /* a tighter spread: the sequence goes on to 16.5 C, 16.25 P */
    status = run_sequence(st, &sh, &p, 1, 14, 6, &r);
    static const double seq8[] = {20, 4, 12, 16, 18, 17, 16.5, 16.25};
    check_speeds(st, &sh, seq8, 8, "spread 6");
    CHECK(st, status == WFF_MIL662_MET, "spread 6: status %d", status);
    CHECK_CLOSE(st, r.v50, 95.75 / 6, 1e-14, 0, "V50 of 12 16 16.25 | 16.5 17 18");
    CHECK_CLOSE(st, r.spread, 6, 1e-12, 0, "spread 6");
    CHECK(st, r.highest_partial < r.v50 + 2 && r.v50 > 12 && r.v50 < 18, "V50 %g", r.v50);

    /* the budget: 8 shots, a 3 m/s spread never reached with these six */
    status = run_sequence(st, &sh, &p, 1, 8, 3, &r);
    CHECK(st, status == WFF_MIL662_TOO_WIDE && sh.n == 8, "budget: status %d, %d shots", status, sh.n);
    CHECK(st, isnan(r.v50) && fabs(r.spread - 6) < 1e-12, "budget: no V50 (%g), spread %g", r.v50,
          r.spread);

    /* the step after the walk: halved to 0.25 m/s */
    double next[1], step;
    wff_error err;
    int m = wff_mil662_next(sh.speed, sh.outcome, sh.n, &p, 1, next, &step, &err);
    CHECK(st, m == 1 && fabs(step - 0.125) < 1e-15, "after 8 shots: %d speeds, step %g", m, step);
}

static void test_two_a_round(check_state *st)
{
    wff_mil662_params p = test_params();
    shooter sh = {.threshold = 16.3};
    wff_mil662_result r;
    int status = run_sequence(st, &sh, &p, 2, 14, WFF_MIL662_SPREAD, &r);
    /* round 1: 20 and 20 + 16 (no direction yet: up); round 2: 4, and 4 + 8
     * (4 - 16 out, 20 fired, 4 - 8 out); round 3: the walk 20 C, 4 P (step 8),
     * 12 P, 20 taken -> step 4: 16; beside it 20 and 12 fired, 18: the six
     * 16 12 4 | 18 20 36 span 32 m/s <= 38.1 */
    static const double seq[] = {20, 36, 4, 12, 16, 18};
    check_speeds(st, &sh, seq, 6, "two a round");
    CHECK(st, status == WFF_MIL662_MET && sh.rounds == 3, "status %d, %d rounds", status, sh.rounds);
    CHECK_CLOSE(st, r.v50, (4 + 12 + 16 + 18 + 20 + 36) / 6.0, 1e-14, 0, "V50 two a round");
    CHECK_CLOSE(st, r.spread, 32, 1e-14, 0, "spread two a round");
    /* with a 14 m/s spread: round 4, the walk 18 C, 16 taken -> step 1: 17, beside it 16.5 */
    status = run_sequence(st, &sh, &p, 2, 14, 14, &r);
    static const double seq8[] = {20, 36, 4, 12, 16, 18, 17, 16.5};
    check_speeds(st, &sh, seq8, 8, "two a round, spread 14");
    CHECK(st, status == WFF_MIL662_MET && sh.rounds == 4, "spread 14: status %d, %d rounds", status,
          sh.rounds);
    CHECK_CLOSE(st, r.v50, (4 + 12 + 16 + 16.5 + 17 + 18) / 6.0, 1e-14, 0, "V50 two a round, spread 14");
    for (int i = 0; i < sh.n; i++)
        for (int j = 0; j < i; j++)
            CHECK(st, fabs(sh.speed[i] - sh.speed[j]) > 0.005, "shots %d and %d at one speed", j, i);
}

/* An extra does not land next to a shot fired: the 12-ply FSP sequence of
 * docs/ballistic_limit.md (sighting shots 421.18 C, 336.95 C; from 306.75 P,
 * 321.99 P; the walk takes 336.95 -> the step 7.62: c = 329.33). Beside it
 * 321.71 is 0.28 m/s from 321.99 and 336.95 fired: the half step's 325.52. */
static void test_extra_not_near(check_state *st)
{
    wff_mil662_params p = wff_mil662_defaults(306.75);
    const double speed[] = {421.18, 336.95, 306.75, 321.99};
    const int outcome[] = {WFF_MIL662_COMPLETE, WFF_MIL662_COMPLETE, WFF_MIL662_PARTIAL,
                           WFF_MIL662_PARTIAL};
    double next[2];
    wff_error err;
    int m = wff_mil662_next(speed, outcome, 4, &p, 2, next, NULL, &err);
    CHECK(st, m == 2, "extra not near: %d speeds", m);
    CHECK_CLOSE(st, next[0], 329.33, 1e-9, 0, "extra not near: the sequence's shot");
    CHECK_CLOSE(st, next[1], 325.52, 1e-9, 0, "extra not near: the extra a half step down");
}

static void test_v50_list(check_state *st)
{
    wff_error err;
    wff_mil662_result r;
    /* ties: two partials at 100 compete for the third place (the earlier, shot 2,
     * is taken); a shot neither partial nor complete (at 130) is left out */
    const double v[] = {90, 100, 120, 100, 110, 130, 125, 118, 140};
    const int o[] = {0, 0, 0, 0, 1, -1, 1, 1, 1};
    int rc = wff_mil662_v50(v, o, 9, WFF_MIL662_SPREAD, &r, &err);
    CHECK(st, rc == 0, "%s", rc ? err.message : "");
    CHECK(st, r.status == WFF_MIL662_MET, "status %d", r.status);
    CHECK(st, r.n_partial == 4 && r.n_complete == 4 && r.n_none == 1, "counts");
    CHECK(st, r.chosen[0] == 2 && r.chosen[1] == 1 && r.chosen[2] == 3, "partials %d %d %d",
          r.chosen[0], r.chosen[1], r.chosen[2]);
    CHECK(st, r.chosen[3] == 4 && r.chosen[4] == 7 && r.chosen[5] == 6, "completes %d %d %d",
          r.chosen[3], r.chosen[4], r.chosen[5]);
    /* partial 120 above complete 110: a mixed zone; the six 100 100 120 | 110 118 125 */
    CHECK_CLOSE(st, r.v50, (100 + 100 + 120 + 110 + 118 + 125) / 6.0, 1e-14, 0, "V50 with ties");
    CHECK_CLOSE(st, r.spread, 25, 1e-14, 0, "spread with ties");
    CHECK(st, r.highest_partial == 120 && r.lowest_complete == 110, "mixed zone");
    /* the same shots with the largest spread 20: too wide, no V50, the spread said */
    rc = wff_mil662_v50(v, o, 9, 20, &r, &err);
    CHECK(st, rc == 0 && r.status == WFF_MIL662_TOO_WIDE && isnan(r.v50) && r.spread == 25,
          "too wide: %d %g %g", r.status, r.v50, r.spread);
    /* exactly the spread: met (38.1 m/s from rounded speeds) */
    const double w[] = {100, 101, 102, 110, 120, 138.1};
    const int ow[] = {0, 0, 0, 1, 1, 1};
    rc = wff_mil662_v50(w, ow, 6, 38.1, &r, &err);
    CHECK(st, rc == 0 && r.status == WFF_MIL662_MET, "a spread of exactly 38.1: status %d", r.status);
    /* too few: two completes */
    rc = wff_mil662_v50(v, o, 5, WFF_MIL662_SPREAD, &r, &err);
    CHECK(st, rc == 0 && r.status == WFF_MIL662_TOO_FEW && isnan(r.v50) && isnan(r.spread) &&
                  r.chosen[5] == -1,
          "too few: %d", r.status);
}

static void test_no_speed_and_errors(check_state *st)
{
    wff_error err;
    double next[4];
    /* the highest speed 0.06 m/s: 0.03 P, 0.05 P, 0.07 too fast -> step 0.01:
     * 0.06 C (reversal), 0.05 taken -> step 0.005, below the resolution: none */
    const double v[] = {0.03, 0.05, 0.06, 0.01, 0.02, 0.04};
    const int o[] = {0, 0, 1, 0, 0, 0};
    wff_mil662_params p = wff_mil662_defaults(0.03);
    p.step = 0.02;
    p.step_after = 0.01;
    p.speed_max = 0.06;
    int m = wff_mil662_next(v, o, 6, &p, 1, next, NULL, &err);
    CHECK(st, m == WFF_MIL662_NO_SPEED, "no speed left: %d (%g)", m, m > 0 ? next[0] : 0);
    /* a shot neither partial nor complete steers as a partial (up) and is not counted:
     * 20 neither -> 20 + 16; then 36 complete -> 36 - 16 = 20 taken -> step 8: 28 */
    const double vn[] = {20, 36};
    const int on[] = {WFF_MIL662_NONE, WFF_MIL662_COMPLETE};
    wff_mil662_params q = test_params();
    m = wff_mil662_next(vn, on, 1, &q, 1, next, NULL, &err);
    CHECK(st, m == 1 && next[0] == 36, "after a shot neither: %d speeds, %g m/s (want 36)", m, next[0]);
    m = wff_mil662_next(vn, on, 2, &q, 1, next, NULL, &err);
    CHECK(st, m == 1 && next[0] == 28, "then a complete: %d speeds, %g m/s (want 28)", m, next[0]);
    wff_mil662_result rn;
    CHECK(st, wff_mil662_v50(vn, on, 2, 38.1, &rn, &err) == 0 && rn.n_none == 1 && rn.n_complete == 1 &&
                  rn.n_partial == 0,
          "neither not counted: %d %d %d", rn.n_partial, rn.n_complete, rn.n_none);
    /* bad input, named */
    p = wff_mil662_defaults(-5);
    m = wff_mil662_next(v, o, 6, &p, 1, next, NULL, &err);
    CHECK(st, m == -1 && strstr(err.message, "first speed"), "negative first speed: %s", err.message);
    p = wff_mil662_defaults(20);
    const int bad[] = {0, 2};
    m = wff_mil662_next(v, bad, 2, &p, 1, next, NULL, &err);
    CHECK(st, m == -1 && strstr(err.message, "shot 2: outcome 2"), "bad outcome: %s", err.message);
    m = wff_mil662_next(v, o, 6, &p, 0, next, NULL, &err);
    CHECK(st, m == -1 && strstr(err.message, "shots a round"), "0 jobs: %s", err.message);
    wff_mil662_result r;
    const double nanv[] = {NAN};
    CHECK(st, wff_mil662_v50(nanv, o, 1, 38.1, &r, &err) == -1 && strstr(err.message, "shot 1: speed"),
          "NaN speed: %s", err.message);
    CHECK(st, wff_mil662_v50(v, o, 6, 0, &r, &err) == -1 && strstr(err.message, "largest spread"),
          "spread 0: %s", err.message);
}

int main(void)
{
    check_state st = {0, 0};
    test_textbook(&st);
    test_two_a_round(&st);
    test_extra_not_near(&st);
    test_v50_list(&st);
    test_no_speed_and_errors(&st);
    return check_summary(&st, "test_mil662");
}

/* The V50 of MIL-STD-662F: the up-and-down sequence and the six-shot V50
 * (include/wovenff/mil662.h states the rule; docs/ballistic_limit.md
 * "MIL-STD-662F" what in the standard it rests on). */
#include "wovenff/mil662.h"

#include <math.h>
#include <stdlib.h>

/* Two speeds are one shot's when within half the resolution. */
#define SAME_SPEED(a, b, res) (fabs((a) - (b)) < 0.5 * (res))

wff_mil662_params wff_mil662_defaults(double first_speed)
{
    wff_mil662_params p = {.first_speed = first_speed,
                           .step = WFF_MIL662_STEP,
                           .step_after = WFF_MIL662_STEP_AFTER,
                           .resolution = WFF_MIL662_RESOLUTION,
                           .speed_max = WFF_MIL662_SPEED_MAX};
    return p;
}

double wff_mil662_round(double speed, double resolution)
{
    return round(speed / resolution) * resolution;
}

/* Index of the first shot at speed v (−1: none). */
static int find_shot(const double *speed, int n, double v, double res)
{
    for (int i = 0; i < n; i++)
        if (SAME_SPEED(speed[i], v, res))
            return i;
    return -1;
}

static int check_history(const double *speed, const int *outcome, int n, wff_error *err)
{
    if (n < 0 || (n > 0 && (!speed || !outcome)))
        return wff_fail(err, "MIL-STD-662F: a history of %d shots without its arrays", n);
    for (int i = 0; i < n; i++) {
        if (!(isfinite(speed[i]) && speed[i] > 0))
            return wff_fail(err, "MIL-STD-662F: shot %d: speed %g m/s (a striking speed is > 0)", i + 1,
                            speed[i]);
        if (outcome[i] < WFF_MIL662_NONE || outcome[i] > WFF_MIL662_COMPLETE)
            return wff_fail(err, "MIL-STD-662F: shot %d: outcome %d (1 complete, 0 partial, -1 neither)",
                            i + 1, outcome[i]);
    }
    return 0;
}

static int check_params(const wff_mil662_params *p, wff_error *err)
{
    const double v[] = {p->first_speed, p->step, p->step_after, p->resolution, p->speed_max};
    const char *name[] = {"first speed", "step", "step after the first reversal", "resolution",
                          "highest speed"};
    for (int k = 0; k < 5; k++)
        if (!(isfinite(v[k]) && v[k] > 0))
            return wff_fail(err, "MIL-STD-662F: the %s %g m/s is not a number > 0", name[k], v[k]);
    if (!(p->first_speed >= p->resolution && p->first_speed <= p->speed_max))
        return wff_fail(err, "MIL-STD-662F: the first speed %g m/s is outside [%g, %g] m/s",
                        p->first_speed, p->resolution, p->speed_max);
    return 0;
}

/* Where the walk goes from cur by dir * s: the speed (m/s), or −1 when the
 * step halves below the resolution first. A speed within half the step of a
 * shot the walk has taken (or outside [resolution, speed_max]) halves the
 * step (for good, *s); one within half the step of a shot fired but not yet
 * taken (another round's extra) is that shot. */
static double walk_to(double cur, int dir, double *s, const double *speed, const char *visited, int n,
                      const wff_mil662_params *p)
{
    const double res = p->resolution;
    for (; *s >= res; *s *= 0.5) {
        double v = wff_mil662_round(cur + dir * *s, res);
        if (!(v >= res && v <= p->speed_max) || SAME_SPEED(v, cur, res))
            continue;
        int near_taken = 0, near = -1;
        for (int i = 0; i < n; i++) {
            double d = fabs(speed[i] - v);
            if (d < 0.5 * *s && visited[i])
                near_taken = 1;
            else if (d < 0.5 * *s && (near < 0 || d < fabs(speed[near] - v)))
                near = i;
        }
        if (near_taken)
            continue;   /* (a deterministic model: a speed fired would only repeat itself) */
        return near >= 0 ? speed[near] : v;
    }
    return -1;
}

/* Is a shot fired within `within` of v (at least the same shot at the
 * resolution)? An extra there would only repeat what is known. */
static int near_shot(const double *speed, int n, double v, double within, double res)
{
    for (int i = 0; i < n; i++)
        if (SAME_SPEED(speed[i], v, res) || fabs(speed[i] - v) < within)
            return 1;
    return 0;
}

/* Speeds of this round so far: is v one of them? */
static int planned(const double *next, int m, double v, double res)
{
    for (int k = 0; k < m; k++)
        if (SAME_SPEED(next[k], v, res))
            return 1;
    return 0;
}

int wff_mil662_next(const double *speed, const int *outcome, int n, const wff_mil662_params *p,
                    int jobs, double *next, double *step_now, wff_error *err)
{
    if (!p || !next)
        return wff_fail(err, "MIL-STD-662F: no parameters or no room for the next speeds");
    if (check_params(p, err) || check_history(speed, outcome, n, err))
        return -1;
    if (jobs < 1 || jobs > WFF_MIL662_JOBS_MAX)
        return wff_fail(err, "MIL-STD-662F: %d shots a round (1 to %d)", jobs, WFF_MIL662_JOBS_MAX);
    char *visited = calloc((size_t)(n > 0 ? n : 1), 1);
    if (!visited)
        return wff_fail(err, "MIL-STD-662F: out of memory for %d shots", n);
    const double res = p->resolution;
    double cur = wff_mil662_round(p->first_speed, res), s = p->step;
    int last = WFF_MIL662_NONE, reversed = 0, dir = +1, found = 1;
    /* The walk: each pass takes a shot of the history not taken before, so it
     * ends within n + 1 passes. */
    for (int i; (i = find_shot(speed, n, cur, res)) >= 0;) {
        visited[i] = 1;
        int o = outcome[i];
        if (o != WFF_MIL662_NONE && last != WFF_MIL662_NONE && o != last && !reversed) {
            reversed = 1;   /* the first reversal: the standard's smaller step */
            s = fmin(s, p->step_after);
        }
        if (o != WFF_MIL662_NONE)
            last = o;
        dir = o == WFF_MIL662_COMPLETE ? -1 : +1;   /* (neither: as a partial) */
        double v = walk_to(cur, dir, &s, speed, visited, n, p);
        if (v < 0) {
            found = 0;
            break;
        }
        cur = v;
    }
    free(visited);
    if (step_now)
        *step_now = s;
    if (!found)
        return WFF_MIL662_NO_SPEED;
    /* The round: the sequence's next shot, then speeds a step on either side
     * of it (the walk's direction first), a half step where those are fired. */
    int m = 0;
    next[m++] = cur;
    for (double off = s; m < jobs && off >= res; off *= 0.5)
        for (int side = 0; side < 2 && m < jobs; side++) {
            double v = wff_mil662_round(cur + (side ? -dir : dir) * off, res);
            if (v >= res && v <= p->speed_max && !near_shot(speed, n, v, 0.25 * off, res) &&
                !planned(next, m, v, res))
                next[m++] = v;
        }
    return m;
}

/* Sort idx[0..m-1] by speed (ascending when up, else descending); ties: the
 * earlier shot first (an insertion sort: stable, m small). */
static void sort_shots(int *idx, int m, const double *speed, int up)
{
    for (int a = 1; a < m; a++) {
        int t = idx[a], b = a - 1;
        while (b >= 0 && (up ? speed[idx[b]] > speed[t] : speed[idx[b]] < speed[t])) {
            idx[b + 1] = idx[b];
            b--;
        }
        idx[b + 1] = t;
    }
}

int wff_mil662_v50(const double *speed, const int *outcome, int n, double spread_max,
                   wff_mil662_result *r, wff_error *err)
{
    if (!r)
        return wff_fail(err, "MIL-STD-662F: no result to fill");
    if (check_history(speed, outcome, n, err))
        return -1;
    if (!(isfinite(spread_max) && spread_max > 0))
        return wff_fail(err, "MIL-STD-662F: the largest spread %g m/s is not a number > 0", spread_max);
    const double nan = NAN;
    *r = (wff_mil662_result){.status = WFF_MIL662_TOO_FEW, .v50 = nan, .mean = nan, .spread = nan,
                             .std_dev = nan, .highest_partial = nan, .lowest_complete = nan};
    for (int k = 0; k < 6; k++)
        r->chosen[k] = -1;
    /* the three highest partial and three lowest complete, by a pass each
     * (keep the best three seen: insertion into a sorted list of three) */
    int best[2][3], nb[2] = {0, 0};
    for (int i = 0; i < n; i++) {
        int o = outcome[i];
        if (o == WFF_MIL662_NONE) {
            r->n_none++;
            continue;
        }
        if (o == WFF_MIL662_PARTIAL)
            r->n_partial++;
        else
            r->n_complete++;
        int up = (o == WFF_MIL662_COMPLETE);   /* completes: lowest first */
        int *b = best[o];
        if (nb[o] < 3)
            b[nb[o]++] = i;
        else if (up ? speed[i] < speed[b[2]] : speed[i] > speed[b[2]])
            b[2] = i;   /* (replaces the worst kept; ties keep the earlier shot) */
        sort_shots(b, nb[o], speed, up);
    }
    if (nb[0] > 0)
        r->highest_partial = speed[best[0][0]];
    if (nb[1] > 0)
        r->lowest_complete = speed[best[1][0]];
    for (int k = 0; k < nb[0]; k++)
        r->chosen[k] = best[0][k];
    for (int k = 0; k < nb[1]; k++)
        r->chosen[3 + k] = best[1][k];
    if (nb[0] < 3 || nb[1] < 3)
        return 0;
    double lo = INFINITY, hi = -INFINITY, sum = 0;
    for (int k = 0; k < 6; k++) {
        double v = speed[r->chosen[k]];
        lo = fmin(lo, v);
        hi = fmax(hi, v);
        sum += v;
    }
    r->mean = sum / 6;
    double ss = 0;
    for (int k = 0; k < 6; k++) {
        double d = speed[r->chosen[k]] - r->mean;
        ss += d * d;
    }
    r->std_dev = sqrt(ss / 5);
    r->spread = hi - lo;
    /* (1e-12: a spread of rounded speeds equal to the largest is within it) */
    r->status = r->spread <= spread_max * (1 + 1e-12) ? WFF_MIL662_MET : WFF_MIL662_TOO_WIDE;
    if (r->status == WFF_MIL662_MET)
        r->v50 = r->mean;
    return 0;
}

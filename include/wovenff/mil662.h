/* wovenff — the V50 of MIL-STD-662F ("V50 Ballistic Test for Armor", US DoD,
 * 1997): the up-and-down firing sequence and its six-shot V50
 * (plugin/mil662.c; docs/ballistic_limit.md "MIL-STD-662F").
 *
 * The sequence. The first shot at an estimated V50 (first_speed); after a
 * complete penetration the next shot is slower by the step, after a partial
 * one faster. The step is `step` (the standard's 50 ft/s, 15.24 m/s) until
 * the first reversal (a shot whose outcome differs from the decided shot
 * before it), then min(step, step_after) (25 ft/s, 7.62 m/s). A model is
 * deterministic: a shot at a speed already fired would only repeat its
 * outcome, so where the sequence would come back to within half its step
 * of a speed it has fired, or leave [resolution, speed_max], the step is
 * halved (for the rest of the sequence) until the speed is clear; below
 * `resolution` there is none (the sequence ends: WFF_MIL662_NO_SPEED). Speeds are rounded to `resolution`
 * (0.01 m/s: the limit scene's run folders). A shot neither partial nor
 * complete (undecided at the run's end, or failed) steers as a partial (it
 * has not got through: a faster shot decides) and is counted as neither.
 *
 * The history is replayed as a walk from first_speed: where the walk goes
 * within half its step of a shot of the history it has not taken (fired
 * before: another round's extra), it takes that shot and its outcome; the
 * first speed it reaches with no shot there is the sequence's next shot c. With jobs > 1 a round also fires speeds a step on
 * either side of it, c + dir s, c − dir s, then c ± s/2, c ± s/4, ... (dir
 * the walk's last direction, s its step; new speeds only: none within a
 * quarter of its offset of a shot fired, while the offset is at least the
 * resolution): extra shots, counted in the V50 like any
 * other, which steer only when the walk comes to them.
 * With jobs = 1 the walk is the textbook sequence, shot for shot.
 *
 * The V50. Of the counted shots (partial or complete), the three highest
 * partial and the three lowest complete penetrations (equal speeds: the
 * earlier shot first); the rule is met when the spread of these six (max −
 * min) is at most spread_max (the standard's 125 ft/s, 38.1 m/s). V50 is
 * their mean, with the spread and the sample standard deviation (n − 1) of
 * the six. Fewer than three of either, or a wider spread: no V50 (NaN).
 * Knows nothing of scenes, files or FreeFEM. */
#ifndef WOVENFF_MIL662_H
#define WOVENFF_MIL662_H

#include "wovenff/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The standard's numbers in SI (1 ft/s = 0.3048 m/s). */
#define WFF_MIL662_STEP 15.24       /* m/s: 50 ft/s, before the first reversal */
#define WFF_MIL662_STEP_AFTER 7.62  /* m/s: 25 ft/s, after it */
#define WFF_MIL662_SPREAD 38.1      /* m/s: 125 ft/s, the six shots' largest spread */
#define WFF_MIL662_RESOLUTION 0.01  /* m/s: speeds are rounded to this */
#define WFF_MIL662_SPEED_MAX 1e5    /* m/s: no projectile strikes faster (a slip of units) */
#define WFF_MIL662_JOBS_MAX 64      /* shots in one round */

/* A shot's outcome as the standard judges it. */
enum { WFF_MIL662_NONE = -1, WFF_MIL662_PARTIAL = 0, WFF_MIL662_COMPLETE = 1 };

/* wff_mil662_v50's verdict on the rule. */
enum { WFF_MIL662_MET = 0, WFF_MIL662_TOO_FEW = 1, WFF_MIL662_TOO_WIDE = 2 };

/* wff_mil662_next returns this when the sequence has no new speed. */
#define WFF_MIL662_NO_SPEED 0

typedef struct wff_mil662_params {
    double first_speed;  /* m/s: the estimated V50, the first shot */
    double step;         /* m/s: until the first reversal */
    double step_after;   /* m/s: after it (the smaller of the two is taken) */
    double resolution;   /* m/s: speeds rounded to it; a step halved below it ends the sequence */
    double speed_max;    /* m/s: no shot faster */
} wff_mil662_params;

/* The standard's params for a first speed (m/s). */
wff_mil662_params wff_mil662_defaults(double first_speed);

/* A speed rounded to the resolution (m/s), as the shots are fired. */
double wff_mil662_round(double speed, double resolution);

/* The next round's speeds from the history speed[0..n-1] (m/s) and outcome[i]
 * (WFF_MIL662_PARTIAL, _COMPLETE, _NONE), in firing order: next[0] the
 * sequence's next shot, next[1..] the extra shots (at most jobs in all; the
 * caller gives room for jobs). Returns the number of speeds (0 =
 * WFF_MIL662_NO_SPEED: none left at the resolution), −1 on bad input (err
 * names it: a non-finite or non-positive parameter or speed, jobs outside
 * 1..64, an outcome not −1/0/1). Two shots at one speed may be given (the
 * walk takes the first). *step_now (may be NULL): the walk's step after the
 * last shot, m/s. */
int wff_mil662_next(const double *speed, const int *outcome, int n, const wff_mil662_params *p,
                    int jobs, double *next, double *step_now, wff_error *err);

typedef struct wff_mil662_result {
    int status;          /* WFF_MIL662_MET, _TOO_FEW, _TOO_WIDE */
    int n_partial, n_complete, n_none; /* shots of each outcome */
    int chosen[6];       /* the six: three highest partial (highest first), three lowest complete
                            (lowest first); −1 where there is none */
    double v50;          /* m/s: the six's mean when met, else NaN */
    double mean;         /* m/s: the six's mean whenever there are six (NaN otherwise) */
    double spread;       /* m/s: max − min of the six (NaN without six) */
    double std_dev;      /* m/s: their sample standard deviation (NaN without six) */
    double highest_partial, lowest_complete; /* m/s of all counted shots (NaN: none) */
} wff_mil662_result;

/* The six-shot V50 of the history (see above) with the largest spread
 * spread_max (m/s). Returns 0, −1 on bad input (err names it). */
int wff_mil662_v50(const double *speed, const int *outcome, int n, double spread_max,
                   wff_mil662_result *r, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

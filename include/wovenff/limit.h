/* wovenff — the ballistic limit from a set of impacts: the Lambert–Jonas law
 *
 *     V_r = a (V_s^p − V_bl^p)^(1/p)   for V_s > V_bl,   V_r = 0 otherwise
 *
 * (Lambert & Jonas, BRL report 1691, 1976; V_s striking speed, V_r residual
 * speed, V_bl the ballistic limit, a ≤ 1 for a projectile that loses momentum
 * to the plug or fabric, p ≥ 1 the shape of the knee) fitted by GSL nonlinear
 * least squares (Levenberg–Marquardt) to (V_s, V_r) pairs, and V50 from the
 * bracket of stopped and perforating runs (freefem_scripts/ballistic_limit.edp
 * runs the sweep that gives the pairs).
 *
 * What each run says:
 *  - a perforating run (V_r > 0) is a fitted point: residual V_r − model;
 *  - a stopped run (V_r = 0) only says V_bl ≥ V_s; stopped runs enter as a
 *    bound, not as residuals (a zero residual below V_bl carries no
 *    information on a or p, and a stopped run fitted as 0 would pull the law
 *    through the knee). V_bl is kept in the bracket
 *        (highest stopped speed below the lowest perforating speed, or 0,
 *         lowest perforating speed)
 *    by the parametrisation V_bl = lo + (hi − lo) σ(t), σ the logistic
 *    function; a = 1.5 σ(u) in (0, 1.5); p = 1 + 9 σ(w) in (1, 10).
 *  - stopped runs above the lowest perforating speed (the "mixed zone" of
 *    scatter) are counted (n_mixed) and are outside the fit's bracket.
 * Standard errors: the linearised covariance s² (JᵀJ)⁻¹ in (V_bl, a, p), J
 * the analytic Jacobian at the solution, s² = SSR/(n_perforated − 3): NaN
 * when n_perforated = 3 (an exact fit has no residual variance).
 * V50 from the fit is V_bl (the law is deterministic: every run above it
 * perforates) ± its standard error; V50 from the bracket is the mid-point
 * of the highest stopped and the lowest perforating speed ± half their gap
 * (NaN when there is no stopped run).
 * Knows nothing of scenes, files or FreeFEM. */
#ifndef WOVENFF_LIMIT_H
#define WOVENFF_LIMIT_H

#include "wovenff/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Parameter order in the arrays below. */
enum { WFF_LIMIT_VBL = 0, WFF_LIMIT_A = 1, WFF_LIMIT_P = 2, WFF_LIMIT_NP = 3 };

/* Bounds the fit keeps (open intervals; "at bound" when within 1e-6 relative). */
#define WFF_LIMIT_A_MAX 1.5
#define WFF_LIMIT_P_MIN 1.0
#define WFF_LIMIT_P_MAX 10.0

typedef struct wff_limit_fit {
    double value[WFF_LIMIT_NP];          /* V_bl (m/s), a (−), p (−) */
    double std_error[WFF_LIMIT_NP];      /* same units; NaN without residual variance */
    double covariance[WFF_LIMIT_NP][WFF_LIMIT_NP];
    int at_bound[WFF_LIMIT_NP];          /* 1 when the estimate sits on a bound */
    double residual_sd;                  /* s = sqrt(SSR / (n_perforated − 3)), m/s */
    double rms_residual;                 /* sqrt(SSR / n_perforated), m/s */
    double bracket_low, bracket_high;    /* the bound kept on V_bl, m/s */
    double v50_fit, v50_fit_error;       /* V_bl ± its standard error, m/s */
    double v50_bracket, v50_bracket_half_gap; /* from the runs alone, m/s (NaN: no stopped run) */
    double highest_stopped, lowest_perforated; /* m/s (NaN when there is none) */
    int n_points, n_perforated, n_stopped, n_mixed;
    int iterations;
    int converged; /* GSL's reason (1 step, 2 gradient, 3 cost), 0 not converged */
    int starts;    /* starting points tried (the best kept) */
} wff_limit_fit;

/* The law at striking speed vs (m/s): 0 at and below vbl. */
double wff_lambert_jonas(double vs, double vbl, double a, double p);

/* Fit n pairs (vs[i], vr[i]) (m/s; vr = 0 a stopped run). Refuses (−1, a
 * message naming the run) non-finite or negative values, vs = 0, a residual
 * above its striking speed (a physical invariant: vr <= vs), fewer than 3
 * perforating runs. */
int wff_limit_fit_run(const double *vs, const double *vr, int n, wff_limit_fit *out,
                      wff_error *err);

/* V50 from the bracket alone (no fit; at least one stopped and one
 * perforating run, else *v50 and *half_gap are NaN and −1 is returned). */
int wff_limit_bracket(const double *vs, const double *vr, int n, double *v50, double *half_gap);

#ifdef __cplusplus
}
#endif
#endif

/* The Lambert–Jonas fit of a ballistic-limit study (include/wovenff/limit.h).
 *
 * Speeds are fitted in units of the lowest perforating speed (scale), so the
 * powers V^p stay near 1 for any p in [1, 10]. Unknowns θ = (t, u, w):
 *   V_bl / scale = lo + (hi − lo) σ(t),  a = 1.5 σ(u),  p = 1 + 9 σ(w),
 * σ the logistic function: every θ is physical. Residuals of the perforating
 * runs only, f_i = a (x_i^p − b^p)^(1/p) − y_i (x, y the scaled V_s, V_r), with
 * the analytic Jacobian. Several starts (b at 1/5, 1/2, 4/5 of the bracket,
 * p = 2, 1.3, 4, a the linear least-squares value for that b and p); the one
 * with the smallest SSR is kept. */
#include "wovenff/limit.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

double wff_lambert_jonas(double vs, double vbl, double a, double p)
{
    if (!(vs > vbl))
        return 0;
    return a * pow(pow(vs, p) - pow(vbl, p), 1 / p);
}

typedef struct limit_ctx {
    const double *x, *y; /* perforating runs, scaled */
    int n;
    double lo, hi;       /* scaled bracket of b */
} limit_ctx;

static double logistic(double z) { return 1 / (1 + exp(-z)); }
static double logit(double s) { return log(s / (1 - s)); }

static void natural(const limit_ctx *c, const double *th, double *b, double *a, double *p)
{
    *b = c->lo + (c->hi - c->lo) * logistic(th[0]);
    *a = WFF_LIMIT_A_MAX * logistic(th[1]);
    *p = WFF_LIMIT_P_MIN + (WFF_LIMIT_P_MAX - WFF_LIMIT_P_MIN) * logistic(th[2]);
}

/* The model at x and its derivatives in (b, a, p) (d may be NULL). */
static double model(double x, double b, double a, double p, double d[3])
{
    double xp = pow(x, p), bp = b > 0 ? pow(b, p) : 0, D = xp - bp;
    if (!(D > 0)) {
        if (d)
            d[0] = d[1] = d[2] = 0;
        return 0;
    }
    double g = pow(D, 1 / p), f = a * g;
    if (d) {
        d[0] = -a * g / D * (b > 0 ? pow(b, p - 1) : 0);
        d[1] = g;
        double dD = xp * log(x) - (b > 0 ? bp * log(b) : 0);
        d[2] = f * (-log(D) / (p * p) + dD / (p * D));
    }
    return f;
}

static int residuals_f(const gsl_vector *th_v, void *params, gsl_vector *f)
{
    const limit_ctx *c = params;
    double th[3] = {gsl_vector_get(th_v, 0), gsl_vector_get(th_v, 1), gsl_vector_get(th_v, 2)};
    double b, a, p;
    natural(c, th, &b, &a, &p);
    for (int i = 0; i < c->n; i++) {
        double r = model(c->x[i], b, a, p, NULL) - c->y[i];
        if (!isfinite(r))
            return GSL_EDOM;
        gsl_vector_set(f, (size_t)i, r);
    }
    return GSL_SUCCESS;
}

static int residuals_df(const gsl_vector *th_v, void *params, gsl_matrix *J)
{
    const limit_ctx *c = params;
    double th[3] = {gsl_vector_get(th_v, 0), gsl_vector_get(th_v, 1), gsl_vector_get(th_v, 2)};
    double b, a, p;
    natural(c, th, &b, &a, &p);
    double s0 = logistic(th[0]), s1 = logistic(th[1]), s2 = logistic(th[2]);
    double chain[3] = {(c->hi - c->lo) * s0 * (1 - s0), WFF_LIMIT_A_MAX * s1 * (1 - s1),
                       (WFF_LIMIT_P_MAX - WFF_LIMIT_P_MIN) * s2 * (1 - s2)};
    for (int i = 0; i < c->n; i++) {
        double d[3];
        model(c->x[i], b, a, p, d);
        for (int j = 0; j < 3; j++) {
            if (!isfinite(d[j]))
                return GSL_EDOM;
            gsl_matrix_set(J, (size_t)i, (size_t)j, d[j] * chain[j]);
        }
    }
    return GSL_SUCCESS;
}

static double ssr_at(const limit_ctx *c, double b, double a, double p)
{
    double s = 0;
    for (int i = 0; i < c->n; i++) {
        double r = model(c->x[i], b, a, p, NULL) - c->y[i];
        s += r * r;
    }
    return s;
}

int wff_limit_bracket(const double *vs, const double *vr, int n, double *v50, double *half_gap)
{
    double stopped = -INFINITY, perforated = INFINITY;
    for (int i = 0; i < n; i++) {
        if (vr[i] > 0)
            perforated = fmin(perforated, vs[i]);
        else
            stopped = fmax(stopped, vs[i]);
    }
    if (!isfinite(stopped) || !isfinite(perforated)) {
        *v50 = *half_gap = NAN;
        return -1;
    }
    *v50 = 0.5 * (stopped + perforated);
    *half_gap = 0.5 * fabs(perforated - stopped);
    return 0;
}

/* One Levenberg–Marquardt solve from th (updated); its SSR, or INFINITY. */
static double solve(limit_ctx *c, double th[3], int *iterations, int *converged)
{
    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    fp.trs = gsl_multifit_nlinear_trs_lm;
    fp.scale = gsl_multifit_nlinear_scale_more;
    fp.solver = gsl_multifit_nlinear_solver_qr;
    gsl_multifit_nlinear_fdf fdf = {.f = residuals_f, .df = residuals_df, .fvv = NULL,
                                    .n = (size_t)c->n, .p = 3, .params = c};
    gsl_multifit_nlinear_workspace *w =
        gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, (size_t)c->n, 3);
    gsl_vector *z = gsl_vector_alloc(3);
    double ssr = INFINITY;
    if (w && z) {
        for (int j = 0; j < 3; j++)
            gsl_vector_set(z, (size_t)j, th[j]);
        int info = 0, status = gsl_multifit_nlinear_init(z, &fdf, w);
        if (status == GSL_SUCCESS)
            status = gsl_multifit_nlinear_driver(500, 1e-12, 1e-12, 1e-14, NULL, NULL, &info, w);
        *iterations = (int)gsl_multifit_nlinear_niter(w);
        *converged = status == GSL_SUCCESS ? info : 0;
        if (status == GSL_SUCCESS || status == GSL_ENOPROG || status == GSL_EMAXITER) {
            const gsl_vector *zf = gsl_multifit_nlinear_position(w);
            for (int j = 0; j < 3; j++)
                th[j] = gsl_vector_get(zf, (size_t)j);
            double b, a, p;
            natural(c, th, &b, &a, &p);
            ssr = ssr_at(c, b, a, p);
            if (!isfinite(ssr))
                ssr = INFINITY;
        }
    }
    gsl_vector_free(z);
    if (w)
        gsl_multifit_nlinear_free(w);
    return ssr;
}

int wff_limit_fit_run(const double *vs, const double *vr, int n, wff_limit_fit *out,
                      wff_error *err)
{
    memset(out, 0, sizeof *out);
    if (!vs || !vr || n < 0)
        return wff_fail(err, "Lambert-Jonas fit: no runs given");
    double stopped_max = -INFINITY, perforated_min = INFINITY;
    for (int i = 0; i < n; i++) {
        if (!isfinite(vs[i]) || !isfinite(vr[i]))
            return wff_fail(err,
                            "Lambert-Jonas fit: run %d: striking speed %g m/s, residual %g m/s: "
                            "not a finite number",
                            i + 1, vs[i], vr[i]);
        if (!(vs[i] > 0) || vr[i] < 0)
            return wff_fail(err,
                            "Lambert-Jonas fit: run %d: striking speed %g m/s, residual %g m/s: "
                            "the striking speed must be > 0 and the residual >= 0",
                            i + 1, vs[i], vr[i]);
        if (vr[i] > vs[i])
            return wff_fail(err,
                            "Lambert-Jonas fit: run %d: residual speed %g m/s above the striking "
                            "speed %g m/s: a projectile leaves the target no faster than it "
                            "struck (residual <= striking)",
                            i + 1, vr[i], vs[i]);
        if (vr[i] > 0) {
            out->n_perforated++;
            perforated_min = fmin(perforated_min, vs[i]);
        }
    }
    if (out->n_perforated < 3)
        return wff_fail(err,
                        "Lambert-Jonas fit: %d perforating run%s (residual speed > 0) of %d: "
                        "V_bl, a and p need at least 3",
                        out->n_perforated, out->n_perforated == 1 ? "" : "s", n);
    out->n_points = n;
    for (int i = 0; i < n; i++)
        if (!(vr[i] > 0)) {
            out->n_stopped++;
            if (vs[i] < perforated_min)
                stopped_max = fmax(stopped_max, vs[i]);
            else
                out->n_mixed++;
        }
    double all_stopped_max = -INFINITY;
    for (int i = 0; i < n; i++)
        if (!(vr[i] > 0))
            all_stopped_max = fmax(all_stopped_max, vs[i]);
    out->highest_stopped = isfinite(all_stopped_max) ? all_stopped_max : NAN;
    out->lowest_perforated = perforated_min;
    wff_limit_bracket(vs, vr, n, &out->v50_bracket, &out->v50_bracket_half_gap);

    double scale = perforated_min;
    double *xy = malloc(2 * (size_t)out->n_perforated * sizeof *xy);
    if (!xy)
        return wff_fail(err, "Lambert-Jonas fit: out of memory");
    limit_ctx c = {.x = xy, .y = xy + out->n_perforated, .n = out->n_perforated,
                   .lo = isfinite(stopped_max) ? stopped_max / scale : 0, .hi = 1};
    for (int i = 0, k = 0; i < n; i++)
        if (vr[i] > 0) {
            xy[k] = vs[i] / scale;
            xy[out->n_perforated + k] = vr[i] / scale;
            k++;
        }
    out->bracket_low = c.lo * scale;
    out->bracket_high = c.hi * scale;

    gsl_error_handler_t *old = gsl_set_error_handler_off();
    static const double b_frac[] = {0.5, 0.2, 0.8}, p_start[] = {2, 1.3, 4};
    double best = INFINITY, best_th[3] = {0, 0, 0};
    for (size_t ib = 0; ib < sizeof b_frac / sizeof *b_frac; ib++)
        for (size_t ip = 0; ip < sizeof p_start / sizeof *p_start; ip++) {
            double b = c.lo + b_frac[ib] * (c.hi - c.lo), p = p_start[ip];
            double gy = 0, gg = 0; /* a: linear least squares for this b, p */
            for (int i = 0; i < c.n; i++) {
                double g = model(c.x[i], b, 1, p, NULL);
                gy += g * c.y[i];
                gg += g * g;
            }
            double a = gg > 0 ? gy / gg : 1;
            a = fmin(fmax(a, 0.02), 0.98 * WFF_LIMIT_A_MAX);
            double th[3] = {logit(b_frac[ib]), logit(a / WFF_LIMIT_A_MAX),
                            logit((p - WFF_LIMIT_P_MIN) / (WFF_LIMIT_P_MAX - WFF_LIMIT_P_MIN))};
            int iters = 0, conv = 0;
            double ssr = solve(&c, th, &iters, &conv);
            out->starts++;
            if (ssr < best) {
                best = ssr;
                memcpy(best_th, th, sizeof th);
                out->iterations = iters;
                out->converged = conv;
            }
        }
    int rc = 0;
    if (!isfinite(best))
        rc = wff_fail(err, "Lambert-Jonas fit: GSL nonlinear least squares failed from every "
                           "start (%d perforating runs)", c.n);
    if (rc == 0) {
        double b, a, p;
        natural(&c, best_th, &b, &a, &p);
        out->value[WFF_LIMIT_VBL] = b * scale;
        out->value[WFF_LIMIT_A] = a;
        out->value[WFF_LIMIT_P] = p;
        double tol = 1e-6;
        out->at_bound[WFF_LIMIT_VBL] =
            (b - c.lo) <= tol * c.hi || (c.hi - b) <= tol * c.hi;
        out->at_bound[WFF_LIMIT_A] = a >= WFF_LIMIT_A_MAX * (1 - tol) || a <= tol;
        out->at_bound[WFF_LIMIT_P] =
            p <= WFF_LIMIT_P_MIN + tol * WFF_LIMIT_P_MAX || p >= WFF_LIMIT_P_MAX * (1 - tol);
        int dof = c.n - 3;
        double s2 = dof > 0 ? best / dof : NAN;
        out->residual_sd = sqrt(s2) * scale;
        out->rms_residual = sqrt(best / c.n) * scale;
        /* covariance s² (JᵀJ)⁻¹ in the natural parameters (scaled speeds) */
        gsl_matrix *J = gsl_matrix_alloc((size_t)c.n, 3), *C = gsl_matrix_alloc(3, 3);
        if (!J || !C)
            rc = wff_fail(err, "Lambert-Jonas fit: out of memory");
        for (int i = 0; rc == 0 && i < c.n; i++) {
            double d[3];
            model(c.x[i], b, a, p, d);
            for (int j = 0; j < 3; j++)
                gsl_matrix_set(J, (size_t)i, (size_t)j, d[j]);
        }
        if (rc == 0) {
            double unit[3] = {scale, 1, 1};
            gsl_multifit_nlinear_covar(J, 0.0, C);
            for (int i = 0; i < 3; i++)
                for (int j = 0; j < 3; j++)
                    out->covariance[i][j] = s2 * gsl_matrix_get(C, (size_t)i, (size_t)j) *
                                            unit[i] * unit[j];
            for (int i = 0; i < 3; i++)
                out->std_error[i] = sqrt(fmax(out->covariance[i][i], 0)) +
                                    (isnan(out->covariance[i][i]) ? NAN : 0);
        }
        gsl_matrix_free(J);
        gsl_matrix_free(C);
        out->v50_fit = out->value[WFF_LIMIT_VBL];
        out->v50_fit_error = out->std_error[WFF_LIMIT_VBL];
    }
    gsl_set_error_handler(old);
    free(xy);
    return rc;
}

/* fit.c: parameter identification with GSL's nonlinear least squares (see
 * include/wovenff/fit.h and docs/fit.md): the parameter lists, the bounds'
 * change of variable, the residuals, the trust-region fit and the
 * covariance at the solution.
 *
 * The residual function maps the solver's variables z to the parameters x
 * (bounds by change of variable), writes x into a copy of the material text
 * (material.c's editor), re-parses it (so every check of the material reader
 * applies to every candidate) and solves the static states of the data's
 * tests by continuation (fit_data.c). A candidate the model cannot evaluate
 * (rejected by the cell, or a static state that does not converge) gets a
 * huge residual so that the trust region rejects the step and shrinks; the
 * fit fails only if the final point cannot be evaluated. Knows nothing of
 * files (fit_report.c writes them), meshes or the solver. */
#include "wovenff/fit.h"
#include "wall_clock.h"

#include "wovenff/text_io.h"

#include <ctype.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Residual given to a candidate the model cannot evaluate. */
#define FAILED_RESIDUAL 1e8
/* Relative step of the central differences for the covariance's Jacobian. */
#define COVARIANCE_STEP 1e-5
/* Step of GSL's central-difference Jacobian in the solver's variables. */
#define SOLVER_FD_STEP 1e-6
/* Relative weighting: smallest load a residual is divided by, as a fraction
 * of its test's RMS load (points at zero load would otherwise dominate). */
#define RELATIVE_FLOOR 1e-3

/* ---- material text (material.c's editor, with the fit's rules) --------------------- */

static int key_missing(const char *text, const char *source, const char *key, wff_error *err)
{
    char keys[400];
    wff_material_text_keys(text, keys, sizeof keys);
    return wff_fail(err, "fit: parameter '%s' is not a key of material %s (its keys: %s)", key,
                    source, keys);
}

int wff_fit_material_value(const char *text, const char *source, const char *key,
                           double *value, wff_error *err)
{
    const char *vb, *ve;
    int line;
    if (!wff_material_text_find(text, key, &vb, &ve, &line))
        return key_missing(text, source, key, err);
    if (wff_parse_number_span(vb, ve, value) || !isfinite(*value))
        return wff_fail(err, "%s:%d: key '%s': '%.*s' is not a number", source, line, key,
                        (int)(ve - vb), vb);
    return 0;
}

int wff_fit_material_edit(const char *text, const char *source, int n,
                          const char *const *names, const double *values, char *out,
                          size_t cap, wff_error *err)
{
    if (n < 0 || n > WFF_FIT_PARAMS_MAX)
        return wff_fail(err, "fit: %d parameters (at most %d)", n, WFF_FIT_PARAMS_MAX);
    char number[WFF_FIT_PARAMS_MAX][32];
    const char *value_text[WFF_FIT_PARAMS_MAX];
    for (int i = 0; i < n; i++) {
        if (strcmp(names[i], "cell") == 0)
            return wff_fail(err, "fit: parameter 'cell' names the unit cell: it cannot be fitted");
        double old;
        if (wff_fit_material_value(text, source, names[i], &old, err))
            return -1;
        for (int j = 0; j < i; j++)
            if (strcmp(names[j], names[i]) == 0)
                return wff_fail(err, "fit: parameter '%s' given twice", names[i]);
        snprintf(number[i], sizeof number[i], "%.17g", values[i]);
        value_text[i] = number[i];
    }
    char *edited;
    if (wff_material_text_replace(text, source, n, names, value_text, &edited, err))
        return -1;
    size_t len = strlen(edited);
    if (len + 1 > cap) {
        free(edited);
        return wff_fail(err, "fit: edited material %s does not fit in %zu bytes", source, cap);
    }
    memcpy(out, edited, len + 1);
    free(edited);
    return 0;
}

/* ---- parameters --------------------------------------------------------------------- */

/* Next comma-separated item of list at *pos: [b, e) trimmed. Returns 0 at the end. */
static int next_item(const char *list, const char **pos, const char **b, const char **e)
{
    const char *p = *pos;
    if (!p)
        return 0;
    const char *end = list + strlen(list);
    const char *comma = memchr(p, ',', (size_t)(end - p));
    const char *ie = comma ? comma : end;
    *b = wff_skip_space(p, ie);
    *e = wff_trim_end(*b, ie);
    *pos = comma ? comma + 1 : NULL;
    return 1;
}

static int blank(const char *s)
{
    return !s || *wff_skip_space(s, s + strlen(s)) == '\0';
}

int wff_fit_params_parse(const char *names, const char *bounds, const char *starts,
                         wff_fit_param *params, int max, int *n, wff_error *err)
{
    *n = 0;
    if (blank(names))
        return wff_fail(err, "fit: no parameter names given (e.g. \"K_I,a\")");
    const char *pos = names, *b, *e;
    while (next_item(names, &pos, &b, &e)) {
        size_t len = (size_t)(e - b);
        if (len == 0)
            return wff_fail(err, "fit: parameter list '%s' has an empty name", names);
        if (*n >= max || *n >= WFF_FIT_PARAMS_MAX)
            return wff_fail(err, "fit: more than %d parameters in '%s'",
                            max < WFF_FIT_PARAMS_MAX ? max : WFF_FIT_PARAMS_MAX, names);
        if (len >= WFF_KV_KEY_MAX)
            return wff_fail(err, "fit: parameter name '%.*s' too long", (int)len, b);
        for (const char *c = b; c < e; c++)
            if (!(isalnum((unsigned char)*c) || *c == '_'))
                return wff_fail(err, "fit: parameter name '%.*s' has a character other than "
                                "letters, digits and '_'", (int)len, b);
        wff_fit_param *pp = &params[*n];
        snprintf(pp->name, sizeof pp->name, "%.*s", (int)len, b);
        for (int j = 0; j < *n; j++)
            if (strcmp(params[j].name, pp->name) == 0)
                return wff_fail(err, "fit: parameter '%s' given twice", pp->name);
        pp->lo = pp->hi = NAN; /* default bounds, resolved with the start value */
        pp->start = NAN;
        (*n)++;
    }
    if (!blank(bounds)) {
        int i = 0;
        pos = bounds;
        while (next_item(bounds, &pos, &b, &e)) {
            if (i >= *n)
                return wff_fail(err, "fit: bounds '%s': more items than the %d parameters",
                                bounds, *n);
            const char *colon = memchr(b, ':', (size_t)(e - b));
            if (!colon)
                return wff_fail(err, "fit: bounds of '%s': '%.*s' is not lo:hi (either side "
                                "may be empty)", params[i].name, (int)(e - b), b);
            const char *lb = b, *le = wff_trim_end(b, colon);
            const char *hb = wff_skip_space(colon + 1, e), *he = e;
            double lo = -INFINITY, hi = INFINITY;
            if ((le > lb && wff_parse_number_span(lb, le, &lo)) ||
                (he > hb && wff_parse_number_span(hb, he, &hi)) || isnan(lo) || isnan(hi))
                return wff_fail(err, "fit: bounds of '%s': '%.*s' is not lo:hi with numbers",
                                params[i].name, (int)(e - b), b);
            if (!(lo < hi))
                return wff_fail(err, "fit: bounds of '%s': lower %g not below upper %g",
                                params[i].name, lo, hi);
            params[i].lo = lo;
            params[i].hi = hi;
            i++;
        }
        if (i != *n)
            return wff_fail(err, "fit: bounds '%s' has %d items for %d parameters", bounds, i,
                            *n);
    }
    if (!blank(starts)) {
        int i = 0;
        pos = starts;
        while (next_item(starts, &pos, &b, &e)) {
            if (i >= *n)
                return wff_fail(err, "fit: starting values '%s': more items than the %d "
                                "parameters", starts, *n);
            double *start = &params[i].start;
            if (e > b && (wff_parse_number_span(b, e, start) || !isfinite(*start)))
                return wff_fail(err, "fit: starting value of '%s': '%.*s' is not a number",
                                params[i].name, (int)(e - b), b);
            i++;
        }
        if (i != *n)
            return wff_fail(err, "fit: starting values '%s' has %d items for %d parameters",
                            starts, i, *n);
    }
    return 0;
}

/* ---- the fit ------------------------------------------------------------------------------ */

void wff_fit_options_default(wff_fit_options *opt)
{
    opt->max_iterations = 200;
    opt->xtol = 1e-10;
    opt->gtol = 1e-12;
    opt->ftol = 1e-14;
    opt->weighting = WFF_FIT_WEIGHT_TEST;
}

static const char *const weighting_names[] = {"test", "relative"};

const char *wff_fit_weighting_name(int weighting)
{
    return weighting == WFF_FIT_WEIGHT_TEST || weighting == WFF_FIT_WEIGHT_RELATIVE
               ? weighting_names[weighting]
               : NULL;
}

int wff_fit_weighting_find(const char *name)
{
    for (int k = 0; k < 2; k++)
        if (strcmp(name, weighting_names[k]) == 0)
            return k;
    return -1;
}

enum { T_LOGTANH, T_TANH, T_LOWER, T_UPPER, T_FREE };

typedef struct transform {
    int kind;
    double lo, hi, scale;
} transform;

static double to_x(const transform *t, double z)
{
    switch (t->kind) {
    case T_LOGTANH: {
        double ll = log(t->lo), lh = log(t->hi);
        double x = exp(ll + (lh - ll) * 0.5 * (1 + tanh(z)));
        return fmin(fmax(x, t->lo), t->hi);
    }
    case T_TANH:
        return fmin(fmax(t->lo + (t->hi - t->lo) * 0.5 * (1 + tanh(z)), t->lo), t->hi);
    case T_LOWER:
        return t->lo + exp(z);
    case T_UPPER:
        return t->hi - exp(z);
    default:
        return t->scale * z;
    }
}

static double to_z(const transform *t, double x)
{
    switch (t->kind) {
    case T_LOGTANH: {
        double ll = log(t->lo), lh = log(t->hi);
        return atanh(2 * (log(x) - ll) / (lh - ll) - 1);
    }
    case T_TANH:
        return atanh(2 * (x - t->lo) / (t->hi - t->lo) - 1);
    case T_LOWER:
        return log(x - t->lo);
    case T_UPPER:
        return log(t->hi - x);
    default:
        return x / t->scale;
    }
}

/* 1 when x sits on a bound: within 1e-6 of it, relative to the range (in the
 * logarithm for log-tanh) or to the start's distance from it. The solver
 * approaches a bound slowly (the change of variable flattens there), so the
 * test is loose. */
#define BOUND_TOLERANCE 1e-6
static int on_bound(const transform *t, double z, double x, double start)
{
    switch (t->kind) {
    case T_LOGTANH:
    case T_TANH:
        return 1 - fabs(tanh(z)) < 2 * BOUND_TOLERANCE;
    case T_LOWER:
        return x - t->lo <= BOUND_TOLERANCE * fabs(start - t->lo);
    case T_UPPER:
        return t->hi - x <= BOUND_TOLERANCE * fabs(t->hi - start);
    default:
        return 0;
    }
}

typedef struct fit_ctx {
    const char *text, *source;
    const wff_fit_data *data;
    int p, n;
    const char *names[WFF_FIT_PARAMS_MAX];
    transform tr[WFF_FIT_PARAMS_MAX];
    char *buf;
    size_t cap;
    char cand_source[300];
    /* points grouped by test: idx[test_begin[t] .. test_begin[t+1]) */
    int *idx;
    int test_begin[WFF_FIT_TESTS + 1];
    double scale[WFF_FIT_TESTS];
    double *xs, *ys, *r; /* scratch, n each */
    double *weight;      /* 1 / (what each residual is measured in), n */
    int failures;
    wff_error last;
} fit_ctx;

/* Model predictions at parameters x into model[] (data order). */
static int ctx_model(fit_ctx *c, const double *x, double *model, wff_error *err)
{
    if (wff_fit_material_edit(c->text, c->source, c->p, c->names, x, c->buf, c->cap, err))
        return -1;
    wff_material mat;
    if (wff_material_parse_text(c->buf, c->cand_source, &mat, err))
        return -1;
    for (int t = 0; t < WFF_FIT_TESTS; t++) {
        int b = c->test_begin[t], m = c->test_begin[t + 1] - b;
        if (m == 0)
            continue;
        for (int k = 0; k < m; k++)
            c->xs[k] = c->data->point[c->idx[b + k]].x;
        if (wff_fit_predict(&mat, t, m, c->xs, c->ys, err))
            return -1;
        for (int k = 0; k < m; k++)
            model[c->idx[b + k]] = c->ys[k];
    }
    return 0;
}

/* Weighted residuals at parameters x. */
static int ctx_residuals(fit_ctx *c, const double *x, double *r, wff_error *err)
{
    if (ctx_model(c, x, r, err))
        return -1;
    for (int i = 0; i < c->n; i++) {
        const wff_fit_point *pt = &c->data->point[i];
        r[i] = (r[i] - pt->y) * c->weight[i];
        if (!isfinite(r[i]))
            return wff_fail(err, "fit: non-finite prediction for %s at x = %g",
                            wff_fit_test_name(pt->test), pt->x);
    }
    return 0;
}

static int gsl_residuals(const gsl_vector *z, void *params, gsl_vector *f)
{
    fit_ctx *c = params;
    double x[WFF_FIT_PARAMS_MAX];
    for (int j = 0; j < c->p; j++)
        x[j] = to_x(&c->tr[j], gsl_vector_get(z, (size_t)j));
    /* f may be a strided view (GSL's finite differences write Jacobian columns) */
    if (ctx_residuals(c, x, c->r, &c->last)) {
        c->failures++;
        for (int i = 0; i < c->n; i++)
            c->r[i] = FAILED_RESIDUAL;
    }
    for (int i = 0; i < c->n; i++)
        gsl_vector_set(f, (size_t)i, c->r[i]);
    return GSL_SUCCESS;
}

/* Set up c from the inputs: resolved bounds and starts, grouping, scales. */
static int ctx_init(fit_ctx *c, const char *text, const char *source, const wff_fit_data *data,
                    const wff_fit_param *params, int p, int weighting, wff_fit_result *res,
                    wff_error *err)
{
    memset(c, 0, sizeof *c);
    c->text = text;
    c->source = source;
    c->data = data;
    c->p = p;
    c->n = data->n;
    snprintf(c->cand_source, sizeof c->cand_source, "%s", source);
    if (p < 1 || p > WFF_FIT_PARAMS_MAX)
        return wff_fail(err, "fit: %d parameters (want 1 to %d)", p, WFF_FIT_PARAMS_MAX);
    if (data->n <= p)
        return wff_fail(err, "fit: %s has %d points for %d parameters (need more points than "
                        "parameters)", data->source, data->n, p);
    memset(res, 0, sizeof *res);
    res->n_params = p;
    res->n_points = data->n;
    for (int j = 0; j < p; j++) {
        const wff_fit_param *pp = &params[j];
        c->names[j] = pp->name;
        for (int k = 0; k < j; k++)
            if (strcmp(params[k].name, pp->name) == 0)
                return wff_fail(err, "fit: parameter '%s' given twice", pp->name);
        if (strcmp(pp->name, "cell") == 0)
            return wff_fail(err, "fit: parameter 'cell' names the unit cell: it cannot be fitted");
        double file_value;
        if (wff_fit_material_value(text, source, pp->name, &file_value, err))
            return -1;
        double x0 = isnan(pp->start) ? file_value : pp->start;
        double lo = pp->lo, hi = pp->hi;
        if (isnan(lo) && isnan(hi)) {
            lo = x0 > 0 ? 0 : -INFINITY;
            hi = INFINITY;
        }
        if (isnan(lo) || isnan(hi) || !(lo < hi))
            return wff_fail(err, "fit: parameter '%s': bounds [%g, %g] are not lo < hi",
                            pp->name, lo, hi);
        if (!(x0 > lo && x0 < hi) || !isfinite(x0))
            return wff_fail(err, "fit: parameter '%s': start %g is not strictly inside its "
                            "bounds [%g, %g]", pp->name, x0, lo, hi);
        transform *t = &c->tr[j];
        t->lo = lo;
        t->hi = hi;
        t->scale = x0 != 0 ? fabs(x0) : 1;
        if (isfinite(lo) && isfinite(hi))
            t->kind = lo > 0 ? T_LOGTANH : T_TANH;
        else if (isfinite(lo))
            t->kind = T_LOWER;
        else if (isfinite(hi))
            t->kind = T_UPPER;
        else
            t->kind = T_FREE;
        snprintf(res->name[j], sizeof res->name[j], "%s", pp->name);
        res->lo[j] = lo;
        res->hi[j] = hi;
        res->start[j] = x0;
    }
    /* group the points by test, scale each test by its RMS load */
    c->idx = malloc((size_t)c->n * sizeof *c->idx);
    c->xs = malloc(4 * (size_t)c->n * sizeof *c->xs);
    size_t tlen = strlen(text);
    c->cap = tlen + (size_t)p * 32 + 64;
    c->buf = malloc(c->cap);
    if (!c->idx || !c->xs || !c->buf)
        return wff_fail(err, "fit: out of memory");
    c->ys = c->xs + c->n;
    c->r = c->ys + c->n;
    c->weight = c->r + c->n;
    int k = 0;
    for (int t = 0; t < WFF_FIT_TESTS; t++) {
        c->test_begin[t] = k;
        double sum = 0;
        for (int i = 0; i < c->n; i++)
            if (data->point[i].test == t) {
                c->idx[k++] = i;
                sum += data->point[i].y * data->point[i].y;
            }
        int m = k - c->test_begin[t];
        res->test_points[t] = m;
        if (m > 0) {
            c->scale[t] = sqrt(sum / m);
            if (!(c->scale[t] > 0))
                return wff_fail(err, "fit: %s: every %s load is zero: nothing to scale the "
                                "residuals by", data->source, wff_fit_test_name(t));
        }
        res->test_scale[t] = c->scale[t];
    }
    c->test_begin[WFF_FIT_TESTS] = k;
    for (int i = 0; i < c->n; i++) {
        const wff_fit_point *pt = &data->point[i];
        double unit = c->scale[pt->test];
        if (weighting == WFF_FIT_WEIGHT_RELATIVE)
            unit = fmax(fabs(pt->y), RELATIVE_FLOOR * unit);
        c->weight[i] = 1 / unit;
    }
    return 0;
}

static void ctx_free(fit_ctx *c)
{
    free(c->idx);
    free(c->xs);
    free(c->buf);
}

static double sum_squares(const double *r, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += r[i] * r[i];
    return s;
}

/* Covariance s² (JᵀJ)⁻¹ with J = ∂r/∂x by central differences, computed on
 * relative parameters (columns scaled by |x|) for conditioning. */
static int covariance(fit_ctx *c, const double *x, double s2, wff_fit_result *res, wff_error *err)
{
    int n = c->n, p = c->p;
    gsl_matrix *J = gsl_matrix_alloc((size_t)n, (size_t)p);
    gsl_matrix *C = gsl_matrix_alloc((size_t)p, (size_t)p);
    double *rp = malloc(2 * (size_t)n * sizeof *rp);
    if (!J || !C || !rp) {
        gsl_matrix_free(J);
        gsl_matrix_free(C);
        free(rp);
        return wff_fail(err, "fit: out of memory");
    }
    double *rm = rp + n, xs[WFF_FIT_PARAMS_MAX], unit[WFF_FIT_PARAMS_MAX];
    int rc = 0;
    for (int j = 0; j < p && rc == 0; j++) {
        unit[j] = x[j] != 0 ? fabs(x[j]) : c->tr[j].scale;
        double h = COVARIANCE_STEP * unit[j];
        memcpy(xs, x, (size_t)p * sizeof *xs);
        xs[j] = x[j] + h;
        int up = ctx_residuals(c, xs, rp, err) == 0;
        xs[j] = x[j] - h;
        int down = ctx_residuals(c, xs, rm, err) == 0;
        double span = 2 * h;
        if (up && !down) { /* one-sided where the model stops at one side */
            if (ctx_residuals(c, x, rm, err)) { rc = -1; break; }
            span = h;
        } else if (!up && down) {
            if (ctx_residuals(c, x, rp, err)) { rc = -1; break; }
            span = h;
        } else if (!up) {
            rc = wff_fail(err, "fit: covariance: the model cannot be evaluated on either side "
                          "of %s = %g: %s", c->names[j], x[j], err ? err->message : "");
            break;
        }
        for (int i = 0; i < n; i++) /* ∂r/∂(x_j/unit_j) */
            gsl_matrix_set(J, (size_t)i, (size_t)j, (rp[i] - rm[i]) / span * unit[j]);
    }
    if (rc == 0) {
        /* reciprocal condition number of the relative-sensitivity matrix */
        gsl_matrix *U = gsl_matrix_alloc((size_t)n, (size_t)p);
        gsl_matrix *V = gsl_matrix_alloc((size_t)p, (size_t)p);
        gsl_vector *S = gsl_vector_alloc((size_t)p), *wk = gsl_vector_alloc((size_t)p);
        if (U && V && S && wk) {
            gsl_matrix_memcpy(U, J);
            if (gsl_linalg_SV_decomp(U, V, S, wk) == GSL_SUCCESS) {
                double smax = gsl_vector_get(S, 0), smin = gsl_vector_get(S, (size_t)p - 1);
                res->condition = smax > 0 ? smin / smax : 0;
            }
        }
        gsl_matrix_free(U);
        gsl_matrix_free(V);
        gsl_vector_free(S);
        gsl_vector_free(wk);
        gsl_multifit_nlinear_covar(J, 0.0, C);
        for (int a = 0; a < p; a++)
            for (int b = 0; b < p; b++)
                res->covariance[a][b] = s2 * gsl_matrix_get(C, (size_t)a, (size_t)b) *
                                        unit[a] * unit[b];
        for (int a = 0; a < p; a++)
            res->std_error[a] = sqrt(fmax(res->covariance[a][a], 0));
        for (int a = 0; a < p; a++)
            for (int b = 0; b < p; b++) {
                double d = res->std_error[a] * res->std_error[b];
                res->correlation[a][b] = d > 0 ? res->covariance[a][b] / d : (a == b);
            }
        if (res->condition == 0 || res->condition < 1e-14)
            for (int a = 0; a < p; a++) /* not identifiable: say so, not a number */
                res->std_error[a] = INFINITY;
    }
    gsl_matrix_free(J);
    gsl_matrix_free(C);
    free(rp);
    return rc;
}

int wff_fit_run(const char *material_text, const char *source_name, const wff_fit_data *data,
                const wff_fit_param *params, int n_params, const wff_fit_options *opt,
                wff_fit_result *res, wff_error *err)
{
    double t0 = wff_wall_seconds();
    wff_fit_options defaults;
    if (!opt) {
        wff_fit_options_default(&defaults);
        opt = &defaults;
    }
    if (!source_name)
        source_name = "(material)";
    fit_ctx c;
    if (opt->weighting != WFF_FIT_WEIGHT_TEST && opt->weighting != WFF_FIT_WEIGHT_RELATIVE)
        return wff_fail(err, "fit: weighting %d unknown (0 test, 1 relative)", opt->weighting);
    if (ctx_init(&c, material_text, source_name, data, params, n_params, opt->weighting, res,
                 err)) {
        ctx_free(&c);
        return -1;
    }
    int n = c.n, p = c.p;
    double *r = malloc((size_t)n * sizeof *r);
    if (!r) {
        ctx_free(&c);
        return wff_fail(err, "fit: out of memory");
    }
    /* the model must work at the start: its error is the user's to see */
    if (ctx_residuals(&c, res->start, r, err)) {
        char msg[WFF_ERROR_MAX];
        snprintf(msg, sizeof msg, "%s", err ? err->message : "");
        free(r);
        ctx_free(&c);
        return wff_fail(err, "fit: the model fails at the starting values: %s", msg);
    }
    res->start_residual_norm = sqrt(sum_squares(r, n));
    res->weighting = opt->weighting;

    gsl_multifit_nlinear_parameters fp = gsl_multifit_nlinear_default_parameters();
    fp.trs = gsl_multifit_nlinear_trs_lm; /* Levenberg–Marquardt, no geodesic acceleration */
    fp.scale = gsl_multifit_nlinear_scale_more;
    fp.solver = gsl_multifit_nlinear_solver_qr;
    fp.fdtype = GSL_MULTIFIT_NLINEAR_CTRDIFF;
    fp.h_df = SOLVER_FD_STEP;
    gsl_multifit_nlinear_fdf fdf = {
        .f = gsl_residuals, .df = NULL, .fvv = NULL, .n = (size_t)n, .p = (size_t)p,
        .params = &c};
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    gsl_multifit_nlinear_workspace *w =
        gsl_multifit_nlinear_alloc(gsl_multifit_nlinear_trust, &fp, (size_t)n, (size_t)p);
    gsl_vector *z = gsl_vector_alloc((size_t)p);
    int rc = 0;
    if (!w || !z)
        rc = wff_fail(err, "fit: out of memory");
    if (rc == 0) {
        for (int j = 0; j < p; j++)
            gsl_vector_set(z, (size_t)j, to_z(&c.tr[j], res->start[j]));
        int status = gsl_multifit_nlinear_init(z, &fdf, w);
        int info = 0;
        if (status == GSL_SUCCESS)
            status = gsl_multifit_nlinear_driver((size_t)opt->max_iterations, opt->xtol,
                                                 opt->gtol, opt->ftol, NULL, NULL, &info, w);
        res->iterations = (int)gsl_multifit_nlinear_niter(w);
        res->f_evals = (int)fdf.nevalf;
        if (status == GSL_SUCCESS)
            res->converged = info;
        else if (status == GSL_ENOPROG || status == GSL_EMAXITER)
            res->converged = 0; /* stalled or out of iterations: reported, not an error */
        else
            rc = wff_fail(err, "fit: GSL nonlinear least squares failed: %s",
                          gsl_strerror(status));
        if (status == GSL_ENOPROG) /* no step improves any more: converged to the */
            res->converged = 4;    /* resolution of the model's static solves */
    }
    if (rc == 0) {
        const gsl_vector *zf = gsl_multifit_nlinear_position(w);
        for (int j = 0; j < p; j++) {
            double zj = gsl_vector_get(zf, (size_t)j);
            res->value[j] = to_x(&c.tr[j], zj);
            res->at_bound[j] = on_bound(&c.tr[j], zj, res->value[j], res->start[j]);
        }
        if (ctx_residuals(&c, res->value, r, err)) {
            char msg[WFF_ERROR_MAX];
            snprintf(msg, sizeof msg, "%s", err ? err->message : "");
            rc = wff_fail(err, "fit: the model fails at the solution: %s", msg);
        }
    }
    if (rc == 0) {
        res->ssr = sum_squares(r, n);
        res->residual_norm = sqrt(res->ssr);
        res->s2 = res->ssr / (n - p);
        for (int i = 0; i < n; i++) {
            int t = data->point[i].test;
            double d = r[i] / c.weight[i];
            res->test_rms[t] += d * d;
        }
        for (int t = 0; t < WFF_FIT_TESTS; t++)
            if (res->test_points[t])
                res->test_rms[t] = sqrt(res->test_rms[t] / res->test_points[t]);
        rc = covariance(&c, res->value, res->s2, res, err);
    }
    gsl_vector_free(z);
    if (w)
        gsl_multifit_nlinear_free(w);
    gsl_set_error_handler(old);
    free(r);
    ctx_free(&c);
    res->wall_seconds = wff_wall_seconds() - t0;
    return rc;
}

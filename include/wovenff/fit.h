/* wovenff — parameter identification: fit material keys to test curves with
 * GSL's nonlinear least squares (gsl_multifit_nlinear, trust region with
 * Levenberg–Marquardt steps, finite-difference Jacobian). docs/fit.md has the
 * whole story; in short:
 *
 * Data: a CSV file with the header `test,x,y`, one point a line (`#` comments
 * and blank lines allowed). `test` selects the model prediction:
 *
 *   test               x                         y (N/m)                   static state
 *   strip_warp         nominal strain λ1 − 1     P11, load per width       wff_uniaxial_static, family 0
 *   strip_weft         nominal strain λ2 − 1     P22                       wff_uniaxial_static, family 1
 *   equibiaxial_warp   strain λ1 − 1 = λ2 − 1    P11                       wff_biaxial_static, both stretches held
 *   equibiaxial_weft   strain λ1 − 1 = λ2 − 1    P22                       the same state
 *   shear              shear angle γ, rad        S = ∂W/∂γ                 wff_shear_static (balance.h)
 *
 * Every state is quasi-static and elastic: amplitudes in balance, γᶠ = 0 held
 * (no shear flow). For `shear` the resultant S is the work conjugate of the
 * shear angle per unit reference area (the picture-frame power balance):
 * a frame of side L pulled along its diagonal carries F_frame = S L / sin(π/4 − γ/2),
 * and the "normalised shear force per unit length" of Peng & Cao (2004) is
 * S / cos γ. At small γ, S ≈ (P12 + P21)/2.
 *
 * Residuals: r_i = (model_i − y_i) / scale_t, scale_t the RMS of y over the
 * points of test t, so that tests of different size weigh alike per point
 * (or relative to each load: see wff_fit_options).
 * Parameters: material keys by name; the fitter edits their values in the
 * material text and re-parses it for every candidate (no global state).
 * Bounds hold through a change of variable (see wff_fit_param). Confidence:
 * covariance = s² (JᵀJ)⁻¹ with s² = SSR/(n − p) and J the Jacobian of the
 * weighted residuals with respect to the parameters themselves at the
 * solution (central differences) — the delta method applied to the
 * transformed variables gives the same matrix, and this form stays finite
 * when an estimate sits on a bound.
 *
 * All functions return 0 or -1 with err naming the file, line, parameter or
 * test at fault. */
#ifndef WOVENFF_FIT_H
#define WOVENFF_FIT_H

#include <stddef.h>

#include "wovenff/balance.h"
#include "wovenff/cell.h"
#include "wovenff/material.h"
#include "wovenff/fit_data.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Most parameters fitted at once (a handful is all a few curves identify). */
#define WFF_FIT_PARAMS_MAX 8

/* ---- material text --------------------------------------------------------- */

/* Copy `text` (a material file) to out (capacity cap) with key names[i] set to
 * values[i] (%.17g, the comment after the value kept). Every key must already
 * be in the text as `key = number`; `cell` cannot be set. */
int wff_fit_material_edit(const char *text, const char *source, int n,
                          const char *const *names, const double *values, char *out,
                          size_t cap, wff_error *err);
/* The number given for `key` in the material text. */
int wff_fit_material_value(const char *text, const char *source, const char *key,
                           double *value, wff_error *err);

/* ---- the fit ---------------------------------------------------------------- */

/* One fitted parameter. Bounds, and the variable z the solver moves:
 *   lo, hi finite, lo > 0   x = exp(log lo + (log hi − log lo)(1 + tanh z)/2)
 *   lo, hi finite, lo <= 0  x = lo + (hi − lo)(1 + tanh z)/2
 *   lo finite only          x = lo + exp(z)
 *   hi finite only          x = hi − exp(z)
 *   neither                 x = |x_start| z    (|x_start| = 1 when x_start = 0)
 * The start must lie strictly inside the bounds. */
typedef struct wff_fit_param {
    char name[WFF_KV_KEY_MAX];
    double lo, hi;  /* -INFINITY / INFINITY when open; both NAN: (0, inf) for a
                       positive start, (-inf, inf) otherwise */
    double start;   /* NAN: the material file's value */
} wff_fit_param;

/* Parameters from script-style lists:
 *   names  "K_I,a,kb_1"
 *   bounds ""  or  "1e-3:1e-1,1e4:1e6,:"  — one lo:hi per name, either side may
 *          be empty (open); an empty list makes every bound (0, inf) for a
 *          positive starting value and (-inf, inf) otherwise
 *   starts ""  or  "0.01,8e4,3e-4" — one number per name (empty: from the file)
 * Unknown keys are caught by wff_fit_run (it knows the material). */
int wff_fit_params_parse(const char *names, const char *bounds, const char *starts,
                         wff_fit_param *params, int max, int *n, wff_error *err);

/* How residuals are made dimensionless:
 *   TEST      r_i = (model_i − y_i) / scale_t, scale_t the RMS of y over test t:
 *             right for noise of constant size within each test (default)
 *   RELATIVE  r_i = (model_i − y_i) / max(|y_i|, 1e-3 scale_t): right for
 *             noise proportional to the load (multiplicative) */
enum { WFF_FIT_WEIGHT_TEST = 0, WFF_FIT_WEIGHT_RELATIVE = 1 };
/* "test", "relative"; NULL outside the range. */
const char *wff_fit_weighting_name(int weighting);
/* The weighting named `name`, or -1. */
int wff_fit_weighting_find(const char *name);

typedef struct wff_fit_options {
    int max_iterations; /* 200 */
    double xtol;        /* 1e-10: relative step in the solver's variables */
    double gtol;        /* 1e-12: scaled gradient */
    double ftol;        /* 1e-14: relative change of the cost */
    int weighting;      /* WFF_FIT_WEIGHT_TEST */
} wff_fit_options;

void wff_fit_options_default(wff_fit_options *opt);

typedef struct wff_fit_result {
    int n_params, n_points;
    int weighting;         /* the options' weighting */
    char name[WFF_FIT_PARAMS_MAX][WFF_KV_KEY_MAX];
    double lo[WFF_FIT_PARAMS_MAX], hi[WFF_FIT_PARAMS_MAX];
    double start[WFF_FIT_PARAMS_MAX];      /* values the fit started from */
    double value[WFF_FIT_PARAMS_MAX];      /* estimates */
    double std_error[WFF_FIT_PARAMS_MAX];  /* sqrt of the covariance's diagonal */
    int at_bound[WFF_FIT_PARAMS_MAX];      /* 1: the estimate is on a bound (its
                                              standard error is then a local one) */
    double covariance[WFF_FIT_PARAMS_MAX][WFF_FIT_PARAMS_MAX];
    double correlation[WFF_FIT_PARAMS_MAX][WFF_FIT_PARAMS_MAX];
    double ssr;            /* Σ r_i², weighted residuals */
    double residual_norm;  /* √SSR */
    double s2;             /* SSR/(n − p), the residual variance */
    double start_residual_norm; /* √SSR at the start */
    double condition;      /* reciprocal condition number of J (GSL), 0 when singular */
    int iterations, f_evals;
    int converged;         /* 1 small step, 2 small gradient, 3 small cost change;
                              0: iteration limit */
    int test_points[WFF_FIT_TESTS];
    double test_scale[WFF_FIT_TESTS]; /* N/m */
    double test_rms[WFF_FIT_TESTS];   /* RMS of model − y, N/m (fitted) */
    double wall_seconds;
} wff_fit_result;

/* Fit params (n_params of them) of the material given as text (source_name
 * for messages) to data. opt may be NULL (defaults). */
int wff_fit_run(const char *material_text, const char *source_name, const wff_fit_data *data,
                const wff_fit_param *params, int n_params, const wff_fit_options *opt,
                wff_fit_result *result, wff_error *err);

/* ---- reports ---------------------------------------------------------------- */

/* fit.json: parameters (start, value, std_error, relative, bounds, at_bound),
 * correlation, residual norms, s², iterations, per-test points/scale/RMS.
 * Written to a temporary file and renamed (whole or not at all). */
int wff_fit_write_json(const wff_fit_result *res, const char *material_path,
                       const char *data_path, const char *path, wff_error *err);
/* The material text with the fitted values and a header comment saying so. */
int wff_fit_write_material(const char *material_text, const char *source_name,
                           const wff_fit_result *res, const char *data_path, const char *path,
                           wff_error *err);
/* For plots: `path` gets, for each test present in data (in wff_fit_test
 * order), a gnuplot block (separated by two blank lines, headed by
 * `# test NAME`) of n_curve rows `x,y_start,y_fit` from min(0, x_min) to
 * x_max; points_path gets the data the same way, rows `x,y,y_fit`. */
int wff_fit_write_curves(const char *material_text, const char *source_name,
                         const wff_fit_result *res, const wff_fit_data *data, int n_curve,
                         const char *path, const char *points_path, wff_error *err);

/* ---- files in, files out (what the FreeFEM binding calls) ------------------------ */

/* Read the material and the data, parse the lists (wff_fit_params_parse),
 * fit, and when out_dir is not NULL write there fit.json, fitted_material.txt,
 * fit_curves.csv (80 points a curve) and fit_points.csv. opt may be NULL. */
int wff_fit_files(const char *material_path, const char *data_path, const char *names,
                  const char *bounds, const char *starts, const wff_fit_options *opt,
                  const char *out_dir, wff_fit_result *res, wff_error *err);

/* Synthetic data from a material file written to csv_path; returns the
 * number of points in *n_points. */
int wff_fit_synthesize_file(const char *material_path, const wff_fit_synth *spec,
                            const char *csv_path, int *n_points, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

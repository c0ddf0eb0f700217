/* wovenff — the fit's test data and the model's predictions of them
 * (plugin/fit_data.c): the tests, `test,x,y` CSV data, the predictions by
 * continuation and synthetic curves. The fit itself is wovenff/fit.h
 * (docs/fit.md), which includes this. */
#ifndef WOVENFF_FIT_DATA_H
#define WOVENFF_FIT_DATA_H

#include "wovenff/material.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum wff_fit_test {
    WFF_FIT_STRIP_WARP = 0,
    WFF_FIT_STRIP_WEFT = 1,
    WFF_FIT_EQUIBIAXIAL_WARP = 2,
    WFF_FIT_EQUIBIAXIAL_WEFT = 3,
    WFF_FIT_SHEAR = 4,
    WFF_FIT_TESTS = 5
} wff_fit_test;

/* "strip_warp", ...; NULL outside the range. */
const char *wff_fit_test_name(int test);
/* The test named `name`, or -1. */
int wff_fit_test_find(const char *name);

/* ---- data ---------------------------------------------------------------- */

typedef struct wff_fit_point {
    int test;    /* wff_fit_test */
    double x, y; /* the table at the top of wovenff/fit.h */
    int line;    /* 1-based line in the source (0 when made in memory) */
} wff_fit_point;

typedef struct wff_fit_data {
    int n, capacity;
    wff_fit_point *point; /* malloc'ed; wff_fit_data_free releases it */
    char source[256];     /* file name for messages */
} wff_fit_data;

/* Read `test,x,y` CSV text / a file. data is initialised here (its previous
 * contents are not freed). On failure data is empty and err names the source
 * and line. */
int wff_fit_data_parse_text(const char *text, const char *source, wff_fit_data *data,
                            wff_error *err);
int wff_fit_data_read(const char *path, wff_fit_data *data, wff_error *err);
/* Start an empty data set (source used in messages). */
void wff_fit_data_init(wff_fit_data *data, const char *source);
/* Append one point. */
int wff_fit_data_add(wff_fit_data *data, int test, double x, double y, wff_error *err);
/* Write as `test,x,y` CSV (17 significant digits), whole or not at all. */
int wff_fit_data_write(const wff_fit_data *data, const char *path, wff_error *err);
void wff_fit_data_free(wff_fit_data *data);

/* ---- model predictions ------------------------------------------------------ */

/* y[i] = the model's prediction of test `test` at x[i], i < n. The points may
 * come in any order: they are solved by continuation from the reference state
 * outwards in x (with intermediate states where x jumps), each from its
 * neighbour's solution. */
int wff_fit_predict(const wff_material *mat, int test, int n, const double *x, double *y,
                    wff_error *err);

/* Synthetic curves: for every test whose bit (1 << test) is in test_mask,
 * n_per_test points evenly spaced in (0, strain_max] (shear: (0, shear_max]
 * rad), y = model × (1 + noise ε), ε standard normal from a seeded
 * xorshift64* generator with Box–Muller (same seed, same data everywhere). */
typedef struct wff_fit_synth {
    unsigned test_mask;
    int n_per_test;
    double strain_max; /* − */
    double shear_max;  /* rad */
    double noise;      /* relative standard deviation, e.g. 0.01 */
    unsigned long long seed;
} wff_fit_synth;

int wff_fit_synthesize(const wff_material *mat, const wff_fit_synth *spec, wff_fit_data *out,
                       wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

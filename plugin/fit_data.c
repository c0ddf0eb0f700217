/* fit_data.c: the fit's test data and what the model predicts for them:
 * the tests' names, `test,x,y` CSV read and written, the static state of each
 * test followed along x by continuation (wff_fit_predict), and synthetic
 * curves with seeded noise. Knows the static balance (balance.h) and the
 * material, nothing of the GSL fit, of meshes or of the solver. */
#include "wovenff/fit_data.h"

#include "wovenff/balance.h"
#include "wovenff/text_io.h"
#include "rng.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Largest data file read, with the reason: test curves are a few hundred
 * points; megabytes mean a wrong file. */
#define DATA_FILE_MAX (4 * 1024 * 1024)
/* Continuation: largest jump in x solved in one go (strain; shear angle, rad). */
#define STRAIN_STEP_MAX 0.005
#define SHEAR_STEP_MAX 0.05

static const char *const test_names[WFF_FIT_TESTS] = {
    "strip_warp", "strip_weft", "equibiaxial_warp", "equibiaxial_weft", "shear"};

const char *wff_fit_test_name(int test)
{
    return test >= 0 && test < WFF_FIT_TESTS ? test_names[test] : NULL;
}

int wff_fit_test_find(const char *name)
{
    for (int t = 0; t < WFF_FIT_TESTS; t++)
        if (strcmp(name, test_names[t]) == 0)
            return t;
    return -1;
}

static void known_tests(char *buf, size_t cap)
{
    buf[0] = '\0';
    for (int t = 0; t < WFF_FIT_TESTS; t++) {
        size_t used = strlen(buf);
        snprintf(buf + used, cap - used, "%s%s", t ? ", " : "", test_names[t]);
    }
}

/* ---- data ------------------------------------------------------------------- */

void wff_fit_data_init(wff_fit_data *data, const char *source)
{
    data->n = data->capacity = 0;
    data->point = NULL;
    snprintf(data->source, sizeof data->source, "%s", source ? source : "(data)");
}

void wff_fit_data_free(wff_fit_data *data)
{
    free(data->point);
    data->point = NULL;
    data->n = data->capacity = 0;
}

static int data_push(wff_fit_data *data, int test, double x, double y, int line, wff_error *err)
{
    if (data->n == data->capacity) {
        int cap = data->capacity ? 2 * data->capacity : 64;
        wff_fit_point *p = realloc(data->point, (size_t)cap * sizeof *p);
        if (!p)
            return wff_fail(err, "%s: out of memory", data->source);
        data->point = p;
        data->capacity = cap;
    }
    data->point[data->n++] = (wff_fit_point){.test = test, .x = x, .y = y, .line = line};
    return 0;
}

int wff_fit_data_add(wff_fit_data *data, int test, double x, double y, wff_error *err)
{
    if (!wff_fit_test_name(test))
        return wff_fail(err, "%s: test %d out of range", data->source, test);
    if (!isfinite(x) || !isfinite(y))
        return wff_fail(err, "%s: %s point (%g, %g) is not finite", data->source,
                        test_names[test], x, y);
    return data_push(data, test, x, y, 0, err);
}

int wff_fit_data_parse_text(const char *text, const char *source, wff_fit_data *data,
                            wff_error *err)
{
    wff_fit_data_init(data, source);
    const char *p = text;
    int line_no = 0, header_seen = 0;
    char known[160];
    known_tests(known, sizeof known);
    while (*p) {
        const char *eol = strchr(p, '\n');
        const char *end = eol ? eol : p + strlen(p);
        const char *next = eol ? eol + 1 : end;
        line_no++;
        const char *hash = memchr(p, '#', (size_t)(end - p));
        const char *b = wff_skip_space(p, hash ? hash : end);
        const char *e = wff_trim_end(b, hash ? hash : end);
        p = next;
        if (b == e)
            continue;
        /* split into fields at commas */
        const char *field[4][2];
        int nf = 0;
        const char *f = b;
        for (;;) {
            const char *comma = memchr(f, ',', (size_t)(e - f));
            const char *fe = comma ? comma : e;
            if (nf < 4) {
                field[nf][0] = wff_skip_space(f, fe);
                field[nf][1] = wff_trim_end(field[nf][0], fe);
            }
            nf++;
            if (!comma)
                break;
            f = comma + 1;
        }
        if (!header_seen) {
            int ok = nf == 3;
            static const char *const want[3] = {"test", "x", "y"};
            for (int i = 0; ok && i < 3; i++)
                ok = (size_t)(field[i][1] - field[i][0]) == strlen(want[i]) &&
                     memcmp(field[i][0], want[i], strlen(want[i])) == 0;
            if (!ok) {
                wff_fit_data_free(data);
                return wff_fail(err, "%s:%d: expected the header 'test,x,y', got '%.*s'",
                                source, line_no, (int)(e - b), b);
            }
            header_seen = 1;
            continue;
        }
        if (nf != 3) {
            wff_fit_data_free(data);
            return wff_fail(err, "%s:%d: expected 3 comma-separated fields test,x,y, got %d "
                            "in '%.*s'", source, line_no, nf, (int)(e - b), b);
        }
        char name[48];
        size_t len = (size_t)(field[0][1] - field[0][0]);
        snprintf(name, sizeof name, "%.*s", (int)(len < sizeof name ? len : sizeof name - 1),
                 field[0][0]);
        int test = len < sizeof name ? wff_fit_test_find(name) : -1;
        if (test < 0) {
            wff_fit_data_free(data);
            return wff_fail(err, "%s:%d: unknown test '%.*s' (known: %s)", source, line_no,
                            (int)len, field[0][0], known);
        }
        double v[2];
        for (int i = 0; i < 2; i++)
            if (wff_parse_number_span(field[1 + i][0], field[1 + i][1], &v[i]) || !isfinite(v[i])) {
                wff_fit_data_free(data);
                return wff_fail(err, "%s:%d: column %s: '%.*s' is not a finite number", source,
                                line_no, i ? "y" : "x",
                                (int)(field[1 + i][1] - field[1 + i][0]), field[1 + i][0]);
            }
        if (data_push(data, test, v[0], v[1], line_no, err)) {
            wff_fit_data_free(data);
            return -1;
        }
    }
    if (!header_seen)
        return wff_fail(err, "%s: empty: expected the header 'test,x,y' and data lines", source);
    if (data->n == 0)
        return wff_fail(err, "%s: no data lines after the header", source);
    return 0;
}

int wff_fit_data_read(const char *path, wff_fit_data *data, wff_error *err)
{
    char *text = NULL;
    wff_fit_data_init(data, path);
    if (wff_read_text_file(path, "data file", DATA_FILE_MAX, &text, err))
        return -1;
    int rc = wff_fit_data_parse_text(text, path, data, err);
    free(text);
    return rc;
}

int wff_fit_data_write(const wff_fit_data *data, const char *path, wff_error *err)
{
    wff_text b = {0};
    wff_text_printf(&b, "test,x,y\n");
    for (int i = 0; i < data->n; i++)
        wff_text_printf(&b, "%s,%.17g,%.17g\n", test_names[data->point[i].test], data->point[i].x,
                        data->point[i].y);
    int rc = wff_text_write(&b, path, "data file", err);
    free(b.s);
    return rc;
}

/* ---- model predictions -------------------------------------------------------- */

/* The static state of one test followed along x. */
typedef struct tracker {
    const wff_material *mat;
    int test;
    double x;               /* where the state below is solved */
    wff_biaxial_state bs;   /* strip and equibiaxial */
    double dA[2];           /* shear */
    double y;
} tracker;

static void tracker_reset(tracker *tr)
{
    tr->x = 0;
    memset(&tr->bs, 0, sizeof tr->bs);
    tr->bs.stretch[0] = tr->bs.stretch[1] = 1;
    tr->dA[0] = tr->dA[1] = 0;
    tr->y = 0;
}

/* First guesses within SNAP of zero are set to zero: the static solver's
 * finite-difference Jacobian steps relative to each unknown (GSL's multiroot
 * fdjac: ε|u| with ε = 1.5e-8, or ε when u = 0), so a tiny nonzero guess gets
 * a step below the resolution of A⁰ + ΔA (≈ 1e-20 m) or of 1 + strain
 * (2e-16) and a singular Jacobian (seen: ΔA ≈ 1e-13 m on the shear path).
 * Snapping keeps the step at least ~1e3 times that resolution. */
#define SNAP_AMPLITUDE 1e-9 /* m */
#define SNAP_STRAIN 1e-6

static double snap(double v, double tol)
{
    return fabs(v) < tol ? 0 : v;
}

static void tracker_snap(tracker *tr)
{
    for (int k = 0; k < 2; k++) {
        tr->dA[k] = snap(tr->dA[k], SNAP_AMPLITUDE);
        tr->bs.dA[k] = snap(tr->bs.dA[k], SNAP_AMPLITUDE);
        tr->bs.stretch[k] = 1 + snap(tr->bs.stretch[k] - 1, SNAP_STRAIN);
    }
}

/* Solve at x from the current state in one go. */
static int tracker_solve(tracker *tr, double x, wff_error *err)
{
    tracker_snap(tr);
    switch (tr->test) {
    case WFF_FIT_STRIP_WARP:
    case WFF_FIT_STRIP_WEFT: {
        int fam = tr->test == WFF_FIT_STRIP_WARP ? 0 : 1;
        wff_biaxial_state s = tr->bs;
        if (wff_uniaxial_static(tr->mat, fam, 1 + x, &s, err))
            return -1;
        tr->bs = s;
        tr->y = s.resultant[fam];
        break;
    }
    case WFF_FIT_EQUIBIAXIAL_WARP:
    case WFF_FIT_EQUIBIAXIAL_WEFT: {
        const wff_hold hold[2] = {WFF_HOLD_STRETCH, WFF_HOLD_STRETCH};
        const double target[2] = {1 + x, 1 + x};
        wff_biaxial_state s = tr->bs;
        if (wff_biaxial_static(tr->mat, hold, target, wff_rest_state, &s, err))
            return -1;
        tr->bs = s;
        tr->y = s.resultant[tr->test == WFF_FIT_EQUIBIAXIAL_WARP ? 0 : 1];
        break;
    }
    case WFF_FIT_SHEAR: {
        double dA[2] = {tr->dA[0], tr->dA[1]}, S;
        if (wff_shear_static(tr->mat, x, dA, &S, NULL, err))
            return -1;
        tr->dA[0] = dA[0];
        tr->dA[1] = dA[1];
        tr->y = S;
        break;
    }
    default:
        return wff_fail(err, "fit: test %d out of range", tr->test);
    }
    tr->x = x;
    return 0;
}

/* Move to x in steps no larger than the continuation limit; a step that
 * fails is retried in quarters (twice). */
static int tracker_move(tracker *tr, double x, int depth, wff_error *err)
{
    double max_step = tr->test == WFF_FIT_SHEAR ? SHEAR_STEP_MAX : STRAIN_STEP_MAX;
    for (int d = 0; d < depth; d++)
        max_step *= 0.25;
    double x0 = tr->x;
    int steps = (int)ceil(fabs(x - x0) / max_step);
    if (steps < 1)
        steps = 1;
    for (int i = 1; i <= steps; i++) {
        double xi = i == steps ? x : x0 + (x - x0) * i / steps;
        if (tracker_solve(tr, xi, err) == 0)
            continue;
        if (depth >= 2)
            return -1;
        if (tracker_move(tr, xi, depth + 1, err))
            return -1;
    }
    return 0;
}

/* Points sorted by x with their index (qsort without global keys). */
typedef struct keyed { double x; int i; } keyed;
static int cmp_keyed(const void *a, const void *b)
{
    const keyed *u = a, *v = b;
    if (u->x != v->x)
        return (u->x > v->x) - (u->x < v->x);
    return u->i - v->i;
}

int wff_fit_predict(const wff_material *mat, int test, int n, const double *x, double *y,
                    wff_error *err)
{
    if (!wff_fit_test_name(test))
        return wff_fail(err, "fit: test %d out of range", test);
    if (n <= 0)
        return 0;
    keyed *order = malloc((size_t)n * sizeof *order);
    if (!order)
        return wff_fail(err, "fit: out of memory");
    for (int i = 0; i < n; i++) {
        if (!isfinite(x[i])) {
            free(order);
            return wff_fail(err, "fit: %s: x = %g is not finite", test_names[test], x[i]);
        }
        order[i] = (keyed){x[i], i};
    }
    qsort(order, (size_t)n, sizeof *order, cmp_keyed);
    int first_pos = 0;
    while (first_pos < n && order[first_pos].x < 0)
        first_pos++;
    tracker tr = {.mat = mat, .test = test};
    int rc = 0;
    /* x >= 0 upwards, then x < 0 downwards, each from the reference state */
    tracker_reset(&tr);
    for (int k = first_pos; k < n && rc == 0; k++) {
        rc = tracker_move(&tr, order[k].x, 0, err);
        if (rc == 0)
            y[order[k].i] = tr.y;
    }
    tracker_reset(&tr);
    for (int k = first_pos - 1; k >= 0 && rc == 0; k--) {
        rc = tracker_move(&tr, order[k].x, 0, err);
        if (rc == 0)
            y[order[k].i] = tr.y;
    }
    free(order);
    if (rc) {
        char msg[WFF_ERROR_MAX];
        snprintf(msg, sizeof msg, "%s", err ? err->message : "");
        return wff_fail(err, "fit: %s prediction: %s", test_names[test], msg);
    }
    return 0;
}

/* ---- synthetic data -------------------------------------------------------------- */

int wff_fit_synthesize(const wff_material *mat, const wff_fit_synth *spec, wff_fit_data *out,
                       wff_error *err)
{
    wff_fit_data_init(out, "(synthetic)");
    if (spec->n_per_test < 1 || spec->n_per_test > 100000)
        return wff_fail(err, "synthetic data: %d points per test (want 1 to 100000)",
                        spec->n_per_test);
    if ((spec->test_mask & ((1u << WFF_FIT_TESTS) - 1)) == 0)
        return wff_fail(err, "synthetic data: no test selected");
    if (!(spec->noise >= 0) || !isfinite(spec->noise))
        return wff_fail(err, "synthetic data: noise %g must be >= 0", spec->noise);
    wff_rng state = {spec->seed ? (uint64_t)spec->seed : 0x9E3779B97F4A7C15ULL};
    int n = spec->n_per_test;
    double *x = malloc(2 * (size_t)n * sizeof *x);
    if (!x)
        return wff_fail(err, "synthetic data: out of memory");
    double *y = x + n;
    int rc = 0;
    for (int t = 0; t < WFF_FIT_TESTS && rc == 0; t++) {
        if (!(spec->test_mask & (1u << t)))
            continue;
        double xmax = t == WFF_FIT_SHEAR ? spec->shear_max : spec->strain_max;
        if (!(xmax > 0) || !isfinite(xmax)) {
            rc = wff_fail(err, "synthetic data: %s needs a largest %s > 0, got %g",
                          test_names[t], t == WFF_FIT_SHEAR ? "shear angle" : "strain", xmax);
            break;
        }
        for (int i = 0; i < n; i++)
            x[i] = xmax * (i + 1) / n;
        rc = wff_fit_predict(mat, t, n, x, y, err);
        for (int i = 0; i < n && rc == 0; i++)
            rc = data_push(out, t, x[i], y[i] * (1 + spec->noise * wff_rng_normal(&state)), 0, err);
    }
    free(x);
    if (rc)
        wff_fit_data_free(out);
    return rc;
}

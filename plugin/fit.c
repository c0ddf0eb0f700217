/* Parameter identification with GSL's nonlinear least squares (see
 * include/wovenff/fit.h and docs/fit.md).
 *
 * The residual function maps the solver's variables z to the parameters x
 * (bounds by change of variable), writes x into a copy of the material text,
 * re-parses it (so every check of the material reader applies to every
 * candidate) and solves the static states of the data's tests by
 * continuation. A candidate the model cannot evaluate (rejected by the cell,
 * or a static state that does not converge) gets a huge residual so that the
 * trust region rejects the step and shrinks; the fit fails only if the final
 * point cannot be evaluated. */
#include "wovenff/fit.h"

#include "wovenff/balance.h"

#include <ctype.h>
#include <errno.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_multifit_nlinear.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* Largest data file read, with the reason: test curves are a few hundred
 * points; megabytes mean a wrong file. */
#define DATA_FILE_MAX (4 * 1024 * 1024)
/* Continuation: largest jump in x solved in one go (strain; shear angle, rad). */
#define STRAIN_STEP_MAX 0.005
#define SHEAR_STEP_MAX 0.05
/* Residual given to a candidate the model cannot evaluate. */
#define FAILED_RESIDUAL 1e8
/* Relative step of the central differences for the covariance's Jacobian. */
#define COVARIANCE_STEP 1e-5
/* Step of GSL's central-difference Jacobian in the solver's variables. */
#define SOLVER_FD_STEP 1e-6
/* Relative weighting: smallest load a residual is divided by, as a fraction
 * of its test's RMS load (points at zero load would otherwise dominate). */
#define RELATIVE_FLOOR 1e-3

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

/* ---- small text helpers ---------------------------------------------------- */

static const char *skip_space(const char *p, const char *end)
{
    while (p < end && isspace((unsigned char)*p))
        p++;
    return p;
}

static const char *trim_end(const char *begin, const char *end)
{
    while (end > begin && isspace((unsigned char)end[-1]))
        end--;
    return end;
}

/* A number spanning exactly [begin, end). */
static int parse_span_number(const char *begin, const char *end, double *value)
{
    char buf[96];
    size_t len = (size_t)(end - begin);
    if (len == 0 || len >= sizeof buf)
        return -1;
    memcpy(buf, begin, len);
    buf[len] = '\0';
    char *stop;
    errno = 0;
    double v = strtod(buf, &stop);
    if (stop == buf || *stop != '\0' || errno == ERANGE)
        return -1;
    *value = v;
    return 0;
}

static int read_file(const char *path, size_t max, char **text, wff_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return wff_fail(err, "%s: cannot open: %s", path, strerror(errno));
    char *buf = malloc(max + 1);
    if (!buf) {
        fclose(f);
        return wff_fail(err, "%s: out of memory", path);
    }
    size_t n = fread(buf, 1, max + 1, f);
    int bad = ferror(f);
    fclose(f);
    if (bad || n > max || memchr(buf, '\0', n)) {
        free(buf);
        if (bad)
            return wff_fail(err, "%s: read error", path);
        if (n > max)
            return wff_fail(err, "%s: larger than %zu bytes", path, max);
        return wff_fail(err, "%s: contains a NUL byte: not a text file", path);
    }
    buf[n] = '\0';
    *text = buf;
    return 0;
}

/* Write text to path through path.tmp and a rename. */
static int write_whole(const char *path, const char *text, size_t len, wff_error *err)
{
    char tmp[1024];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp)
        return wff_fail(err, "%s: path too long", path);
    FILE *f = fopen(tmp, "wb");
    if (!f)
        return wff_fail(err, "%s: cannot write: %s", tmp, strerror(errno));
    size_t n = fwrite(text, 1, len, f);
    int bad = ferror(f) || n != len;
    if (fclose(f) != 0)
        bad = 1;
    if (bad) {
        remove(tmp);
        return wff_fail(err, "%s: write error", tmp);
    }
    if (rename(tmp, path) != 0) {
        remove(tmp);
        return wff_fail(err, "%s: cannot rename %s to it: %s", path, tmp, strerror(errno));
    }
    return 0;
}

/* Growable text buffer for the report writers. */
typedef struct strbuf {
    char *s;
    size_t len, cap;
    int failed;
} strbuf;

static void sb_printf(strbuf *b, const char *format, ...) __attribute__((format(printf, 2, 3)));

static void sb_printf(strbuf *b, const char *format, ...)
{
    if (b->failed)
        return;
    for (;;) {
        va_list args;
        va_start(args, format);
        size_t room = b->cap - b->len;
        int n = vsnprintf(b->s ? b->s + b->len : NULL, b->s ? room : 0, format, args);
        va_end(args);
        if (n < 0) {
            b->failed = 1;
            return;
        }
        if (b->s && (size_t)n < room) {
            b->len += (size_t)n;
            return;
        }
        size_t cap = b->cap ? b->cap : 4096;
        while (cap <= b->len + (size_t)n)
            cap *= 2;
        char *s = realloc(b->s, cap);
        if (!s) {
            b->failed = 1;
            return;
        }
        b->s = s;
        b->cap = cap;
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
        const char *b = skip_space(p, hash ? hash : end);
        const char *e = trim_end(b, hash ? hash : end);
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
                field[nf][0] = skip_space(f, fe);
                field[nf][1] = trim_end(field[nf][0], fe);
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
            if (parse_span_number(field[1 + i][0], field[1 + i][1], &v[i]) || !isfinite(v[i])) {
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
    if (read_file(path, DATA_FILE_MAX, &text, err))
        return -1;
    int rc = wff_fit_data_parse_text(text, path, data, err);
    free(text);
    return rc;
}

int wff_fit_data_write(const wff_fit_data *data, const char *path, wff_error *err)
{
    strbuf b = {0};
    sb_printf(&b, "test,x,y\n");
    for (int i = 0; i < data->n; i++)
        sb_printf(&b, "%s,%.17g,%.17g\n", test_names[data->point[i].test], data->point[i].x,
                  data->point[i].y);
    int rc = b.failed ? wff_fail(err, "%s: out of memory", path)
                      : write_whole(path, b.s, b.len, err);
    free(b.s);
    return rc;
}

/* ---- model predictions -------------------------------------------------------- */

int wff_shear_static(const wff_material *mat, double gamma, double dA[2],
                     double *shear_resultant, wff_point_result *point, wff_error *err)
{
    if (!isfinite(gamma) || fabs(gamma) >= M_PI_2)
        return wff_fail(err, "shear static state: shear angle %g rad outside (-pi/2, pi/2)",
                        gamma);
    double c = cos(0.5 * gamma), s = sin(0.5 * gamma);
    const double F[6] = {c, s, s, c, 0, 0};
    double a[2] = {dA[0], dA[1]};
    if (wff_balance_amplitudes(mat, F, 0, a, err))
        return -1;
    wff_point_result r;
    if (wff_material_evaluate(mat, F, a, 0, 0, &r) != WFF_POINT_OK)
        return wff_fail(err, "shear static state: degenerate point at %g rad (material %s)",
                        gamma, mat->source);
    /* S = P : dF/dγ, dF/dγ = ½ [−s c; c −s; 0 0] */
    *shear_resultant = 0.5 * (c * (r.stress[1] + r.stress[2]) - s * (r.stress[0] + r.stress[3]));
    dA[0] = a[0];
    dA[1] = a[1];
    if (point)
        *point = r;
    return 0;
}

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
        if (wff_biaxial_static(tr->mat, hold, target, 0, &s, err))
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

/* xorshift64* and Box–Muller: the same numbers on every platform. */
static double rng_uniform01(uint64_t *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    uint64_t x = *s * 2685821657736338717ULL;
    return ((double)(x >> 11) + 0.5) / 9007199254740992.0; /* (0, 1) */
}

static double rng_normal(uint64_t *s)
{
    double u = rng_uniform01(s), v = rng_uniform01(s);
    return sqrt(-2 * log(u)) * cos(2 * M_PI * v);
}

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
    uint64_t state = spec->seed ? (uint64_t)spec->seed : 0x9E3779B97F4A7C15ULL;
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
            rc = data_push(out, t, x[i], y[i] * (1 + spec->noise * rng_normal(&state)), 0, err);
    }
    free(x);
    if (rc)
        wff_fit_data_free(out);
    return rc;
}

/* ---- material text ------------------------------------------------------------------ */

/* Find `key = value` in text: the value's span (without comment and blanks)
 * and the line number. Returns 1 if found. */
static int find_key(const char *text, const char *key, const char **vb, const char **ve,
                    int *line)
{
    size_t klen = strlen(key);
    const char *p = text;
    int line_no = 0;
    while (*p) {
        const char *eol = strchr(p, '\n');
        const char *end = eol ? eol : p + strlen(p);
        line_no++;
        const char *hash = memchr(p, '#', (size_t)(end - p));
        const char *content_end = hash ? hash : end;
        const char *eq = memchr(p, '=', (size_t)(content_end - p));
        if (eq) {
            const char *kb = skip_space(p, eq), *ke = trim_end(kb, eq);
            if ((size_t)(ke - kb) == klen && memcmp(kb, key, klen) == 0) {
                *vb = skip_space(eq + 1, content_end);
                *ve = trim_end(*vb, content_end);
                *line = line_no;
                return 1;
            }
        }
        p = eol ? eol + 1 : end;
    }
    return 0;
}

/* "cell, p0_1, ..." for messages. */
static void list_keys(const char *text, char *buf, size_t cap)
{
    buf[0] = '\0';
    const char *p = text;
    while (*p) {
        const char *eol = strchr(p, '\n');
        const char *end = eol ? eol : p + strlen(p);
        const char *hash = memchr(p, '#', (size_t)(end - p));
        const char *content_end = hash ? hash : end;
        const char *eq = memchr(p, '=', (size_t)(content_end - p));
        if (eq) {
            const char *kb = skip_space(p, eq), *ke = trim_end(kb, eq);
            size_t used = strlen(buf);
            if (ke > kb && used + 8 < cap)
                snprintf(buf + used, cap - used, "%s%.*s", used ? ", " : "", (int)(ke - kb), kb);
        }
        p = eol ? eol + 1 : end;
    }
}

static int key_missing(const char *text, const char *source, const char *key, wff_error *err)
{
    char keys[400];
    list_keys(text, keys, sizeof keys);
    return wff_fail(err, "fit: parameter '%s' is not a key of material %s (its keys: %s)", key,
                    source, keys);
}

int wff_fit_material_value(const char *text, const char *source, const char *key,
                           double *value, wff_error *err)
{
    const char *vb, *ve;
    int line;
    if (!find_key(text, key, &vb, &ve, &line))
        return key_missing(text, source, key, err);
    if (parse_span_number(vb, ve, value) || !isfinite(*value))
        return wff_fail(err, "%s:%d: key '%s': '%.*s' is not a number", source, line, key,
                        (int)(ve - vb), vb);
    return 0;
}

int wff_fit_material_edit(const char *text, const char *source, int n,
                          const char *const *names, const double *values, char *out,
                          size_t cap, wff_error *err)
{
    /* the spans of the values to replace, in text order */
    typedef struct span { const char *b, *e; double v; } span;
    span sp[WFF_FIT_PARAMS_MAX];
    if (n < 0 || n > WFF_FIT_PARAMS_MAX)
        return wff_fail(err, "fit: %d parameters (at most %d)", n, WFF_FIT_PARAMS_MAX);
    for (int i = 0; i < n; i++) {
        if (strcmp(names[i], "cell") == 0)
            return wff_fail(err, "fit: parameter 'cell' names the unit cell: it cannot be fitted");
        int line;
        double old;
        if (wff_fit_material_value(text, source, names[i], &old, err))
            return -1;
        find_key(text, names[i], &sp[i].b, &sp[i].e, &line);
        sp[i].v = values[i];
        for (int j = 0; j < i; j++)
            if (sp[j].b == sp[i].b)
                return wff_fail(err, "fit: parameter '%s' given twice", names[i]);
    }
    for (int i = 1; i < n; i++) /* insertion sort by position */
        for (int j = i; j > 0 && sp[j].b < sp[j - 1].b; j--) {
            span t = sp[j];
            sp[j] = sp[j - 1];
            sp[j - 1] = t;
        }
    size_t len = 0;
    const char *p = text;
    for (int i = 0; i <= n; i++) {
        const char *stop = i < n ? sp[i].b : p + strlen(p);
        size_t chunk = (size_t)(stop - p);
        if (len + chunk + 32 >= cap)
            return wff_fail(err, "fit: edited material %s does not fit in %zu bytes", source, cap);
        memcpy(out + len, p, chunk);
        len += chunk;
        if (i < n) {
            len += (size_t)snprintf(out + len, cap - len, "%.17g", sp[i].v);
            p = sp[i].e;
        }
    }
    out[len] = '\0';
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
    *b = skip_space(p, ie);
    *e = trim_end(*b, ie);
    *pos = comma ? comma + 1 : NULL;
    return 1;
}

static int blank(const char *s)
{
    return !s || *skip_space(s, s + strlen(s)) == '\0';
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
            const char *lb = b, *le = trim_end(b, colon);
            const char *hb = skip_space(colon + 1, e), *he = e;
            double lo = -INFINITY, hi = INFINITY;
            if ((le > lb && parse_span_number(lb, le, &lo)) ||
                (he > hb && parse_span_number(hb, he, &hi)) || isnan(lo) || isnan(hi))
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
            if (e > b && (parse_span_number(b, e, &params[i].start) || !isfinite(params[i].start)))
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
                            test_names[pt->test], pt->x);
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

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
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
                                "residuals by", data->source, test_names[t]);
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
    double t0 = now_seconds();
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
    res->wall_seconds = now_seconds() - t0;
    return rc;
}

/* ---- reports ---------------------------------------------------------------------------- */

static void json_string(strbuf *b, const char *s)
{
    sb_printf(b, "\"");
    for (; s && *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            sb_printf(b, "\\%c", ch);
        else if (ch < 0x20)
            sb_printf(b, "\\u%04x", ch);
        else
            sb_printf(b, "%c", ch);
    }
    sb_printf(b, "\"");
}

static void json_number(strbuf *b, double v)
{
    if (isfinite(v))
        sb_printf(b, "%.10g", v);
    else
        sb_printf(b, "null");
}

int wff_fit_write_json(const wff_fit_result *res, const char *material_path,
                       const char *data_path, const char *path, wff_error *err)
{
    strbuf b = {0};
    int p = res->n_params;
    sb_printf(&b, "{\n  \"status\": \"ok\",\n  \"material\": ");
    json_string(&b, material_path);
    sb_printf(&b, ",\n  \"data\": ");
    json_string(&b, data_path);
    sb_printf(&b, ",\n  \"points\": %d,\n  \"weighting\": \"%s\",\n  \"parameters\": {\n",
              res->n_points, wff_fit_weighting_name(res->weighting) ? wff_fit_weighting_name(res->weighting) : "?");
    for (int j = 0; j < p; j++) {
        sb_printf(&b, "    ");
        json_string(&b, res->name[j]);
        sb_printf(&b, ": {\"value\": ");
        json_number(&b, res->value[j]);
        sb_printf(&b, ", \"std_error\": ");
        json_number(&b, res->std_error[j]);
        sb_printf(&b, ", \"relative_std_error\": ");
        json_number(&b, res->value[j] != 0 ? res->std_error[j] / fabs(res->value[j]) : NAN);
        sb_printf(&b, ", \"start\": ");
        json_number(&b, res->start[j]);
        sb_printf(&b, ", \"lower\": ");
        json_number(&b, res->lo[j]);
        sb_printf(&b, ", \"upper\": ");
        json_number(&b, res->hi[j]);
        sb_printf(&b, ", \"at_bound\": %s}%s\n", res->at_bound[j] ? "true" : "false",
                  j + 1 < p ? "," : "");
    }
    sb_printf(&b, "  },\n  \"correlation\": [");
    for (int a = 0; a < p; a++) {
        sb_printf(&b, "%s[", a ? ", " : "");
        for (int c = 0; c < p; c++) {
            sb_printf(&b, "%s", c ? ", " : "");
            json_number(&b, res->correlation[a][c]);
        }
        sb_printf(&b, "]");
    }
    sb_printf(&b, "],\n  \"residual_norm\": ");
    json_number(&b, res->residual_norm);
    sb_printf(&b, ",\n  \"start_residual_norm\": ");
    json_number(&b, res->start_residual_norm);
    sb_printf(&b, ",\n  \"ssr\": ");
    json_number(&b, res->ssr);
    sb_printf(&b, ",\n  \"residual_variance\": ");
    json_number(&b, res->s2);
    sb_printf(&b, ",\n  \"reciprocal_condition\": ");
    json_number(&b, res->condition);
    sb_printf(&b, ",\n  \"iterations\": %d,\n  \"function_evaluations\": %d,\n"
              "  \"converged\": %d,\n  \"wall_seconds\": ", res->iterations, res->f_evals,
              res->converged);
    json_number(&b, res->wall_seconds);
    sb_printf(&b, ",\n  \"tests\": {");
    int first = 1;
    for (int t = 0; t < WFF_FIT_TESTS; t++) {
        if (!res->test_points[t])
            continue;
        sb_printf(&b, "%s\n    \"%s\": {\"points\": %d, \"scale_N_per_m\": ", first ? "" : ",",
                  test_names[t], res->test_points[t]);
        json_number(&b, res->test_scale[t]);
        sb_printf(&b, ", \"rms_residual_N_per_m\": ");
        json_number(&b, res->test_rms[t]);
        sb_printf(&b, "}");
        first = 0;
    }
    sb_printf(&b, "\n  }\n}\n");
    int rc = b.failed ? wff_fail(err, "%s: out of memory", path)
                      : write_whole(path, b.s, b.len, err);
    free(b.s);
    return rc;
}

static int fitted_text(const char *text, const char *source, const wff_fit_result *res,
                       const double *values, char **out, wff_error *err)
{
    const char *names[WFF_FIT_PARAMS_MAX];
    for (int j = 0; j < res->n_params; j++)
        names[j] = res->name[j];
    size_t cap = strlen(text) + (size_t)res->n_params * 32 + 64;
    *out = malloc(cap);
    if (!*out)
        return wff_fail(err, "fit: out of memory");
    if (wff_fit_material_edit(text, source, res->n_params, names, values, *out, cap, err)) {
        free(*out);
        *out = NULL;
        return -1;
    }
    return 0;
}

int wff_fit_write_material(const char *material_text, const char *source_name,
                           const wff_fit_result *res, const char *data_path, const char *path,
                           wff_error *err)
{
    char *text = NULL;
    if (fitted_text(material_text, source_name, res, res->value, &text, err))
        return -1;
    strbuf b = {0};
    sb_printf(&b, "# Fitted by wovenff (wff_fit_run) from %s to %s:\n", source_name,
              data_path ? data_path : "(data)");
    for (int j = 0; j < res->n_params; j++)
        sb_printf(&b, "#   %s = %.10g +- %.3g (1 standard error; start %.6g)%s\n", res->name[j],
                  res->value[j], res->std_error[j], res->start[j],
                  res->at_bound[j] ? " AT A BOUND" : "");
    sb_printf(&b, "#   residual norm %.6g (start %.6g), %d points, %d iterations\n",
              res->residual_norm, res->start_residual_norm, res->n_points, res->iterations);
    sb_printf(&b, "%s", text);
    free(text);
    int rc = b.failed ? wff_fail(err, "%s: out of memory", path)
                      : write_whole(path, b.s, b.len, err);
    free(b.s);
    return rc;
}

int wff_fit_write_curves(const char *material_text, const char *source_name,
                         const wff_fit_result *res, const wff_fit_data *data, int n_curve,
                         const char *path, const char *points_path, wff_error *err)
{
    if (n_curve < 2)
        n_curve = 2;
    wff_material m0, m1;
    char *t0 = NULL, *t1 = NULL;
    int rc = fitted_text(material_text, source_name, res, res->start, &t0, err);
    if (rc == 0)
        rc = fitted_text(material_text, source_name, res, res->value, &t1, err);
    if (rc == 0)
        rc = wff_material_parse_text(t0, source_name, &m0, err);
    if (rc == 0)
        rc = wff_material_parse_text(t1, source_name, &m1, err);
    free(t0);
    free(t1);
    if (rc)
        return -1;
    size_t size = (size_t)(data->n > n_curve ? data->n : n_curve);
    double *x = malloc(3 * size * sizeof *x);
    if (!x)
        return wff_fail(err, "fit: out of memory");
    double *y0 = x + size, *y1 = y0 + size;
    strbuf cb = {0}, pb = {0};
    int block = 0;
    for (int t = 0; t < WFF_FIT_TESTS && rc == 0; t++) {
        double lo = 0, hi = 0;
        int m = 0;
        for (int i = 0; i < data->n; i++)
            if (data->point[i].test == t) {
                lo = fmin(lo, data->point[i].x);
                hi = fmax(hi, data->point[i].x);
                m++;
            }
        if (m == 0)
            continue;
        for (int k = 0; k < n_curve; k++)
            x[k] = lo + (hi - lo) * k / (n_curve - 1);
        rc = wff_fit_predict(&m0, t, n_curve, x, y0, err);
        if (rc == 0)
            rc = wff_fit_predict(&m1, t, n_curve, x, y1, err);
        if (rc)
            break;
        sb_printf(&cb, "%s# test %s: x,y_start,y_fit\n", block ? "\n\n" : "", test_names[t]);
        for (int k = 0; k < n_curve; k++)
            sb_printf(&cb, "%.10g,%.10g,%.10g\n", x[k], y0[k], y1[k]);
        m = 0;
        for (int i = 0; i < data->n; i++)
            if (data->point[i].test == t)
                x[m++] = data->point[i].x;
        rc = wff_fit_predict(&m1, t, m, x, y1, err);
        if (rc)
            break;
        sb_printf(&pb, "%s# test %s: x,y,y_fit\n", block ? "\n\n" : "", test_names[t]);
        m = 0;
        for (int i = 0; i < data->n; i++)
            if (data->point[i].test == t) {
                sb_printf(&pb, "%.10g,%.10g,%.10g\n", x[m], data->point[i].y, y1[m]);
                m++;
            }
        block++;
    }
    free(x);
    if (rc == 0 && (cb.failed || pb.failed))
        rc = wff_fail(err, "%s: out of memory", path);
    if (rc == 0)
        rc = write_whole(path, cb.s, cb.len, err);
    if (rc == 0 && points_path)
        rc = write_whole(points_path, pb.s, pb.len, err);
    free(cb.s);
    free(pb.s);
    return rc;
}

/* ---- files in, files out ------------------------------------------------------------------ */

/* Largest material file, as in material.c. */
#define MATERIAL_FILE_MAX (64 * 1024)

int wff_fit_files(const char *material_path, const char *data_path, const char *names,
                  const char *bounds, const char *starts, const wff_fit_options *opt,
                  const char *out_dir, wff_fit_result *res, wff_error *err)
{
    wff_fit_param params[WFF_FIT_PARAMS_MAX];
    int n;
    if (wff_fit_params_parse(names, bounds, starts, params, WFF_FIT_PARAMS_MAX, &n, err))
        return -1;
    char *text = NULL;
    if (read_file(material_path, MATERIAL_FILE_MAX, &text, err))
        return -1;
    wff_material check;
    if (wff_material_parse_text(text, material_path, &check, err)) {
        free(text);
        return -1;
    }
    wff_fit_data data;
    if (wff_fit_data_read(data_path, &data, err)) {
        free(text);
        return -1;
    }
    int rc = wff_fit_run(text, material_path, &data, params, n, opt, res, err);
    if (rc == 0 && out_dir) {
        char path[4][1024];
        static const char *const leaf[4] = {"fit.json", "fitted_material.txt", "fit_curves.csv",
                                            "fit_points.csv"};
        for (int k = 0; k < 4 && rc == 0; k++)
            if (snprintf(path[k], sizeof path[k], "%s/%s", out_dir, leaf[k]) >=
                (int)sizeof path[k])
                rc = wff_fail(err, "fit: output folder name too long: %s", out_dir);
        if (rc == 0)
            rc = wff_fit_write_json(res, material_path, data_path, path[0], err);
        if (rc == 0)
            rc = wff_fit_write_material(text, material_path, res, data_path, path[1], err);
        if (rc == 0)
            rc = wff_fit_write_curves(text, material_path, res, &data, 80, path[2], path[3], err);
    }
    wff_fit_data_free(&data);
    free(text);
    return rc;
}

int wff_fit_synthesize_file(const char *material_path, const wff_fit_synth *spec,
                            const char *csv_path, int *n_points, wff_error *err)
{
    wff_material mat;
    if (wff_material_load(material_path, &mat, err))
        return -1;
    wff_fit_data data;
    if (wff_fit_synthesize(&mat, spec, &data, err))
        return -1;
    int rc = wff_fit_data_write(&data, csv_path, err);
    if (n_points)
        *n_points = data.n;
    wff_fit_data_free(&data);
    return rc;
}

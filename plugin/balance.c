/* balance.c: static states of one material point (docs/model.md §5, §13):
 * the balance of the crimp amplitudes, biaxial and uniaxial states, the
 * equal-force preload and the picture-frame shear state, with GSL's hybrid
 * (Powell) root finder. Unknowns and equations are scaled to O(1):
 * amplitudes in units of AMPLITUDE_SCALE, stretches as strains, amplitude
 * residuals as forces per cell (R × yarn_spacing_1 × yarn_spacing_2) and
 * resultants as forces per yarn. (The per-point Newton solve of the
 * static-amplitude path is static inline in balance.h.) Knows a material
 * point only through wff_material_evaluate; nothing of meshes, elements or
 * the solver. */
#include "wovenff/balance.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_multiroots.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <string.h>

/* Crimp amplitudes are tens of micrometres. */
#define AMPLITUDE_SCALE 1e-5
#define MAX_ITERATIONS 400

typedef struct problem {
    const wff_material *mat;
    double state[WFF_STATE_MAX]; /* the point's internal state, held */
    double F[6];          /* used as is when no stretch is unknown */
    int biaxial;          /* 1: F = diag(stretch) with the unknown ones from x */
    wff_hold hold[2];
    double target[2];
    int n_unknown_stretch;
    int stretch_index[2]; /* which direction each unknown stretch is */
    int na;               /* amplitude unknowns: 2, or 0 for a cell without amplitudes */
} problem;

static void unpack(const problem *pb, const gsl_vector *x, double F[6], double dA[2],
                   double stretch[2])
{
    dA[0] = pb->na ? gsl_vector_get(x, 0) * AMPLITUDE_SCALE : 0;
    dA[1] = pb->na ? gsl_vector_get(x, 1) * AMPLITUDE_SCALE : 0;
    if (!pb->biaxial) {
        memcpy(F, pb->F, sizeof pb->F);
        return;
    }
    for (int k = 0; k < 2; k++)
        stretch[k] = pb->hold[k] == WFF_HOLD_STRETCH ? pb->target[k] : 1;
    for (int u = 0; u < pb->n_unknown_stretch; u++)
        stretch[pb->stretch_index[u]] = 1 + gsl_vector_get(x, (size_t)(pb->na + u));
    double f[6] = {stretch[0], 0, 0, stretch[1], 0, 0};
    memcpy(F, f, sizeof f);
}

static int equations(const gsl_vector *x, void *data, gsl_vector *out)
{
    const problem *pb = data;
    double F[6], dA[2], stretch[2];
    unpack(pb, x, F, dA, stretch);
    wff_point_result r;
    if (wff_material_evaluate(pb->mat, F, dA, pb->state, 0, &r) != WFF_POINT_OK)
        return GSL_EDOM;
    double cell = pb->mat->yarn_spacing[0] * pb->mat->yarn_spacing[1];
    if (pb->na) {
        gsl_vector_set(out, 0, r.residual[0] * cell);
        gsl_vector_set(out, 1, r.residual[1] * cell);
    }
    for (int u = 0; u < pb->n_unknown_stretch; u++) {
        int k = pb->stretch_index[u];
        double value;
        if (pb->hold[k] == WFF_HOLD_RESULTANT) /* P_11 or P_22, as force per yarn */
            value = (r.stress[k == 0 ? 0 : 3] - pb->target[k]) * pb->mat->yarn_spacing[k];
        else
            value = r.diag[wff_cell_yarn_tension_diag(pb->mat->cell, k)] - pb->target[k];
        gsl_vector_set(out, (size_t)(pb->na + u), value);
    }
    for (size_t i = 0; i < out->size; i++)
        if (!isfinite(gsl_vector_get(out, i)))
            return GSL_EDOM;
    return GSL_SUCCESS;
}

/* Forward-difference Jacobian with an absolute floor on the step (GSL's own
 * steps relative to each unknown). Unknowns are O(1) here. */
static int jacobian(const gsl_vector *x, void *data, gsl_matrix *J)
{
    size_t n = x->size;
    gsl_vector *f0 = gsl_vector_alloc(n), *f1 = gsl_vector_alloc(n), *xh = gsl_vector_alloc(n);
    int rc = equations(x, data, f0);
    for (size_t j = 0; j < n && rc == GSL_SUCCESS; j++) {
        gsl_vector_memcpy(xh, x);
        double h = 1e-7 * fmax(1.0, fabs(gsl_vector_get(x, j)));
        gsl_vector_set(xh, j, gsl_vector_get(x, j) + h);
        rc = equations(xh, data, f1);
        for (size_t i = 0; i < n && rc == GSL_SUCCESS; i++)
            gsl_matrix_set(J, i, j, (gsl_vector_get(f1, i) - gsl_vector_get(f0, i)) / h);
    }
    gsl_vector_free(f0);
    gsl_vector_free(f1);
    gsl_vector_free(xh);
    return rc;
}

static int equations_and_jacobian(const gsl_vector *x, void *data, gsl_vector *f, gsl_matrix *J)
{
    int rc = equations(x, data, f);
    return rc == GSL_SUCCESS ? jacobian(x, data, J) : rc;
}

static int solve(problem *pb, gsl_vector *x, wff_error *err, const char *what)
{
    size_t n = x->size;
    gsl_multiroot_function_fdf fn = {equations, jacobian, equations_and_jacobian, n, pb};
    gsl_multiroot_fdfsolver *s =
        gsl_multiroot_fdfsolver_alloc(gsl_multiroot_fdfsolver_hybridsj, n);
    if (!s)
        return wff_fail(err, "%s: out of memory", what);
    /* GSL's hybrid method sizes its first trust region from |x|: a guess of a
     * few picometres would start it tiny and stall ("not making progress").
     * Such a guess carries no information: start from zero instead. */
    for (size_t i = 0; i < n; i++)
        if (fabs(gsl_vector_get(x, i)) < 1e-6)
            gsl_vector_set(x, i, 0);
    gsl_error_handler_t *old = gsl_set_error_handler_off();
    int status = gsl_multiroot_fdfsolver_set(s, &fn, x);
    int iter = 0;
    while (status == GSL_SUCCESS && iter++ < MAX_ITERATIONS) {
        status = gsl_multiroot_fdfsolver_iterate(s);
        if (status != GSL_SUCCESS)
            break;
        if (gsl_multiroot_test_residual(s->f, 1e-13) == GSL_SUCCESS)
            break;
        status = gsl_multiroot_test_delta(s->dx, s->x, 0, 1e-14);
        if (status == GSL_SUCCESS)
            break;
        status = GSL_SUCCESS;
    }
    /* A step that can no longer improve (GSL_ENOPROG*) is fine if the residual is tiny. */
    double worst = 0;
    for (size_t i = 0; i < n; i++)
        worst = fmax(worst, fabs(gsl_vector_get(s->f, i)));
    int ok = isfinite(worst) && worst <= 1e-9;
    if (ok)
        gsl_vector_memcpy(x, s->x);
    gsl_multiroot_fdfsolver_free(s);
    gsl_set_error_handler(old);
    if (!ok)
        return wff_fail(err, "%s: static balance did not converge (GSL: %s, largest residual "
                        "%.3g N after %d iterations, material %s)", what,
                        gsl_strerror(status), worst, iter, pb->mat->source);
    return 0;
}

/* The held state: a copy of the caller's (mat->n_state values) or zeros. */
static void hold_state(problem *pb, const double *state)
{
    for (int i = 0; i < WFF_STATE_MAX; i++)
        pb->state[i] = state && i < pb->mat->n_state ? state[i] : 0;
}

int wff_balance_amplitudes(const wff_material *mat, const double F[6], const double *state,
                           double dA[2], wff_error *err)
{
    if (wff_cell_amplitudes(mat->cell) == 0) {
        dA[0] = dA[1] = 0;
        return 0;
    }
    problem pb = {.mat = mat, .na = 2};
    hold_state(&pb, state);
    memcpy(pb.F, F, sizeof pb.F);
    gsl_vector *x = gsl_vector_alloc(2);
    gsl_vector_set(x, 0, dA[0] / AMPLITUDE_SCALE);
    gsl_vector_set(x, 1, dA[1] / AMPLITUDE_SCALE);
    int rc = solve(&pb, x, err, "amplitude balance");
    if (rc == 0) {
        dA[0] = gsl_vector_get(x, 0) * AMPLITUDE_SCALE;
        dA[1] = gsl_vector_get(x, 1) * AMPLITUDE_SCALE;
    }
    gsl_vector_free(x);
    return rc;
}

int wff_biaxial_static(const wff_material *mat, const wff_hold hold[2], const double target[2],
                       const double *point_state, wff_biaxial_state *state,
                       wff_error *err)
{
    problem pb = {.mat = mat, .biaxial = 1};
    hold_state(&pb, point_state);
    for (int k = 0; k < 2; k++) {
        pb.hold[k] = hold[k];
        pb.target[k] = target[k];
        if (hold[k] == WFF_HOLD_YARN_TENSION && wff_cell_yarn_tension_diag(mat->cell, k) < 0)
            return wff_fail(err, "biaxial static state: cell '%s' reports no yarn tension",
                            wff_cell_name(mat->cell));
        if (hold[k] != WFF_HOLD_STRETCH)
            pb.stretch_index[pb.n_unknown_stretch++] = k;
    }
    pb.na = wff_cell_amplitudes(mat->cell) > 0 ? 2 : 0;
    size_t n = (size_t)(pb.na + pb.n_unknown_stretch);
    if (n == 0) { /* everything held: nothing to solve */
        double F[6] = {target[0], 0, 0, target[1], 0, 0};
        state->stretch[0] = target[0];
        state->stretch[1] = target[1];
        state->dA[0] = state->dA[1] = 0;
        if (wff_material_evaluate(mat, F, state->dA, pb.state, 0, &state->point) != WFF_POINT_OK)
            return wff_fail(err, "biaxial static state: degenerate at stretch (%g, %g)",
                            target[0], target[1]);
        state->resultant[0] = state->point.stress[0];
        state->resultant[1] = state->point.stress[3];
        return 0;
    }
    gsl_vector *x = gsl_vector_alloc(n);
    if (pb.na) {
        gsl_vector_set(x, 0, state->dA[0] / AMPLITUDE_SCALE);
        gsl_vector_set(x, 1, state->dA[1] / AMPLITUDE_SCALE);
    }
    for (int u = 0; u < pb.n_unknown_stretch; u++)
        gsl_vector_set(x, (size_t)(pb.na + u), state->stretch[pb.stretch_index[u]] - 1);
    int rc = solve(&pb, x, err, "biaxial static state");
    if (rc == 0) {
        double F[6];
        unpack(&pb, x, F, state->dA, state->stretch);
        wff_material_evaluate(mat, F, state->dA, pb.state, 0, &state->point);
        state->resultant[0] = state->point.stress[0];
        state->resultant[1] = state->point.stress[3];
    }
    gsl_vector_free(x);
    return rc;
}

int wff_preload_equal_force(const wff_material *mat, double yarn_force,
                            wff_biaxial_state *state, wff_error *err)
{
    const wff_hold hold[2] = {WFF_HOLD_YARN_TENSION, WFF_HOLD_YARN_TENSION};
    const double target[2] = {yarn_force, yarn_force};
    return wff_biaxial_static(mat, hold, target, wff_rest_state, state, err);
}

int wff_preload_forces(const wff_material *mat, const double a[2], const double dA[2],
                       double sigma[2])
{
    const double F[6] = {a[0], 0, 0, a[1], 0, 0};
    wff_point_result r;
    if (wff_material_evaluate(mat, F, dA, wff_rest_state, 0, &r) != WFF_POINT_OK)
        return -1;
    sigma[0] = r.stress[0] / a[1];
    sigma[1] = r.stress[3] / a[0];
    return isfinite(sigma[0]) && isfinite(sigma[1]) ? 0 : -1;
}

int wff_preload_matched(const wff_material *mat, const double target[2], const double a0[2],
                        double a_out[2])
{
    const double none[2] = {0, 0};
    double a[2] = {a0[0], a0[1]}, s[2];
    double scale = fmax(fmax(fabs(target[0]), fabs(target[1])), 1e-3); /* N/m */
    for (int it = 0; it < 100; it++) { /* Newton on diag(a1, a2), central-difference Jacobian */
        if (wff_preload_forces(mat, a, none, s))
            break;
        double r[2] = {s[0] - target[0], s[1] - target[1]};
        if (fabs(r[0]) <= 1e-11 * scale && fabs(r[1]) <= 1e-11 * scale) {
            a_out[0] = a[0], a_out[1] = a[1];
            return 0;
        }
        double J[2][2];
        for (int j = 0; j < 2; j++) {
            const double h = 1e-7 * a[j];
            double ap[2] = {a[0], a[1]}, am[2] = {a[0], a[1]}, sp[2], sm[2];
            ap[j] += h, am[j] -= h;
            if (wff_preload_forces(mat, ap, none, sp) || wff_preload_forces(mat, am, none, sm))
                it = 1000;
            for (int i = 0; i < 2; i++)
                J[i][j] = (sp[i] - sm[i]) / (2 * h);
        }
        double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
        if (it >= 1000 || !(fabs(det) > 0))
            break;
        double d0 = -(J[1][1] * r[0] - J[0][1] * r[1]) / det;
        double d1 = -(-J[1][0] * r[0] + J[0][0] * r[1]) / det;
        double big = fmax(fabs(d0) / a[0], fabs(d1) / a[1]), cut = big > 0.05 ? 0.05 / big : 1;
        a[0] += cut * d0, a[1] += cut * d1;
    }
    return -1;
}

int wff_uniaxial_static(const wff_material *mat, int family, double stretch,
                        wff_biaxial_state *state, wff_error *err)
{
    if (family != 0 && family != 1)
        return wff_fail(err, "uniaxial: family must be 0 (warp) or 1 (weft), got %d", family);
    wff_hold hold[2];
    double target[2];
    hold[family] = WFF_HOLD_STRETCH;
    target[family] = stretch;
    hold[1 - family] = WFF_HOLD_RESULTANT;
    target[1 - family] = 0;
    return wff_biaxial_static(mat, hold, target, wff_rest_state, state, err);
}

int wff_shear_static(const wff_material *mat, double gamma, double dA[2],
                     double *shear_resultant, wff_point_result *point, wff_error *err)
{
    if (!isfinite(gamma) || fabs(gamma) >= M_PI_2)
        return wff_fail(err, "shear static state: shear angle %g rad outside (-pi/2, pi/2)",
                        gamma);
    double c = cos(0.5 * gamma), s = sin(0.5 * gamma);
    const double F[6] = {c, s, s, c, 0, 0};
    double a[2] = {dA[0], dA[1]};
    if (wff_balance_amplitudes(mat, F, wff_rest_state, a, err))
        return -1;
    wff_point_result r;
    if (wff_material_evaluate(mat, F, a, wff_rest_state, 0, &r) != WFF_POINT_OK)
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

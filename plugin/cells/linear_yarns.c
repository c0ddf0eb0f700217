/* Straight linear yarns: the cheapest unit cell, and a reference with closed
 * forms (docs/new_cell.md works through it as the example of a new cell).
 *
 * Two families of straight, linear-elastic yarns along the material
 * directions, no crimp, plus an in-plane shear stiffness. Family k = 1 (warp)
 * along E1, k = 2 (weft) along E2; l is the other family. Per unit reference
 * area:
 *
 *   g_k = F E_k,  λ_k = |g_k|,  ĝ_k = g_k / λ_k
 *   cosθ = ĝ_1·ĝ_2,  sinθ = |g_1 × g_2| / (λ_1 λ_2),  γ = π/2 − θ
 *
 *   W = Σ_k ½ S_k (λ_k − 1)² + ½ G γ²
 *
 * S_k, N/m: yarn stiffness per unit width (one yarn's EA over its spacing);
 * G, N/m: in-plane shear stiffness (per unit area per rad²). tension_only = 1
 * replaces λ_k − 1 by max(λ_k − 1, 0): compressed yarns carry nothing and
 * store nothing.
 *
 * Stress: P = ∂W/∂F = Σ_k Q_k ⊗ E_k with Q_k = ∂W/∂g_k. From
 *   ∂λ_k/∂g_k = ĝ_k,   ∂cosθ/∂g_k = (ĝ_l − cosθ ĝ_k)/λ_k,
 *   ∂γ/∂g_k = −∂θ/∂g_k = (ĝ_l − cosθ ĝ_k)/(λ_k sinθ)
 * Q_k lies in the plane of ĝ_1, ĝ_2:
 *
 *   Q_k = N_k ĝ_k + G γ/(λ_k sinθ) (ĝ_l − cosθ ĝ_k),   N_k = S_k (λ_k − 1)
 *
 * N_k is the yarn force per unit width; the shear part has length G γ/λ_k
 * and is normal to ĝ_k. Uniaxial stretch F = diag(λ, 1) gives P11 = S_1 (λ − 1),
 * P22 = 0 (no Poisson effect); the symmetric shear F = [c s; s c], c = cos(γ/2),
 * s = sin(γ/2), gives P12 = P21 = G γ c, P11 = P22 = −G γ s.
 *
 * One yarn carries T_k = N_k × yarn_spacing_k (N), reported as T1, T2.
 *
 * No crimp, so no amplitudes (n_amplitudes = 0): R = 0 and the solver holds
 * ΔA fixed. No shear flow either: the dissipative angle γᶠ is not used (W uses
 * γ), evaluate returns gamma_f unchanged and dissipated = 0 for any dt.
 */
#include "wovenff/cell.h"
#include "wovenff/material.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define FAMILIES 2

/* sinθ below which the stable-step bound stops growing: its shear term goes
 * as 1/sinθ and would be infinite at parallel yarns (about 87° of shear). */
#define SHEAR_SINE_FLOOR 0.05

typedef struct linear_params {
    double stiffness[FAMILIES];    /* S_k, N/m, per unit width */
    double shear_stiffness;        /* G, N/m (per unit area per rad²) */
    double tension_only;           /* 1: yarns carry no compression */
    double yarn_spacing[FAMILIES]; /* m, a copy of mat->yarn_spacing: evaluate()
                                      sees only params and reports T_k = N_k × spacing */
} linear_params;

_Static_assert(sizeof(linear_params) <= sizeof(((wff_material *)0)->params),
               "linear_params must fit in wff_material.params");

/* What one evaluation computes, shared by evaluate, energy_split, wave_speeds. */
typedef struct linear_point {
    double gh[FAMILIES][3];     /* ĝ_k */
    double stretch[FAMILIES];   /* λ_k */
    double force[FAMILIES];     /* N_k = S_k (λ_k − 1), clipped when tension_only, N/m */
    double cos_t, sin_t;        /* cosθ, sinθ */
    double gamma;               /* γ, rad */
    double energy_yarn, energy_shear;
} linear_point;

static const char *const linear_diag_names[] = {"T1", "T2", "lambda1", "lambda2"};
static const char *const linear_diag_units[] = {"N", "N", "-", "-"};
enum { DIAG_T1, DIAG_T2, DIAG_LAMBDA1, DIAG_LAMBDA2, DIAG_COUNT };
static const char *const linear_mech_names[] = {"yarn_stretch", "shear"};
enum { MECH_YARN, MECH_SHEAR, MECH_COUNT };

static int linear_point_eval(const linear_params *c, const double F[6], linear_point *pt)
{
    double g[FAMILIES][3];
    for (int f = 0; f < FAMILIES; f++) {
        for (int i = 0; i < 3; i++)
            g[f][i] = F[2 * i + f];
        pt->stretch[f] = sqrt(g[f][0] * g[f][0] + g[f][1] * g[f][1] + g[f][2] * g[f][2]);
        if (!(pt->stretch[f] > 0))
            return WFF_POINT_DEGENERATE;
        for (int i = 0; i < 3; i++)
            pt->gh[f][i] = g[f][i] / pt->stretch[f];
    }
    double n0 = pt->gh[0][1] * pt->gh[1][2] - pt->gh[0][2] * pt->gh[1][1];
    double n1 = pt->gh[0][2] * pt->gh[1][0] - pt->gh[0][0] * pt->gh[1][2];
    double n2 = pt->gh[0][0] * pt->gh[1][1] - pt->gh[0][1] * pt->gh[1][0];
    pt->sin_t = sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    pt->cos_t = pt->gh[0][0] * pt->gh[1][0] + pt->gh[0][1] * pt->gh[1][1] +
                pt->gh[0][2] * pt->gh[1][2];
    if (!(pt->sin_t > 0))
        return WFF_POINT_DEGENERATE;
    pt->gamma = M_PI_2 - atan2(pt->sin_t, pt->cos_t);

    pt->energy_yarn = 0;
    for (int f = 0; f < FAMILIES; f++) {
        double strain = pt->stretch[f] - 1;
        if (c->tension_only != 0 && strain < 0)
            strain = 0;
        pt->force[f] = c->stiffness[f] * strain;
        pt->energy_yarn += 0.5 * c->stiffness[f] * strain * strain;
    }
    pt->energy_shear = 0.5 * c->shear_stiffness * pt->gamma * pt->gamma;
    return WFF_POINT_OK;
}

static void fill_nan(wff_point_result *out)
{
    for (int i = 0; i < 6; i++)
        out->stress[i] = NAN;
    out->residual[0] = out->residual[1] = NAN;
    out->energy = out->dissipated = out->gamma_f = NAN;
    for (int i = 0; i < DIAG_COUNT; i++)
        out->diag[i] = NAN;
}

static int linear_evaluate(const void *params, const double F[6], const double dA[2],
                           double gamma_f, double dt, wff_point_result *out)
{
    (void)dA; /* no amplitudes */
    (void)dt; /* no flow: nothing advances in time */
    const linear_params *c = params;
    linear_point pt;
    if (linear_point_eval(c, F, &pt) != WFF_POINT_OK) {
        fill_nan(out);
        return WFF_POINT_DEGENERATE;
    }
    /* q[f][m]: component of Q_f along ĝ_m */
    double q[FAMILIES][FAMILIES];
    double shear = c->shear_stiffness * pt.gamma; /* G γ, N/m */
    for (int f = 0; f < FAMILIES; f++) {
        int l = 1 - f;
        double couple = shear / (pt.stretch[f] * pt.sin_t);
        q[f][f] = pt.force[f] - couple * pt.cos_t;
        q[f][l] = couple;
    }
    for (int i = 0; i < 3; i++)
        for (int f = 0; f < FAMILIES; f++)
            out->stress[2 * i + f] = q[f][0] * pt.gh[0][i] + q[f][1] * pt.gh[1][i];
    out->residual[0] = out->residual[1] = 0;
    out->energy = pt.energy_yarn + pt.energy_shear;
    out->gamma_f = gamma_f;
    out->dissipated = 0;
    out->diag[DIAG_T1] = pt.force[0] * c->yarn_spacing[0];
    out->diag[DIAG_T2] = pt.force[1] * c->yarn_spacing[1];
    out->diag[DIAG_LAMBDA1] = pt.stretch[0];
    out->diag[DIAG_LAMBDA2] = pt.stretch[1];
    return WFF_POINT_OK;
}

/* Fast path for n_points sharing one F (linear triangles): the result does
 * not depend on ΔA or γᶠ, so one evaluation serves every point. */
static int linear_evaluate_shared(const void *params, const double F[6], int n_points,
                                  const double *dA, const double *weight, double *gamma_f,
                                  double dt, double stress_sum[6], double *residual,
                                  double *energy, double *dissipated, int *bad_point)
{
    (void)dA;
    (void)gamma_f; /* held: no flow */
    (void)dissipated; /* += 0 */
    wff_point_result r;
    *bad_point = 0;
    if (linear_evaluate(params, F, NULL, 0, dt, &r) != WFF_POINT_OK)
        return WFF_POINT_DEGENERATE;
    double weight_sum = 0;
    for (int q = 0; q < n_points; q++) {
        weight_sum += weight[q];
        residual[2 * q] = residual[2 * q + 1] = 0;
    }
    for (int i = 0; i < 6; i++)
        stress_sum[i] += weight_sum * r.stress[i];
    *energy += weight_sum * r.energy;
    return WFF_POINT_OK;
}

static void linear_energy_split(const void *params, const double F[6], const double dA[2],
                                double gamma_f, double *mech)
{
    (void)dA;
    (void)gamma_f;
    const linear_params *c = params;
    linear_point pt;
    if (linear_point_eval(c, F, &pt) != WFF_POINT_OK) {
        mech[MECH_YARN] = mech[MECH_SHEAR] = NAN;
        return;
    }
    mech[MECH_YARN] = pt.energy_yarn;
    mech[MECH_SHEAR] = pt.energy_shear;
}

/* Stable-step bound: speed = sqrt(S/ρ_A) with S an upper bound of the
 * largest stiffness per unit width, a Gershgorin-style sum of
 *   axial        S_f (0 for a slack tension-only yarn)
 *   geometric    |N_f|/λ_f (the yarn force turning with the yarn)
 *   shear        2 G (1 + |γ| (1 + 1/sinθ)) / λ_min²: the Hessian of ½Gγ² is
 *                G ∂γ⊗∂γ + G γ ∂²γ with |∂γ/∂g_k| = 1/λ_k and second
 *                derivatives of the angle at most (1 + 1/sinθ)/λ² (in-plane 1/λ²,
 *                out-of-plane cotθ/λ², across the two yarns 1/(λ_1 λ_2 sinθ)).
 * No amplitudes: amplitude_omega = 0. */
static void linear_wave_speeds(const void *params, double areal_density, const double F[6],
                               const double dA[2], double *membrane_speed,
                               double *amplitude_omega)
{
    (void)dA;
    const linear_params *c = params;
    linear_point pt;
    *amplitude_omega = 0;
    if (linear_point_eval(c, F, &pt) != WFF_POINT_OK) {
        *membrane_speed = INFINITY;
        return;
    }
    double sn = fmax(pt.sin_t, SHEAR_SINE_FLOOR);
    double stretch_min = fmin(pt.stretch[0], pt.stretch[1]);
    double shear = 2 * c->shear_stiffness * (1 + fabs(pt.gamma) * (1 + 1 / sn)) /
                   (stretch_min * stretch_min);
    double membrane = 0;
    for (int f = 0; f < FAMILIES; f++) {
        /* a slack yarn (tension_only) keeps its stiffness in the bound: it can pull
         * tight within one step */
        double s_f = c->stiffness[f] + fabs(pt.force[f]) / pt.stretch[f] + shear;
        membrane = fmax(membrane, s_f);
    }
    *membrane_speed = sqrt(membrane / areal_density);
}

static int linear_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    linear_params *c = (linear_params *)mat->params;
    memset(c, 0, sizeof *c);
    if (wff_kv_number(kv, "S_1", &c->stiffness[0], err) ||
        wff_kv_number(kv, "S_2", &c->stiffness[1], err) ||
        wff_kv_number(kv, "G", &c->shear_stiffness, err) ||
        wff_kv_number(kv, "yarn_spacing_1", &mat->yarn_spacing[0], err) ||
        wff_kv_number(kv, "yarn_spacing_2", &mat->yarn_spacing[1], err) ||
        wff_kv_number_or(kv, "tension_only", 0.0, &c->tension_only, err))
        return -1;
    if (!(c->stiffness[0] > 0))
        return wff_kv_reject(kv, "S_1", err, "yarn stiffness per width must be > 0 N/m");
    if (!(c->stiffness[1] > 0))
        return wff_kv_reject(kv, "S_2", err, "yarn stiffness per width must be > 0 N/m");
    if (!(c->shear_stiffness >= 0))
        return wff_kv_reject(kv, "G", err, "shear stiffness must be >= 0 N/m");
    if (!(mat->yarn_spacing[0] > 0))
        return wff_kv_reject(kv, "yarn_spacing_1", err, "must be > 0 m");
    if (!(mat->yarn_spacing[1] > 0))
        return wff_kv_reject(kv, "yarn_spacing_2", err, "must be > 0 m");
    if (c->tension_only != 0 && c->tension_only != 1)
        return wff_kv_reject(kv, "tension_only", err, "must be 0 or 1");
    c->yarn_spacing[0] = mat->yarn_spacing[0];
    c->yarn_spacing[1] = mat->yarn_spacing[1];
    return 0;
}

static const wff_cell_type linear_yarns = {
    .name = "linear_yarns",
    .summary = "straight linear-elastic yarns along E1, E2 and an in-plane shear stiffness; "
               "no crimp, no amplitudes, no shear flow",
    .n_amplitudes = 0,
    .n_diag = DIAG_COUNT,
    .diag_names = linear_diag_names,
    .diag_units = linear_diag_units,
    .yarn_tension_diag = {DIAG_T1, DIAG_T2},
    .n_mech = MECH_COUNT,
    .mech_names = linear_mech_names,
    .parse = linear_parse,
    .evaluate = linear_evaluate,
    .wave_speeds = linear_wave_speeds,
    .energy_split = linear_energy_split,
    .evaluate_shared = linear_evaluate_shared,
};
WFF_REGISTER_CELL(linear_yarns);

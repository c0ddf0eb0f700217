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
 * ΔA fixed. No shear flow either (W uses γ): dissipated = 0 for any dt.
 *
 * Yarn failure (docs/model.md §20, optional: failure = 1): N_k and ½ S_k ε_k²
 * times 1 − d_k where the yarn is stretched, d_k growing with the largest
 * engineering yarn strain reached, here the straight yarn's
 *
 *   ε_k = λ_k − 1
 *
 * (yarn_failure.h). The only internal state is failure's: d_1, d_2, then ε_1,
 * ε_2 of the last update with the rate law or the crack band, then the element
 * length h with the band (the element code's, never changed here; n_state 0
 * without failure, 2, 4 or 5 with it). The blocked kernel declines a material with failure on; the
 * wave speeds stay the undamaged bounds.
 */
#include "wovenff/cell.h"
#include "wovenff/material.h"
#include "cell_laws.h"
#include "cell_lanes.h"
#include "yarn_failure.h"

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
    wff_yarn_failure failure;      /* yarn failure (docs/model.md §20); off: enabled 0 */
    int n_state;                   /* states per point: 0, or d_1, d_2 [, ε_1, ε_2 [, h]] */
} linear_params;

_Static_assert(sizeof(linear_params) <= sizeof(((wff_material *)0)->params),
               "linear_params must fit in wff_material.params");

/* What one evaluation computes, shared by evaluate, energy_split, wave_speeds. */
typedef struct linear_point {
    wff_yarn_frame fr;          /* ĝ_k, λ_k (as p_k with p_k⁰ = 1), θ, γ */
    double force[FAMILIES];     /* N_k = S_k (λ_k − 1), clipped when tension_only, N/m
                                   (times 1 − d_k once linear_point_fail has run) */
    double energy_family[FAMILIES]; /* ½ S_k (λ_k − 1)² (damaged likewise), J/m² */
    double energy_yarn, energy_shear;
    double failure_state[WFF_YARN_STATES_MAX]; /* d_1, d_2, ε_1, ε_2, h after the update
                                                  (with failure) */
    double failure_released;    /* Σ_k Δd_k W_k⁺, J/m² */
} linear_point;

static const char *const linear_diag_names[] = {"T1", "T2", "lambda1", "lambda2"};
static const char *const linear_diag_units[] = {"N", "N", "-", "-"};
enum { DIAG_T1, DIAG_T2, DIAG_LAMBDA1, DIAG_LAMBDA2, DIAG_COUNT };
static const char *const linear_mech_names[] = {"yarn_stretch", "shear"};
enum { MECH_YARN, MECH_SHEAR, MECH_COUNT };
/* The internal state, only with yarn failure: the damages d_1, d_2, with its
 * rate law (or the crack band) the yarn strains of the last update, with the
 * crack band the element length (the element code's). */
static const char *const linear_state_names[] = {"damage1", "damage2", "yarn_strain1",
                                                 "yarn_strain2", "element_length"};
static const char *const linear_state_units[] = {"-", "-", "-", "-", "m"};
enum { STATE_DAMAGE1, STATE_DAMAGE2, STATE_STRAIN1, STATE_STRAIN2, STATE_LENGTH,
       STATE_COUNT };
_Static_assert(STATE_LENGTH - STATE_DAMAGE1 == WFF_YARN_STATE_LENGTH,
               "linear_yarns: the failure states are yarn_failure.h's");
_Static_assert(STATE_COUNT <= WFF_STATE_MAX, "linear_yarns carries too many states");

/* The kinematics with G_k = E_k (docs/model.md §1, p_k⁰ = 1), N_k and W. */
static int linear_point_eval(const linear_params *c, const double F[6], linear_point *pt)
{
    static const double unit_pitch[FAMILIES] = {1, 1};
    if (wff_yarn_kinematics(unit_pitch, F, &pt->fr) != WFF_POINT_OK)
        return WFF_POINT_DEGENERATE;
    pt->energy_yarn = 0;
    for (int f = 0; f < FAMILIES; f++) {
        double strain = pt->fr.p[f] - 1;
        if (c->tension_only != 0 && strain < 0)
            strain = 0;
        pt->force[f] = c->stiffness[f] * strain;
        pt->energy_family[f] = 0.5 * c->stiffness[f] * strain * strain;
        pt->energy_yarn += pt->energy_family[f];
    }
    pt->failure_released = 0;
    pt->energy_shear = 0.5 * c->shear_stiffness * pt->fr.gamma * pt->fr.gamma;
    return WFF_POINT_OK;
}

/* docs/model.md §20: yarn failure at ε_k = λ_k − 1 from the point's state over
 * dt: N_k and its energy times 1 − d_k where stretched; nothing without failure. */
static void linear_point_fail(const linear_params *c, const double *state, double dt,
                              linear_point *pt)
{
    if (c->failure.enabled == 0)
        return;
    const int kept = wff_yarn_failure_keeps_strain(&c->failure); /* ε_k of the last update */
    const double length = wff_yarn_failure_length(&c->failure, state + STATE_DAMAGE1);
    pt->failure_state[WFF_YARN_STATE_LENGTH] = length; /* (the element code's) */
    pt->energy_yarn = 0;
    for (int f = 0; f < FAMILIES; f++) {
        wff_yarn_damage d = wff_yarn_damage_step(
            &c->failure, f, pt->fr.p[f] - 1, pt->energy_family[f], state[STATE_DAMAGE1 + f],
            kept ? state[STATE_STRAIN1 + f] : 0, length, dt);
        pt->force[f] *= d.factor;
        pt->energy_family[f] *= d.factor;
        pt->energy_yarn += pt->energy_family[f];
        pt->failure_state[f] = d.damage;
        pt->failure_state[2 + f] = d.strain_prev;
        pt->failure_released += d.released;
    }
}

/* P = Σ_k Q_k ⊗ E_k, Q_k = N_k ĝ_k + G γ/(λ_k sinθ) (ĝ_l − cosθ ĝ_k): the
 * shared Q coefficients with the yarn term N_k, the couple G γ, no spars. */
WFF_INLINE int linear_evaluate(const void *params, const double F[6], const double dA[2],
                               const double *state, double dt, wff_point_result *out)
{
    (void)dA; /* no amplitudes */
    const linear_params *c = params;
    linear_point pt;
    if (linear_point_eval(c, F, &pt) != WFF_POINT_OK) {
        wff_point_result_nan(out, DIAG_COUNT);
        return WFF_POINT_DEGENERATE;
    }
    linear_point_fail(c, state, dt, &pt); /* (no flow: only failure's states advance) */
    static const double no_spars[FAMILIES] = {0, 0}, unit_scale[FAMILIES] = {1, 1};
    double q[FAMILIES][FAMILIES]; /* Q_f along ĝ_m */
    double shear = c->shear_stiffness * pt.fr.gamma; /* G γ, N/m */
    for (int f = 0; f < FAMILIES; f++)
        wff_q_coefficients(&pt.fr, f, pt.force[f], shear, no_spars, &q[f][f], &q[f][1 - f]);
    wff_stress_from_q(&pt.fr, q, unit_scale, out->stress);
    out->residual[0] = out->residual[1] = 0;
    out->energy = pt.energy_yarn + pt.energy_shear;
    out->dissipated = 0;
    out->failure_dissipated = pt.failure_released;
    out->slip_dissipated = 0; /* (no slip in this cell) */
    for (int i = 0; i < c->n_state; i++)
        out->state[i] = pt.failure_state[i];
    out->diag[DIAG_T1] = pt.force[0] * c->yarn_spacing[0];
    out->diag[DIAG_T2] = pt.force[1] * c->yarn_spacing[1];
    out->diag[DIAG_LAMBDA1] = pt.fr.p[0];
    out->diag[DIAG_LAMBDA2] = pt.fr.p[1];
    return WFF_POINT_OK;
}

/* Fast path for n_points sharing one F (linear triangles): without failure the
 * result does not depend on ΔA (and there is no state), so one evaluation
 * serves every point; with it each point has its damage, and is evaluated. */
static int linear_evaluate_shared(const void *params, const double F[6], int n_points,
                                  const double *dA, const double *weight, double *state,
                                  double dt, double stress_sum[6], double *residual,
                                  double *energy, double *dissipated,
                                  double *failure_dissipated, double *slip_dissipated,
                                  int *bad_point)
{
    (void)dA;
    (void)dissipated; /* += 0 */
    (void)slip_dissipated; /* += 0 */
    wff_point_result r;
    *bad_point = 0;
    const linear_params *c = params;
    if (c->failure.enabled != 0) {
        for (int q = 0; q < n_points; q++) {
            double *point_state = state + q * c->n_state;
            if (linear_evaluate(params, F, NULL, point_state, dt, &r) != WFF_POINT_OK) {
                *bad_point = q;
                return WFF_POINT_DEGENERATE;
            }
            for (int i = 0; i < 6; i++)
                stress_sum[i] += weight[q] * r.stress[i];
            residual[2 * q] = residual[2 * q + 1] = 0;
            *energy += weight[q] * r.energy;
            *failure_dissipated += weight[q] * r.failure_dissipated;
            for (int i = 0; i < c->n_state; i++)
                point_state[i] = r.state[i];
        }
        return WFF_POINT_OK;
    }
    if (linear_evaluate(params, F, NULL, state, dt, &r) != WFF_POINT_OK)
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

/* What the lanes of a triangle block share: tension_only as a double. */
typedef struct linear_tri_ctx {
    double slack;
} linear_tri_ctx;

/* Blocks of linear triangles (the far field of a zonal model): no state,
 * residuals and dissipation 0; a material with yarn failure goes back to the
 * general path. */
WFF_INLINE int linear_tri_accepts(const linear_params *c)
{
    return c->failure.enabled == 0;
}

WFF_INLINE void linear_tri_setup(const linear_params *c, double dt, linear_tri_ctx *ctx,
                                 wff_tri_block *blk)
{
    (void)dt; /* no flow */
    ctx->slack = c->tension_only;
    memset(blk->residual, 0, sizeof blk->residual); /* (outside the lanes' loop: a store
                                                     gcc makes a memset stops it vectorising) */
    memset(blk->dissipated, 0, sizeof blk->dissipated);
    memset(blk->failure_dissipated, 0, sizeof blk->failure_dissipated);
    memset(blk->slip_dissipated, 0, sizeof blk->slip_dissipated);
}

/* Lane b of a block: linear_evaluate's formulas for one triangle. */
WFF_INLINE void linear_tri_lane(const linear_params *c, const linear_tri_ctx *ctx,
                                wff_tri_block *blk, double flag[WFF_BLOCK], int b)
{
    (void)flag;
    const double slack = ctx->slack;
    const double unit_pitch[FAMILIES] = {1, 1}, no_spars[FAMILIES] = {0, 0},
                 unit_scale[FAMILIES] = {1, 1};
    const double F[6] = {blk->F[0][b], blk->F[1][b], blk->F[2][b],
                         blk->F[3][b], blk->F[4][b], blk->F[5][b]};
    wff_yarn_frame fr;
    blk->degenerate[b] = wff_yarn_kinematics(unit_pitch, F, &fr) != WFF_POINT_OK;
    double s0 = fr.p[0] - 1, s1 = fr.p[1] - 1; /* strains; slack (tension_only): none below 0,
                                                  written branch-free (a && or fmin
                                                  keeps gcc from vectorising the lanes) */
    s0 = (s0 < 0) & (slack != 0) ? 0.0 : s0;
    s1 = (s1 < 0) & (slack != 0) ? 0.0 : s1;
    double force[FAMILIES] = {c->stiffness[0] * s0, c->stiffness[1] * s1};
    double energy = 0.5 * c->stiffness[0] * s0 * s0 + 0.5 * c->stiffness[1] * s1 * s1;
    double shear = c->shear_stiffness * fr.gamma, q[FAMILIES][FAMILIES], stress[6];
#pragma GCC unroll 2
    for (int f = 0; f < FAMILIES; f++)
        wff_q_coefficients(&fr, f, force[f], shear, no_spars, &q[f][f], &q[f][1 - f]);
    wff_stress_from_q(&fr, q, unit_scale, stress);
#pragma GCC unroll 6
    for (int i = 0; i < 6; i++)
        blk->stress[i][b] = stress[i];
    blk->energy[b] = energy + 0.5 * c->shear_stiffness * fr.gamma * fr.gamma;
}

/* The blocked ops (cell_lanes.h), one vectorised loop over the lanes each:
 * linear_evaluate_tri_block with the lane above; linear_evaluate_point_block
 * (quads' Gauss points) and linear_wave_speeds_block generated from
 * linear_evaluate and linear_wave_speeds. */
WFF_CELL_TRI_BLOCK(linear, linear_params, linear_tri_accepts, linear_tri_ctx, linear_tri_setup,
                   linear_tri_lane, wff_lanes_nothing_after)
WFF_CELL_GENERATED(POINT, linear, linear_params, linear_evaluate)

static void linear_energy_split(const void *params, const double F[6], const double dA[2],
                                const double *state, double *mech)
{
    (void)dA;
    const linear_params *c = params;
    linear_point pt;
    if (linear_point_eval(c, F, &pt) != WFF_POINT_OK) {
        mech[MECH_YARN] = mech[MECH_SHEAR] = NAN;
        return;
    }
    linear_point_fail(c, state, 0, &pt);
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
WFF_INLINE void linear_wave_speeds(const void *params, double areal_density,
                                   const double F[6], const double dA[2],
                                   double *membrane_speed, double *amplitude_omega)
{
    /* undamaged (§20): damage only lowers the yarn terms, so this stays an upper bound */
    (void)dA;
    const linear_params *c = params;
    linear_point pt;
    *amplitude_omega = 0;
    if (linear_point_eval(c, F, &pt) != WFF_POINT_OK) {
        *membrane_speed = INFINITY;
        return;
    }
    double sn = fmax(pt.fr.sin_t, SHEAR_SINE_FLOOR);
    double stretch_min = fmin(pt.fr.p[0], pt.fr.p[1]);
    double shear = 2 * c->shear_stiffness * (1 + fabs(pt.fr.gamma) * (1 + 1 / sn)) /
                   (stretch_min * stretch_min);
    double membrane = 0;
    for (int f = 0; f < FAMILIES; f++) {
        /* a slack yarn (tension_only) keeps its stiffness in the bound: it can pull
         * tight within one step */
        double s_f = c->stiffness[f] + fabs(pt.force[f]) / pt.fr.p[f] + shear;
        membrane = fmax(membrane, s_f);
    }
    *membrane_speed = sqrt(membrane / areal_density);
}

WFF_CELL_GENERATED(WAVE, linear, linear_params, linear_wave_speeds)

static int linear_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    linear_params *c = (linear_params *)mat->params;
    memset(c, 0, sizeof *c);
    if (wff_kv_number(kv, "S_1", &c->stiffness[0], err) ||
        wff_kv_number(kv, "S_2", &c->stiffness[1], err) ||
        wff_kv_number(kv, "G", &c->shear_stiffness, err) ||
        wff_kv_number(kv, "yarn_spacing_1", &mat->yarn_spacing[0], err) ||
        wff_kv_number(kv, "yarn_spacing_2", &mat->yarn_spacing[1], err) ||
        wff_kv_number_or(kv, "tension_only", 0.0, &c->tension_only, err) ||
        wff_yarn_failure_parse(kv, &c->failure, err) ||
        wff_yarn_failure_no_cutting(kv, &c->failure, "linear_yarns", err))
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
    mat->n_state = c->n_state = wff_yarn_failure_states(&c->failure); /* failure's only */
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
    .n_state_max = STATE_COUNT,
    .state_names = linear_state_names,
    .state_units = linear_state_units,
    .damage_state = {STATE_DAMAGE1, STATE_DAMAGE2},
    .parse = linear_parse,
    .evaluate = linear_evaluate,
    .wave_speeds = linear_wave_speeds,
    .energy_split = linear_energy_split,
    .evaluate_shared = linear_evaluate_shared,
    .evaluate_tri_block = linear_evaluate_tri_block,
    .evaluate_point_block = linear_evaluate_point_block,
    .wave_speeds_block = linear_wave_speeds_block,
};
WFF_REGISTER_CELL(linear_yarns);

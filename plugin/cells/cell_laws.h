/* wovenff — pieces the truss-and-spring weave cells share (King et al. 2005):
 * the yarn kinematics of eq. (1) (docs/model.md §1), the compaction
 * exponential with its overflow guard and the locking power law (§3, §4),
 * the backward-Euler update of the visco-elastic shear angle (§7), the
 * in-plane coefficients of Q_k and the stress assembled from them (§6), and
 * the parameter-table checks of the cells' parse() (§9).
 *
 * Everything here is a pure function of its arguments, with no state.
 * The per-point pieces are always inlined and branch-free where a cell's
 * blocked kernel calls them inside its lane loop: written once, used by the
 * plain evaluate, the shared-kinematics path and the vectorised kernel alike
 * (docs/model.md §11). This header knows no cell's parameter struct. */
#ifndef WOVENFF_CELL_LAWS_H
#define WOVENFF_CELL_LAWS_H

#include <math.h>
#include <stddef.h>

#include "wovenff/cell.h"
#include "wovenff/material.h"

#define WFF_INLINE static inline __attribute__((always_inline))

/* glibc's libmvec has vector versions of atan and exp; declaring them SIMD-
 * callable lets gcc vectorise a blocked kernel's loop across its lanes
 * (glibc declares them so only under -ffast-math, which we do not use). */
extern double atan(double) __attribute__((__simd__("notinbranch")));
extern double exp(double) __attribute__((__simd__("notinbranch")));

/* The in-plane frame of the two yarn families at a point (docs/model.md §1). */
typedef struct wff_yarn_frame {
    double gh[2][3];   /* ĝ_k = g_k / p_k */
    double p[2];       /* p_k = |g_k|, m (the stretch λ_k when p_k⁰ = 1) */
    double inv_p[2];   /* 1 / p_k */
    double J;          /* |g_1 × g_2|, m² */
    double cos_t;      /* cosθ = ĝ_1·ĝ_2 */
    double sin_t;      /* sinθ = J/(p_1 p_2) */
    double inv_sin;    /* 1 / sinθ */
    double gamma;      /* γ = θ⁰ − θ = atan(cosθ/sinθ), θ⁰ = π/2, rad */
} wff_yarn_frame;

/* Eq. (1), docs/model.md §1: g_k = F G_k with G_k = p_k⁰ E_k; p_k = |g_k|,
 * ĝ_k = g_k/p_k, J = |g_1 × g_2|, cosθ = ĝ_1·ĝ_2, sinθ = J/(p_1 p_2),
 * γ = π/2 − θ = atan(cosθ/sinθ) for sinθ > 0. Computes everything without
 * branching (so it runs in a lane loop) and returns WFF_POINT_DEGENERATE if a
 * yarn has zero length or the yarns are parallel (the frame is then
 * meaningless), else WFF_POINT_OK. */
WFF_INLINE int wff_yarn_kinematics(const double pitch0[2], const double F[6],
                                   wff_yarn_frame *fr)
{
    double g[2][3];
#pragma GCC unroll 2
    for (int f = 0; f < 2; f++) {
#pragma GCC unroll 3
        for (int i = 0; i < 3; i++)
            g[f][i] = pitch0[f] * F[2 * i + f];
        fr->p[f] = sqrt(g[f][0] * g[f][0] + g[f][1] * g[f][1] + g[f][2] * g[f][2]);
        fr->inv_p[f] = 1 / fr->p[f];
#pragma GCC unroll 3
        for (int i = 0; i < 3; i++)
            fr->gh[f][i] = g[f][i] * fr->inv_p[f];
    }
    double n0 = g[0][1] * g[1][2] - g[0][2] * g[1][1];
    double n1 = g[0][2] * g[1][0] - g[0][0] * g[1][2];
    double n2 = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    fr->J = sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    fr->cos_t = (g[0][0] * g[1][0] + g[0][1] * g[1][1] + g[0][2] * g[1][2]) * fr->inv_p[0] *
                fr->inv_p[1];
    fr->sin_t = fr->J * fr->inv_p[0] * fr->inv_p[1];
    fr->inv_sin = 1 / fr->sin_t;
    fr->gamma = atan(fr->cos_t * fr->inv_sin);
    int degenerate = !(fr->p[0] > 0) | !(fr->p[1] > 0) | !(fr->sin_t > 0);
    return degenerate ? WFF_POINT_DEGENERATE : WFF_POINT_OK;
}

/* Exponent a·I past which the compaction exponential is continued by its
 * third-order Taylor polynomial: exp(30) ≈ 1e13, far beyond any physical
 * compaction force, and far below overflow. */
#define WFF_COMPACTION_EXPONENT_MAX 30.0

/* One crossover's compaction spring (docs/model.md §3). */
typedef struct wff_compaction {
    double force;      /* F_I = K_I (exp(a I) − 1), N */
    double energy;     /* (K_I/a)(exp(a I) − 1) − K_I I, J */
    double stiffness;  /* ∂F_I/∂I, N/m */
} wff_compaction;

/* F_I at the interference I = −ΔA_1 − ΔA_2, with exp continued past
 * WFF_COMPACTION_EXPONENT_MAX by a polynomial of the same value, slope and
 * curvature (so the energy stays finite and consistent when compaction is
 * extreme). Branch-free. */
WFF_INLINE wff_compaction wff_compaction_law(double force_scale, double rate, const double dA[2])
{
    double x = rate * (-dA[0] - dA[1]);
    double u = x > WFF_COMPACTION_EXPONENT_MAX ? x - WFF_COMPACTION_EXPONENT_MAX : 0.0;
    double e = exp(x - u);
    double value = 1 + u + 0.5 * u * u;   /* exp(x) = e × value */
    double primitive = value + u * u * u / 6;
    wff_compaction c;
    c.force = force_scale * (e * value - 1);
    c.energy = force_scale / rate * (e * primitive - 1) + force_scale * (dA[0] + dA[1]);
    c.stiffness = force_scale * rate * e * (1 + u);
    return c;
}

/* K gap^c for the locking law; integer exponents by multiplication (pow with
 * a run-time exponent costs ~10 ns, and does not vectorise). */
WFF_INLINE double wff_locking_force(double stiffness, double gap, double exponent)
{
    if (exponent == 1.0)
        return stiffness * gap;
    if (exponent == 2.0)
        return stiffness * gap * gap;
    if (exponent == 3.0)
        return stiffness * gap * gap * gap;
    return stiffness * pow(gap, exponent);
}

/* One locking spar (docs/model.md §4). */
typedef struct wff_spar {
    double force;      /* F_L = K_d (d⁰ − d)^c while d < d⁰, else 0, N */
    double energy;     /* K_d (d⁰ − d)₊^(c+1)/(c+1), J */
    double stiffness;  /* −∂F_L/∂d = c K_d (d⁰ − d)₊^(c−1), N/m */
} wff_spar;

/* A spar of reference length length0 at length `length`. A blocked kernel
 * passes a constant exponent, which leaves one multiplication. */
WFF_INLINE wff_spar wff_spar_law(double stiffness, double exponent, double length0,
                                 double length)
{
    double gap = length0 > length ? length0 - length : 0.0; /* (d⁰ − d)₊ */
    wff_spar s;
    s.force = wff_locking_force(stiffness, gap, exponent);
    s.energy = s.force * gap * (1 / (exponent + 1)); /* a constant for a constant exponent */
    s.stiffness = gap > 0 ? exponent * wff_locking_force(stiffness, gap, exponent - 1) : 0.0;
    return s;
}

/* The visco-elastic shear spring M_s = K_s (γ − γᶠ), γ̇ᶠ = γ̇₀ sign(M_s)|M_s/M₀|^n,
 * for one step Δt (docs/model.md §7). */
typedef struct wff_shear_flow {
    double stiffness;  /* K_s, N·m/rad */
    double moment;     /* M₀, N·m */
    double step;       /* Δt γ̇₀, 0 when γᶠ is held (Δt ≤ 0, γ̇₀ = 0 or K_s = 0) */
    double ratio;      /* r = Δt γ̇₀ K_s/M₀ of the closed form for n = 1 */
    double inv_ratio1; /* 1/(1 + r) */
} wff_shear_flow;

WFF_INLINE wff_shear_flow wff_shear_flow_step(double stiffness, double moment, double rate,
                                              double dt)
{
    wff_shear_flow s;
    int flows = dt > 0 && rate != 0 && stiffness != 0;
    s.stiffness = stiffness;
    s.moment = moment;
    s.step = flows ? dt * rate : 0;
    s.ratio = flows ? dt * rate * stiffness / moment : 0;
    s.inv_ratio1 = 1 / (1 + s.ratio);
    return s;
}

/* Backward-Euler update of γᶠ (docs/model.md §7): solve
 *   x = γᶠ + Δt γ̇₀ sign(m)|m/M₀|^n,  m = K_s (γ − x)
 * for x. `exponent` is n (a blocked kernel passes the constant 1: the closed
 * form x = (γᶠ + r γ)/(1 + r), branch-free). Otherwise the root lies between
 * γᶠ and γ: a bracketed Newton iteration. A held γᶠ comes back unchanged. */
WFF_INLINE double wff_shear_flow_update(const wff_shear_flow *s, double exponent, double gamma,
                                        double gamma_f)
{
    if (exponent == 1.0)
        return (gamma_f + s->ratio * gamma) * s->inv_ratio1;
    if (s->step == 0)
        return gamma_f;
    double lo = fmin(gamma_f, gamma), hi = fmax(gamma_f, gamma), x = gamma_f;
    for (int it = 0; it < 100; it++) {
        double m = s->stiffness * (gamma - x);
        double ratio = fabs(m) / s->moment;
        double flow = s->step * pow(ratio, exponent);
        double f = x - gamma_f - (m >= 0 ? flow : -flow);
        if (f > 0)
            hi = x;
        else
            lo = x;
        /* d/dx of sign(m)|m/M₀|^n is −n K_s |m/M₀|^(n−1)/M₀ */
        double df = 1 + s->step * exponent * s->stiffness / s->moment * pow(ratio, exponent - 1);
        double next = x - f / df;
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        if (fabs(next - x) <= 1e-15 * (fabs(x) + fabs(gamma) + 1e-300))
            return next;
        x = next;
    }
    return x;
}

/* In-plane coefficients of Q_f = ∂W_cell/∂g_f = q_own ĝ_f + q_other ĝ_l
 * (docs/model.md §6), l the other family, from
 *   yarn        the yarn and bending terms along ĝ_f
 *   couple      M_s/(p_f sinθ) (ĝ_l − cosθ ĝ_f), shear_moment the cell's total M_s
 *   own spars   −N_f p_l cosθ/(p_f sinθ) (cosθ ĝ_f − ĝ_l)     (s_f = J/p_f)
 *   other spars −N_l (ĝ_f − cosθ ĝ_l)/sinθ                     (s_l = J/p_l)
 * with N_m = spar_pull[m] = Σ F_L ∂d/∂s_m, the spars' pull on s_m, and
 * ∂J/∂g_f = p_l (ĝ_f − cosθ ĝ_l)/sinθ. */
WFF_INLINE void wff_q_coefficients(const wff_yarn_frame *fr, int f, double yarn,
                                   double shear_moment, const double spar_pull[2],
                                   double *q_own, double *q_other)
{
    int l = 1 - f;
    double cs = fr->cos_t;
    double arm = fr->inv_p[f] * fr->inv_sin; /* 1/(p_f sinθ) */
    double couple = shear_moment * arm;
    double own = spar_pull[f] * fr->p[l] * cs * arm;
    double other = spar_pull[l] * fr->inv_sin;
    *q_own = yarn - couple * cs - own * cs - other;
    *q_other = couple + own + other * cs;
}

/* P = Σ_k scale_k Q_k ⊗ E_k with Q_k = q[k][0] ĝ_1 + q[k][1] ĝ_2, row-major
 * 3×2 (docs/model.md §6); scale_k = p_k⁰ / (cell area) times any weight. */
WFF_INLINE void wff_stress_from_q(const wff_yarn_frame *fr, const double q[2][2],
                                  const double scale[2], double stress[6])
{
#pragma GCC unroll 3
    for (int i = 0; i < 3; i++)
#pragma GCC unroll 2
        for (int f = 0; f < 2; f++)
            stress[2 * i + f] = scale[f] * (q[f][0] * fr->gh[0][i] + q[f][1] * fr->gh[1][i]);
}

/* NaN in every output of a failed evaluation (n_diag diagnostics). */
static inline void wff_point_result_nan(wff_point_result *out, int n_diag)
{
    for (int i = 0; i < 6; i++)
        out->stress[i] = NAN;
    out->residual[0] = out->residual[1] = NAN;
    out->energy = out->dissipated = out->failure_dissipated = out->slip_dissipated = NAN;
    for (int i = 0; i < WFF_STATE_MAX; i++)
        out->state[i] = NAN;
    for (int i = 0; i < n_diag; i++)
        out->diag[i] = NAN;
}

/* reference_geometry() of a cell that keeps p_k⁰ and A_k⁰ (docs/model.md §2). */
static inline void wff_reference_geometry_copy(const double pitch0[2], const double amplitude0[2],
                                               double pitch_out[2], double amplitude_out[2])
{
    for (int f = 0; f < 2; f++) {
        pitch_out[f] = pitch0[f];
        amplitude_out[f] = amplitude0[f];
    }
}

/* A parameter read from a material file into a cell's struct. */
typedef struct wff_param_key {
    const char *key;
    double *value;
} wff_param_key;

#define WFF_KEYS(table) (table), sizeof(table) / sizeof((table)[0])

/* parse() helpers (docs/model.md §9). Read every key (missing: an error),
 * then check signs; each returns 0 or -1 with err naming the key. */
static inline int wff_params_read(wff_kv *kv, const wff_param_key *keys, size_t n, wff_error *err)
{
    for (size_t i = 0; i < n; i++)
        if (wff_kv_number(kv, keys[i].key, keys[i].value, err))
            return -1;
    return 0;
}

static inline int wff_params_positive(const wff_kv *kv, const wff_param_key *keys, size_t n,
                                      wff_error *err)
{
    for (size_t i = 0; i < n; i++)
        if (!(*keys[i].value > 0))
            return wff_kv_reject(kv, keys[i].key, err, "must be > 0");
    return 0;
}

static inline int wff_params_nonnegative(const wff_kv *kv, const wff_param_key *keys, size_t n,
                                         wff_error *err)
{
    for (size_t i = 0; i < n; i++)
        if (!(*keys[i].value >= 0))
            return wff_kv_reject(kv, keys[i].key, err, "must be >= 0");
    return 0;
}

/* Where a truss-and-spring cell keeps the parameters King-type cells share
 * (docs/model.md §9; arrays are per family). */
typedef struct wff_weave_params {
    double *pitch0, *amplitude0;       /* p0_k, A0_k, m */
    const char *yarn_key[2];           /* the yarn stiffness's keys: "k_1" or "EA_1", ... */
    double *yarn_stiffness;            /* under yarn_key */
    double *bending_stiffness;         /* kb_k */
    double *compaction_force, *compaction_rate;  /* K_I, a */
    double *locking_stiffness, *locking_exponent; /* K_d, c */
    double *shear_stiffness, *flow_moment, *flow_rate, *flow_exponent; /* K_s, M_0, gammadot_0, n */
    double *tension_only;
} wff_weave_params;

/* Read and check them: every key but n (default 1) and tension_only
 * (default 0) required; p0, A0, the yarn stiffness, K_I, a, M_0 > 0; kb, K_d,
 * K_s, gammadot_0 >= 0; c >= 1, n >= 1; tension_only 0 or 1. (Numbers are
 * finite: wff_kv_number rejects inf and nan.) */
static inline int wff_weave_parse(wff_kv *kv, const wff_weave_params *w, wff_error *err)
{
    const wff_param_key required[] = {
        {"p0_1", &w->pitch0[0]}, {"p0_2", &w->pitch0[1]},
        {"A0_1", &w->amplitude0[0]}, {"A0_2", &w->amplitude0[1]},
        {w->yarn_key[0], &w->yarn_stiffness[0]}, {w->yarn_key[1], &w->yarn_stiffness[1]},
        {"kb_1", &w->bending_stiffness[0]}, {"kb_2", &w->bending_stiffness[1]},
        {"K_I", w->compaction_force}, {"a", w->compaction_rate},
        {"K_d", w->locking_stiffness}, {"c", w->locking_exponent},
        {"K_s", w->shear_stiffness}, {"M_0", w->flow_moment},
        {"gammadot_0", w->flow_rate},
    };
    const wff_param_key positive[] = {
        {"p0_1", &w->pitch0[0]}, {"p0_2", &w->pitch0[1]},
        {"A0_1", &w->amplitude0[0]}, {"A0_2", &w->amplitude0[1]},
        {w->yarn_key[0], &w->yarn_stiffness[0]}, {w->yarn_key[1], &w->yarn_stiffness[1]},
        {"K_I", w->compaction_force}, {"a", w->compaction_rate}, {"M_0", w->flow_moment},
    };
    const wff_param_key nonnegative[] = {
        {"kb_1", &w->bending_stiffness[0]}, {"kb_2", &w->bending_stiffness[1]},
        {"K_d", w->locking_stiffness}, {"K_s", w->shear_stiffness},
        {"gammadot_0", w->flow_rate},
    };
    if (wff_params_read(kv, WFF_KEYS(required), err) ||
        wff_kv_number_or(kv, "n", 1.0, w->flow_exponent, err) ||
        wff_kv_number_or(kv, "tension_only", 0.0, w->tension_only, err) ||
        wff_params_positive(kv, WFF_KEYS(positive), err) ||
        wff_params_nonnegative(kv, WFF_KEYS(nonnegative), err))
        return -1;
    if (!(*w->locking_exponent >= 1))
        return wff_kv_reject(kv, "c", err, "locking exponent must be >= 1 "
                             "(below 1 the locking stiffness is infinite at contact)");
    if (!(*w->flow_exponent >= 1))
        return wff_kv_reject(kv, "n", err, "shear-flow exponent must be >= 1 "
                             "(below 1 the flow rate is singular at rest)");
    if (*w->tension_only != 0 && *w->tension_only != 1)
        return wff_kv_reject(kv, "tension_only", err, "must be 0 or 1");
    return 0;
}

#endif

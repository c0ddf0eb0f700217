/* The King plain-weave unit cell (King, Jearanaisilawong & Socrate 2005), as
 * run by Parsons, Socrate, Arata & Weerasooriya: see docs/MODEL.md, §1–7.
 *
 * Reference cell 2 p1⁰ × 2 p2⁰, one crossover. Family k = 1 (warp) along E1,
 * k = 2 (weft) along E2; l is the other family. Kinematics (eq. 1):
 *
 *   g_k = F G_k,  G_k = p_k⁰ E_k,  p_k = |g_k|,  ĝ_k = g_k / p_k
 *   J = |g_1 × g_2|,  cosθ = ĝ_1·ĝ_2,  sinθ = J/(p_1 p_2),  γ = θ⁰ − θ, θ⁰ = π/2
 *
 * Crimp truss: A_k = A_k⁰ + ΔA_k, L_k = √(p_k² + A_k²), β_k = atan2(A_k, p_k),
 * interference I = −ΔA_1 − ΔA_2. Locking spar: s_k = J/p_k, d_k = √(s_k² + A_k²).
 *
 * Laws:   T_k = k_k (L_k − L_k⁰)           M_bk = k_bk (β_k − β_k⁰)
 *         F_I = K_I (exp(a I) − 1)          F_Lk = K_d (d_k⁰ − d_k)^c, d_k < d_k⁰
 *         M_s = K_s (γ − γᶠ),  dγᶠ/dt = γ̇₀ sign(M_s) |M_s/M₀|^n
 *
 * Stored energy per cell (one truss pair and one bending pair per yarn):
 *
 *   W_cell = Σ_k [k_k (L_k − L_k⁰)² + k_bk (β_k − β_k⁰)²]
 *          + (K_I/a)(exp(a I) − 1) − K_I I
 *          + 2 Σ_k K_d (d_k⁰ − d_k)^(c+1)/(c+1)
 *          + ½ K_s (γ − γᶠ)²,                 W = W_cell / (4 p1⁰ p2⁰)
 *
 * Amplitude residual (eq. 2–3, 9):  R_k = (F_I − F_k^N)/(4 p1⁰ p2⁰) = −∂W/∂ΔA_k,
 *   F_k^N = 2 T_k sinβ_k − 2 F_Lk sinα_k [1 + λ p_l|cosθ|cosβ_k/L_k] + 2 M_bk cosβ_k/L_k
 * (λ = 0 by default keeps R = −∂W/∂ΔA exactly; λ = 1 is the paper's literal eq. 3.)
 *
 * Stress: P = (1/(4 p1⁰ p2⁰)) Σ_k Q_k ⊗ G_k with Q_k = ∂W_cell/∂g_k. Every term
 * of Q_k lies in the plane of ĝ_1, ĝ_2, so Q_k = q_k1 ĝ_1 + q_k2 ĝ_2 with
 *
 *   yarn and bending   2 (T_k cosβ_k − M_bk sinβ_k/L_k)            on ĝ_k
 *   shear couple       M_s/(p_k sinθ) (ĝ_l − cosθ ĝ_k)
 *   own spar (s_k)     −2 F_Lk cosα_k · p_l cosθ/(p_k sinθ) (cosθ ĝ_k − ĝ_l)
 *   other spar (s_l)   −2 F_Ll cosα_l · (ĝ_k − cosθ ĝ_l)/sinθ
 *
 * using ∂J/∂g_k = p_l (ĝ_k − cosθ ĝ_l)/sinθ. The compaction law is continued
 * past exp(30) by a cubic in the exponent (same value, slope and curvature)
 * so that the energy stays finite and consistent when compaction is extreme.
 */
#include "wovenff/cell.h"
#include "wovenff/material.h"
#include "cell_laws.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

/* glibc's libmvec has vector versions of atan and exp; declaring them SIMD-
 * callable lets gcc vectorise the blocked kernel's loop across its lanes
 * (glibc declares them so only under -ffast-math, which we do not use). */
extern double atan(double) __attribute__((__simd__("notinbranch")));
extern double exp(double) __attribute__((__simd__("notinbranch")));

#define FAMILIES 2

typedef struct king_params {
    double pitch0[FAMILIES];             /* p_k⁰, quarter wavelength, m */
    double amplitude0[FAMILIES];         /* A_k⁰, crimp amplitude, m */
    double yarn_stiffness[FAMILIES];     /* k_k, N/m */
    double bending_stiffness[FAMILIES];  /* k_bk, N·m/rad */
    double compaction_force;             /* K_I, N */
    double compaction_rate;              /* a, 1/m */
    double locking_stiffness;            /* K_d, N/m^c */
    double locking_exponent;             /* c, - */
    double shear_stiffness;              /* K_s, N·m/rad */
    double flow_moment;                  /* M₀, N·m */
    double flow_rate;                    /* γ̇₀, 1/s */
    double flow_exponent;                /* n, - */
    double lever;                        /* λ, 0 or 1 */
    double tension_only;                 /* 1: yarns carry no compression */
    /* derived from the reference state */
    double length0[FAMILIES];            /* L_k⁰, m */
    double crimp_angle0[FAMILIES];       /* β_k⁰, rad */
    double spar_length0[FAMILIES];       /* d_k⁰, m */
    double cell_area;                    /* 4 p1⁰ p2⁰, m² */
} king_params;

_Static_assert(sizeof(king_params) <= sizeof(((wff_material *)0)->params),
               "king_params must fit in wff_material.params");

/* Everything one evaluation computes, kept for evaluate() and energy_split(). */
typedef struct king_point {
    double gh[FAMILIES][3];     /* ĝ_k */
    double p[FAMILIES];         /* p_k */
    double cos_t, sin_t;        /* cosθ, sinθ */
    double gamma;               /* γ, rad */
    double amplitude[FAMILIES]; /* A_k */
    double length[FAMILIES];    /* L_k */
    double crimp[FAMILIES];     /* β_k */
    double tension[FAMILIES];   /* T_k */
    double moment[FAMILIES];    /* M_bk */
    double interference;        /* I */
    double compaction;          /* F_I */
    double spar[FAMILIES];      /* s_k */
    double spar_length[FAMILIES]; /* d_k */
    double locking[FAMILIES];   /* F_Lk */
    double energy_yarn, energy_bending, energy_compaction, energy_locking;
} king_point;

static const char *const king_diag_names[] = {"T1", "T2", "beta1", "beta2",
                                              "F_I", "F_L1", "F_L2", "M_s"};
static const char *const king_diag_units[] = {"N", "N", "rad", "rad", "N", "N", "N", "N*m"};
enum { DIAG_T1, DIAG_T2, DIAG_BETA1, DIAG_BETA2, DIAG_FI, DIAG_FL1, DIAG_FL2, DIAG_MS,
       DIAG_COUNT };
static const char *const king_mech_names[] = {"yarn_stretch", "yarn_bending", "compaction",
                                              "locking", "shear"};
enum { MECH_YARN, MECH_BENDING, MECH_COMPACTION, MECH_LOCKING, MECH_SHEAR, MECH_COUNT };

/* Kinematics, laws and energies (all but shear, which needs the flow update). */
static int king_point_eval(const king_params *k, const double F[6], const double dA[2],
                           king_point *pt)
{
    double area; /* J */
    if (wff_yarn_kinematics(k->pitch0, F, pt->gh, pt->p, &area, &pt->cos_t, &pt->sin_t) !=
        WFF_POINT_OK)
        return WFF_POINT_DEGENERATE;
    pt->gamma = M_PI_2 - atan2(pt->sin_t, pt->cos_t);

    pt->interference = -dA[0] - dA[1];
    double x = k->compaction_rate * pt->interference, primitive, slope;
    double e = wff_compaction_exp(x, &primitive, &slope);
    pt->compaction = k->compaction_force * (e - 1);
    pt->energy_compaction = k->compaction_force / k->compaction_rate * (primitive - 1) -
                            k->compaction_force * pt->interference;

    pt->energy_yarn = pt->energy_bending = pt->energy_locking = 0;
    for (int f = 0; f < FAMILIES; f++) {
        double A = k->amplitude0[f] + dA[f];
        pt->amplitude[f] = A;
        pt->length[f] = sqrt(pt->p[f] * pt->p[f] + A * A);
        pt->crimp[f] = atan2(A, pt->p[f]);
        double stretch = pt->length[f] - k->length0[f];
        if (k->tension_only != 0 && stretch < 0)
            stretch = 0;
        pt->tension[f] = k->yarn_stiffness[f] * stretch;
        pt->energy_yarn += k->yarn_stiffness[f] * stretch * stretch;
        double bend = pt->crimp[f] - k->crimp_angle0[f];
        pt->moment[f] = k->bending_stiffness[f] * bend;
        pt->energy_bending += k->bending_stiffness[f] * bend * bend;

        pt->spar[f] = area / pt->p[f];
        pt->spar_length[f] = sqrt(pt->spar[f] * pt->spar[f] + A * A);
        double gap = k->spar_length0[f] - pt->spar_length[f];
        if (gap > 0) {
            double power = wff_locking_power(gap, k->locking_exponent);
            pt->locking[f] = k->locking_stiffness * power;
            pt->energy_locking +=
                2 * k->locking_stiffness * power * gap / (k->locking_exponent + 1);
        } else {
            pt->locking[f] = 0;
        }
    }
    return WFF_POINT_OK;
}

static void fill_nan(wff_point_result *out)
{
    double nan = NAN;
    for (int i = 0; i < 6; i++)
        out->stress[i] = nan;
    out->residual[0] = out->residual[1] = nan;
    out->energy = out->dissipated = out->gamma_f = nan;
    for (int i = 0; i < DIAG_COUNT; i++)
        out->diag[i] = nan;
}

static int king_evaluate(const void *params, const double F[6], const double dA[2],
                         double gamma_f, double dt, wff_point_result *out)
{
    const king_params *k = params;
    king_point pt;
    if (king_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        fill_nan(out);
        return WFF_POINT_DEGENERATE;
    }
    double gamma_f_new = wff_shear_flow_update(k->shear_stiffness, k->flow_moment, k->flow_rate,
                         k->flow_exponent, pt.gamma, gamma_f, dt);
    double shear_moment = k->shear_stiffness * (pt.gamma - gamma_f_new); /* M_s */
    double shear_elastic = pt.gamma - gamma_f_new;                        /* γᵉ */

    /* q[f][m]: component of Q_f along ĝ_m */
    double q[FAMILIES][FAMILIES] = {{0, 0}, {0, 0}};
    double cs = pt.cos_t, sn = pt.sin_t;
    for (int f = 0; f < FAMILIES; f++) {
        int l = 1 - f;
        double L = pt.length[f];
        double sin_b = pt.amplitude[f] / L, cos_b = pt.p[f] / L;
        q[f][f] += 2 * (pt.tension[f] * cos_b - pt.moment[f] * sin_b / L);
        double couple = shear_moment / (pt.p[f] * sn);
        q[f][l] += couple;
        q[f][f] -= couple * cs;
        /* own spar s_f = J/p_f */
        double own = 2 * pt.locking[f] * (pt.spar[f] / pt.spar_length[f]);
        double c_own = own * pt.p[l] * cs / (pt.p[f] * sn);
        q[f][f] -= c_own * cs;
        q[f][l] += c_own;
        /* the other spar s_l = J/p_l */
        double other = 2 * pt.locking[l] * (pt.spar[l] / pt.spar_length[l]) / sn;
        q[f][f] -= other;
        q[f][l] += other * cs;

        double sin_a = pt.amplitude[f] / pt.spar_length[f];
        double lever = 1 + k->lever * pt.p[l] * fabs(cs) * cos_b / L;
        double normal = 2 * pt.tension[f] * sin_b - 2 * pt.locking[f] * sin_a * lever +
                        2 * pt.moment[f] * cos_b / L; /* F_k^N, eq. 3 */
        out->residual[f] = (pt.compaction - normal) / k->cell_area;
    }
    for (int i = 0; i < 3; i++)
        for (int f = 0; f < FAMILIES; f++)
            out->stress[2 * i + f] = k->pitch0[f] / k->cell_area *
                                     (q[f][0] * pt.gh[0][i] + q[f][1] * pt.gh[1][i]);

    double energy_shear = 0.5 * k->shear_stiffness * shear_elastic * shear_elastic;
    out->energy = (pt.energy_yarn + pt.energy_bending + pt.energy_compaction +
                   pt.energy_locking + energy_shear) / k->cell_area;
    out->gamma_f = gamma_f_new;
    out->dissipated = shear_moment * (gamma_f_new - gamma_f) / k->cell_area;
    out->diag[DIAG_T1] = pt.tension[0];
    out->diag[DIAG_T2] = pt.tension[1];
    out->diag[DIAG_BETA1] = pt.crimp[0];
    out->diag[DIAG_BETA2] = pt.crimp[1];
    out->diag[DIAG_FI] = pt.compaction;
    out->diag[DIAG_FL1] = pt.locking[0];
    out->diag[DIAG_FL2] = pt.locking[1];
    out->diag[DIAG_MS] = shear_moment;
    return WFF_POINT_OK;
}

static void king_energy_split(const void *params, const double F[6], const double dA[2],
                              double gamma_f, double *mech)
{
    const king_params *k = params;
    king_point pt;
    if (king_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        for (int i = 0; i < MECH_COUNT; i++)
            mech[i] = NAN;
        return;
    }
    double shear_elastic = pt.gamma - gamma_f;
    mech[MECH_YARN] = pt.energy_yarn / k->cell_area;
    mech[MECH_BENDING] = pt.energy_bending / k->cell_area;
    mech[MECH_COMPACTION] = pt.energy_compaction / k->cell_area;
    mech[MECH_LOCKING] = pt.energy_locking / k->cell_area;
    mech[MECH_SHEAR] = 0.5 * k->shear_stiffness * shear_elastic * shear_elastic / k->cell_area;
}

/* Stable-step bounds. Membrane: the straight-yarn stiffness per unit width
 * k_k p_k⁰/(2 p_l⁰) (crimp only lowers it) plus geometric, shear and locking
 * terms; speed = sqrt(S/ρ_A). Amplitudes: Gershgorin bound of the 2×2
 * Hessian ∂²W_cell/∂A_k∂A_m over the lumped mass ρ_A/6 per unit area. */
static void king_wave_speeds(const void *params, double areal_density, const double F[6],
                             const double dA[2], double *membrane_speed,
                             double *amplitude_omega)
{
    const king_params *k = params;
    king_point pt;
    if (king_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        *membrane_speed = *amplitude_omega = INFINITY;
        return;
    }
    double primitive, slope;
    wff_compaction_exp(k->compaction_rate * pt.interference, &primitive, &slope);
    double compaction_stiffness = k->compaction_force * k->compaction_rate * slope; /* ∂F_I/∂I */
    double sn = fmax(pt.sin_t, 0.05);
    double shear = k->shear_stiffness / (sn * sn); /* torsional, per rad², N·m */
    double membrane = 0, amplitude = 0;
    for (int f = 0; f < FAMILIES; f++) {
        int l = 1 - f;
        double L = pt.length[f];
        double sin_b = pt.amplitude[f] / L, cos_b = pt.p[f] / L;
        /* a slack yarn (tension_only) keeps its stiffness in the bound: it can pull
         * tight within one step, and a step sized for slack yarns is ~20x too long */
        double lock_stiff = 0; /* ∂F_L/∂d */
        double gap = k->spar_length0[f] - pt.spar_length[f];
        if (gap > 0)
            lock_stiff = k->locking_stiffness * k->locking_exponent *
                         wff_locking_power(gap, k->locking_exponent - 1);
        double axial = k->yarn_stiffness[f] + fabs(pt.tension[f]) / L +
                       k->bending_stiffness[f] / (L * L);
        /* stiffness per unit width when family f is stretched: two trusses per
         * cell (2 k p_f⁰² / 4p1⁰p2⁰ = k p_f⁰/2p_l⁰), the spars across, shear */
        double s_f = (2 * axial * k->pitch0[f] * k->pitch0[f] +
                      4 * lock_stiff * k->pitch0[l] * k->pitch0[l] + shear) / k->cell_area;
        membrane = fmax(membrane, s_f);
        double a_diag = 2 * (k->yarn_stiffness[f] * sin_b * sin_b +
                             fabs(pt.tension[f]) * cos_b * cos_b / L) +
                        2 * k->bending_stiffness[f] * cos_b * cos_b / (L * L) +
                        4 * fabs(pt.moment[f]) / (L * L) + compaction_stiffness +
                        2 * (lock_stiff + pt.locking[f] / pt.spar_length[f]) * (1 + k->lever);
        amplitude = fmax(amplitude, a_diag + compaction_stiffness);
    }
    *membrane_speed = sqrt(membrane / areal_density);
    *amplitude_omega = sqrt(amplitude / k->cell_area / (areal_density / 6));
}

/* Fast path (MODEL.md notes in docs/model.md): n points sharing one F. The
 * F-dependent kinematics (g_k, p_k, θ, J, the spars' in-plane lengths) are
 * computed once; cheaper exact forms replace the angles: γ = atan(cosθ/sinθ)
 * for sinθ > 0, β − β⁰ = atan((A p⁰ − A⁰ p)/(p p⁰ + A A⁰)). The stress is
 * assembled once from the weighted sum of the points' in-plane coefficients.
 * Same model as king_evaluate, term by term; tests compare the two. */
static int king_evaluate_shared(const void *params, const double F[6], int n_points,
                                const double *dA, const double *weight, double *gamma_f,
                                double dt, double stress_sum[6], double *residual,
                                double *energy, double *dissipated, int *bad_point)
{
    const king_params *k = params;
    double gh[FAMILIES][3], p[FAMILIES], g[FAMILIES][3];
    *bad_point = 0;
    for (int f = 0; f < FAMILIES; f++) {
        for (int i = 0; i < 3; i++)
            g[f][i] = k->pitch0[f] * F[2 * i + f];
        p[f] = sqrt(g[f][0] * g[f][0] + g[f][1] * g[f][1] + g[f][2] * g[f][2]);
        if (!(p[f] > 0))
            return WFF_POINT_DEGENERATE;
        double inv = 1 / p[f];
        for (int i = 0; i < 3; i++)
            gh[f][i] = g[f][i] * inv;
    }
    double n0 = g[0][1] * g[1][2] - g[0][2] * g[1][1];
    double n1 = g[0][2] * g[1][0] - g[0][0] * g[1][2];
    double n2 = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    double area = sqrt(n0 * n0 + n1 * n1 + n2 * n2); /* J */
    double cs = gh[0][0] * gh[1][0] + gh[0][1] * gh[1][1] + gh[0][2] * gh[1][2];
    double sn = area / (p[0] * p[1]);
    if (!(sn > 0))
        return WFF_POINT_DEGENERATE;
    double gamma = atan(cs / sn);
    double spar[FAMILIES] = {area / p[0], area / p[1]};
    double couple_arm[FAMILIES] = {1 / (p[0] * sn), 1 / (p[1] * sn)};
    double inv_cell = 1 / k->cell_area;

    double q[FAMILIES][FAMILIES] = {{0, 0}, {0, 0}};
    double energy_sum = 0, dissipated_sum = 0;
    for (int pt = 0; pt < n_points; pt++) {
        const double *a = dA + 2 * pt;
        const double w = weight[pt];
        double x = k->compaction_rate * (-a[0] - a[1]), primitive, slope;
        double e = wff_compaction_exp(x, &primitive, &slope);
        double compaction = k->compaction_force * (e - 1);
        double W = k->compaction_force / k->compaction_rate * (primitive - 1) +
                   k->compaction_force * (a[0] + a[1]);
        double locking[FAMILIES], cos_a[FAMILIES], yarn_q[FAMILIES];
        for (int f = 0; f < FAMILIES; f++) {
            int l = 1 - f;
            double A = k->amplitude0[f] + a[f];
            double L = sqrt(p[f] * p[f] + A * A), inv_L = 1 / L;
            double sin_b = A * inv_L, cos_b = p[f] * inv_L;
            double stretch = L - k->length0[f];
            if (k->tension_only != 0 && stretch < 0)
                stretch = 0;
            double tension = k->yarn_stiffness[f] * stretch;
            double bend = atan((A * k->pitch0[f] - k->amplitude0[f] * p[f]) /
                               (p[f] * k->pitch0[f] + A * k->amplitude0[f]));
            double moment = k->bending_stiffness[f] * bend;
            W += k->yarn_stiffness[f] * stretch * stretch + k->bending_stiffness[f] * bend * bend;
            double d = sqrt(spar[f] * spar[f] + A * A), inv_d = 1 / d;
            double gap = k->spar_length0[f] - d;
            locking[f] = 0;
            if (gap > 0) {
                double power = wff_locking_power(gap, k->locking_exponent);
                locking[f] = k->locking_stiffness * power;
                W += 2 * k->locking_stiffness * power * gap / (k->locking_exponent + 1);
            }
            cos_a[f] = spar[f] * inv_d;
            double lever = 1 + k->lever * p[l] * fabs(cs) * cos_b * inv_L;
            double normal = 2 * tension * sin_b - 2 * locking[f] * (A * inv_d) * lever +
                            2 * moment * cos_b * inv_L;
            residual[2 * pt + f] = (compaction - normal) * inv_cell;
            yarn_q[f] = 2 * (tension * cos_b - moment * sin_b * inv_L);
        }
        double gf_new = wff_shear_flow_update(k->shear_stiffness, k->flow_moment, k->flow_rate,
                        k->flow_exponent, gamma, gamma_f[pt], dt);
        double shear_moment = k->shear_stiffness * (gamma - gf_new);
        W += 0.5 * k->shear_stiffness * (gamma - gf_new) * (gamma - gf_new);
        dissipated_sum += w * shear_moment * (gf_new - gamma_f[pt]);
        gamma_f[pt] = gf_new;
        for (int f = 0; f < FAMILIES; f++) {
            int l = 1 - f;
            double couple = shear_moment * couple_arm[f];
            double own = 2 * locking[f] * cos_a[f] * p[l] * cs * couple_arm[f];
            double other = 2 * locking[l] * cos_a[l] / sn;
            q[f][f] += w * (yarn_q[f] - couple * cs - own * cs - other);
            q[f][l] += w * (couple + own + other * cs);
        }
        energy_sum += w * W;
    }
    for (int i = 0; i < 3; i++)
        for (int f = 0; f < FAMILIES; f++)
            stress_sum[2 * i + f] += k->pitch0[f] * inv_cell *
                                     (q[f][0] * gh[0][i] + q[f][1] * gh[1][i]);
    *energy += energy_sum * inv_cell;
    *dissipated += dissipated_sum * inv_cell;
    return WFF_POINT_OK;
}

/* Blocked fast path: WFF_BLOCK triangles at once, one loop over the lanes
 * with the whole model inside, so gcc vectorises it (libmvec's atan and exp,
 * sqrt and divisions in vector registers). Same formulas as
 * king_evaluate_shared with equal weights 1/3; handles the common case of a
 * quadratic locking law (c = 2) and linear shear flow (n = 1), and hands any
 * other parameter set back to the general path. */
static int king_evaluate_tri_block(const void *params, double dt, wff_tri_block *blk)
{
    const king_params *k = params;
    if (k->locking_exponent != 2 || k->flow_exponent != 1)
        return -1;
    const double p01 = k->pitch0[0], p02 = k->pitch0[1];
    const double A01 = k->amplitude0[0], A02 = k->amplitude0[1];
    const double k1 = k->yarn_stiffness[0], k2 = k->yarn_stiffness[1];
    const double kb1 = k->bending_stiffness[0], kb2 = k->bending_stiffness[1];
    const double L01 = k->length0[0], L02 = k->length0[1];
    const double d01 = k->spar_length0[0], d02 = k->spar_length0[1];
    const double KI = k->compaction_force, a = k->compaction_rate, KI_a = KI / a;
    const double Kd = k->locking_stiffness, Ks = k->shear_stiffness, lam = k->lever;
    const double stretch_floor = k->tension_only != 0 ? 0.0 : -INFINITY; /* tension_only */
    const double r = (dt > 0 && k->flow_rate != 0 && Ks != 0)
                         ? dt * k->flow_rate * Ks / k->flow_moment : 0; /* n = 1 */
    const double inv_r1 = 1 / (1 + r);
    const double inv_cell = 1 / k->cell_area, third = 1.0 / 3.0;
    const double xmax = WFF_COMPACTION_EXPONENT_MAX;

#pragma omp simd
    for (int b = 0; b < WFF_BLOCK; b++) {
        /* kinematics, once per element */
        double g0x = p01 * blk->F[0][b], g0y = p01 * blk->F[2][b], g0z = p01 * blk->F[4][b];
        double g1x = p02 * blk->F[1][b], g1y = p02 * blk->F[3][b], g1z = p02 * blk->F[5][b];
        double pa = sqrt(g0x * g0x + g0y * g0y + g0z * g0z);
        double pb = sqrt(g1x * g1x + g1y * g1y + g1z * g1z);
        double nx = g0y * g1z - g0z * g1y, ny = g0z * g1x - g0x * g1z, nz = g0x * g1y - g0y * g1x;
        double J = sqrt(nx * nx + ny * ny + nz * nz);
        double ia = 1 / pa, ib = 1 / pb;
        double cs = (g0x * g1x + g0y * g1y + g0z * g1z) * ia * ib;
        double sn = J * ia * ib;
        blk->degenerate[b] = !(pa > 0) | !(pb > 0) | !(sn > 0);
        double isn = 1 / sn;
        double gamma = atan(cs * isn);
        double sa_len = J * ia, sb_len = J * ib;   /* spars s_1, s_2 */
        double arm1 = ia * isn, arm2 = ib * isn;   /* 1/(p_k sinθ) */
        double q11 = 0, q12 = 0, q21 = 0, q22 = 0, Wsum = 0, Dsum = 0;
#pragma GCC unroll 3
        for (int q = 0; q < 3; q++) {
            double a1 = blk->dA[q][0][b], a2 = blk->dA[q][1][b];
            /* compaction, continued past exp(xmax) as in wff_compaction_exp */
            double x = a * (-a1 - a2);
            double u = x > xmax ? x - xmax : 0.0; /* (fmax would not vectorise) */
            double ex = exp(x - u);
            double poly2 = 1 + u + 0.5 * u * u, poly3 = poly2 + u * u * u / 6;
            double comp = KI * (ex * poly2 - 1);
            double W = KI_a * (ex * poly3 - 1) + KI * (a1 + a2);
            /* warp (1) */
            double A1 = A01 + a1, L1 = sqrt(pa * pa + A1 * A1), iL1 = 1 / L1;
            double sb1 = A1 * iL1, cb1 = pa * iL1;
            double st1 = L1 - L01;
            st1 = st1 > stretch_floor ? st1 : stretch_floor;
            double T1 = k1 * st1;
            double bend1 = atan((A1 * p01 - A01 * pa) / (pa * p01 + A1 * A01));
            double M1 = kb1 * bend1;
            double d1 = sqrt(sa_len * sa_len + A1 * A1), id1 = 1 / d1;
            double gap1 = d01 > d1 ? d01 - d1 : 0.0, FL1 = Kd * gap1 * gap1;
            double ca1 = sa_len * id1;
            /* weft (2) */
            double A2 = A02 + a2, L2 = sqrt(pb * pb + A2 * A2), iL2 = 1 / L2;
            double sb2 = A2 * iL2, cb2 = pb * iL2;
            double st2 = L2 - L02;
            st2 = st2 > stretch_floor ? st2 : stretch_floor;
            double T2 = k2 * st2;
            double bend2 = atan((A2 * p02 - A02 * pb) / (pb * p02 + A2 * A02));
            double M2 = kb2 * bend2;
            double d2 = sqrt(sb_len * sb_len + A2 * A2), id2 = 1 / d2;
            double gap2 = d02 > d2 ? d02 - d2 : 0.0, FL2 = Kd * gap2 * gap2;
            double ca2 = sb_len * id2;
            W += k1 * st1 * st1 + kb1 * bend1 * bend1 + k2 * st2 * st2 + kb2 * bend2 * bend2 +
                 2 * Kd * (gap1 * gap1 * gap1 + gap2 * gap2 * gap2) / 3;
            double acs = fabs(cs);
            double FN1 = 2 * T1 * sb1 - 2 * FL1 * (A1 * id1) * (1 + lam * pb * acs * cb1 * iL1) +
                         2 * M1 * cb1 * iL1;
            double FN2 = 2 * T2 * sb2 - 2 * FL2 * (A2 * id2) * (1 + lam * pa * acs * cb2 * iL2) +
                         2 * M2 * cb2 * iL2;
            blk->residual[q][0][b] = (comp - FN1) * inv_cell;
            blk->residual[q][1][b] = (comp - FN2) * inv_cell;
            /* shear, backward Euler with n = 1 */
            double gf = blk->gamma_f[q][b];
            double gfn = (gf + r * gamma) * inv_r1;
            double Ms = Ks * (gamma - gfn);
            W += 0.5 * Ks * (gamma - gfn) * (gamma - gfn);
            Dsum += Ms * (gfn - gf);
            blk->gamma_f[q][b] = gfn;
            /* in-plane coefficients of Q_1 and Q_2 on ĝ_1, ĝ_2 */
            double c1 = Ms * arm1, c2 = Ms * arm2;
            double own1 = 2 * FL1 * ca1 * pb * cs * arm1, own2 = 2 * FL2 * ca2 * pa * cs * arm2;
            double oth1 = 2 * FL2 * ca2 * isn, oth2 = 2 * FL1 * ca1 * isn;
            q11 += 2 * (T1 * cb1 - M1 * sb1 * iL1) - c1 * cs - own1 * cs - oth1;
            q12 += c1 + own1 + oth1 * cs;
            q22 += 2 * (T2 * cb2 - M2 * sb2 * iL2) - c2 * cs - own2 * cs - oth2;
            q21 += c2 + own2 + oth2 * cs;
            Wsum += W;
        }
        /* P = (1/cell) Σ_k p_k⁰ Q_k ⊗ E_k, mean over the three points */
        double s1 = p01 * inv_cell * third, s2 = p02 * inv_cell * third;
        double h0x = g0x * ia, h0y = g0y * ia, h0z = g0z * ia;
        double h1x = g1x * ib, h1y = g1y * ib, h1z = g1z * ib;
        blk->stress[0][b] = s1 * (q11 * h0x + q12 * h1x);
        blk->stress[1][b] = s2 * (q21 * h0x + q22 * h1x);
        blk->stress[2][b] = s1 * (q11 * h0y + q12 * h1y);
        blk->stress[3][b] = s2 * (q21 * h0y + q22 * h1y);
        blk->stress[4][b] = s1 * (q11 * h0z + q12 * h1z);
        blk->stress[5][b] = s2 * (q21 * h0z + q22 * h1z);
        blk->energy[b] = Wsum * third * inv_cell;
        blk->dissipated[b] = Dsum * third * inv_cell;
    }
    return 0;
}

static int king_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    king_params *k = (king_params *)mat->params;
    memset(k, 0, sizeof *k);
    struct { const char *key; double *value; } required[] = {
        {"p0_1", &k->pitch0[0]}, {"p0_2", &k->pitch0[1]},
        {"A0_1", &k->amplitude0[0]}, {"A0_2", &k->amplitude0[1]},
        {"k_1", &k->yarn_stiffness[0]}, {"k_2", &k->yarn_stiffness[1]},
        {"kb_1", &k->bending_stiffness[0]}, {"kb_2", &k->bending_stiffness[1]},
        {"K_I", &k->compaction_force}, {"a", &k->compaction_rate},
        {"K_d", &k->locking_stiffness}, {"c", &k->locking_exponent},
        {"K_s", &k->shear_stiffness}, {"M_0", &k->flow_moment},
        {"gammadot_0", &k->flow_rate},
    };
    for (size_t i = 0; i < sizeof required / sizeof required[0]; i++)
        if (wff_kv_number(kv, required[i].key, required[i].value, err))
            return -1;
    if (wff_kv_number_or(kv, "n", 1.0, &k->flow_exponent, err) ||
        wff_kv_number_or(kv, "lever", 0.0, &k->lever, err) ||
        wff_kv_number_or(kv, "tension_only", 0.0, &k->tension_only, err))
        return -1;

    const char *positive[] = {"p0_1", "p0_2", "A0_1", "A0_2", "k_1", "k_2",
                              "K_I", "a", "M_0"};
    double *positive_v[] = {&k->pitch0[0], &k->pitch0[1], &k->amplitude0[0],
                            &k->amplitude0[1], &k->yarn_stiffness[0], &k->yarn_stiffness[1],
                            &k->compaction_force, &k->compaction_rate, &k->flow_moment};
    for (size_t i = 0; i < sizeof positive / sizeof positive[0]; i++)
        if (!(*positive_v[i] > 0))
            return wff_kv_reject(kv, positive[i], err, "must be > 0");
    const char *nonneg[] = {"kb_1", "kb_2", "K_d", "K_s", "gammadot_0"};
    double *nonneg_v[] = {&k->bending_stiffness[0], &k->bending_stiffness[1],
                          &k->locking_stiffness, &k->shear_stiffness, &k->flow_rate};
    for (size_t i = 0; i < sizeof nonneg / sizeof nonneg[0]; i++)
        if (!(*nonneg_v[i] >= 0))
            return wff_kv_reject(kv, nonneg[i], err, "must be >= 0");
    if (!(k->locking_exponent >= 1))
        return wff_kv_reject(kv, "c", err, "locking exponent must be >= 1 "
                             "(below 1 the locking stiffness is infinite at contact)");
    if (!(k->flow_exponent >= 1))
        return wff_kv_reject(kv, "n", err, "shear-flow exponent must be >= 1 "
                             "(below 1 the flow rate is singular at rest)");
    if (k->lever != 0 && k->lever != 1)
        return wff_kv_reject(kv, "lever", err, "must be 0 (energy-consistent) or 1 "
                             "(the paper's literal eq. 3)");
    if (k->tension_only != 0 && k->tension_only != 1)
        return wff_kv_reject(kv, "tension_only", err, "must be 0 or 1");
    for (int f = 0; f < FAMILIES; f++)
        if (!(k->amplitude0[f] < k->pitch0[f]))
            return wff_kv_reject(kv, f == 0 ? "A0_1" : "A0_2", err,
                                 "crimp amplitude must be smaller than the quarter "
                                 "wavelength p0 (crimp angle above 45 degrees)");

    for (int f = 0; f < FAMILIES; f++) {
        int l = 1 - f;
        k->length0[f] = sqrt(k->pitch0[f] * k->pitch0[f] + k->amplitude0[f] * k->amplitude0[f]);
        k->crimp_angle0[f] = atan2(k->amplitude0[f], k->pitch0[f]);
        double s0 = k->pitch0[l]; /* J⁰/p_f⁰ at θ⁰ = 90° */
        k->spar_length0[f] = sqrt(s0 * s0 + k->amplitude0[f] * k->amplitude0[f]);
        mat->yarn_spacing[f] = 2 * k->pitch0[l];
    }
    k->cell_area = 4 * k->pitch0[0] * k->pitch0[1];
    return 0;
}

static void king_reference_geometry(const void *params, double pitch0[2], double amplitude0[2])
{
    const king_params *k = params;
    for (int f = 0; f < FAMILIES; f++) {
        pitch0[f] = k->pitch0[f];
        amplitude0[f] = k->amplitude0[f];
    }
}

static const wff_cell_type king_plain = {
    .name = "king_plain",
    .summary = "King et al. (2005) plain weave: crimped yarn trusses, bending, compaction, "
               "locking spars, visco-elastic shear",
    .n_amplitudes = 2,
    .n_diag = DIAG_COUNT,
    .diag_names = king_diag_names,
    .diag_units = king_diag_units,
    .yarn_tension_diag = {DIAG_T1, DIAG_T2},
    .n_mech = MECH_COUNT,
    .mech_names = king_mech_names,
    .parse = king_parse,
    .evaluate = king_evaluate,
    .wave_speeds = king_wave_speeds,
    .energy_split = king_energy_split,
    .evaluate_shared = king_evaluate_shared,
    .evaluate_tri_block = king_evaluate_tri_block,
    .reference_geometry = king_reference_geometry,
};
WFF_REGISTER_CELL(king_plain);

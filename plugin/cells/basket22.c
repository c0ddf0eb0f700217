/* A 2/2 basket-weave unit cell in the truss-and-spring spirit of the King
 * plain weave (king_plain.c): see docs/basket_cell.md.
 *
 * Weave: yarns go in pairs; a pair of warp yarns passes over a pair of weft
 * yarns, then under the next pair. Family k = 1 (warp) along E1, k = 2 (weft)
 * along E2; l is the other family. p_k⁰ is half the spacing of the yarns that
 * cross yarn k (as in king_plain), so yarn k meets a crossing yarn every
 * 2 p_k. Along yarn k one repeat, 8 p_k long, is
 *
 *   float at +A_k over two crossing yarns (horizontal 2 p_k), a straight
 *   descent to −A_k (horizontal 2 p_k), float at −A_k under two crossing
 *   yarns, a straight ascent back to +A_k.
 *
 * The cell is one 2×2 block, 4 p1⁰ × 4 p2⁰ (area 16 p1⁰ p2⁰): two warp and two
 * weft half-repeats (one float and one transition each) and four crossovers.
 * All four crossovers are alike (a float on a float); one side of each yarn
 * faces its pair partner, the other the next pair.
 *
 * Kinematics, as king_plain:
 *
 *   g_k = F G_k,  G_k = p_k⁰ E_k,  p_k = |g_k|,  ĝ_k = g_k / p_k
 *   J = |g_1 × g_2|,  cosθ = ĝ_1·ĝ_2,  sinθ = J/(p_1 p_2),  γ = π/2 − θ
 *
 * Yarn path: A_k = A_k⁰ + ΔA_k,  L_k = √(p_k² + A_k²),  β_k = atan2(A_k, p_k)
 * (the transition, 2 L_k long, rises 2 A_k over 2 p_k), half-repeat length
 * ℓ_k = 2 p_k + 2 L_k; interference I = −ΔA_1 − ΔA_2 at every crossover.
 * Spars on yarn k (in-plane half-gap s_k = J/p_k to each neighbour):
 *   towards the next pair, where yarn l passes the mid-plane:  d_k = √(s_k² + A_k²)
 *   towards the pair partner, where yarn l floats at ∓A_l:      e_k = √(s_k² + (A_1 + A_2)²)
 *
 * Laws:   T_k = (EA_k/ℓ_k⁰)(ℓ_k − ℓ_k⁰)      M_bk = k_bk (β_k − β_k⁰)
 *         F_I = K_I (exp(a I) − 1)             F_Lk = K_d (d_k⁰ − d_k)^c, d_k < d_k⁰
 *         F_Pk = K_d (e_k⁰ − e_k)^c, e_k < e_k⁰
 *         M_s = K_s (γ − γᶠ),  dγᶠ/dt = γ̇₀ sign(M_s) |M_s/M₀|^n
 * T_k is uniform along the yarn (it slides freely over the crossovers).
 *
 * Stored energy per cell (two yarns per family, two bending springs per yarn
 * half-repeat, four crossovers each with a compaction spring, a shear spring
 * and, per family, one spar of each kind):
 *
 *   W_cell = Σ_k [(EA_k/ℓ_k⁰)(ℓ_k − ℓ_k⁰)² + 2 k_bk (β_k − β_k⁰)²]
 *          + 4 [(K_I/a)(exp(a I) − 1) − K_I I]
 *          + 4 Σ_k K_d [(d_k⁰ − d_k)₊^(c+1) + (e_k⁰ − e_k)₊^(c+1)]/(c+1)
 *          + 2 K_s (γ − γᶠ)²,                 W = W_cell / (16 p1⁰ p2⁰)
 *
 * Amplitude residual, per crossover (∂W_cell/∂A_k = 4 (F_k^N − F_I)):
 *   R_k = (F_I − F_k^N)/(4 p1⁰ p2⁰) = −∂W/∂ΔA_k,
 *   F_k^N = T_k sinβ_k + M_bk cosβ_k/L_k − F_Lk A_k/d_k − (F_P1/e_1 + F_P2/e_2)(A_1 + A_2)
 *
 * Stress: P = (1/(16 p1⁰ p2⁰)) Σ_k Q_k ⊗ G_k, Q_k = ∂W_cell/∂g_k = q_k1 ĝ_1 + q_k2 ĝ_2:
 *
 *   yarn and bending   4 (T_k (1 + cosβ_k) − M_bk sinβ_k/L_k)     on ĝ_k
 *   shear couple       4 M_s/(p_k sinθ) (ĝ_l − cosθ ĝ_k)
 *   own spars (s_k)    −N_k · p_l cosθ/(p_k sinθ) (cosθ ĝ_k − ĝ_l)
 *   other spars (s_l)  −N_l · (ĝ_k − cosθ ĝ_l)/sinθ
 *
 * with N_m = 4 (F_Lm s_m/d_m + F_Pm s_m/e_m), the spars' pull on s_m. The
 * compaction exponential is continued past exp(30) by a cubic in the exponent,
 * as in king_plain.
 */
#include "wovenff/cell.h"
#include "wovenff/material.h"
#include "cell_laws.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define FAMILIES 2

/* sinθ below which the stable-step bound stops growing: the shear term goes
 * as 1/sin²θ and would be infinite at parallel yarns. */
#define SHEAR_SINE_FLOOR 0.05

/* Counts per cell (one 2×2 block). */
#define CROSSOVERS 4.0      /* compaction springs, shear springs, spars per family and type */
#define YARNS_PER_FAMILY 2.0

typedef struct basket_params {
    double pitch0[FAMILIES];             /* p_k⁰, half the crossing yarns' spacing, m */
    double amplitude0[FAMILIES];         /* A_k⁰, float height above the mid-plane, m */
    double axial_rigidity[FAMILIES];     /* EA_k, N */
    double bending_stiffness[FAMILIES];  /* k_bk, N·m/rad, one spring per crossover per yarn */
    double compaction_force;             /* K_I, N */
    double compaction_rate;              /* a, 1/m */
    double locking_stiffness;            /* K_d, N/m^c */
    double locking_exponent;             /* c, - */
    double shear_stiffness;              /* K_s, N·m/rad, per crossover */
    double flow_moment;                  /* M₀, N·m */
    double flow_rate;                    /* γ̇₀, 1/s */
    double flow_exponent;                /* n, - */
    double tension_only;                 /* 1: yarns carry no compression */
    /* derived from the reference state */
    double path0[FAMILIES];              /* ℓ_k⁰ = 2 p_k⁰ + 2 L_k⁰, m */
    double yarn_stiffness[FAMILIES];     /* EA_k/ℓ_k⁰, N/m */
    double crimp_angle0[FAMILIES];       /* β_k⁰, rad */
    double spar_length0[FAMILIES];       /* d_k⁰, m */
    double pair_spar_length0[FAMILIES];  /* e_k⁰, m */
    double cell_area;                    /* 16 p1⁰ p2⁰, m² */
} basket_params;

_Static_assert(sizeof(basket_params) <= sizeof(((wff_material *)0)->params),
               "basket_params must fit in wff_material.params");

/* Everything one evaluation computes, kept for evaluate, energy_split and wave_speeds. */
typedef struct basket_point {
    double gh[FAMILIES][3];          /* ĝ_k */
    double p[FAMILIES];              /* p_k */
    double cos_t, sin_t;             /* cosθ, sinθ */
    double gamma;                    /* γ, rad */
    double amplitude[FAMILIES];      /* A_k */
    double length[FAMILIES];         /* L_k, half the transition */
    double path[FAMILIES];           /* ℓ_k */
    double crimp[FAMILIES];          /* β_k */
    double tension[FAMILIES];        /* T_k */
    double moment[FAMILIES];         /* M_bk */
    double interference;             /* I */
    double compaction;               /* F_I */
    double compaction_slope;         /* ∂F_I/∂I */
    double spar[FAMILIES];           /* s_k */
    double spar_length[FAMILIES];    /* d_k */
    double locking[FAMILIES];        /* F_Lk */
    double locking_slope[FAMILIES];  /* −∂F_Lk/∂d_k */
    double pair_length[FAMILIES];    /* e_k */
    double pair_locking[FAMILIES];   /* F_Pk */
    double pair_slope[FAMILIES];     /* −∂F_Pk/∂e_k */
    double energy_yarn, energy_bending, energy_compaction, energy_locking;
} basket_point;

static const char *const basket_diag_names[] = {"T1",   "T2",   "beta1", "beta2", "F_I",
                                                "F_L1", "F_L2", "F_P1",  "F_P2",  "M_s"};
static const char *const basket_diag_units[] = {"N", "N", "rad", "rad", "N",
                                                "N", "N", "N",   "N",   "N*m"};
enum { DIAG_T1, DIAG_T2, DIAG_BETA1, DIAG_BETA2, DIAG_FI, DIAG_FL1, DIAG_FL2, DIAG_FP1,
       DIAG_FP2, DIAG_MS, DIAG_COUNT };
_Static_assert(DIAG_COUNT <= WFF_DIAG_MAX, "basket_2x2 reports too many diagnostics");
static const char *const basket_mech_names[] = {"yarn_stretch", "yarn_bending", "compaction",
                                                "locking", "shear"};
enum { MECH_YARN, MECH_BENDING, MECH_COMPACTION, MECH_LOCKING, MECH_SHEAR, MECH_COUNT };

/* One spar of reference length length0 at length `length`: force (K_d gap^c
 * when shorter than length0, else 0), its stiffness −∂F/∂length, and the
 * energy K_d gap^(c+1)/(c+1) of one spar. */
static double spar_law(const basket_params *k, double length0, double length, double *slope,
                       double *energy)
{
    double gap = length0 - length;
    if (!(gap > 0)) {
        *slope = *energy = 0;
        return 0;
    }
    double c = k->locking_exponent;
    double power = wff_locking_power(gap, c);
    *energy = k->locking_stiffness * power * gap / (c + 1);
    *slope = k->locking_stiffness * c * wff_locking_power(gap, c - 1);
    return k->locking_stiffness * power;
}

/* Kinematics, laws and energies (all but shear, which needs the flow update). */
static int basket_point_eval(const basket_params *k, const double F[6], const double dA[2],
                             basket_point *pt)
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
    pt->compaction_slope = k->compaction_force * k->compaction_rate * slope;
    pt->energy_compaction = CROSSOVERS * (k->compaction_force / k->compaction_rate *
                                              (primitive - 1) -
                                          k->compaction_force * pt->interference);

    for (int f = 0; f < FAMILIES; f++)
        pt->amplitude[f] = k->amplitude0[f] + dA[f];
    double stack = pt->amplitude[0] + pt->amplitude[1]; /* A_1 + A_2 */
    pt->energy_yarn = pt->energy_bending = pt->energy_locking = 0;
    for (int f = 0; f < FAMILIES; f++) {
        double A = pt->amplitude[f];
        pt->length[f] = sqrt(pt->p[f] * pt->p[f] + A * A);
        pt->path[f] = 2 * pt->p[f] + 2 * pt->length[f];
        pt->crimp[f] = atan2(A, pt->p[f]);
        double stretch = pt->path[f] - k->path0[f];
        if (k->tension_only != 0 && stretch < 0)
            stretch = 0;
        pt->tension[f] = k->yarn_stiffness[f] * stretch;
        pt->energy_yarn += YARNS_PER_FAMILY * 0.5 * k->yarn_stiffness[f] * stretch * stretch;
        double bend = pt->crimp[f] - k->crimp_angle0[f];
        pt->moment[f] = k->bending_stiffness[f] * bend;
        /* two springs per yarn half-repeat, two yarns per family */
        pt->energy_bending += 2 * k->bending_stiffness[f] * bend * bend;

        double energy;
        pt->spar[f] = area / pt->p[f];
        pt->spar_length[f] = sqrt(pt->spar[f] * pt->spar[f] + A * A);
        pt->locking[f] = spar_law(k, k->spar_length0[f], pt->spar_length[f],
                                  &pt->locking_slope[f], &energy);
        pt->energy_locking += CROSSOVERS * energy;
        pt->pair_length[f] = sqrt(pt->spar[f] * pt->spar[f] + stack * stack);
        pt->pair_locking[f] = spar_law(k, k->pair_spar_length0[f], pt->pair_length[f],
                                       &pt->pair_slope[f], &energy);
        pt->energy_locking += CROSSOVERS * energy;
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

static int basket_evaluate(const void *params, const double F[6], const double dA[2],
                           double gamma_f, double dt, wff_point_result *out)
{
    const basket_params *k = params;
    basket_point pt;
    if (basket_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        fill_nan(out);
        return WFF_POINT_DEGENERATE;
    }
    double gamma_f_new = wff_shear_flow_update(k->shear_stiffness, k->flow_moment, k->flow_rate,
                         k->flow_exponent, pt.gamma, gamma_f, dt);
    double shear_elastic = pt.gamma - gamma_f_new;            /* γᵉ */
    double shear_moment = k->shear_stiffness * shear_elastic; /* M_s, one crossover */

    double cs = pt.cos_t, sn = pt.sin_t;
    double stack = pt.amplitude[0] + pt.amplitude[1];
    /* N_m: the spars' pull on the in-plane half-gap s_m, all spars of the cell */
    double spar_pull[FAMILIES];
    double pair_normal = 0; /* Σ_m F_Pm/e_m, times (A_1 + A_2) in F_k^N */
    for (int m = 0; m < FAMILIES; m++) {
        spar_pull[m] = CROSSOVERS * pt.spar[m] *
                       (pt.locking[m] / pt.spar_length[m] + pt.pair_locking[m] / pt.pair_length[m]);
        pair_normal += pt.pair_locking[m] / pt.pair_length[m];
    }

    /* q[f][m]: component of Q_f along ĝ_m */
    double q[FAMILIES][FAMILIES] = {{0, 0}, {0, 0}};
    for (int f = 0; f < FAMILIES; f++) {
        int l = 1 - f;
        double L = pt.length[f];
        double sin_b = pt.amplitude[f] / L, cos_b = pt.p[f] / L;
        /* two yarns, each ∂ℓ/∂p = 2(1 + cosβ) and two springs with ∂β/∂p = −sinβ/L */
        q[f][f] += YARNS_PER_FAMILY * 2 *
                   (pt.tension[f] * (1 + cos_b) - pt.moment[f] * sin_b / L);
        double couple = CROSSOVERS * shear_moment / (pt.p[f] * sn);
        q[f][l] += couple;
        q[f][f] -= couple * cs;
        double c_own = spar_pull[f] * pt.p[l] * cs / (pt.p[f] * sn); /* s_f = J/p_f */
        q[f][f] -= c_own * cs;
        q[f][l] += c_own;
        double other = spar_pull[l] / sn;                              /* s_l = J/p_l */
        q[f][f] -= other;
        q[f][l] += other * cs;

        double normal = pt.tension[f] * sin_b + pt.moment[f] * cos_b / L -
                        pt.locking[f] * pt.amplitude[f] / pt.spar_length[f] -
                        pair_normal * stack; /* F_k^N, per crossover: each yarn
                                                half-repeat bears on two crossovers */
        out->residual[f] = CROSSOVERS * (pt.compaction - normal) / k->cell_area;
    }
    for (int i = 0; i < 3; i++)
        for (int f = 0; f < FAMILIES; f++)
            out->stress[2 * i + f] = k->pitch0[f] / k->cell_area *
                                     (q[f][0] * pt.gh[0][i] + q[f][1] * pt.gh[1][i]);

    double energy_shear = CROSSOVERS * 0.5 * k->shear_stiffness * shear_elastic * shear_elastic;
    out->energy = (pt.energy_yarn + pt.energy_bending + pt.energy_compaction +
                   pt.energy_locking + energy_shear) / k->cell_area;
    out->gamma_f = gamma_f_new;
    out->dissipated = CROSSOVERS * shear_moment * (gamma_f_new - gamma_f) / k->cell_area;
    out->diag[DIAG_T1] = pt.tension[0];
    out->diag[DIAG_T2] = pt.tension[1];
    out->diag[DIAG_BETA1] = pt.crimp[0];
    out->diag[DIAG_BETA2] = pt.crimp[1];
    out->diag[DIAG_FI] = pt.compaction;
    out->diag[DIAG_FL1] = pt.locking[0];
    out->diag[DIAG_FL2] = pt.locking[1];
    out->diag[DIAG_FP1] = pt.pair_locking[0];
    out->diag[DIAG_FP2] = pt.pair_locking[1];
    out->diag[DIAG_MS] = shear_moment;
    return WFF_POINT_OK;
}

static void basket_energy_split(const void *params, const double F[6], const double dA[2],
                                double gamma_f, double *mech)
{
    const basket_params *k = params;
    basket_point pt;
    if (basket_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        for (int i = 0; i < MECH_COUNT; i++)
            mech[i] = NAN;
        return;
    }
    double shear_elastic = pt.gamma - gamma_f;
    mech[MECH_YARN] = pt.energy_yarn / k->cell_area;
    mech[MECH_BENDING] = pt.energy_bending / k->cell_area;
    mech[MECH_COMPACTION] = pt.energy_compaction / k->cell_area;
    mech[MECH_LOCKING] = pt.energy_locking / k->cell_area;
    mech[MECH_SHEAR] =
        CROSSOVERS * 0.5 * k->shear_stiffness * shear_elastic * shear_elastic / k->cell_area;
}

/* Stable-step bounds (docs/basket_cell.md §7). Membrane: bound on
 * ∂²W/∂ε² when family f is stretched, from the yarn path (∂ℓ/∂p = 2(1 + cosβ)
 * ≤ 4, so straight yarns give EA_k/(2 p_l⁰), one yarn per spacing), bending,
 * the spars and the shear springs; speed = sqrt(S/ρ_A). Amplitudes:
 * Gershgorin bound of the 2×2 Hessian ∂²W_cell/∂A_k∂A_m over the lumped mass
 * ρ_A/6 per unit area. */
static void basket_wave_speeds(const void *params, double areal_density, const double F[6],
                               const double dA[2], double *membrane_speed,
                               double *amplitude_omega)
{
    const basket_params *k = params;
    basket_point pt;
    if (basket_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        *membrane_speed = *amplitude_omega = INFINITY;
        return;
    }
    double sn = fmax(pt.sin_t, SHEAR_SINE_FLOOR);
    double shear = CROSSOVERS * k->shear_stiffness / (sn * sn);
    double lock = 0, pair = 0; /* Σ spar stiffness bounds K' + F/length */
    for (int m = 0; m < FAMILIES; m++) {
        lock += pt.locking_slope[m] + pt.locking[m] / pt.spar_length[m];
        pair += pt.pair_slope[m] + pt.pair_locking[m] / pt.pair_length[m];
    }
    double membrane = 0, amplitude = 0;
    for (int f = 0; f < FAMILIES; f++) {
        int l = 1 - f;
        double L = pt.length[f];
        double sin_b = pt.amplitude[f] / L, cos_b = pt.p[f] / L;
        /* a slack yarn (tension_only) keeps its stiffness in the bound: it can pull
         * tight within one step */
        double EAl = k->yarn_stiffness[f]; /* EA/ℓ⁰ */
        double bend = 4 * (k->bending_stiffness[f] + fabs(pt.moment[f])) / (L * L);
        double axial = YARNS_PER_FAMILY * (4 * EAl * (1 + cos_b) * (1 + cos_b) +
                                           2 * fabs(pt.tension[f]) / L) + bend;
        double s_f = (axial * k->pitch0[f] * k->pitch0[f] +
                      2 * CROSSOVERS * (lock + pair) * k->pitch0[l] * k->pitch0[l] + shear) /
                     k->cell_area;
        membrane = fmax(membrane, s_f);
        double own = YARNS_PER_FAMILY * (4 * EAl * sin_b * sin_b +
                                         2 * fabs(pt.tension[f]) * cos_b * cos_b / L) +
                     bend + CROSSOVERS * (pt.locking_slope[f] + pt.locking[f] / pt.spar_length[f]);
        double shared = CROSSOVERS * (pt.compaction_slope + pair); /* on every entry */
        amplitude = fmax(amplitude, own + 2 * shared);
    }
    *membrane_speed = sqrt(membrane / areal_density);
    *amplitude_omega = sqrt(amplitude / k->cell_area / (areal_density / 6));
}

static int basket_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    basket_params *k = (basket_params *)mat->params;
    memset(k, 0, sizeof *k);
    struct { const char *key; double *value; } required[] = {
        {"p0_1", &k->pitch0[0]}, {"p0_2", &k->pitch0[1]},
        {"A0_1", &k->amplitude0[0]}, {"A0_2", &k->amplitude0[1]},
        {"EA_1", &k->axial_rigidity[0]}, {"EA_2", &k->axial_rigidity[1]},
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
        wff_kv_number_or(kv, "tension_only", 0.0, &k->tension_only, err))
        return -1;

    const char *positive[] = {"p0_1", "p0_2", "A0_1", "A0_2", "EA_1", "EA_2",
                              "K_I", "a", "M_0"};
    double *positive_v[] = {&k->pitch0[0], &k->pitch0[1], &k->amplitude0[0],
                            &k->amplitude0[1], &k->axial_rigidity[0], &k->axial_rigidity[1],
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
    for (size_t i = 0; i < sizeof required / sizeof required[0]; i++)
        if (!isfinite(*required[i].value))
            return wff_kv_reject(kv, required[i].key, err, "must be finite");
    if (!(k->locking_exponent >= 1))
        return wff_kv_reject(kv, "c", err, "locking exponent must be >= 1 "
                             "(below 1 the locking stiffness is infinite at contact)");
    if (!(k->flow_exponent >= 1) || !isfinite(k->flow_exponent))
        return wff_kv_reject(kv, "n", err, "shear-flow exponent must be >= 1 and finite "
                             "(below 1 the flow rate is singular at rest)");
    if (k->tension_only != 0 && k->tension_only != 1)
        return wff_kv_reject(kv, "tension_only", err, "must be 0 or 1");
    for (int f = 0; f < FAMILIES; f++)
        if (!(k->amplitude0[f] < k->pitch0[f]))
            return wff_kv_reject(kv, f == 0 ? "A0_1" : "A0_2", err,
                                 "float height must be smaller than p0 (half the crossing-yarn "
                                 "spacing): the transition would be steeper than 45 degrees");

    double stack0 = k->amplitude0[0] + k->amplitude0[1];
    for (int f = 0; f < FAMILIES; f++) {
        int l = 1 - f;
        double L0 = sqrt(k->pitch0[f] * k->pitch0[f] + k->amplitude0[f] * k->amplitude0[f]);
        k->path0[f] = 2 * k->pitch0[f] + 2 * L0;
        k->yarn_stiffness[f] = k->axial_rigidity[f] / k->path0[f];
        k->crimp_angle0[f] = atan2(k->amplitude0[f], k->pitch0[f]);
        double s0 = k->pitch0[l]; /* J⁰/p_f⁰ with the orthogonal reference weave */
        k->spar_length0[f] = sqrt(s0 * s0 + k->amplitude0[f] * k->amplitude0[f]);
        k->pair_spar_length0[f] = sqrt(s0 * s0 + stack0 * stack0);
        mat->yarn_spacing[f] = 2 * k->pitch0[l];
    }
    k->cell_area = 16 * k->pitch0[0] * k->pitch0[1];
    return 0;
}

static void basket_reference_geometry(const void *params, double pitch0[2], double amplitude0[2])
{
    const basket_params *k = params;
    for (int f = 0; f < FAMILIES; f++) {
        pitch0[f] = k->pitch0[f];
        amplitude0[f] = k->amplitude0[f];
    }
}

static const wff_cell_type basket_2x2 = {
    .name = "basket_2x2",
    .summary = "2/2 basket weave: paired yarns with floats, one-truss yarn path, crossover "
               "bending, compaction, locking spars, visco-elastic shear",
    .n_amplitudes = 2,
    .n_diag = DIAG_COUNT,
    .diag_names = basket_diag_names,
    .diag_units = basket_diag_units,
    .yarn_tension_diag = {DIAG_T1, DIAG_T2},
    .n_mech = MECH_COUNT,
    .mech_names = basket_mech_names,
    .parse = basket_parse,
    .evaluate = basket_evaluate,
    .wave_speeds = basket_wave_speeds,
    .energy_split = basket_energy_split,
    .evaluate_shared = NULL,
    .reference_geometry = basket_reference_geometry,
};
WFF_REGISTER_CELL(basket_2x2);

/* The King plain-weave unit cell (King, Jearanaisilawong & Socrate 2005), as
 * run by Parsons, Socrate, Arata & Weerasooriya: see docs/model.md §1–7.
 * This file knows its own parameters and laws; nothing about meshes or solvers.
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
 *
 * Yarn failure (docs/model.md §20, optional: material key failure = 1): the
 * truss tension T_k and its energy k_k (L_k − L_k⁰)² are multiplied by 1 − d_k
 * where the truss is stretched, d_k growing with the largest engineering yarn
 * strain reached, here the truss's own length along the crimped path,
 *
 *   ε_k = (L_k − L_k⁰)/L_k⁰     (k_k = EA/L_k⁰, so T_k = EA ε_k),
 *
 * (yarn_failure.h). Bending, compaction, locking and shear are not damaged.
 * States: γᶠ, then d_1, d_2 with failure, then ε_1, ε_2 of the last update
 * with the rate law or the crack band, then the element length h with the
 * band (set by the element code, never changed here; n_state 1, 3, 5 or 6; 8 with yarn
 * slip, below). The blocked kernels decline a
 * material with failure on; the wave speeds stay the undamaged bounds.
 *
 * Yarn slip at the crossovers (docs/model.md §24, optional: material key
 * yarn_friction = μ_yy > 0 with slip_crossovers = n_c): yarn_slip.h. States s_1,
 * s_2 after the others (n_state 8 with slip). The blocked kernels (king_lanes.h)
 * decline slip.
 *
 * The model is written once: king_family_at (one yarn family at a point),
 * king_point_at (a point: compaction, both families, shear flow, residuals,
 * Q_k coefficients, W_cell) on the frame of wff_yarn_kinematics (cell_laws.h).
 * evaluate, energy_split, wave_speeds, the shared-kinematics path and the
 * blocked kernel's lane loop all call them (docs/model.md §11).
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
    wff_yarn_failure failure;            /* yarn failure (docs/model.md §20); off: enabled 0 */
    double yarn_friction;                /* μ_yy, yarn-on-yarn Coulomb friction at the
                                            crossovers, -; 0: no slip (docs/model.md §24) */
    double slip_crossovers;              /* n_c, crossovers whose friction anchors a family's
                                            tension, - */
    double slip_capacity;                /* n_c μ_yy: the slip tension per newton of
                                            crossover force, -; 0 without slip */
    int n_state;                         /* states per point (mat->n_state): γᶠ [, d_1, d_2
                                            [, ε_1, ε_2 [, h]]]; with slip eight (the
                                            slips s_1, s_2 last); with cutting all nine
                                            (the contact pressure p last) */
} king_params;

_Static_assert(sizeof(king_params) <= sizeof(((wff_material *)0)->params),
               "king_params must fit in wff_material.params");

static const char *const king_diag_names[] = {"T1", "T2", "beta1", "beta2",
                                              "F_I", "F_L1", "F_L2", "M_s"};
static const char *const king_diag_units[] = {"N", "N", "rad", "rad", "N", "N", "N", "N*m"};
enum { DIAG_T1, DIAG_T2, DIAG_BETA1, DIAG_BETA2, DIAG_FI, DIAG_FL1, DIAG_FL2, DIAG_MS,
       DIAG_COUNT };
_Static_assert(DIAG_COUNT <= WFF_DIAG_MAX, "king_plain reports too many diagnostics");
static const char *const king_mech_names[] = {"yarn_stretch", "yarn_bending", "compaction",
                                              "locking", "shear"};
enum { MECH_YARN, MECH_BENDING, MECH_COMPACTION, MECH_LOCKING, MECH_SHEAR, MECH_COUNT };
/* The internal state of a point: γᶠ, the dissipative shear angle; with yarn
 * failure the damages d_1, d_2; with its rate law (or the crack band) the yarn
 * strains of the last update (for the strain rate); with the crack band the
 * element length (the element code's); with yarn slip (docs/model.md §24) the
 * slip strains s_1, s_2, after all the others (a material's states are a
 * prefix of these: with slip a point carries the first eight, those of a law
 * that is off held at 0); with transverse cutting (yarn_failure.h) the contact
 * pressure last, set by the projectile's contact (all nine). */
static const char *const king_state_names[] = {"gamma_f", "damage1", "damage2",
                                               "yarn_strain1", "yarn_strain2",
                                               "element_length", "slip_1", "slip_2",
                                               WFF_CONTACT_PRESSURE_STATE};
static const char *const king_state_units[] = {"rad", "-", "-", "-", "-", "m", "-", "-", "Pa"};
enum { STATE_GAMMA_F, STATE_DAMAGE1, STATE_DAMAGE2, STATE_STRAIN1, STATE_STRAIN2,
       STATE_LENGTH, STATE_SLIP1, STATE_SLIP2, STATE_PRESSURE, STATE_COUNT };
_Static_assert(STATE_LENGTH - STATE_DAMAGE1 == WFF_YARN_STATE_LENGTH,
               "king_plain: the failure states are yarn_failure.h's");
_Static_assert(STATE_COUNT <= WFF_STATE_MAX, "king_plain carries too many states");

/* One yarn family k at one point: king_family_at fills the laws,
 * king_family_forces the last two forces. */
typedef struct king_family {
    double amplitude;      /* A_k, m */
    double length;         /* L_k, m */
    double inv_length;     /* 1/L_k */
    double sin_b, cos_b;   /* sinβ_k, cosβ_k */
    double stretch;        /* L_k − L_k⁰ (1 + s_k), the truss's elastic stretch before any
                              tension_only floor, m (s_k the slip, 0 without it) */
    double tension;        /* T_k, N (times 1 − d_k once king_family_fail has run) */
    double tension_factor; /* ∂T_k/∂(k_k ΔL_k): 1, or 1 − d_k for a damaged stretched truss */
    double bend;           /* β_k − β_k⁰, rad */
    double moment;         /* M_bk, N·m */
    double spar_length;    /* d_k, m */
    wff_spar lock;         /* F_Lk, one spar's energy, −∂F_Lk/∂d_k */
    double spar_pull;      /* N_k = 2 F_Lk cosα_k, the two spars' pull on s_k, N */
    double sin_a;          /* sinα_k = A_k/d_k */
    double normal;         /* F_k^N, N */
    double yarn_q;         /* 2 (T_k cosβ_k − M_bk sinβ_k/L_k): Q_k along ĝ_k, N */
    double energy_yarn, energy_bending, energy_locking; /* J, per cell */
} king_family;

/* docs/model.md §2–4, the laws of family k at amplitude change ΔA_k:
 *   A_k = A_k⁰ + ΔA_k,  L_k = √(p_k² + A_k²),  sinβ_k = A_k/L_k,  cosβ_k = p_k/L_k
 *   T_k = k_k (L_k − L_k⁰)  (≥ 0 when tension_only)
 *   β_k − β_k⁰ = atan((A_k p_k⁰ − A_k⁰ p_k)/(p_k p_k⁰ + A_k A_k⁰)),  M_bk = k_bk (β_k − β_k⁰)
 *   s_k = J/p_k,  d_k = √(s_k² + A_k²),  F_Lk = K_d (d_k⁰ − d_k)₊^c,
 *   sinα_k = A_k/d_k,  cosα_k = s_k/d_k,  N_k = 2 F_Lk cosα_k
 *   energies k_k (L_k − L_k⁰)², k_bk (β_k − β_k⁰)², 2 K_d (d_k⁰ − d_k)₊^(c+1)/(c+1)
 * locking_exponent is c (the blocked kernel passes the constant 2). */
WFF_INLINE king_family king_family_at(const king_params *k, const wff_yarn_frame *fr, int f,
                                      double dA, double locking_exponent)
{
    const double p = fr->p[f], p0 = k->pitch0[f], A0 = k->amplitude0[f];
    const double stretch_floor = k->tension_only != 0 ? 0.0 : -INFINITY;
    king_family y;
    double A = A0 + dA;
    y.amplitude = A;
    y.length = sqrt(p * p + A * A);
    y.inv_length = 1 / y.length;
    y.sin_b = A * y.inv_length;
    y.cos_b = p * y.inv_length;
    double stretch = y.length - k->length0[f];
    y.stretch = stretch;
    stretch = stretch > stretch_floor ? stretch : stretch_floor; /* (fmax would not vectorise) */
    y.tension = k->yarn_stiffness[f] * stretch;
    y.tension_factor = 1.0;
    y.bend = atan((A * p0 - A0 * p) / (p * p0 + A * A0));
    y.moment = k->bending_stiffness[f] * y.bend;
    double spar = fr->J * fr->inv_p[f]; /* s_k */
    y.spar_length = sqrt(spar * spar + A * A);
    double inv_d = 1 / y.spar_length;
    y.lock = wff_spar_law(k->locking_stiffness, locking_exponent, k->spar_length0[f],
                          y.spar_length);
    y.spar_pull = 2 * y.lock.force * (spar * inv_d);
    y.sin_a = A * inv_d;
    y.energy_yarn = k->yarn_stiffness[f] * stretch * stretch;
    y.energy_bending = k->bending_stiffness[f] * y.bend * y.bend;
    y.energy_locking = 2 * y.lock.energy;
    return y;
}

/* docs/model.md §20, yarn failure on family f's truss at engineering strain
 * ε_k = (L_k − L_k⁰)/L_k⁰ (the crimped path's own length; with slip the elastic
 * strain (L_k − L_k⁰(1 + s_k))/L_k⁰, §24): the damage update of yarn_failure.h
 * from state d_k (and ε_k of the last update for the rate law), then T_k and
 * k_k (L_k − L_k⁰)² times 1 − d_k where stretched. */
WFF_INLINE wff_yarn_damage king_family_fail(const king_params *k, int f, king_family *y,
                                            double damage, double strain_prev,
                                            double element_length, double pressure, double dt)
{
    double strain = y->stretch / k->length0[f];
    wff_yarn_damage d = wff_yarn_damage_step_pressed(&k->failure, f, strain, y->energy_yarn,
                                                     damage, strain_prev, element_length,
                                                     pressure, dt);
    y->tension *= d.factor;
    y->energy_yarn *= d.factor;
    y->tension_factor = d.factor;
    return d;
}

#include "yarn_slip.h"

/* docs/model.md §5–6, what family k's laws push with, l the other family:
 *   F_k^N = 2 T_k sinβ_k − 2 F_Lk sinα_k [1 + λ p_l|cosθ|cosβ_k/L_k] + 2 M_bk cosβ_k/L_k
 *   yarn term of Q_k along ĝ_k: 2 (T_k cosβ_k − M_bk sinβ_k/L_k) */
WFF_INLINE void king_family_forces(const king_params *k, const wff_yarn_frame *fr, int f,
                                   king_family *y)
{
    double lever = 1 + k->lever * fr->p[1 - f] * fabs(fr->cos_t) * y->cos_b * y->inv_length;
    y->normal = 2 * y->tension * y->sin_b - 2 * y->lock.force * y->sin_a * lever +
                2 * y->moment * y->cos_b * y->inv_length;
    y->yarn_q = 2 * (y->tension * y->cos_b - y->moment * y->sin_b * y->inv_length);
}

/* Everything one material point computes. */
typedef struct king_point {
    king_family yarn[FAMILIES];
    wff_compaction compaction; /* F_I at I = −ΔA_1 − ΔA_2 */
    double gamma_f;            /* γᶠ after the step */
    double shear_moment;       /* M_s = K_s (γ − γᶠ), N·m */
    double energy_shear;       /* ½ K_s (γ − γᶠ)², J per cell */
    double dissipated;         /* M_s Δγᶠ, J per cell */
    double residual[FAMILIES]; /* R_k, N/m² */
    double q[FAMILIES][FAMILIES]; /* Q_k along ĝ_m, N */
    double energy;             /* W_cell, J per cell */
    double failure_state[WFF_YARN_STATES_MAX]; /* d_1, d_2, ε_1, ε_2, h after the step
                                                  (with failure) */
    double failure_released;   /* Σ_k Δd_k W_k⁺, J per cell */
    double slip[FAMILIES];     /* s_k after the step (with slip) */
    double slip_released;      /* Σ_k the slip's dissipation, J per cell (with slip) */
} king_point;

/* docs/model.md §3, §5–7 at one point of the frame fr, amplitudes dA, state γᶠ:
 *   R_k = (F_I − F_k^N)/(4 p1⁰ p2⁰)
 *   γᶠ by backward Euler, M_s = K_s (γ − γᶠ)
 *   Q_k = q_kk ĝ_k + q_kl ĝ_l (wff_q_coefficients) with the yarn term 2 (T_k cosβ_k −
 *         M_bk sinβ_k/L_k), the shear couple M_s and the spar pulls N_m = 2 F_Lm cosα_m
 *   W_cell = Σ_k [k_k (L_k − L_k⁰)² + k_bk (β_k − β_k⁰)² + 2 K_d (d_k⁰ − d_k)₊^(c+1)/(c+1)]
 *          + (K_I/a)(exp(a I) − 1) − K_I I + ½ K_s (γ − γᶠ)²
 * locking_exponent and flow_exponent are c and n (constants 2 and 1 in the
 * blocked kernel, which leaves it branch-free). failure_state: NULL without
 * yarn failure (the blocked kernels), else d_1, d_2 [, ε_1, ε_2 [, h]] of the
 * point, advanced over dt (§20; h held). slip_state: NULL without yarn slip
 * (the blocked kernels), else s_1, s_2, advanced over dt (§24: slip first, at
 * the damage before the step, then the damage at the slipped strain). */
WFF_INLINE void king_point_at(const king_params *k, const wff_yarn_frame *fr, const double dA[2],
                              double gamma_f, const double *failure_state,
                              const double *slip_state, double dt, const wff_shear_flow *flow,
                              double locking_exponent, double flow_exponent, king_point *pt)
{
    const double inv_cell = 1 / k->cell_area;
    pt->compaction = wff_compaction_law(k->compaction_force, k->compaction_rate, dA);
#pragma GCC unroll 2
    for (int f = 0; f < FAMILIES; f++)
        pt->yarn[f] = king_family_at(k, fr, f, dA[f], locking_exponent);
    pt->failure_released = 0;
    pt->slip_released = 0;
    if (slip_state) {
        const double slip_tension = king_slip_tension(k, pt->compaction.force);
        for (int f = 0; f < FAMILIES; f++) {
            king_slip s = king_family_slip(k, f, &pt->yarn[f], slip_state[f],
                                           failure_state ? failure_state[f] : 0.0,
                                           slip_tension, dt);
            pt->slip[f] = s.slip;
            pt->slip_released += s.released;
        }
    }
    if (failure_state) {
        const int kept = wff_yarn_failure_keeps_strain(&k->failure); /* ε_k of the last update */
        const double length = wff_yarn_failure_length(&k->failure, failure_state);
        /* the contact pressure (the projectile's, cell.h) with transverse cutting */
        const double pressure = k->failure.cutting_pressure > 0
                                    ? failure_state[STATE_PRESSURE - STATE_DAMAGE1] : 0.0;
        for (int f = 0; f < FAMILIES; f++) {
            wff_yarn_damage d = king_family_fail(k, f, &pt->yarn[f], failure_state[f],
                                                 kept ? failure_state[2 + f] : 0, length,
                                                 pressure, dt);
            pt->failure_state[f] = d.damage;
            pt->failure_state[2 + f] = d.strain_prev;
            pt->failure_released += d.released;
        }
        pt->failure_state[WFF_YARN_STATE_LENGTH] = length; /* (the element code's) */
    }
    /* both families' laws first, then their forces: fewer values live across
     * the vector atan calls (the blocked kernel runs 2-3 % faster so) */
#pragma GCC unroll 2
    for (int f = 0; f < FAMILIES; f++) {
        king_family_forces(k, fr, f, &pt->yarn[f]);
        pt->residual[f] = (pt->compaction.force - pt->yarn[f].normal) * inv_cell;
    }
    pt->gamma_f = wff_shear_flow_update(flow, flow_exponent, fr->gamma, gamma_f);
    double shear_elastic = fr->gamma - pt->gamma_f; /* γᵉ */
    pt->shear_moment = k->shear_stiffness * shear_elastic;
    pt->energy_shear = 0.5 * k->shear_stiffness * shear_elastic * shear_elastic;
    pt->dissipated = pt->shear_moment * (pt->gamma_f - gamma_f);
    const double spar_pull[FAMILIES] = {pt->yarn[0].spar_pull, pt->yarn[1].spar_pull};
#pragma GCC unroll 2
    for (int f = 0; f < FAMILIES; f++)
        wff_q_coefficients(fr, f, pt->yarn[f].yarn_q, pt->shear_moment, spar_pull,
                           &pt->q[f][f], &pt->q[f][1 - f]);
    pt->energy = pt->compaction.energy + pt->energy_shear;
#pragma GCC unroll 2
    for (int f = 0; f < FAMILIES; f++)
        pt->energy += pt->yarn[f].energy_yarn + pt->yarn[f].energy_bending +
                      pt->yarn[f].energy_locking;
}

/* docs/model.md §5, ∂F_k^N/∂ΔA_k at fixed F (F_k^N depends on its own amplitude
 * only), from family f's laws y, with p, s_k = J/p_k and θ held:
 *   ∂L/∂A = sinβ,  ∂sinβ/∂A = cos²β/L,  ∂β/∂A = cosβ/L,  ∂(cosβ/L)/∂A = −2 sinβ cosβ/L²
 *   ∂T/∂A = k sinβ (0 where a tension-only yarn is slack; × (1 − d) where a damaged
 *           yarn is stretched, §20),  ∂M_b/∂A = k_b cosβ/L
 *   ∂d/∂A = sinα,  ∂F_L/∂A = −(−∂F_L/∂d) sinα,  ∂sinα/∂A = cos²α/d
 *   ∂F^N/∂A = 2 (∂T sinβ + T cos²β/L)
 *           − 2 (∂F_L sinα Λ + F_L cos²α/d Λ + F_L sinα ∂Λ)       Λ = 1 + λ p_l|cosθ|cosβ/L
 *           + 2 (k_b cos²β − 2 M_b sinβ cosβ)/L² */
WFF_INLINE double king_normal_slope(const king_params *k, const wff_yarn_frame *fr, int f,
                                    const king_family *y)
{
    const double sb = y->sin_b, cb = y->cos_b, inv_L = y->inv_length;
    const double stretch_floor = k->tension_only != 0 ? 0.0 : -INFINITY;
    double stretch = y->stretch; /* (with slip held: §24) */
    double tension_slope =
        (stretch > stretch_floor ? k->yarn_stiffness[f] : 0.0) * y->tension_factor * sb;
    double arm = k->lever * fr->p[1 - f] * fabs(fr->cos_t); /* λ p_l |cosθ| */
    double lever = 1 + arm * cb * inv_L;
    double lever_slope = -2 * arm * sb * cb * inv_L * inv_L;
    double inv_d = 1 / y->spar_length, spar = fr->J * fr->inv_p[f] * inv_d; /* cosα */
    double lock_slope = -y->lock.stiffness * y->sin_a;
    double yarn = tension_slope * sb + y->tension * cb * cb * inv_L;
    double locking = (lock_slope * y->sin_a + y->lock.force * spar * spar * inv_d) * lever +
                     y->lock.force * y->sin_a * lever_slope;
    double bending = (k->bending_stiffness[f] * cb * cb - 2 * y->moment * sb * cb) * inv_L * inv_L;
    return 2 * (yarn - locking + bending);
}

/* docs/model.md §5: R_k = (F_I − F_k^N)/(4 p1⁰ p2⁰) (as king_point_at computes it) and
 *   ∂R_k/∂ΔA_m = (−∂F_I/∂I − δ_km ∂F_k^N/∂ΔA_k)/(4 p1⁰ p2⁰)   (I = −ΔA_1 − ΔA_2)
 * into tangent[2k + m]. locking_exponent is c (the blocked kernel passes 2).
 * damage: NULL without failure, else d_1, d_2, held (§20); slip: NULL without
 * slip, else s_1, s_2, held (§24). */
WFF_INLINE void king_residual_tangent_at(const king_params *k, const wff_yarn_frame *fr,
                                         const double dA[2], double locking_exponent,
                                         const double *damage, const double *slip,
                                         double residual[2], double tangent[4])
{
    const double inv_cell = 1 / k->cell_area;
    const wff_compaction c = wff_compaction_law(k->compaction_force, k->compaction_rate, dA);
    king_family y[FAMILIES];
#pragma GCC unroll 2
    for (int f = 0; f < FAMILIES; f++)
        y[f] = king_family_at(k, fr, f, dA[f], locking_exponent);
    if (slip)
        for (int f = 0; f < FAMILIES; f++)
            (void)king_family_slip(k, f, &y[f], slip[f], 0, 0, 0); /* (held) */
    if (damage)
        for (int f = 0; f < FAMILIES; f++)
            (void)king_family_fail(k, f, &y[f], damage[f], 0, 0, 0, 0); /* (held) */
#pragma GCC unroll 2
    for (int f = 0; f < FAMILIES; f++) {
        king_family_forces(k, fr, f, &y[f]);
        residual[f] = (c.force - y[f].normal) * inv_cell;
        double slope = king_normal_slope(k, fr, f, &y[f]);
        tangent[2 * f + f] = (-c.stiffness - slope) * inv_cell;
        tangent[2 * f + 1 - f] = -c.stiffness * inv_cell;
    }
}

static wff_shear_flow king_flow(const king_params *k, double dt)
{
    return wff_shear_flow_step(k->shear_stiffness, k->flow_moment, k->flow_rate, dt);
}

/* A point's failure states (d_1 on), or NULL when the material has no yarn failure. */
static inline const double *king_failure_state(const king_params *k, const double *state)
{
    return k->failure.enabled != 0 ? state + STATE_DAMAGE1 : NULL;
}

/* A point's updated states into out (n_state values): γᶠ, the failure law's
 * (with failure), the slips (with slip); a state of a law that is off held
 * (the input's). */
static inline void king_state_out(const king_params *k, const double *state,
                                  const king_point *pt, double *out)
{
    out[STATE_GAMMA_F] = pt->gamma_f;
    const int failing = k->failure.enabled != 0 ? wff_yarn_failure_states(&k->failure) : 0;
    for (int i = STATE_DAMAGE1; i < k->n_state && i < STATE_SLIP1; i++)
        out[i] = i - STATE_DAMAGE1 < failing ? pt->failure_state[i - STATE_DAMAGE1] : state[i];
    if (k->slip_capacity > 0) {
        out[STATE_SLIP1] = pt->slip[0];
        out[STATE_SLIP2] = pt->slip[1];
    } else if (k->n_state > STATE_SLIP1) {
        out[STATE_SLIP1] = state[STATE_SLIP1]; /* (held: slip is off) */
        out[STATE_SLIP2] = state[STATE_SLIP2];
    }
    if (k->n_state > STATE_PRESSURE)
        out[STATE_PRESSURE] = state[STATE_PRESSURE]; /* the contact's, never changed here */
}

/* docs/model.md §1–7, §20, §24: one material point. P = (1/(4 p1⁰ p2⁰)) Σ_k Q_k ⊗ G_k,
 * R_k, W = W_cell/(4 p1⁰ p2⁰); dt > 0 advances γᶠ, the damages and the slips. */
static int king_evaluate(const void *params, const double F[6], const double dA[2],
                         const double *state, double dt, wff_point_result *out)
{
    const king_params *k = params;
    wff_yarn_frame fr;
    if (wff_yarn_kinematics(k->pitch0, F, &fr) != WFF_POINT_OK) {
        wff_point_result_nan(out, DIAG_COUNT);
        return WFF_POINT_DEGENERATE;
    }
    const wff_shear_flow flow = king_flow(k, dt);
    king_point pt;
    const double *failure_state = king_failure_state(k, state);
    king_point_at(k, &fr, dA, state[STATE_GAMMA_F], failure_state, king_slip_state(k, state),
                  dt, &flow, k->locking_exponent, k->flow_exponent, &pt);
    const double inv_cell = 1 / k->cell_area;
    const double scale[FAMILIES] = {k->pitch0[0] * inv_cell, k->pitch0[1] * inv_cell};
    wff_stress_from_q(&fr, pt.q, scale, out->stress);
    out->residual[0] = pt.residual[0];
    out->residual[1] = pt.residual[1];
    out->energy = pt.energy * inv_cell;
    out->dissipated = pt.dissipated * inv_cell;
    out->failure_dissipated = pt.failure_released * inv_cell;
    out->slip_dissipated = pt.slip_released * inv_cell;
    king_state_out(k, state, &pt, out->state);
    out->diag[DIAG_T1] = pt.yarn[0].tension;
    out->diag[DIAG_T2] = pt.yarn[1].tension;
    out->diag[DIAG_BETA1] = k->crimp_angle0[0] + pt.yarn[0].bend;
    out->diag[DIAG_BETA2] = k->crimp_angle0[1] + pt.yarn[1].bend;
    out->diag[DIAG_FI] = pt.compaction.force;
    out->diag[DIAG_FL1] = pt.yarn[0].lock.force;
    out->diag[DIAG_FL2] = pt.yarn[1].lock.force;
    out->diag[DIAG_MS] = pt.shear_moment;
    return WFF_POINT_OK;
}

/* docs/model.md §5: W by mechanism, γᶠ held; the terms of king_point_at's W_cell. */
static void king_energy_split(const void *params, const double F[6], const double dA[2],
                              const double *state, double *mech)
{
    const king_params *k = params;
    wff_yarn_frame fr;
    if (wff_yarn_kinematics(k->pitch0, F, &fr) != WFF_POINT_OK) {
        for (int i = 0; i < MECH_COUNT; i++)
            mech[i] = NAN;
        return;
    }
    const wff_shear_flow held = king_flow(k, 0);
    king_point pt;
    king_point_at(k, &fr, dA, state[STATE_GAMMA_F], king_failure_state(k, state),
                  king_slip_state(k, state), 0, &held, k->locking_exponent, k->flow_exponent,
                  &pt);
    const double inv_cell = 1 / k->cell_area;
    mech[MECH_YARN] = (pt.yarn[0].energy_yarn + pt.yarn[1].energy_yarn) * inv_cell;
    mech[MECH_BENDING] = (pt.yarn[0].energy_bending + pt.yarn[1].energy_bending) * inv_cell;
    mech[MECH_COMPACTION] = pt.compaction.energy * inv_cell;
    mech[MECH_LOCKING] = (pt.yarn[0].energy_locking + pt.yarn[1].energy_locking) * inv_cell;
    mech[MECH_SHEAR] = pt.energy_shear * inv_cell;
}

/* Stable-step bounds (docs/model.md §12). Membrane: the straight-yarn
 * stiffness per unit width k_k p_k⁰/(2 p_l⁰) (crimp only lowers it) plus
 * geometric, shear and locking terms; speed = sqrt(S/ρ_A). Amplitudes:
 * Gershgorin bound of the 2×2 Hessian ∂²W_cell/∂A_k∂A_m over the lumped mass
 * ρ_A/6 per unit area. With yarn slip (slip_capacity = n_c μ_yy > 0; the blocked
 * lane passes the constant 0, §24) the state is not known here: the tension of a
 * point a force pass has updated is at most T_slip, of one it has not the
 * unslipped T_k, so the geometric terms take the larger. While a yarn slips its
 * tension follows T_slip(ΔA) instead of its stretch: its axial term k_k sin²β_k
 * goes and ∂R_k/∂ΔA_m gains +2 n_c μ_yy sinβ_k ∂F_I/∂I, which lowers the
 * stiffness (below zero when 2 n_c μ_yy sinβ_k > 1: a growth the step does not
 * govern), so the stick's bound holds for it too (tests/c/test_stable_bound.c
 * runs slipping states through the integrator). */
WFF_INLINE void king_wave_speeds_at(const king_params *k, double areal_density,
                                    const double F[6], const double dA[2],
                                    double locking_exponent, double flow_exponent,
                                    double slip_capacity, double *membrane_speed,
                                    double *amplitude_omega)
{
    wff_yarn_frame fr;
    const int degenerate = wff_yarn_kinematics(k->pitch0, F, &fr) != WFF_POINT_OK;
    const wff_shear_flow held = king_flow(k, 0);
    king_point pt;
    /* undamaged (§20): damage only lowers the yarn terms, so these stay upper bounds;
     * unslipped (§24: the tension bound below) */
    king_point_at(k, &fr, dA, 0, NULL, NULL, 0, &held, locking_exponent, flow_exponent, &pt);
    const double compaction_stiffness = pt.compaction.stiffness; /* ∂F_I/∂I */
    /* maxima as comparisons (fmax would not vectorise; the same value here: the
     * first operand is never NaN) */
    double sn = fr.sin_t > 0.05 ? fr.sin_t : 0.05;
    double shear = k->shear_stiffness / (sn * sn); /* torsional, per rad², N·m */
    double membrane = 0, amplitude = 0;
#pragma GCC unroll 2
    for (int f = 0; f < FAMILIES; f++) {
        int l = 1 - f;
        const king_family *y = &pt.yarn[f];
        double L = y->length;
        /* a slack yarn (tension_only) keeps its stiffness in the bound: it can pull
         * tight within one step, and a step sized for slack yarns is ~20x too long */
        double lock_stiff = y->lock.stiffness; /* ∂F_L/∂d */
        double tension = fabs(y->tension); /* |T_k| */
        if (slip_capacity > 0) {
            const double slip_tension =
                slip_capacity * (pt.compaction.force > 0 ? pt.compaction.force : 0.0);
            tension = slip_tension > tension ? slip_tension : tension;
        }
        double axial = k->yarn_stiffness[f] + tension / L + k->bending_stiffness[f] / (L * L);
        /* stiffness per unit width when family f is stretched: two trusses per
         * cell (2 k p_f⁰² / 4p1⁰p2⁰ = k p_f⁰/2p_l⁰), the spars across, shear */
        double s_f = (2 * axial * k->pitch0[f] * k->pitch0[f] +
                      4 * lock_stiff * k->pitch0[l] * k->pitch0[l] + shear) / k->cell_area;
        membrane = s_f > membrane ? s_f : membrane;
        double a_diag = 2 * (k->yarn_stiffness[f] * y->sin_b * y->sin_b +
                             tension * y->cos_b * y->cos_b / L) +
                        2 * k->bending_stiffness[f] * y->cos_b * y->cos_b / (L * L) +
                        4 * fabs(y->moment) / (L * L) + compaction_stiffness +
                        2 * (lock_stiff + y->lock.force / y->spar_length) * (1 + k->lever);
        double a_f = a_diag + compaction_stiffness;
        amplitude = a_f > amplitude ? a_f : amplitude;
    }
    double speed = sqrt(membrane / areal_density);
    double omega = sqrt(amplitude / k->cell_area / (areal_density / 6));
    *membrane_speed = degenerate ? INFINITY : speed;
    *amplitude_omega = degenerate ? INFINITY : omega;
}

static void king_wave_speeds(const void *params, double areal_density, const double F[6],
                             const double dA[2], double *membrane_speed,
                             double *amplitude_omega)
{
    const king_params *k = params;
    king_wave_speeds_at(k, areal_density, F, dA, k->locking_exponent, k->flow_exponent,
                        k->slip_capacity, membrane_speed, amplitude_omega);
}

/* Shared-kinematics fast path (docs/model.md §11): n points sharing one F, the
 * frame (g_k, p_k, θ, J) computed once, each point by king_point_at, the
 * stress assembled once from the weighted sum of the points' Q_k coefficients:
 *   P = Σ_q w_q P_q = (1/(4 p1⁰ p2⁰)) Σ_k (Σ_q w_q Q_k,q) ⊗ G_k. */
static int king_evaluate_shared(const void *params, const double F[6], int n_points,
                                const double *dA, const double *weight, double *state,
                                double dt, double stress_sum[6], double *residual,
                                double *energy, double *dissipated,
                                double *failure_dissipated, double *slip_dissipated,
                                int *bad_point)
{
    const king_params *k = params;
    wff_yarn_frame fr;
    *bad_point = 0;
    if (wff_yarn_kinematics(k->pitch0, F, &fr) != WFF_POINT_OK)
        return WFF_POINT_DEGENERATE;
    const wff_shear_flow flow = king_flow(k, dt);
    double q[FAMILIES][FAMILIES] = {{0, 0}, {0, 0}};
    double energy_sum = 0, dissipated_sum = 0, released_sum = 0, slipped_sum = 0;
    for (int i = 0; i < n_points; i++) {
        king_point pt;
        double *point_state = state + i * k->n_state;
        const double *failure_state = king_failure_state(k, point_state);
        king_point_at(k, &fr, dA + 2 * i, point_state[STATE_GAMMA_F], failure_state,
                      king_slip_state(k, point_state), dt, &flow, k->locking_exponent,
                      k->flow_exponent, &pt);
        const double w = weight[i];
        for (int f = 0; f < FAMILIES; f++) {
            residual[2 * i + f] = pt.residual[f];
            for (int m = 0; m < FAMILIES; m++)
                q[f][m] += w * pt.q[f][m];
        }
        energy_sum += w * pt.energy;
        dissipated_sum += w * pt.dissipated;
        released_sum += w * pt.failure_released;
        if (k->slip_capacity > 0)
            slipped_sum += w * pt.slip_released;
        king_state_out(k, point_state, &pt, point_state);
    }
    const double inv_cell = 1 / k->cell_area;
    const double scale[FAMILIES] = {k->pitch0[0] * inv_cell, k->pitch0[1] * inv_cell};
    double stress[6];
    wff_stress_from_q(&fr, q, scale, stress);
    for (int i = 0; i < 6; i++)
        stress_sum[i] += stress[i];
    *energy += energy_sum * inv_cell;
    *dissipated += dissipated_sum * inv_cell;
    *failure_dissipated += released_sum * inv_cell;
    if (k->slip_capacity > 0)
        *slip_dissipated += slipped_sum * inv_cell;
    return WFF_POINT_OK;
}

/* The amplitude residual and its exact tangent at one point (king_residual_tangent_at);
 * γᶠ does not enter R, the damages (held) do. */
static int king_amplitude_tangent(const void *params, const double F[6], const double dA[2],
                                  const double *state, double residual[2], double tangent[4])
{
    const king_params *k = params;
    wff_yarn_frame fr;
    if (wff_yarn_kinematics(k->pitch0, F, &fr) != WFF_POINT_OK) {
        residual[0] = residual[1] = NAN;
        for (int i = 0; i < 4; i++)
            tangent[i] = NAN;
        return WFF_POINT_DEGENERATE;
    }
    king_residual_tangent_at(k, &fr, dA, k->locking_exponent, king_failure_state(k, state),
                             king_slip_state(k, state),
                             residual, tangent);
    return WFF_POINT_OK;
}

#include "king_lanes.h"

/* docs/model.md §9: the material file's keys, checked; derived reference
 * quantities L_k⁰, β_k⁰, d_k⁰ (at θ⁰ = 90°) and the cell area; the yarn
 * failure keys (§20, yarn_failure.h), the yarn slip keys (§24) and the states
 * they add. */
static int king_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    king_params *k = (king_params *)mat->params;
    memset(k, 0, sizeof *k);
    const wff_weave_params shared = {
        k->pitch0, k->amplitude0, {"k_1", "k_2"}, k->yarn_stiffness, k->bending_stiffness,
        &k->compaction_force, &k->compaction_rate, &k->locking_stiffness,
        &k->locking_exponent, &k->shear_stiffness, &k->flow_moment, &k->flow_rate,
        &k->flow_exponent, &k->tension_only,
    };
    if (wff_weave_parse(kv, &shared, err) ||
        wff_kv_number_or(kv, "lever", 0.0, &k->lever, err) ||
        wff_yarn_failure_parse(kv, &k->failure, err) || king_slip_parse(kv, k, err))
        return -1;
    if (k->lever != 0 && k->lever != 1)
        return wff_kv_reject(kv, "lever", err, "must be 0 (energy-consistent) or 1 "
                             "(the paper's literal eq. 3)");
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
    mat->n_state = k->n_state = k->failure.cutting_pressure > 0 ? STATE_COUNT
                                : k->slip_capacity > 0 ? STATE_SLIP2 + 1
                                : 1 + wff_yarn_failure_states(&k->failure);
    return 0;
}

/* cell.h yarns_fail: the damage states evolve only with failure = 1 (with yarn
 * slip and failure off they are slots held at 0 before s_1, s_2, §24). */
static int king_yarns_fail(const void *params)
{
    return ((const king_params *)params)->failure.enabled != 0;
}

static void king_reference_geometry(const void *params, double pitch0[2], double amplitude0[2])
{
    const king_params *k = params;
    wff_reference_geometry_copy(k->pitch0, k->amplitude0, pitch0, amplitude0);
}

/* The compaction exponential's length 1/a: the amplitude stiffness's fastest
 * growth (cell.h, amplitude_length). */
static double king_amplitude_length(const void *params)
{
    const king_params *k = params;
    return k->compaction_rate > 0 ? 1 / k->compaction_rate : 0;
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
    .n_state_max = STATE_COUNT,
    .state_names = king_state_names,
    .state_units = king_state_units,
    .damage_state = {STATE_DAMAGE1, STATE_DAMAGE2},
    .parse = king_parse,
    .evaluate = king_evaluate,
    .wave_speeds = king_wave_speeds,
    .energy_split = king_energy_split,
    .evaluate_shared = king_evaluate_shared,
    .evaluate_tri_block = king_evaluate_tri_block,
    .reference_geometry = king_reference_geometry,
    .yarns_fail = king_yarns_fail,
    .evaluate_point_block = king_evaluate_point_block,
    .amplitude_tangent = king_amplitude_tangent,
    .amplitude_tangent_block = king_amplitude_tangent_block,
    .wave_speeds_block = king_wave_speeds_block,
    .amplitude_length = king_amplitude_length,
};
WFF_REGISTER_CELL(king_plain);

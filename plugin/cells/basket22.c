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
 *
 * Yarn failure (docs/model.md §20, optional: failure = 1): T_k and the yarn
 * energy (EA_k/ℓ_k⁰)(ℓ_k − ℓ_k⁰)² times 1 − d_k where the yarn is stretched,
 * d_k growing with the largest engineering yarn strain reached, here that of
 * the half-repeat path (the float and the transition),
 *
 *   ε_k = (ℓ_k − ℓ_k⁰)/ℓ_k⁰      (T_k = EA_k ε_k),
 *
 * (yarn_failure.h). States: γᶠ, then d_1, d_2, then ε_1, ε_2 of the last update
 * with the rate law or the crack band, then the element length h with the band
 * (the element code's, never changed here; n_state 1, 3, 5 or 6); the wave speeds stay the undamaged
 * bounds.
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
    wff_yarn_failure failure;            /* yarn failure (docs/model.md §20); off: enabled 0 */
    int n_state;                         /* states per point: γᶠ [, d_1, d_2 [, ε_1, ε_2
                                            [, h]]] */
} basket_params;

_Static_assert(sizeof(basket_params) <= sizeof(((wff_material *)0)->params),
               "basket_params must fit in wff_material.params");

/* One yarn family k at one point. */
typedef struct basket_family {
    double amplitude;      /* A_k, m */
    double length;         /* L_k, half the transition, m */
    double sin_b, cos_b;   /* sinβ_k, cosβ_k */
    double tension;        /* T_k, N (times 1 − d_k once basket_point_fail has run) */
    double tension_factor; /* 1, or 1 − d_k for a damaged stretched yarn */
    double bend;           /* β_k − β_k⁰, rad */
    double moment;         /* M_bk, N·m */
    double spar;           /* s_k = J/p_k, m */
    double spar_length;    /* d_k, m */
    wff_spar lock;         /* F_Lk, one spar's energy, −∂F_Lk/∂d_k */
    double pair_length;    /* e_k, m */
    wff_spar pair;         /* F_Pk, one spar's energy, −∂F_Pk/∂e_k */
    double energy_yarn, energy_bending, energy_locking; /* J, per cell */
} basket_family;

/* Everything one evaluation computes, kept for evaluate, energy_split and wave_speeds. */
typedef struct basket_point {
    wff_yarn_frame fr;             /* g_k, p_k, θ, J, γ */
    wff_compaction compaction;     /* F_I at I = −ΔA_1 − ΔA_2, one crossover */
    basket_family yarn[FAMILIES];
    double failure_state[WFF_YARN_STATES_MAX]; /* d_1, d_2, ε_1, ε_2, h after the update
                                                  (with failure) */
    double failure_released;       /* Σ_k Δd_k W_k⁺, J per cell */
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
/* The internal state of a point: γᶠ, the dissipative shear angle; with yarn
 * failure the damages d_1, d_2; with its rate law (or the crack band) the yarn
 * strains of the last update; with the crack band the element length (the
 * element code's). */
static const char *const basket_state_names[] = {"gamma_f", "damage1", "damage2",
                                                 "yarn_strain1", "yarn_strain2",
                                                 "element_length"};
static const char *const basket_state_units[] = {"rad", "-", "-", "-", "-", "m"};
enum { STATE_GAMMA_F, STATE_DAMAGE1, STATE_DAMAGE2, STATE_STRAIN1, STATE_STRAIN2,
       STATE_LENGTH, STATE_COUNT };
_Static_assert(STATE_LENGTH - STATE_DAMAGE1 == WFF_YARN_STATE_LENGTH,
               "basket_2x2: the failure states are yarn_failure.h's");
_Static_assert(STATE_COUNT <= WFF_STATE_MAX, "basket_2x2 carries too many states");

/* Kinematics, laws and energies (all but shear, which needs the flow update):
 * the yarn path, T_k, M_bk and both spars of each family, as in the header. */
static int basket_point_eval(const basket_params *k, const double F[6], const double dA[2],
                             basket_point *pt)
{
    if (wff_yarn_kinematics(k->pitch0, F, &pt->fr) != WFF_POINT_OK)
        return WFF_POINT_DEGENERATE;
    pt->compaction = wff_compaction_law(k->compaction_force, k->compaction_rate, dA);
    double stack = k->amplitude0[0] + dA[0] + k->amplitude0[1] + dA[1]; /* A_1 + A_2 */
    for (int f = 0; f < FAMILIES; f++) {
        basket_family *y = &pt->yarn[f];
        double p = pt->fr.p[f], p0 = k->pitch0[f], A0 = k->amplitude0[f];
        double A = A0 + dA[f];
        y->amplitude = A;
        y->length = sqrt(p * p + A * A);
        y->sin_b = A / y->length;
        y->cos_b = p / y->length;
        double stretch = 2 * p + 2 * y->length - k->path0[f]; /* ℓ_k − ℓ_k⁰ */
        if (k->tension_only != 0 && stretch < 0)
            stretch = 0;
        y->tension = k->yarn_stiffness[f] * stretch;
        y->tension_factor = 1.0;
        y->energy_yarn = YARNS_PER_FAMILY * 0.5 * k->yarn_stiffness[f] * stretch * stretch;
        y->bend = atan((A * p0 - A0 * p) / (p * p0 + A * A0)); /* β_k − β_k⁰ */
        y->moment = k->bending_stiffness[f] * y->bend;
        /* two springs per yarn half-repeat, two yarns per family */
        y->energy_bending = 2 * k->bending_stiffness[f] * y->bend * y->bend;

        y->spar = pt->fr.J * pt->fr.inv_p[f];
        y->spar_length = sqrt(y->spar * y->spar + A * A);
        y->lock = wff_spar_law(k->locking_stiffness, k->locking_exponent, k->spar_length0[f],
                               y->spar_length);
        y->pair_length = sqrt(y->spar * y->spar + stack * stack);
        y->pair = wff_spar_law(k->locking_stiffness, k->locking_exponent,
                               k->pair_spar_length0[f], y->pair_length);
        y->energy_locking = CROSSOVERS * (y->lock.energy + y->pair.energy);
    }
    return WFF_POINT_OK;
}

/* docs/model.md §20: yarn failure on both families of a point evaluated by
 * basket_point_eval, at the half-repeat strain ε_k = (ℓ_k − ℓ_k⁰)/ℓ_k⁰, from
 * the point's state (d_1 on) over dt; nothing without failure. */
static void basket_point_fail(const basket_params *k, const double *state, double dt,
                              basket_point *pt)
{
    pt->failure_released = 0;
    if (k->failure.enabled == 0)
        return;
    const double *fs = state + STATE_DAMAGE1;
    const int kept = wff_yarn_failure_keeps_strain(&k->failure); /* ε_k of the last update */
    const double length = wff_yarn_failure_length(&k->failure, fs);
    pt->failure_state[WFF_YARN_STATE_LENGTH] = length; /* (the element code's) */
    for (int f = 0; f < FAMILIES; f++) {
        basket_family *y = &pt->yarn[f];
        double strain = (2 * pt->fr.p[f] + 2 * y->length - k->path0[f]) / k->path0[f];
        wff_yarn_damage d = wff_yarn_damage_step(&k->failure, f, strain, y->energy_yarn, fs[f],
                                                 kept ? fs[2 + f] : 0, length, dt);
        y->tension *= d.factor;
        y->energy_yarn *= d.factor;
        y->tension_factor = d.factor;
        pt->failure_state[f] = d.damage;
        pt->failure_state[2 + f] = d.strain_prev;
        pt->failure_released += d.released;
    }
}

/* The basket's W_cell terms but shear, J per cell. */
static double basket_energy_but_shear(const basket_point *pt)
{
    double W = CROSSOVERS * pt->compaction.energy;
    for (int f = 0; f < FAMILIES; f++)
        W += pt->yarn[f].energy_yarn + pt->yarn[f].energy_bending + pt->yarn[f].energy_locking;
    return W;
}

/* One material point (header: residual, stress, energy): P = (1/(16 p1⁰ p2⁰))
 * Σ_k Q_k ⊗ G_k with Q_k from wff_q_coefficients (yarn term 4 (T_k (1 + cosβ_k)
 * − M_bk sinβ_k/L_k), four shear couples, spar pulls N_m); dt > 0 advances γᶠ. */
WFF_INLINE int basket_evaluate(const void *params, const double F[6], const double dA[2],
                               const double *state, double dt, wff_point_result *out)
{
    const double gamma_f = state[STATE_GAMMA_F];
    const basket_params *k = params;
    basket_point pt;
    if (basket_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        wff_point_result_nan(out, DIAG_COUNT);
        return WFF_POINT_DEGENERATE;
    }
    basket_point_fail(k, state, dt, &pt);
    const wff_shear_flow flow = wff_shear_flow_step(k->shear_stiffness, k->flow_moment,
                                                    k->flow_rate, dt);
    double gamma_f_new = wff_shear_flow_update(&flow, k->flow_exponent, pt.fr.gamma, gamma_f);
    double shear_elastic = pt.fr.gamma - gamma_f_new;         /* γᵉ */
    double shear_moment = k->shear_stiffness * shear_elastic; /* M_s, one crossover */

    double stack = pt.yarn[0].amplitude + pt.yarn[1].amplitude;
    /* N_m: the spars' pull on the in-plane half-gap s_m, all spars of the cell */
    double spar_pull[FAMILIES];
    double pair_normal = 0; /* Σ_m F_Pm/e_m, times (A_1 + A_2) in F_k^N */
    for (int m = 0; m < FAMILIES; m++) {
        const basket_family *y = &pt.yarn[m];
        spar_pull[m] = CROSSOVERS * y->spar *
                       (y->lock.force / y->spar_length + y->pair.force / y->pair_length);
        pair_normal += y->pair.force / y->pair_length;
    }

    double q[FAMILIES][FAMILIES]; /* Q_f along ĝ_m */
    for (int f = 0; f < FAMILIES; f++) {
        const basket_family *y = &pt.yarn[f];
        /* two yarns, each ∂ℓ/∂p = 2(1 + cosβ) and two springs with ∂β/∂p = −sinβ/L */
        double yarn = YARNS_PER_FAMILY * 2 *
                      (y->tension * (1 + y->cos_b) - y->moment * y->sin_b / y->length);
        wff_q_coefficients(&pt.fr, f, yarn, CROSSOVERS * shear_moment, spar_pull, &q[f][f],
                           &q[f][1 - f]);
        double normal = y->tension * y->sin_b + y->moment * y->cos_b / y->length -
                        y->lock.force * y->amplitude / y->spar_length -
                        pair_normal * stack; /* F_k^N, per crossover: each yarn
                                                half-repeat bears on two crossovers */
        out->residual[f] = CROSSOVERS * (pt.compaction.force - normal) / k->cell_area;
    }
    const double scale[FAMILIES] = {k->pitch0[0] / k->cell_area, k->pitch0[1] / k->cell_area};
    wff_stress_from_q(&pt.fr, q, scale, out->stress);

    double energy_shear = CROSSOVERS * 0.5 * k->shear_stiffness * shear_elastic * shear_elastic;
    out->energy = (basket_energy_but_shear(&pt) + energy_shear) / k->cell_area;
    out->state[STATE_GAMMA_F] = gamma_f_new;
    out->dissipated = CROSSOVERS * shear_moment * (gamma_f_new - gamma_f) / k->cell_area;
    out->failure_dissipated = pt.failure_released / k->cell_area;
    out->slip_dissipated = 0; /* (no slip in this cell) */
    for (int i = STATE_DAMAGE1; k->failure.enabled != 0 && i < k->n_state; i++)
        out->state[i] = pt.failure_state[i - STATE_DAMAGE1];
    out->diag[DIAG_T1] = pt.yarn[0].tension;
    out->diag[DIAG_T2] = pt.yarn[1].tension;
    out->diag[DIAG_BETA1] = k->crimp_angle0[0] + pt.yarn[0].bend;
    out->diag[DIAG_BETA2] = k->crimp_angle0[1] + pt.yarn[1].bend;
    out->diag[DIAG_FI] = pt.compaction.force;
    out->diag[DIAG_FL1] = pt.yarn[0].lock.force;
    out->diag[DIAG_FL2] = pt.yarn[1].lock.force;
    out->diag[DIAG_FP1] = pt.yarn[0].pair.force;
    out->diag[DIAG_FP2] = pt.yarn[1].pair.force;
    out->diag[DIAG_MS] = shear_moment;
    return WFF_POINT_OK;
}

static void basket_energy_split(const void *params, const double F[6], const double dA[2],
                                const double *state, double *mech)
{
    const basket_params *k = params;
    basket_point pt;
    if (basket_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        for (int i = 0; i < MECH_COUNT; i++)
            mech[i] = NAN;
        return;
    }
    basket_point_fail(k, state, 0, &pt);
    double shear_elastic = pt.fr.gamma - state[STATE_GAMMA_F];
    mech[MECH_YARN] = (pt.yarn[0].energy_yarn + pt.yarn[1].energy_yarn) / k->cell_area;
    mech[MECH_BENDING] = (pt.yarn[0].energy_bending + pt.yarn[1].energy_bending) / k->cell_area;
    mech[MECH_COMPACTION] = CROSSOVERS * pt.compaction.energy / k->cell_area;
    mech[MECH_LOCKING] = (pt.yarn[0].energy_locking + pt.yarn[1].energy_locking) / k->cell_area;
    mech[MECH_SHEAR] =
        CROSSOVERS * 0.5 * k->shear_stiffness * shear_elastic * shear_elastic / k->cell_area;
}

/* Stable-step bounds (docs/basket_cell.md §7). Membrane: bound on
 * ∂²W/∂ε² when family f is stretched, from the yarn path (∂ℓ/∂p = 2(1 + cosβ)
 * ≤ 4, so straight yarns give EA_k/(2 p_l⁰), one yarn per spacing), bending,
 * the spars and the shear springs; speed = sqrt(S/ρ_A). Amplitudes:
 * Gershgorin bound of the 2×2 Hessian ∂²W_cell/∂A_k∂A_m over the lumped mass
 * ρ_A/6 per unit area. */
WFF_INLINE void basket_wave_speeds(const void *params, double areal_density,
                                   const double F[6], const double dA[2],
                                   double *membrane_speed, double *amplitude_omega)
{
    /* undamaged (§20): damage only lowers the yarn terms, so these stay upper bounds */
    const basket_params *k = params;
    basket_point pt;
    if (basket_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        *membrane_speed = *amplitude_omega = INFINITY;
        return;
    }
    double sn = fmax(pt.fr.sin_t, SHEAR_SINE_FLOOR);
    double shear = CROSSOVERS * k->shear_stiffness / (sn * sn);
    double lock = 0, pair = 0; /* Σ spar stiffness bounds K' + F/length */
    for (int m = 0; m < FAMILIES; m++) {
        const basket_family *y = &pt.yarn[m];
        lock += y->lock.stiffness + y->lock.force / y->spar_length;
        pair += y->pair.stiffness + y->pair.force / y->pair_length;
    }
    double membrane = 0, amplitude = 0;
    for (int f = 0; f < FAMILIES; f++) {
        int l = 1 - f;
        const basket_family *y = &pt.yarn[f];
        double L = y->length, sin_b = y->sin_b, cos_b = y->cos_b;
        /* a slack yarn (tension_only) keeps its stiffness in the bound: it can pull
         * tight within one step */
        double EAl = k->yarn_stiffness[f]; /* EA/ℓ⁰ */
        double bend = 4 * (k->bending_stiffness[f] + fabs(y->moment)) / (L * L);
        double axial = YARNS_PER_FAMILY * (4 * EAl * (1 + cos_b) * (1 + cos_b) +
                                           2 * fabs(y->tension) / L) + bend;
        double s_f = (axial * k->pitch0[f] * k->pitch0[f] +
                      2 * CROSSOVERS * (lock + pair) * k->pitch0[l] * k->pitch0[l] + shear) /
                     k->cell_area;
        membrane = fmax(membrane, s_f);
        double own = YARNS_PER_FAMILY * (4 * EAl * sin_b * sin_b +
                                         2 * fabs(y->tension) * cos_b * cos_b / L) +
                     bend + CROSSOVERS * (y->lock.stiffness + y->lock.force / y->spar_length);
        double shared = CROSSOVERS * (pt.compaction.stiffness + pair); /* on every entry */
        amplitude = fmax(amplitude, own + 2 * shared);
    }
    *membrane_speed = sqrt(membrane / areal_density);
    *amplitude_omega = sqrt(amplitude / k->cell_area / (areal_density / 6));
}

/* The material file's keys, checked; derived reference quantities ℓ_k⁰,
 * EA_k/ℓ_k⁰, β_k⁰, d_k⁰, e_k⁰ (orthogonal reference weave) and the cell area. */
static int basket_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    basket_params *k = (basket_params *)mat->params;
    memset(k, 0, sizeof *k);
    const wff_weave_params shared = {
        k->pitch0, k->amplitude0, {"EA_1", "EA_2"}, k->axial_rigidity, k->bending_stiffness,
        &k->compaction_force, &k->compaction_rate, &k->locking_stiffness,
        &k->locking_exponent, &k->shear_stiffness, &k->flow_moment, &k->flow_rate,
        &k->flow_exponent, &k->tension_only,
    };
    if (wff_weave_parse(kv, &shared, err) || wff_yarn_failure_parse(kv, &k->failure, err) ||
        wff_yarn_failure_no_cutting(kv, &k->failure, "basket_2x2", err))
        return -1;
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
    mat->n_state = k->n_state = 1 + wff_yarn_failure_states(&k->failure);
    return 0;
}

/* The amplitude residual (as basket_evaluate computes it) and its exact tangent,
 * the state held (γᶠ does not enter R, the damages do). With F held, per crossover:
 *   ∂F_k^N/∂A_m = δ_km [∂T_k sinβ_k + T_k cos²β_k/L_k + (k_bk cos²β_k − 2 M_bk sinβ_k cosβ_k)/L_k²
 *                       + (−∂F_Lk/∂d) sin²α_k − F_Lk s_k²/d_k³]
 *                 − ∂[(F_P1/e_1 + F_P2/e_2)(A_1 + A_2)]/∂A_m
 * with ∂T_k/∂A_k = 2 (EA_k/ℓ_k⁰) sinβ_k (0 where a tension-only yarn is slack;
 * × (1 − d_k) where a damaged yarn is stretched, §20),
 * sinα_k = A_k/d_k, ∂e_m/∂A_n = (A_1 + A_2)/e_m, so the pair term's slope is
 *   Σ_m F_Pm/e_m − (A_1 + A_2)² Σ_m [(−∂F_Pm/∂e_m)/e_m² + F_Pm/e_m³],
 * and ∂F_I/∂A_m = −∂F_I/∂I:  ∂R_k/∂ΔA_m = 4 (−∂F_I/∂I − ∂F_k^N/∂A_m)/(16 p1⁰ p2⁰). */
WFF_INLINE int basket_amplitude_tangent(const void *params, const double F[6],
                                        const double dA[2], const double *state,
                                        double residual[2], double tangent[4])
{
    const basket_params *k = params;
    basket_point pt;
    if (basket_point_eval(k, F, dA, &pt) != WFF_POINT_OK) {
        residual[0] = residual[1] = NAN;
        for (int i = 0; i < 4; i++)
            tangent[i] = NAN;
        return WFF_POINT_DEGENERATE;
    }
    basket_point_fail(k, state, 0, &pt);
    double stack = pt.yarn[0].amplitude + pt.yarn[1].amplitude;
    double pair_normal = 0, pair_curvature = 0;
    for (int m = 0; m < FAMILIES; m++) {
        const basket_family *y = &pt.yarn[m];
        double inv_e = 1 / y->pair_length;
        pair_normal += y->pair.force / y->pair_length;
        pair_curvature += (y->pair.stiffness + y->pair.force * inv_e) * inv_e * inv_e;
    }
    double pair_slope = pair_normal - stack * stack * pair_curvature;
    for (int f = 0; f < FAMILIES; f++) {
        const basket_family *y = &pt.yarn[f];
        double normal = y->tension * y->sin_b + y->moment * y->cos_b / y->length -
                        y->lock.force * y->amplitude / y->spar_length - pair_normal * stack;
        residual[f] = CROSSOVERS * (pt.compaction.force - normal) / k->cell_area;
        double stretch = 2 * pt.fr.p[f] + 2 * y->length - k->path0[f];
        int slack = k->tension_only != 0 && stretch < 0;
        double sb = y->sin_b, cb = y->cos_b, inv_L = 1 / y->length;
        double inv_d = 1 / y->spar_length, sa = y->amplitude * inv_d, ca = y->spar * inv_d;
        double tension_slope = slack ? 0.0 : 2 * k->yarn_stiffness[f] * y->tension_factor * sb;
        double own = tension_slope * sb +
                     y->tension * cb * cb * inv_L +
                     (k->bending_stiffness[f] * cb * cb - 2 * y->moment * sb * cb) * inv_L * inv_L +
                     y->lock.stiffness * sa * sa - y->lock.force * ca * ca * inv_d;
        double scale = CROSSOVERS / k->cell_area;
        tangent[2 * f + f] = scale * (-pt.compaction.stiffness - own + pair_slope);
        tangent[2 * f + 1 - f] = scale * (-pt.compaction.stiffness + pair_slope);
    }
    return WFF_POINT_OK;
}

/* The blocked ops, generated from basket_evaluate, basket_amplitude_tangent and
 * basket_wave_speeds (cell_lanes.h): basket_evaluate_tri_block,
 * basket_evaluate_point_block, basket_amplitude_tangent_block,
 * basket_wave_speeds_block. */
WFF_CELL_LANES(basket, basket_params, basket_evaluate, basket_amplitude_tangent,
               basket_wave_speeds)

static void basket_reference_geometry(const void *params, double pitch0[2], double amplitude0[2])
{
    const basket_params *k = params;
    wff_reference_geometry_copy(k->pitch0, k->amplitude0, pitch0, amplitude0);
}

/* The compaction exponential's length 1/a: the amplitude stiffness's fastest
 * growth (cell.h, amplitude_length). */
static double basket_amplitude_length(const void *params)
{
    const basket_params *k = params;
    return k->compaction_rate > 0 ? 1 / k->compaction_rate : 0;
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
    .n_state_max = STATE_COUNT,
    .state_names = basket_state_names,
    .state_units = basket_state_units,
    .damage_state = {STATE_DAMAGE1, STATE_DAMAGE2},
    .parse = basket_parse,
    .evaluate = basket_evaluate,
    .wave_speeds = basket_wave_speeds,
    .energy_split = basket_energy_split,
    .evaluate_shared = NULL,
    .evaluate_tri_block = basket_evaluate_tri_block,
    .reference_geometry = basket_reference_geometry,
    .evaluate_point_block = basket_evaluate_point_block,
    .amplitude_tangent = basket_amplitude_tangent,
    .amplitude_tangent_block = basket_amplitude_tangent_block,
    .wave_speeds_block = basket_wave_speeds_block,
    .amplitude_length = basket_amplitude_length,
};
WFF_REGISTER_CELL(basket_2x2);

/* solid_laws.h — pointwise laws of the backing's solids (issue 30 item 1):
 * Roma Plastilina No. 1 clay (clay.c) and 10 % ordnance gelatin (gelatin.c).
 *
 * Pure pointwise physics, like a cell: a parameter struct, a state struct per
 * point, and functions of (parameters, strain, time step, state) -> (stress,
 * new state, dissipation). No mesh, no allocation, no I/O, no global state;
 * reentrant. The 3-D block element that will call them is not built yet.
 *
 * Small strain: ε is the symmetric small-strain tensor (an element at large
 * strain would hand them a rotated, logarithmic or corotational strain; the
 * laws themselves are written for ε, σ in the same frame).
 *
 * Tensors are symmetric 3×3 in 6 entries, tensor (not engineering) shear
 * components, in the order xx yy zz yz xz xy: a:b = Σ_{i<3} a_i b_i +
 * 2 Σ_{i>=3} a_i b_i. SI units: Pa, s, J/m³. */
#ifndef WFF_SOLID_LAWS_H
#define WFF_SOLID_LAWS_H

#include "wovenff/error.h"

#define WFF_SYM 6 /* entries of a symmetric 3×3 tensor */

/* a:b, the double contraction of two symmetric tensors */
static inline double wff_sym_dot(const double a[WFF_SYM], const double b[WFF_SYM])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + 2 * (a[3] * b[3] + a[4] * b[4] + a[5] * b[5]);
}

/* dev a = a − (tr a / 3) I; returns tr a */
static inline double wff_sym_dev(const double a[WFF_SYM], double dev[WFF_SYM])
{
    const double tr = a[0] + a[1] + a[2];
    for (int i = 0; i < WFF_SYM; i++)
        dev[i] = a[i] - (i < 3 ? tr / 3 : 0);
    return tr;
}

/* ---- clay: J2 elastic–plastic, linear isotropic hardening, Cowper–Symonds rate ---- */
typedef struct wff_clay_params {
    double density;      /* ρ, kg/m³ */
    double youngs;       /* E, Pa */
    double poisson;      /* ν */
    double yield_static; /* σ_0, Pa: the uniaxial yield stress at a vanishing plastic rate */
    double hardening;    /* H, Pa: σ_y grows by H per unit equivalent plastic strain */
    double rate_c;       /* Cowper–Symonds C, 1/s */
    double rate_p;       /* Cowper–Symonds p (> 0) */
} wff_clay_params;

typedef struct wff_clay_state {
    double plastic_strain[WFF_SYM]; /* ε^p (deviatoric) */
    double eq_plastic;              /* ᾱ = ∫ √(2/3) |ε̇^p| dt */
    double dissipated;              /* plastic work so far, J/m³ (all of it heat: clay keeps none) */
    double plastic_rate;            /* the last step's equivalent plastic rate √(2/3) Δγ/dt, 1/s */
} wff_clay_state;

/* Roma Plastilina No. 1 as wovenff takes it by default (the sources and what
 * each number rests on: clay.c). */
extern const wff_clay_params wff_clay_roma_plastilina;

/* 0, or -1 (err set, naming the parameter) if a parameter is out of range. */
int wff_clay_check(const wff_clay_params *p, wff_error *err);
/* σ_y(ᾱ, ε̇) = (σ_0 + H ᾱ)(1 + (ε̇/C)^(1/p)), Pa, at the equivalent plastic
 * strain ᾱ and rate ε̇ (1/s, >= 0). */
double wff_clay_yield(const wff_clay_params *p, double eq_plastic, double eq_rate);
/* Stored (elastic) energy density W = ½ K (tr ε^e)² + G |dev ε^e|², J/m³,
 * ε^e = ε − ε^p; and its stress ∂W/∂ε at fixed ε^p. */
double wff_clay_energy(const wff_clay_params *p, const double strain[WFF_SYM],
                       const wff_clay_state *s);
void wff_clay_stress(const wff_clay_params *p, const double strain[WFF_SYM],
                     const wff_clay_state *s, double stress[WFF_SYM]);
/* One step to the total strain `strain` over dt (s, > 0) from `old`: the
 * radial return (backward Euler) with the rate-dependent yield at the step's
 * plastic rate √(2/3) Δγ / dt. Writes `out` (may be `old`) and the stress;
 * returns 1 if the step yielded, 0 if elastic, -1 if dt <= 0 (the trial
 * stress written, `out` untouched). Its dissipation σ : Δε^p >= 0 is added to
 * out->dissipated. */
int wff_clay_update(const wff_clay_params *p, const double strain[WFF_SYM], double dt,
                    const wff_clay_state *old, wff_clay_state *out, double stress[WFF_SYM]);
/* The dilatational wave speed √((K + 4G/3)/ρ), m/s (for a stable step). */
double wff_clay_wave_speed(const wff_clay_params *p);

/* ---- gelatin: visco-elastic, a standard linear solid in shear, elastic in bulk ---- */
typedef struct wff_gelatin_params {
    double density;         /* ρ, kg/m³ */
    double bulk;            /* K, Pa */
    double shear_long;      /* G_∞, Pa: the relaxed shear modulus */
    double shear_branch;    /* G_1, Pa: the Maxwell branch's (instantaneous: G_∞ + G_1) */
    double relaxation_time; /* τ_1, s: the Maxwell branch's η_1 / G_1 */
} wff_gelatin_params;

typedef struct wff_gelatin_state {
    double viscous_strain[WFF_SYM]; /* e^v: the dashpot's (deviatoric) strain */
    double last_dev[WFF_SYM];       /* dev ε at the last update */
    double dissipated;              /* J/m³, in the dashpot so far */
} wff_gelatin_state;

/* 10 % ordnance gelatin as wovenff takes it by default (sources: gelatin.c). */
extern const wff_gelatin_params wff_gelatin_ordnance10;

int wff_gelatin_check(const wff_gelatin_params *p, wff_error *err);
/* W(ε, e^v) = ½ K (tr ε)² + G_∞ |dev ε|² + G_1 |dev ε − e^v|², J/m³, and its
 * stress ∂W/∂ε at fixed e^v. */
double wff_gelatin_energy(const wff_gelatin_params *p, const double strain[WFF_SYM],
                          const wff_gelatin_state *s);
void wff_gelatin_stress(const wff_gelatin_params *p, const double strain[WFF_SYM],
                        const wff_gelatin_state *s, double stress[WFF_SYM]);
/* One step to `strain` over dt (s, >= 0) from `old`, the deviatoric strain
 * taken linear in time over the step: the branch strain q = dev ε − e^v
 * integrated exactly (q̇ = ė − q/τ), and the dashpot's dissipation
 * ∫ 2 (G_1/τ) |q|² dt exactly. Writes `out` (may be `old`) and the stress. */
void wff_gelatin_update(const wff_gelatin_params *p, const double strain[WFF_SYM], double dt,
                        const wff_gelatin_state *old, wff_gelatin_state *out,
                        double stress[WFF_SYM]);
/* The dilatational wave speed at the instantaneous moduli, m/s. */
double wff_gelatin_wave_speed(const wff_gelatin_params *p);

#endif

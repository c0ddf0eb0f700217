/* wovenff — the Phoenix–Porwal membrane estimate of a fabric's ballistic limit
 * (plugin/membrane_limit.c; docs/penetration.md "The Phoenix–Porwal estimate"),
 * the same formulas as tools/phoenix_porwal.sh:
 *
 *   V50 = sqrt(2) (1 + Γ) c (ε_max / K_max)^(3/4)
 *
 *   c       the membrane's tensile wave speed sqrt(S / ρ_A), m/s
 *   ε_max   the yarn failure strain, −
 *   Γ       m_m / M_p: the mass of the pack under the projectile's face,
 *           plies ρ_A π r_p², over the projectile's, −
 *   K_max   the strain concentration at the projectile's edge when the strain
 *           there peaks: our reconstruction (not Phoenix & Porwal's),
 *           K(x) = x exp(−4Γ(x² − 1)/3) at x* = sqrt(3/(8Γ)) (x* ≥ 1), x the
 *           cone's radius over r_p.
 *
 * With a clamp of radius R_o the cone reaches it at x_o = R_o / r_p; when
 * x_o < x* the strain has not peaked by then, and the speed above which the
 * fabric fails before the cone reaches the clamp, with K(x_o), is given too.
 *
 * A starting point for a ballistic-limit search (the first shot of the
 * MIL-STD-662F sequence), not a prediction: K_max alone moves V50 by an order
 * of magnitude. Knows the material reader and the cells' ops; nothing of
 * meshes, the solver or FreeFEM. */
#ifndef WOVENFF_MEMBRANE_LIMIT_H
#define WOVENFF_MEMBRANE_LIMIT_H

#include "wovenff/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The failure strain taken when a material has no fail_strain_1 key: yarns
 * taken out of woven Kevlar (docs/penetration.md; L: no primary source found). */
#define WFF_PP_DEFAULT_FAIL_STRAIN 0.0355

/* The stretch at which a material's wave speed is measured (as the material's
 * scale check, plugin/material_scales.c): 1 %. */
#define WFF_PP_STRETCH 0.01

typedef struct wff_pp_input {
    double wave_speed;     /* c, m/s, > 0 */
    double failure_strain; /* ε_max, −, > 0 */
    double gamma;          /* Γ = m_m / M_p, −, > 0 */
    double opening_ratio;  /* R_o / r_p, −: the clamp's radius over the projectile's;
                              0: no clamp (an infinite membrane) */
} wff_pp_input;

typedef struct wff_pp_result {
    double v50;        /* m/s, the estimate for the infinite membrane */
    double k_max;      /* K_max, −, >= 1 */
    double x_peak;     /* x* = R / r_p at the strain peak, −, >= 1 */
    double k_clamp;    /* K(x_o) when the cone reaches the clamp before the peak (x_o < x*), else 0 */
    double v50_clamp;  /* m/s, failure before the cone reaches the clamp above it (same
                          condition), else 0 */
} wff_pp_result;

/* The estimate from its inputs. Returns 0; −1 with err naming the input when
 * one is not finite or not positive (opening_ratio may be 0). */
int wff_phoenix_porwal(const wff_pp_input *in, wff_pp_result *out, wff_error *err);

/* The edge-strain factor K(x) = x exp(−4Γ(x² − 1)/3) (our reconstruction). */
double wff_pp_edge_factor(double gamma, double x);

/* The estimate for `plies` plies (≥ 1) of the material file material_path
 * struck by a projectile of `mass` (kg) and face radius `radius` (m), clamped
 * at opening_radius (m; 0: no clamp, else > radius):
 *   c = sqrt(S / ρ_A), S the warp's (family 1) stress per width at 1 % stretch
 *       over 1 % (the cell's own, wff_material_specific_stiffness; for
 *       king_plain this is the truss stiffness k_1 p0_1/(2 p0_2) seen through
 *       the crimp, docs/penetration.md); plies do not change it;
 *   ε_max = the material's fail_strain_1 key, else WFF_PP_DEFAULT_FAIL_STRAIN;
 *   Γ = plies ρ_A π r² / mass.
 * *out the result, *used (may be NULL) the inputs taken. Returns 0; −1 with err
 * naming the file, key or argument at fault. */
int wff_membrane_limit_estimate(const char *material_path, int plies, double mass,
                                double radius, double opening_radius, wff_pp_result *out,
                                wff_pp_input *used, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

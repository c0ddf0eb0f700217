/* clay.c: Roma Plastilina No. 1, the backing clay of NIJ 0101.06 — a
 * small-strain J2 elastic–plastic law with linear isotropic hardening and a
 * Cowper–Symonds rate dependence of the yield stress, integrated by the
 * radial return (plugin/solids/solid_laws.h). Pointwise: no allocation. */
#include "solid_laws.h"

#include <math.h>

/* Default parameters and what each rests on (docs/backing_laws.md):
 *
 * The one calibration from a published number: NIJ Standard-0101.06's clay
 * check drops a 1.043 kg, 63.5 mm steel sphere from 2.0 m onto the clay and
 * wants an indentation of 19 ± 2 mm. Tabor's hardness estimate (mean pressure
 * ≈ 3 σ_y under a spherical indenter; Tabor, The Hardness of Metals, 1951),
 * m g (h + δ) = 3 σ_y π (R δ² − δ³/3), gives σ_y = 0.2388 MPa at δ = 19 mm, at
 * the drop's rate ε̇ ≈ v_0 / (2 a) ≈ 108 /s (v_0 = √(2 g h) = 6.26 m/s, a the
 * contact radius at 19 mm, 29.1 mm). σ_0 below is that σ_y divided by the rate
 * factor at 108 /s (tests/c/test_solid_laws.c recomputes it).
 *
 * NOT a published calibration: the rate constants C and p (placeholders of the
 * usual form, chosen so the factor is ~2 at the drop test), E, ν and H. The
 * published constitutive studies to calibrate them from: Hernandez, Buchely &
 * Maranon (2015), "Dynamic characterization of Roma Plastilina No. 1 from a
 * drop test and inverse analysis", Int. J. Mech. Sci. 100; Buchely, Maranon &
 * Silberschmidt (2016), "Material model for modeling clay at high strain
 * rates", Int. J. Impact Eng. 90 (their numbers were not at hand here).
 * Calibration range: one point, the drop test (~100 /s, ~20 % strain); a
 * ballistic BFS loads the clay at 10³–10⁴ /s, where only the placeholders
 * speak. */
const wff_clay_params wff_clay_roma_plastilina = {
    .density = 1500,         /* kg/m³: order of magnitude of modelling clays (to be read) */
    .youngs = 10e6,          /* Pa: assumed (E ≫ σ_y: the crater is plastic) */
    .poisson = 0.45,         /* assumed: nearly incompressible */
    .yield_static = 0.118296e6, /* Pa: the drop test's 0.23881 MPa / (1 + (107.70/100)^(1/4)) */
    .hardening = 0,          /* Pa: assumed perfectly plastic */
    .rate_c = 100,           /* 1/s: placeholder */
    .rate_p = 4,             /* placeholder */
};

static void elastic_moduli(const wff_clay_params *p, double *bulk, double *shear)
{
    *bulk = p->youngs / (3 * (1 - 2 * p->poisson));
    *shear = p->youngs / (2 * (1 + p->poisson));
}

int wff_clay_check(const wff_clay_params *p, wff_error *err)
{
    if (!(p->density > 0))
        return wff_fail(err, "clay: density %g kg/m3 must be > 0", p->density);
    if (!(p->youngs > 0))
        return wff_fail(err, "clay: Young's modulus %g Pa must be > 0", p->youngs);
    if (!(p->poisson > -1 && p->poisson < 0.5))
        return wff_fail(err, "clay: Poisson's ratio %g must be in (-1, 0.5)", p->poisson);
    if (!(p->yield_static > 0))
        return wff_fail(err, "clay: yield stress %g Pa must be > 0", p->yield_static);
    if (!(p->hardening >= 0))
        return wff_fail(err, "clay: hardening %g Pa must be >= 0", p->hardening);
    if (!(p->rate_c > 0) || !(p->rate_p > 0))
        return wff_fail(err, "clay: Cowper-Symonds C %g 1/s and p %g must be > 0", p->rate_c,
                        p->rate_p);
    return 0;
}

double wff_clay_yield(const wff_clay_params *p, double eq_plastic, double eq_rate)
{
    const double factor = eq_rate > 0 ? 1 + pow(eq_rate / p->rate_c, 1 / p->rate_p) : 1;
    return (p->yield_static + p->hardening * eq_plastic) * factor;
}

double wff_clay_energy(const wff_clay_params *p, const double strain[WFF_SYM],
                       const wff_clay_state *s)
{
    double K, G, e[WFF_SYM], dev[WFF_SYM];
    elastic_moduli(p, &K, &G);
    for (int i = 0; i < WFF_SYM; i++)
        e[i] = strain[i] - s->plastic_strain[i];
    const double tr = wff_sym_dev(e, dev);
    return 0.5 * K * tr * tr + G * wff_sym_dot(dev, dev);
}

void wff_clay_stress(const wff_clay_params *p, const double strain[WFF_SYM],
                     const wff_clay_state *s, double stress[WFF_SYM])
{
    double K, G, e[WFF_SYM], dev[WFF_SYM];
    elastic_moduli(p, &K, &G);
    for (int i = 0; i < WFF_SYM; i++)
        e[i] = strain[i] - s->plastic_strain[i];
    const double tr = wff_sym_dev(e, dev);
    for (int i = 0; i < WFF_SYM; i++)
        stress[i] = 2 * G * dev[i] + (i < 3 ? K * tr : 0);
}

/* The return's residual g(Δγ) = q_tr − 2 G Δγ − √(2/3) σ_y(ᾱ + √(2/3) Δγ,
 * √(2/3) Δγ / dt) (decreasing in Δγ) and its slope. */
static double residual(const wff_clay_params *p, double q_trial, double G, double alpha,
                       double dt, double dgamma, double *slope)
{
    const double c = sqrt(2.0 / 3.0), rate = c * dgamma / dt;
    const double base = p->yield_static + p->hardening * (alpha + c * dgamma);
    const double power = rate > 0 ? pow(rate / p->rate_c, 1 / p->rate_p) : 0;
    const double dpower = rate > 0 ? power / (p->rate_p * rate) * c / dt : INFINITY;
    *slope = -2 * G - c * (p->hardening * c * (1 + power) + base * dpower);
    return q_trial - 2 * G * dgamma - c * base * (1 + power);
}

/* Radial return (Simo & Hughes, Computational Inelasticity, §3.3) with the
 * viscoplastic yield at the step's rate:
 *   ε^e_tr = ε − ε^p_n,   s_tr = 2 G dev ε^e_tr,   q_tr = |s_tr|,
 *   elastic if q_tr <= √(2/3) σ_y(ᾱ_n, 0);
 *   else Δγ > 0 solves q_tr − 2 G Δγ = √(2/3) σ_y(ᾱ_n + √(2/3) Δγ, √(2/3) Δγ/dt),
 *   n = s_tr / q_tr,  ε^p += Δγ n,  ᾱ += √(2/3) Δγ,  s = s_tr − 2 G Δγ n,
 *   dissipation σ : Δε^p = |s| Δγ >= 0.
 * Δγ by Newton's method kept inside a shrinking bracket [lo, hi] (bisection
 * when a Newton step leaves it: the rate term's slope is infinite at 0). */
int wff_clay_update(const wff_clay_params *p, const double strain[WFF_SYM], double dt,
                    const wff_clay_state *old, wff_clay_state *out, double stress[WFF_SYM])
{
    double K, G, e[WFF_SYM], s_trial[WFF_SYM];
    elastic_moduli(p, &K, &G);
    for (int i = 0; i < WFF_SYM; i++)
        e[i] = strain[i] - old->plastic_strain[i];
    const double tr = wff_sym_dev(e, s_trial);
    for (int i = 0; i < WFF_SYM; i++)
        s_trial[i] *= 2 * G;
    const double q_trial = sqrt(wff_sym_dot(s_trial, s_trial));
    const double alpha = old->eq_plastic, c = sqrt(2.0 / 3.0);
    for (int i = 0; i < WFF_SYM; i++)
        stress[i] = s_trial[i] + (i < 3 ? K * tr : 0);
    if (!(dt > 0))
        return -1; /* (no rate without a step: the trial stress, the state unchanged) */
    if (out != old)
        *out = *old;
    out->plastic_rate = 0;
    if (!(q_trial > c * wff_clay_yield(p, alpha, 0)))
        return 0;
    double lo = 0, hi = q_trial / (2 * G), dgamma = hi, slope;
    for (int iteration = 0; iteration < 200; iteration++) {
        const double g = residual(p, q_trial, G, alpha, dt, dgamma, &slope);
        if (g > 0)
            lo = dgamma;
        else
            hi = dgamma;
        if (fabs(g) <= 1e-13 * q_trial || hi - lo <= 1e-15 * hi)
            break;
        double next = dgamma - g / slope;
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        dgamma = next;
    }
    const double scale = 1 - 2 * G * dgamma / q_trial; /* s = scale s_tr */
    for (int i = 0; i < WFF_SYM; i++) {
        const double n = s_trial[i] / q_trial;
        out->plastic_strain[i] = old->plastic_strain[i] + dgamma * n;
        stress[i] = scale * s_trial[i] + (i < 3 ? K * tr : 0);
    }
    out->eq_plastic = alpha + c * dgamma;
    out->plastic_rate = c * dgamma / dt;
    out->dissipated = old->dissipated + scale * q_trial * dgamma;
    return 1;
}

double wff_clay_wave_speed(const wff_clay_params *p)
{
    double K, G;
    elastic_moduli(p, &K, &G);
    return sqrt((K + 4 * G / 3) / p->density);
}

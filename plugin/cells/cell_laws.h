/* wovenff — constitutive pieces the truss-and-spring weave cells share
 * (King et al. 2005 laws, MODEL.md §3 and §7): the compaction exponential
 * with its overflow guard, the locking power law, and the backward-Euler
 * update of the visco-elastic shear angle. Pure functions, no state. */
#ifndef WOVENFF_CELL_LAWS_H
#define WOVENFF_CELL_LAWS_H

#include <math.h>

/* Exponent a·I past which the compaction exponential is continued by its
 * third-order Taylor polynomial: exp(30) ≈ 1e13, far beyond any physical
 * compaction force, and far below overflow. */
#define WFF_COMPACTION_EXPONENT_MAX 30.0

/* exp(x) continued past WFF_COMPACTION_EXPONENT_MAX (same value, slope and
 * curvature); *primitive gets ∫exp (for the energy), *slope its derivative. */
static inline double wff_compaction_exp(double x, double *primitive, double *slope)
{
    if (x <= WFF_COMPACTION_EXPONENT_MAX) {
        double e = exp(x);
        *primitive = e;
        *slope = e;
        return e;
    }
    double e = exp(WFF_COMPACTION_EXPONENT_MAX), u = x - WFF_COMPACTION_EXPONENT_MAX;
    *primitive = e * (1 + u + u * u / 2 + u * u * u / 6);
    *slope = e * (1 + u);
    return e * (1 + u + u * u / 2);
}

/* gap^c for the locking law; integer exponents by multiplication (pow with a
 * run-time exponent costs ~10 ns). */
static inline double wff_locking_power(double gap, double c)
{
    if (c == 1.0)
        return gap;
    if (c == 2.0)
        return gap * gap;
    if (c == 3.0)
        return gap * gap * gap;
    return pow(gap, c);
}

/* Backward-Euler update of γᶠ (MODEL.md §7): solve
 *   x = γᶠ + Δt γ̇₀ sign(m)|m/M₀|^n,  m = K_s (γ − x)
 * for x, with K_s = stiffness, M₀ = moment, γ̇₀ = rate, n = exponent ≥ 1.
 * The root lies between γᶠ and γ; n = 1 has a closed form, otherwise a
 * bracketed Newton iteration. dt ≤ 0 holds γᶠ. */
static inline double wff_shear_flow_update(double stiffness, double moment, double rate,
                                           double exponent, double gamma, double gamma_f,
                                           double dt)
{
    if (!(dt > 0) || rate == 0 || stiffness == 0)
        return gamma_f;
    double step = dt * rate; /* Δt γ̇₀ */
    if (exponent == 1.0) {
        double r = step * stiffness / moment;
        return (gamma_f + r * gamma) / (1 + r);
    }
    double lo = fmin(gamma_f, gamma), hi = fmax(gamma_f, gamma), x = gamma_f;
    for (int it = 0; it < 100; it++) {
        double m = stiffness * (gamma - x);
        double ratio = fabs(m) / moment;
        double flow = step * pow(ratio, exponent);
        double f = x - gamma_f - (m >= 0 ? flow : -flow);
        if (f > 0)
            hi = x;
        else
            lo = x;
        /* d/dx of sign(m)|m/M₀|^n is −n K_s |m/M₀|^(n−1)/M₀ */
        double df = 1 + step * exponent * stiffness / moment * pow(ratio, exponent - 1);
        double next = x - f / df;
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        if (fabs(next - x) <= 1e-15 * (fabs(x) + fabs(gamma) + 1e-300))
            return next;
        x = next;
    }
    return x;
}

#endif

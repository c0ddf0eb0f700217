/* wovenff — pieces the truss-and-spring weave cells share (King et al. 2005,
 * MODEL.md §1, §3 and §7): the yarn kinematics of eq. (1), the compaction
 * exponential with its overflow guard, the locking power law, and the
 * backward-Euler update of the visco-elastic shear angle. Pure functions, no
 * state. */
#ifndef WOVENFF_CELL_LAWS_H
#define WOVENFF_CELL_LAWS_H

#include <math.h>

#include "wovenff/cell.h"

/* Eq. (1): g_k = F G_k with G_k = p_k⁰ E_k; p_k = |g_k|, ĝ_k = g_k/p_k,
 * J = |g_1 × g_2|, cosθ = ĝ_1·ĝ_2, sinθ = J/(p_1 p_2). Returns
 * WFF_POINT_DEGENERATE if a yarn has zero length or the yarns are parallel. */
static inline int wff_yarn_kinematics(const double pitch0[2], const double F[6], double gh[2][3],
                                      double p[2], double *J, double *cos_t, double *sin_t)
{
    double g[2][3];
    for (int f = 0; f < 2; f++) {
        for (int i = 0; i < 3; i++)
            g[f][i] = pitch0[f] * F[2 * i + f];
        p[f] = sqrt(g[f][0] * g[f][0] + g[f][1] * g[f][1] + g[f][2] * g[f][2]);
        if (!(p[f] > 0))
            return WFF_POINT_DEGENERATE;
        for (int i = 0; i < 3; i++)
            gh[f][i] = g[f][i] / p[f];
    }
    double n0 = g[0][1] * g[1][2] - g[0][2] * g[1][1];
    double n1 = g[0][2] * g[1][0] - g[0][0] * g[1][2];
    double n2 = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    *J = sqrt(n0 * n0 + n1 * n1 + n2 * n2);
    *cos_t = gh[0][0] * gh[1][0] + gh[0][1] * gh[1][1] + gh[0][2] * gh[1][2];
    *sin_t = *J / (p[0] * p[1]);
    return *sin_t > 0 ? WFF_POINT_OK : WFF_POINT_DEGENERATE;
}

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

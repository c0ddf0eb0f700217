/* The largest eigenvalue of M⁻¹K for an element's 24×24 stiffness K (N/m)
 * and a lumped mass m (kg) at every DOF, by 3000 steps of the power
 * iteration from a random start (the elements' stable-step tests: 2/√λ is
 * the element's own 2/ω_max). */
#ifndef WFF_TEST_POWER_ITERATION_H
#define WFF_TEST_POWER_ITERATION_H

#include "rng.h"

#include <math.h>

static inline double test_largest_frequency_squared(const double K[24][24], double m, wff_rng *r)
{
    double x[24], y[24], lambda = 0;
    for (int i = 0; i < 24; i++)
        x[i] = wff_rng_uniform(r, -1, 1);
    for (int it = 0; it < 3000; it++) {
        double n = 0;
        for (int i = 0; i < 24; i++) {
            y[i] = 0;
            for (int j = 0; j < 24; j++)
                y[i] += K[i][j] * x[j] / m;
            n += y[i] * y[i];
        }
        n = sqrt(n);
        lambda = n;
        for (int i = 0; i < 24; i++)
            x[i] = y[i] / n;
    }
    return lambda;
}

#endif

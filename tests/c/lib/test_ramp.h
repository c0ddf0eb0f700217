/* The tests' smooth prescribed motion: a (1 − cos) velocity ramp from 0 up
 * to V over t_ramp, a cruise at V for t_cruise, the mirror ramp down to 0
 * over t_ramp, then rest. Smooth in velocity so that a pull starts and stops
 * without a shock. */
#ifndef WFF_TEST_RAMP_H
#define WFF_TEST_RAMP_H

#include <math.h>

/* Velocity at time t (s) of the ramp-cruise-ramp motion (m/s, like V). */
static inline double test_ramp_velocity(double t, double V, double t_ramp, double t_cruise)
{
    const double t_move = 2 * t_ramp + t_cruise;
    if (t < t_ramp)
        return 0.5 * V * (1 - cos(M_PI * t / t_ramp));
    if (t > t_move)
        return 0;
    if (t > t_ramp + t_cruise)
        return 0.5 * V * (1 + cos(M_PI * (t - t_ramp - t_cruise) / t_ramp));
    return V;
}
#endif

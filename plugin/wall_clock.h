/* wall_clock.h: the monotonic wall clock, s (progress lines, timers). */
#ifndef WFF_WALL_CLOCK_H
#define WFF_WALL_CLOCK_H

#include <time.h>

static inline double wff_wall_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
#endif

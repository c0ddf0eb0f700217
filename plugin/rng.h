/* rng.h: deterministic random numbers, the same on every platform: the
 * xorshift64* generator with its state passed explicitly (no global state),
 * uniform numbers and Box–Muller normal ones. For synthetic fit data
 * (fit_data.c) and the C tests. Knows nothing else. */
#ifndef WFF_RNG_H
#define WFF_RNG_H

#include <math.h>
#include <stdint.h>

typedef struct wff_rng { uint64_t state; } wff_rng;

/* The next 64 random bits. */
static inline uint64_t wff_rng_next(wff_rng *r)
{
    r->state ^= r->state >> 12;
    r->state ^= r->state << 25;
    r->state ^= r->state >> 27;
    return r->state * 2685821657736338717ULL;
}

/* Uniform in [lo, hi) (53 random bits). */
static inline double wff_rng_uniform(wff_rng *r, double lo, double hi)
{
    return lo + (hi - lo) * ((double)(wff_rng_next(r) >> 11) / 9007199254740992.0);
}

/* Uniform in the open interval (0, 1): never 0, so log() of it is finite. */
static inline double wff_rng_open01(wff_rng *r)
{
    return ((double)(wff_rng_next(r) >> 11) + 0.5) / 9007199254740992.0;
}

/* Standard normal (Box–Muller, the cosine branch). */
static inline double wff_rng_normal(wff_rng *r)
{
    double u = wff_rng_open01(r), v = wff_rng_open01(r);
    return sqrt(-2 * log(u)) * cos(2 * M_PI * v);
}
#endif

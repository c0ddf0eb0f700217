/* Deterministic random numbers for tests (xorshift64*), state passed explicitly. */
#ifndef WFF_TEST_RNG_H
#define WFF_TEST_RNG_H
#include <stdint.h>

typedef struct rng { uint64_t s; } rng;

static inline double rng_uniform(rng *r, double lo, double hi)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    uint64_t x = r->s * 2685821657736338717ULL;
    return lo + (hi - lo) * ((double)(x >> 11) / 9007199254740992.0);
}
#endif

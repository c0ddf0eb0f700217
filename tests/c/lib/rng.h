/* The old names of the tests' random numbers (cell_suite.c uses them), kept
 * as aliases of plugin/rng.h: one generator for the core and the tests. */
#ifndef WFF_TEST_RNG_H
#define WFF_TEST_RNG_H
#include "../../../plugin/rng.h"

typedef wff_rng rng;
#define rng_uniform wff_rng_uniform
#endif

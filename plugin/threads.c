/* threads.c: the default thread count, what a run uses unless told: the
 * first level of OMP_NUM_THREADS when it is set, else the processors this
 * process may run on (its affinity mask, as a container or taskset limits
 * it; not the machine's count). Knows the process and the environment;
 * nothing of models, elements or FreeFEM. */
#define _GNU_SOURCE /* sched_getaffinity, CPU_COUNT */
#include "wovenff/membrane.h"
#include "wovenff/solver.h"

#include <sched.h>
#include <stdlib.h>
#ifdef _OPENMP
#include <omp.h>
#endif

int wff_default_threads(void)
{
    int n = 0;
    const char *env = getenv("OMP_NUM_THREADS");
    if (env && *env) {
        char *end;
        long first = strtol(env, &end, 10); /* "4" or "4,2" (nested levels) */
        if (end != env && first >= 1)
            n = first > WFF_MAX_THREADS ? WFF_MAX_THREADS : (int)first;
    }
    if (n == 0) {
        cpu_set_t set;
        CPU_ZERO(&set);
        if (sched_getaffinity(0, sizeof set, &set) == 0)
            n = CPU_COUNT(&set);
    }
#ifdef _OPENMP
    if (n == 0)
        n = omp_get_num_procs();
#endif
    if (n < 1)
        n = 1;
    return n > WFF_MAX_THREADS ? WFF_MAX_THREADS : n;
}

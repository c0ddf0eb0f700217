/* step_parts.h: how a per-step pass over DOFs, nodes or clamped nodes is
 * split for threads (step_threads.c, clamp.c): into parts whose bounds depend
 * on the item count alone (never on the thread count); a part sums its items
 * in order and the parts are added in order, so a result is the same bit for
 * bit whatever the number of threads. */
#ifndef WFF_STEP_PARTS_H
#define WFF_STEP_PARTS_H

#include "solver_internal.h"

/* Most parts a pass is split into (their partial sums live on the stack). */
#define MAX_PARTS 64
/* Items per part (the parts fix the sums' order; small parts balance the
 * threads) */
#define DOF_GRAIN 2048
#define NODE_GRAIN 512
/* Fewest DOFs for which a pass over the DOFs or nodes takes a team: a pass
 * costs ~1 ns a DOF, a team's start and end ~10 µs when its threads sleep
 * between passes (OMP_WAIT_POLICY=passive, tools/ff.sh's default) */
#define TEAM_MIN_DOFS 16384

/* Parts for n items at `grain` items a part: depends on n alone. */
static inline int wff_part_count(int n, int grain)
{
    int parts = n / grain;
    return parts < 1 ? 1 : parts > MAX_PARTS ? MAX_PARTS : parts;
}

static inline int wff_part_begin(int n, int parts, int k)
{
    return (int)((long long)n * k / parts);
}

/* Threads for a pass of `parts` parts: the model's, at most one a part;
 * one for a model too small to repay a team. */
static inline int wff_pass_threads(const wff_model *m, int parts)
{
    int t = m->n_dofs < TEAM_MIN_DOFS ? 1 : wff_elements_team(&m->el);
    return t > parts ? parts : t < 1 ? 1 : t;
}

/* Sum of the parts' partials in part order. */
static inline double wff_sum_parts(const double *partial, int parts)
{
    double s = 0;
    for (int k = 0; k < parts; k++)
        s += partial[k];
    return s;
}

#endif

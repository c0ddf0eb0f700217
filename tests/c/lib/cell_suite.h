/* The consistency suite every unit cell passes (docs/model.md §10): the ops
 * table's sizes against cell.h's limits, P = ∂W/∂F and R = −∂W/∂ΔA by
 * central differences at random states, zero stress and residual at the
 * reference state, objectivity, warp/weft swap symmetry, energy split adding
 * up, fast paths equal to evaluate(), degenerate input flagged, and the
 * stable-step estimates (docs/model.md §12) finite and upper bounds: an
 * explicit run of a clamped strip at 0.9x the estimated step stays bounded,
 * at 1.1x it grows (membrane and amplitude waves apart, each on a patch where
 * the estimate is tight: growth sets in between 1.00x and 1.05x). A new cell joins by adding one cell_case line to
 * tests/c/test_cells.c. */
#ifndef WFF_TEST_CELL_SUITE_H
#define WFF_TEST_CELL_SUITE_H

#include "check.h"
#include "wovenff/cell.h"

typedef struct cell_case {
    const char *material;          /* material file (repository-relative) */
    const char *swap_material;     /* same cell with equal warp/weft parameters, or NULL */
    double amplitude_range;        /* random ΔA in [−range, range/3], m */
    int energy_exact;              /* 1: stress and residual derive from W (check FD) */
} cell_case;

/* Load c->material, check the registry finds its cell, run cell_suite_check. */
void cell_suite_run(check_state *st, const cell_case *c);

/* Every check on a loaded material (also for a cell that is not registered;
 * c->material is then only the label). */
void cell_suite_check(check_state *st, const cell_case *c, const wff_material *mat);

/* The stable-step check alone on a loaded material (also for a cell that is
 * not registered); returns the number of its checks that failed. */
int cell_suite_stable_step(check_state *st, const wff_material *mat, const char *label);

#endif

/* The consistency suite every unit cell passes (MODEL.md §10, checks 1–4):
 * P = ∂W/∂F and R = −∂W/∂ΔA by central differences at random states, zero
 * stress and residual at the reference state, objectivity, warp/weft swap
 * symmetry, energy split adding up, stable-step estimates finite, degenerate
 * input flagged. A new cell joins by adding one cell_case line to
 * tests/c/test_cells.c. */
#ifndef WFF_TEST_CELL_SUITE_H
#define WFF_TEST_CELL_SUITE_H

#include "check.h"

typedef struct cell_case {
    const char *material;          /* material file (repository-relative) */
    const char *swap_material;     /* same cell with equal warp/weft parameters, or NULL */
    double amplitude_range;        /* random ΔA in [−range, range/3], m */
    int energy_exact;              /* 1: stress and residual derive from W (check FD) */
} cell_case;

void cell_suite_run(check_state *st, const cell_case *c);

#endif

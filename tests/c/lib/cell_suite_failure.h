/* The cell suite's yarn-failure path (docs/model.md §10, §20): run by
 * cell_suite_run on every cell whose type names damage states, on the case's
 * material with failure switched on (see cell_suite_failure.c). */
#ifndef WFF_TEST_CELL_SUITE_FAILURE_H
#define WFF_TEST_CELL_SUITE_FAILURE_H

#include "cell_suite.h"

/* Every failure check on c->material with failure on; nothing for a cell
 * without damage states. */
void cell_suite_failure(check_state *st, const cell_case *c);

#endif

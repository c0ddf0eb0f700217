/* state_fields.h: the model's evolving state field by field (plugin/state_fields.c):
 * what a checkpoint saves and the adaptive step keeps. */
#ifndef WFF_STATE_FIELDS_H
#define WFF_STATE_FIELDS_H

#include "part.h" /* (wff_state_field, a part's fields) */
#include "solver_internal.h"

#define WFF_STATE_FIELDS_MAX 96 /* room for what wff_state_fields gives: the model's 42 at
                                   most now, then the parts' (a pack's, its contact's and a
                                   backing's: 7 + 5 + 7 at most now) */

/* The fields in file order (pointer, element size, count) into f, with
 * n_candidates contact candidates; returns their number. */
int wff_state_fields(wff_model *m, int n_candidates, wff_state_field *f);

#endif

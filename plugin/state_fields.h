/* state_fields.h: the model's evolving state field by field (plugin/state_fields.c):
 * what a checkpoint saves and the adaptive step keeps. */
#ifndef WFF_STATE_FIELDS_H
#define WFF_STATE_FIELDS_H

#include "solver_internal.h"

typedef struct wff_state_field { void *data; size_t size, count; } wff_state_field;
#define WFF_STATE_FIELDS_MAX 48 /* room for what wff_state_fields gives: 42 at most now */

/* The fields in file order (pointer, element size, count) into f, with
 * n_candidates contact candidates; returns their number. */
int wff_state_fields(wff_model *m, int n_candidates, wff_state_field *f);

#endif

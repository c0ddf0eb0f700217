/* wovenff — which run-level features a model as configured takes
 * (plugin/combine.c; docs/freefem_api.md "wovenffRefuses").
 *
 * One answer, with its reason, to "can this model run with that?", asked
 * once by a scene before its run (ballistic_impact.edp: wffCombineCheck), in
 * place of cross-checks spread over the scene's option blocks. The model is
 * the one built: its material (cell, yarn failure and the erosion it turns
 * on), its plies, its zones. The run-level features are the things a scene
 * asks of it besides stepping:
 *   remesh             a mesh transfer (wovenffRemesh: the scenes' -adapt N)
 *   checkpoint         wovenffSaveCheckpoint (-checkpoint N)
 *   restart            wovenffLoadState from a checkpoint (-restart DIR)
 *   static_amplitudes  balanced amplitudes at every point (-amplitudes static)
 *   zones              zonal materials given after this check (-zonal R)
 *   erosion            erosion of failed elements (-failure on)
 *   obliquity          a projectile path tilted from the normal (-obliquity DEG)
 * The rules are one table in plugin/combine.c, each with its reason and
 * where the core also enforces it (the core's own refusals stay: they guard
 * the state reached, this check the configuration before a step). */
#ifndef WOVENFF_COMBINE_H
#define WOVENFF_COMBINE_H

#include <stddef.h>

#include "wovenff/solver.h"

/* 1 if the model m as configured refuses one of `features` (space-separated
 * names from the list above, the ones the run will use together), with the
 * reason in why (at most size bytes, NUL-terminated, truncated if longer):
 * "FEATURE: reason" or, for two features that do not go together,
 * "FEATURE with OTHER: reason"; the first rule of the table that applies.
 * 0 (why "") if they combine. -1 (why says which) for a name not in the
 * list: a misspelt feature is an error, never silently allowed. */
int wff_model_refuses(const wff_model *m, const char *features, char *why, size_t size);

/* The features the table knows, space-separated (for messages and tests). */
const char *wff_combine_features(void);

#endif

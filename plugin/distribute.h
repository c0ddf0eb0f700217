/* distribute.h: one model over the ranks of its communicator, the same bits
 * as one rank (plugin/distribute.c; docs/distributed.md). Every call is a
 * no-op for a model on one rank (m->dist NULL). */
#ifndef WFF_DISTRIBUTE_H
#define WFF_DISTRIBUTE_H

#include "solver_internal.h"

void wff_dist_free(wff_model *m);
/* Before a force pass over el (a model's, or a zone's: `global` its elements'
 * model indices): the model's split and el's masks, made once (out of memory:
 * the run cannot go on, and stops with a message). */
void wff_dist_prepare(wff_model *m, wff_elements *el, const int *global);
/* After a force pass's gather into f, one exchange: every rank's nodes'
 * forces to every rank (with static amplitudes, its elements' points'
 * amplitudes el->point_dA too: whole on every rank after every pass); the pass's sums t->sums and more[0..n_more) (a zone's,
 * NULL: none) reduced over the ranks, order-free; the Newton count summed; the
 * lowest bad element over the ranks (a second exchange, only then). */
int wff_dist_forces(wff_model *m, double *f, wff_force_totals *t, wff_fixed *more, int n_more);
/* n order-free sums of scratch for wff_dist_forces' more (NULL on one rank). */
wff_fixed *wff_dist_fixed_scratch(wff_model *m, int n);
/* 1 if element e (model order) is this rank's (always on one rank). */
int wff_dist_owns_element(const wff_model *m, int e);
/* Erosion: this rank's n_mine elements taken in a pass (m->eroded_now and
 * their energies, in element order) gathered from every rank in rank order
 * (element order): the count taken over the model. */
int wff_dist_eroded_gather(wff_model *m, int n_mine);
/* The points' states (m->state) whole on every rank: each rank's own. */
void wff_dist_states_whole(wff_model *m);

/* The part (part.h): its values mpi_ranks and exchange_seconds. */
extern const struct wff_part_ops wff_distributed_part;

#endif

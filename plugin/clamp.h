/* clamp.h: the friction clamp (plugin/clamp.c), what model.c, step_threads.c
 * and the whole-model operations share about it. */
#ifndef WFF_CLAMP_H
#define WFF_CLAMP_H

#include "solver_internal.h"

struct wff_part_ops;
/* The part (part.h): after the velocity update, the Coulomb correction of
 * every clamped node (nothing without a friction clamp). */
extern const struct wff_part_ops wff_clamp_part;

/* The clamping force (m->clamp.force_whole, whole specimen) shared among the
 * clamp's nodes into m->clamp.normal_force (modelled part): by area for a
 * surface group, by lumped mass for a curve group, only within clamp.radius
 * of (0, 0) when set; -1 (err set) when no node is within it or out of
 * memory. Called again whenever the masses, the symmetry or the radius
 * change. */
int wff_clamp_share(wff_model *m, wff_error *err);
/* The Coulomb correction of clamped node c (index into m->clamp.node) in v
 * (5 per node) over dt_mid: in-plane, two faces, on the node's free in-plane
 * components; its impulse (x, y, N·s) into impulse[2] unless NULL; returns the
 * energy it dissipates by the friction force over the slip left, J (model
 * part: a script's own loop's measure; the built-in step books the impulse
 * by part.h's book op instead). */
double wff_clamp_node(const wff_model *m, double *v, int c, double dt_mid, double *impulse);
/* The correction of every clamped node in v, threaded (the model's thread
 * count) with the same bits for any, the impulses into m->clamp.impulse
 * when `keep`; returns the dissipation as wff_clamp_node, J (model part). */
double wff_clamp_correct_all(const wff_model *m, double *v, double dt_mid, int keep);

/* The book op's work (part.h) of the impulses in m->clamp.impulse at m's
 * velocities and forces, counted with the friction; dt_before the step before
 * (0 at a start), dt_mid the step's Δt_mid. */
void wff_clamp_book(wff_model *m, double dt_before, double dt_mid);

#endif

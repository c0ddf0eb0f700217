/* wovenff — the verdict of a shot: perforated, stopped or undecided
 * (plugin/perforation.c; docs/limits.md "Perforation").
 *
 * A geometric test of the state now, not of speeds (torn fabric flaps faster
 * than the projectile long after the projectile is through it). For each ply
 * (a model without a pack is one ply) the part of it still *held*: the nodes
 * reached from a node whose u_z is held (the clamp, a fixed edge) through
 * elements not eroded (with no node held, every node of an element not
 * eroded); a fragment torn off whole is not the ply. Held fabric is *in the
 * way* when it lies on the nose or behind its tip (at most a ply's thickness,
 * the pack's ply_thickness, ahead of the tip: a ply resting on the nose has its
 * mid-plane on the nose's surface), or further ahead but held through *intact*
 * elements (not eroded, no yarn family ruptured at any of their points): a
 * piece lifted off ahead and held only through torn elements is a shred flung
 * off ahead, not a ply in the way. Then, on the shot line (the
 * projectile's axis, x and y of its impact point) and in the current
 * positions:
 *   - the ply is *holed* when no held element in the way covers the shot line
 *     (its projection on the x-y plane holds the axis point): the axis passes
 *     through eroded elements (or shreds ahead);
 *   - the projectile is *through* the ply when it is holed and every held node
 *     in the way within r of the axis (the projectile's footprint) lies behind
 *     the nose's rear, z < tip − the nose's length (hemisphere r, flat nose its
 *     edge radius, sphere 2r): the rim of the hole has slid onto the shank or
 *     off the nose.
 * The verdict: *perforated* when the projectile is through every ply and still
 * moves on (v > 0); else *stopped* when it has stopped or turned back (v <= 0:
 * the fabric, which only pushes it back, cannot send it on again); else
 * *undecided*. Every test reads positions: a node left with no element (a free
 * mass riding on the nose), a shred flung ahead and the speeds of flapping
 * fabric do not enter it. A run read at a fixed end time may be undecided:
 * the projectile still in the fabric and moving on. The verdict is of the
 * state now: a torn flap falling back onto the nose after a perforation can
 * make it undecided for a frame or two (a flat nose at 40 m/s on one ply: 3
 * frames of 20, the projectile's speed changed by 0.08 %); a loop ends at the
 * first perforated, as the scene does. */
#ifndef WOVENFF_PERFORATION_H
#define WOVENFF_PERFORATION_H

#include "wovenff/pack.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { WFF_VERDICT_UNDECIDED = -1, WFF_VERDICT_STOPPED = 0, WFF_VERDICT_PERFORATED = 1 };

typedef struct wff_perforation {
    int verdict;       /* WFF_VERDICT_PERFORATED, _STOPPED or _UNDECIDED */
    int plies;         /* plies of the model (1 without a pack) */
    int plies_holed;   /* plies whose held part in the way leaves the shot line open */
    int plies_through; /* plies the nose is through (holed, the footprint behind its rear) */
    double velocity;   /* the projectile's, along +z, m/s */
    double tip;        /* z of its nose tip, m */
    double rear;       /* z of its nose's rear, tip − the nose's length, m */
    int holed[WFF_PLIES_MAX];   /* per ply: 1 holed */
    int through[WFF_PLIES_MAX]; /* per ply: 1 the nose through it */
    double shot_z[WFF_PLIES_MAX]; /* per ply: its z on the shot line (the highest covering
                                     element in the way, interpolated; holed: the largest z of
                                     its held nodes in the way in the footprint, the hole's
                                     rim; NaN when there is none), m */
} wff_perforation;

/* The verdict of model m now into *out. -1 (err set) when the model has no
 * projectile, or out of memory. Reads the state only (one pass over the
 * elements and nodes of each ply). */
int wff_model_perforation(const wff_model *m, wff_perforation *out, wff_error *err);
/* The same for a caller's own loop (plugin/operators.c): the verdict at the
 * caller's displacements U (the caller's numbering, 5 per node, as
 * wff_model_forces takes them) with the projectile as the model holds it (the
 * last wff_model_contact set its tip and velocity); erosion as the caller's
 * wff_model_forces calls with dt > 0 left it. */
int wff_model_perforation_at(wff_model *m, const double *U, wff_perforation *out,
                             wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

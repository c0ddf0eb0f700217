/* ply_contact.h: the ply-to-ply contact of a pack (plugin/ply_contact.c), a
 * part of the step (part.h) and what the pack's files ask of it. */
#ifndef WFF_PLY_CONTACT_H
#define WFF_PLY_CONTACT_H

#include "part.h"
#include "plies.h"

/* The part: after the velocity update (after the projectile's contact), the
 * kinematic contact of one step, impulses on v, forces impulse/dt_mid into
 * f; its dissipation a term of the energy balance. Nothing without a pack of
 * two plies or more. */
extern const wff_part_ops wff_ply_contact_part;

/* The ply contact of one step (the part's correct op); -1 (err set) if out of
 * memory. */
int wff_ply_contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err);
/* The contact thickness t, m: ply_thickness when set, else from rho_A. */
double wff_ply_thickness(const wff_model *m);
/* The contact distance h = min(t, gap) of the mid-planes (m). */
double wff_ply_contact_distance(const wff_model *m);
/* The interpenetration's bound, m: h + the crossing allowance of the node with
 * the longest shortest edge (a pair deeper is left out as crossed); h before
 * the first step. */
double wff_ply_penetration_bound(const wff_model *m);
/* Free the contact's workspace in P (the pack's free). */
void wff_ply_contact_free(struct wff_pack *P);

#endif

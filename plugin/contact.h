/* contact.h: the projectile's kinematic contact (plugin/contact.c), a part
 * of the step (part.h), and the calls the whole-model operations (operators.c,
 * remesh.c) and the settings (model.c) make to it. */
#ifndef WFF_CONTACT_H
#define WFF_CONTACT_H

#include "part.h"

/* The part: the contact candidates refreshed with the stable step; after the
 * velocity update, the contact and friction impulses of the step. Nothing
 * without a projectile. */
extern const wff_part_ops wff_projectile_contact_part;

/* The nodes near enough the projectile's axis to touch it before
 * the next refresh (every node with contact_search 0). */
void wff_contact_refresh_candidates(wff_model *m);
/* The kinematic contact and friction impulses of one step, added
 * to f as forces over dt_mid; -1 (err set) if the projectile has passed
 * through the fabric. */
int wff_contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err);
/* Its impulses' work booked into the friction dissipation at the final
 * velocities (part.h's book op: after every correction of the step; dt_before
 * the step just taken, 0 at a start; dt_mid the step's Δt_mid). */
void wff_contact_book(wff_model *m, double dt_before, double dt_mid);

/* The signed distance of point x from the projectile's surface as it is now
 * (m, > 0 outside, −δ of wff_projectile_penetration inside) and the outward
 * normal at the nearest surface point (always set). */
double wff_projectile_gap(const wff_projectile *p, const double x[3], double normal[3]);

/* projectile_shape.c: the chisel's depth of point x (> 0 inside: the least of
 * its four faces', the normal that face's; <= 0 outside, a lower bound of the
 * distance) and its penetration (0 outside); the oblique projectile's frame:
 * x in it (y; `local` the projectile as a normal shot at the frame's origin)
 * and a normal of it turned back into the fabric's frame; -1 (err set) for an
 * oblique path with a symmetric model. */
double wff_chisel_depth(const wff_projectile *p, const double x[3], double normal[3]);
double wff_chisel_penetration(const wff_projectile *p, const double x[3], double normal[3]);
void wff_projectile_to_frame(const wff_projectile *p, const double x[3], double y[3],
                             wff_projectile *local);
void wff_projectile_from_frame(const wff_projectile *p, double normal[3]);
int wff_contact_oblique_check(double symmetry, const wff_projectile *p, wff_error *err);

/* The symmetry factor changed (or the axis did): the projectile's
 * modelled mass follows; -1 (err set) if its axis is off the symmetry
 * planes. */
int wff_contact_symmetry_changed(wff_model *m, wff_error *err);
/* Move the projectile back along z until no node is inside it
 * now; returns the distance, m. */
double wff_contact_retract(wff_model *m);

#endif

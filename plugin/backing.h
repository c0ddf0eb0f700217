/* backing.h: the backing block behind the pack (plugin/backing.c, the part;
 * plugin/backing_contact.c, its contacts with the back ply and the
 * projectile; the solid itself is plugin/solids/block.h). docs/backing.md. */
#ifndef WFF_BACKING_H
#define WFF_BACKING_H

#include "part.h"
#include "solids/block.h"

/* The contacts of one step between the back ply's nodes and the block's top
 * face (node to face: a ply node over the face's bilinear quad), a damped
 * penalty spring with Coulomb friction (backing_contact.c). */
/* Points of a back-ply node's footprint on the block's face: the centres
 * of the four quarters of the square of its tributary area (each takes a
 * quarter of its contact: the node is not a needle on a face finer than the
 * fabric, backing_contact.c). */
#define WFF_FOOTPRINT_POINTS 4

typedef struct wff_face_contacts {
    int n, max;            /* this step's contacts; room for */
    int *node;             /* the fabric node */
    int *slot;             /* its footprint point, WFF_FOOTPRINT_POINTS t + k (t the back-ply
                              node's index in ply_nodes) */
    int *face;             /* the face's 4 block nodes */
    double *weight;        /* their bilinear weights N_a at the footprint point */
    double *normal;        /* the face's unit normal out of the block, 3 */
    double *gap;           /* the gap now (< 0: overlapping), m */
    double *lambda;        /* the point's normal impulse (on its fabric node), N·s */
    double *bound;         /* the most it may take this step, the spring's F Δt_mid, N·s */
    double *mobility;      /* 1/m_eff of the point's node and face along a direction, 1/kg */
    double *impulse;       /* the point's impulse on its fabric node, normal and friction, 3 */
} wff_face_contacts;

struct wff_backing {
    int law;                 /* WFF_BLOCK_NONE, _CLAY, _GELATIN (setting backing) */
    double depth, finest, growth, mu, hourglass, gap; /* the settings backing_depth,
                                backing_element (m), backing_growth, backing_mu,
                                backing_hourglass, backing_gap (m) */
    double hourglass_damping; /* the setting backing_hourglass_damping (ζ, hex8.h) */
    int integration;         /* the setting backing_integration: 0 the one-point element with
                                hourglass control, 1 fully integrated (F-bar; hex8.h) */
    int built;               /* 1: the block is made (at the run's first step) */
    wff_block block;
    int *ply_nodes, n_ply_nodes; /* the back ply's nodes that may touch the block */
    double *ply_area;        /* per back-ply node (as ply_nodes): its tributary area, m²
                                (the friction's cap: backing_contact.c) */
    double *ply_gap;         /* per footprint point (slot): its gap to the face at the last
                                step, m (0 out of contact) */
    double *ply_held;        /* per footprint point: the part of its overlap no approach made
                                (a jump of the face under it), held, not pushed out, m */
    unsigned char *on_nose;  /* per model node: 1 while the projectile's contact holds it
                                this step (set and cleared by the ply contact below) */
    wff_face_contacts contacts;
    double *block_impulse;   /* per block DOF, this step's contact impulses, N·s */
    double projectile_dv;    /* the projectile's velocity change by the block this step, m/s */
    int projectile_contacts; /* block nodes the projectile pressed this step */
    struct {                 /* its evolving account (one field of the checkpoint) */
        long started;        /* 1 once the block has taken its first half step (a long: the
                                struct has no padding, its bytes all its own) */
        long samples;        /* force passes of the block so far */
        double dt_next;      /* the step planned at the last correction, s */
        double block_step;   /* s, the block's stable step (refreshed every few passes) */
        /* the balance (model part, J) */
        double work_fabric, work_projectile, work_block; /* the contact impulses' work on
                                the fabric, the projectile and the block so far, J */
        double kinetic;      /* the block's kinetic energy, the balance's measure, J */
        double kinetic_peak; /* its largest so far, J (the crater has settled when the
                                kinetic energy is a small part of it) */
        double peak_depth;   /* the top face's largest indentation so far, m */
        double stiffness_per_mass; /* the ply-on-block springs' stiffness per kg of node,
                                1/s² (fixed at the first step: backing_contact.c) */
    } run;
    double overlap;          /* the back ply's largest overlap with the face, the last step, m */
    double seconds;          /* wall time in the block and its contacts, s */
};

extern const wff_part_ops wff_backing_part;

/* The back ply's nodes against the block's top face through their
 * footprints (a footprint point closer than h, m, slowed by a damped penalty
 * spring, no more than stops its approach; Coulomb friction mu capped by the
 * clay's shear strength): impulses on both (the fabric's velocities and the
 * block's) over dt_mid; dt the step to be taken (the spring's stiffness).
 * Fills B->contacts (a contact a footprint point) and B->block_impulse.
 * Returns the largest overlap now, m. */
double wff_backing_ply_contact(wff_model *m, struct wff_backing *B, double h, double dt,
                               double dt_mid);

/* The block's top-face nodes against the rigid projectile (frictionless):
 * impulses on the nodes (into B->block_impulse) and the projectile's velocity
 * change (B->projectile_dv, applied to m->projectile.velocity). */
void wff_backing_projectile_contact(wff_model *m, struct wff_backing *B, double dt);

/* A rigid body's penetration δ (> 0 inside) of point x and the outward
 * normal there, the body moved along +z by `advance` (m). */
typedef double (*wff_rigid_penetration)(const void *body, double advance, const double x[3],
                                        double normal[3]);

/* The top-face nodes of b against a rigid body of mass `mass` (kg) moving
 * along +z at *velocity (m/s, changed by the impulses), frictionless,
 * kinematic: no node ends the step dt inside it (to the sweeps' tolerance).
 * Impulses on the nodes added to impulse (3 per block node, N·s, may be NULL)
 * and to b->v. Returns the number of nodes pressed. */
int wff_block_rigid_contact(wff_block *b, wff_rigid_penetration penetration, const void *body,
                            double mass, double *velocity, double dt, double *impulse);

#endif

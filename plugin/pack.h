/* pack.h: what the solver's files share about multi-ply packs (plugin/pack.c,
 * plugin/ply_contact.c; the public calls are in include/wovenff/pack.h). A
 * model without a pack (m->pack NULL) or of one ply takes the plain path
 * everywhere. Ply p's nodes are p·n .. p·n + n − 1 in the model's order too
 * (the specimen's model order, stacked), its triangles p·t .., its quads
 * N·t + p·q .. (the model's element numbering, triangles first). */
#ifndef WFF_PACK_INTERNAL_H
#define WFF_PACK_INTERNAL_H

#include "solver_internal.h"
#include "wovenff/pack.h"

struct wff_pack {
    int n;                    /* plies */
    double gap;               /* initial spacing of the mid-planes, m */
    int nodes, tris, quads;   /* per ply */
    double mu;                /* ply-on-ply Coulomb friction */
    double thickness;         /* contact thickness t, m (0: the default from rho_A) */
    double orientation[WFF_PLIES_MAX]; /* each ply's warp direction, rad */
    /* energies per ply, model part, J */
    double shear[WFF_PLIES_MAX], failure[WFF_PLIES_MAX], eroded[WFF_PLIES_MAX];
    double stored[WFF_PLIES_MAX];
    double removed[WFF_PLIES_MAX]; /* eroded in the pass under way (erosion.c) */
    /* ply contact (ply_contact.c) */
    double dissipated;        /* kinetic energy the ply contact removed, J (model part) */
    double penetration;       /* largest interpenetration left after the last correction, m */
    int contacts;             /* node pairs corrected in the last step */
    double *impulse;          /* per DOF (3 per node), this step's contact impulses, N·s */
    unsigned char *touched;   /* per node: an impulse this step */
    int *touched_list, n_touched;
    int *active, n_active;    /* node pairs corrected in this step's first sweep */
    int *on_projectile;       /* per node: its index in the projectile's contacts this step,
                                 -1 if none (such a node moves with the projectile along z) */
    double *normal;           /* per node: its ply's normal at the predicted positions (3) */
    unsigned char *live;      /* per node: 1 if an element of it has not eroded */
    double *reach;            /* per specimen node: its shortest reference edge, m */
    double projectile_dv;     /* the projectile's velocity change by the ply contact, m/s */
    double seconds;           /* wall time spent in the ply contact so far, s */
    double *predicted;        /* per node: its position at t + dt before the correction (3) */
    int *facet;               /* per facet of a ply: its specimen nodes, counter-clockwise (3) */
    double *rest;             /* per pair: h − distance after sweep 0, m (the measure's) */
    int left_out;             /* pairs left out in the last step (fragment, slid apart, crossed) */
};

static inline int wff_pack_plies(const wff_model *m)
{
    return m->pack ? m->pack->n : 1;
}

static inline int wff_pack_element_ply(const wff_model *m, int e)
{
    const struct wff_pack *P = m->pack;
    if (!P || P->n == 1)
        return 0;
    int nt = P->n * P->tris;
    return e < nt ? e / P->tris : (e - nt) / P->quads;
}

static inline int wff_pack_node_ply(const wff_model *m, int n)
{
    return m->pack && m->pack->n > 1 ? n / m->pack->nodes : 0;
}

static inline double wff_pack_orientation(const wff_model *m, int p)
{
    return m->pack && p >= 0 && p < m->pack->n ? m->pack->orientation[p] : m->em.orientation;
}

/* The contact distance h = min(t, gap) of the mid-planes (m). */
double wff_pack_contact_distance(const wff_model *m);

void wff_pack_free(wff_model *m);
/* integrator.c, after an accumulating force pass: the per-ply energies. */
void wff_pack_accumulate(wff_model *m);
/* erosion.c: element e (model numbering) eroded with stored energy `energy`. */
void wff_pack_eroded(wff_model *m, int e, double energy);
/* model.c: the model-wide orientation set: every ply's. */
void wff_pack_orientation_all(wff_model *m, double theta);
/* model.c: the settings ply_mu and ply_thickness; 1 if key is one of them (the
 * result in *rc), 0 otherwise. */
int wff_pack_set_option(wff_model *m, const char *key, double value, int *rc, wff_error *err);

/* ply_contact.c: the kinematic contact of one step (after the projectile's),
 * impulses on v, forces impulse/dt_mid into f, the dissipation counted; -1 (err
 * set) if out of memory. */
int wff_ply_contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err);
/* The interpenetration's bound, m: h + the crossing allowance of the node with
 * the longest shortest edge (a pair deeper is left out as crossed); h before
 * the first step. */
double wff_ply_penetration_bound(const wff_model *m);
void wff_ply_contact_free(struct wff_pack *P);

#endif

/* plies.h: the layout of a multi-ply pack (struct wff_pack, plugin/pack.c
 * and plugin/ply_contact.c fill it) and the inline look-ups of a node's or an
 * element's ply, which every layer may read. A model without a pack
 * (m->pack NULL) or of one ply is one ply everywhere. Ply p's nodes are
 * p·n .. p·n + n − 1 in the model's order too (the specimen's model order,
 * stacked), its triangles p·t .., its quads N·t + p·q .. (the model's element
 * numbering, triangles first). */
#ifndef WFF_PLIES_H
#define WFF_PLIES_H

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
    double slip[WFF_PLIES_MAX]; /* yarn slip at the crossovers */
    double stored[WFF_PLIES_MAX];
    double removed[WFF_PLIES_MAX]; /* eroded in the pass under way (erosion.c) */
    double first_damage_time[WFF_PLIES_MAX]; /* s, the time of the first force pass that
                                                damaged a yarn of the ply; -1 while intact */
    /* ply contact (ply_contact.c) */
    double dissipated;        /* kinetic energy the ply contact's pairs removed, J (model
                                 part; the nose contacts its solve holds are the projectile
                                 contact's, in m->dissipated_friction) */
    double penetration;       /* largest interpenetration left after the last correction, m */
    int contacts;             /* node pairs corrected in the last step */
    double *impulse;          /* per DOF (3 per node), this step's pairs' impulses, N·s */
    double *nose_impulse;     /* per DOF (3 per node), this step's impulses of the nose
                                 contacts the solve holds, N·s */
    unsigned char *touched;   /* per node: an impulse this step */
    int *touched_list, n_touched;
    int *on_projectile;       /* per node: its index in the projectile's contacts this step,
                                 -1 if none (the solve holds such a node on the nose) */
    double *normal;           /* per node: its ply's normal at the predicted positions (3) */
    unsigned char *live;      /* per node: 1 if an element of it has not eroded */
    double *reach;            /* per specimen node: its shortest reference edge, m */
    double projectile_dv;     /* the projectile's velocity change by the ply contact, m/s */
    double seconds;           /* wall time spent in the ply contact so far, s */
    double *predicted;        /* per node: its position at t + dt before the correction (3) */
    int *facet;               /* per facet of a ply: its specimen nodes, counter-clockwise (3) */
    double *rest;             /* per pair: h − distance after sweep 0, m (the measure's) */
    int left_out;             /* pairs left out in the last step (fragment, slid apart, crossed) */
    int *node_facets;         /* per specimen node: its facets, from node_facet_start[i] (CSR) */
    int *node_facet_start;    /* nodes + 1 */
    struct wff_ply_solve *solve; /* the contact's solve: its workspace (ply_contact.c) */
    int sweeps;               /* sweeps over the columns in the last step */
    int nose_step_alone;      /* 1: the nose friction's step sized for its node alone (the
                                 plain solve, a reference for tests/c/test_ply_sweeps.c);
                                 0 (the default): for the stack stuck behind the node,
                                 while erosion is off (plugin/ply_column.c) */
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

#endif

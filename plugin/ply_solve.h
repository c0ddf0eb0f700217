/* ply_solve.h: the ply contact's column solve (plugin/ply_column.c), shared
 * with the contact's set-up and its step (plugin/ply_contact.c): the solve's
 * workspace and the step's constants, the inverse masses and the impulse a
 * node is given, and the column's operations. Internal to the ply contact. */
#ifndef WFF_PLY_SOLVE_H
#define WFF_PLY_SOLVE_H

#include "plies.h"

#include <stddef.h>

/* A column's constraints: at most a nose contact per ply and a pair per
 * neighbouring plies. */
#define COLUMN_MAX (2 * WFF_PLIES_MAX)
/* Projected Gauss-Seidel sweeps over a column whose pivoting did not settle
 * (a fallback: not met on the scenes measured). */
#define COLUMN_PGS_SWEEPS 200
/* Sweeps over the columns in contact (block Gauss-Seidel: each column's
 * constraints solved together, the columns coupled through the normals'
 * facets and the projectile), until the largest change a sweep makes to a
 * constraint's gap (normal or, with friction, tangential) is below
 * SWEEP_TOLERANCE h. */
#define MAX_SWEEPS 30
#define SWEEP_TOLERANCE 1e-6
/* A pair whose friction is within STICK_MARGIN of its cone's edge slips. */
#define STICK_MARGIN 1e-6

enum { PAIR = 0, NOSE = 1 };

/* The solve's workspace, allocated at the first step. A constraint is a pair
 * (node i of ply p and of the first live ply above it) or a node held on the
 * projectile's nose; a column is every constraint at specimen node i. */
struct wff_ply_solve {
    /* each specimen node's ring: itself first, then every other node of its
     * facets (CSR) */
    int *ring_start, *ring_node, ring_total;
    int *ring_corner;       /* per entry of node_facets: the facet's corners' places in the ring (3) */
    double *gradient;       /* per slot (pair p, node i): the pair constraint's gradient on
                               ply A's ring of i, then ply B's, 3 per ring node, from
                               6 (p ring_total + ring_start[i]) */
    double *v_first;        /* per node: its velocity at the step's first look (3) */
    unsigned char *in_column; /* per specimen node: a pair of its column is in contact */
    int *columns, n_columns;
    int *column_start;      /* the columns' constraints, n_columns + 1 */
    int max_constraints;
    /* per constraint */
    unsigned char *kind;    /* PAIR, NOSE */
    int *slot;              /* a pair's slot (pair p, node i) = p nodes + i; a nose's node */
    int *a, *b;             /* a pair's nodes A (below) and B; a nose's node, -1 */
    double *lambda;         /* the normal impulse this solve gave it, N·s */
    double *lo;             /* its lower bound (0; a nose: minus the projectile contact's) */
    double *g;              /* its gap at the first look, m (pair: distance − h) */
    double *target;         /* the gap the step ends at, at least, m */
    double *diag;           /* W = G M⁻¹ Gᵀ: its diagonal, */
    double *off;            /* and its entries with the one and two before it in the column (2) */
    double *normal;         /* a pair's unit normal, a nose's outward normal (3) */
    double *friction;       /* a pair's friction impulse on B (−on A), accumulated (3) */
};

/* The solve's state that every constraint reads. */
struct solve_step {
    double h, dt, dt_mid;
    double v_projectile;   /* the projectile's velocity at the first look, m/s */
};

static inline double *gradient_of(const struct wff_pack *P, int slot)
{
    const struct wff_ply_solve *S = P->solve;
    const int p = slot / P->nodes, i = slot % P->nodes;
    return S->gradient + 6 * ((size_t)p * (size_t)S->ring_total + (size_t)S->ring_start[i]);
}

/* The inverse mass of component c of node n: 0 if held (its support takes an
 * impulse on it). */
static inline double inverse_mass_of(const wff_model *m, int n, int c)
{
    return m->dof_kind[D * n + c] == WFF_DOF_FREE ? 1 / m->mass[D * n] : 0;
}

/* The inverse mass of node n along direction d (its free components). */
static inline double inverse_mass(const wff_model *m, int n, const double d[3])
{
    double w = 0;
    for (int c = 0; c < 3; c++)
        w += d[c] * d[c] * inverse_mass_of(m, n, c);
    return w;
}

/* Add impulse j (3) to node n: its free components' velocities, the held
 * ones' reactions; the node's share kept for the forces and work in `account`
 * (P->impulse, a pair's; P->nose_impulse, a nose contact's: its work is the
 * projectile contact's). */
static inline void give(wff_model *m, int n, const double j[3], double dt_mid, double *account)
{
    struct wff_pack *P = m->pack;
    if (j[0] == 0 && j[1] == 0 && j[2] == 0)
        return;
    for (int c = 0; c < 3; c++) {
        if (m->dof_kind[D * n + c] != WFF_DOF_FREE) {
            m->reaction[D * n + c] -= j[c] / dt_mid;
            continue;
        }
        m->v[D * n + c] += j[c] / m->mass[D * n];
        account[3 * n + c] += j[c];
    }
    if (!P->touched[n]) {
        P->touched[n] = 1;
        P->touched_list[P->n_touched++] = n;
    }
}

double wff_ply_gap_now(const wff_model *m, const struct solve_step *T, int c);
double wff_ply_self_coupling(const wff_model *m, int c);
double wff_ply_coupling(const wff_model *m, int c, int d);
void wff_ply_apply_normal(wff_model *m, const struct solve_step *T, int c, double x);
double wff_ply_solve_column(wff_model *m, const struct solve_step *T, int start, int K);
double wff_ply_pair_friction(wff_model *m, const struct solve_step *T, int start, int K);
double wff_ply_nose_friction(wff_model *m, const struct solve_step *T, int start, int K);

/* Facets per ply: triangles, then two per quad. */
static inline int facet_count(const struct wff_pack *P)
{
    return P->tris + 2 * P->quads;
}

/* The workspace of the pack's contact (ply_workspace.c), made at its first
 * step: the facets, the rings, the solve's arrays; -1 (err set) if out of
 * memory. */
int wff_ply_workspace(wff_model *m, wff_error *err);
#endif

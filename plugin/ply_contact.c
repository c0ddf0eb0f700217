/* ply_contact.c: kinematic contact between neighbouring plies of a pack
 * (include/wovenff/pack.h). Every ply is a two-sided surface of thickness t:
 * the mid-planes of plies p and p + 1 keep h = min(t, gap) apart. The plies
 * are copies of one mesh, coincident in plane at the start, so the contact is
 * node to node: node i of ply p against node i of ply p + 1 (a symmetric rule,
 * no facet search). A pair's constraint is
 *     g = (x_B − x_A)·N/|N| − h >= 0,   N = N_A + N_B
 * (the raw sums of the facets' normals at node i of the two plies, at the
 * predicted positions x = X + u + Δt v); its gradient G is −n on A, +n on B and
 * s·∂N/∂x_k / |N| on the nodes of their facets (s the pair's in-plane offset:
 * N turns with those nodes), and sums to 0 (momentum kept exactly). Every
 * impulse is along a constraint's gradient (one on A and B alone, along n,
 * worked against the normal's turn and put energy in: docs/model.md §23).
 *
 * The solve (each step, after the projectile's contact). The columns: every
 * specimen node i at which a pair is closer than h at the first look; a
 * column's constraints are all its pairs (ply by ply, through holes) and the
 * nose contacts of its nodes (a node the projectile's contact pushed this
 * step, or within NOSE_MARGIN h of the nose: the strike face held between the
 * nose and the stack; gradient: the nose's outward normal on the node, −n_z on
 * the projectile, which moves along z), each linearised at the first look:
 *     g(v) = g_first + Δt G·(v − v_first).
 * The impulses λ >= lo (0; a nose contact may take back the projectile
 * contact's normal impulse, not more) solve the linear complementarity problem
 *     W λ − y >= 0,  λ >= lo,  (λ − lo)·(W λ − y) = 0,   W = G M⁻¹ Gᵀ,
 *     y = (target − g(v))/Δt,
 * a column at a time (its W banded: half-bandwidth 2 in its order; solved by
 * pivoting on the constraints at their bound, an LDLᵀ of the band per pivot),
 * the columns swept in turn (block Gauss-Seidel: they are coupled only through
 * the facets' terms and the projectile) until a sweep moves no gap by more
 * than SWEEP_TOLERANCE h. The target is 0 (the distance h), or for a pair
 * already closer than h now (its depth d = −(g_first − Δt G·v_first): along the
 * whole gradient, not n alone, so that a normal that turns under a pair is not
 * read as a depth) −(1 − r) d, r = RECOVERY per full step (dtfactor × the
 * stable step; a shorter step its share), and −d above RECOVERY_SPAN h (a
 * pair that got there by a jump of its geometry, not this step's approach, is
 * only stopped from closing). With the column's pairs in one solve no depth is
 * left to accumulate (a sweep over pairs passes an impulse one pair a sweep:
 * a chain of plies is a 1-D Laplacian to it, and 20 sweeps left the pairs under
 * the nose closing, pushed out afterwards: energy in). Coulomb friction on
 * each constraint against its tangential relative velocity (a pair's B − A,
 * μ = ply_mu; a nose's node less the projectile, μ the projectile's, with the
 * projectile contact's friction), its accumulated impulse F held in the cone
 * |F| <= μ λ (stick if the cone allows), after each column's normal solve.
 *
 * Through a hole: a node whose facets have all eroded has no pair; node i of
 * the ply below it pairs with node i of the first ply above it that has a
 * facet left (plies p − 1 and p + 1 through ply p's hole, the same contact
 * distance h: the eroded ply is not there). Left out: a pair with a fragment (a
 * dead node with no live ply above it; the normals are of the facets left),
 * one slid apart in plane by more than SLIP_LIMIT of the node's shortest edge,
 * one that has crossed (a torn ply's nodes dragged away from their partners). A
 * component held by a boundary condition takes no impulse: its support's
 * reaction does. The impulses enter f as forces j / Δt_mid; their work at the
 * trapezoidal rule's measure (the book op), negated, is the ply contact
 * dissipation, the pairs' (a term of the energy balance), and the nose
 * contacts' the projectile contact's (dissipated_friction: they are that
 * contact, solved again). No effect on the stable step.
 * Limits: the pairs are fixed, so the relative in-plane slip of neighbouring
 * plies must stay small against the element size (a ply that slides by more
 * meets its neighbour's node i still, not the node now below it); plies pair
 * with their neighbours only, or with the next live one through a hole
 * (enough while plies cannot pass each other, which the contact keeps). The
 * normals pass runs one ply a thread; the solve is serial. */
#include "ply_contact.h"
#include "contact.h"
#include "wall_clock.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Interpenetration below ROUND_OFF h is round-off of the flat pack's
 * coordinates (z = p gap), not contact. */
#define ROUND_OFF 1e-9
/* A pair clear of contact by (1 − FILTER_SHARE ROUND_OFF) h takes the squared
 * test; between that and (1 − ROUND_OFF) h, the exact one. */
#define FILTER_SHARE 0.5
#define FILTER_SQUARED ((1 - FILTER_SHARE * ROUND_OFF) * (1 - FILTER_SHARE * ROUND_OFF))
/* Sweeps over the columns in contact (block Gauss-Seidel: each column's
 * constraints solved together, the columns coupled through the normals'
 * facets and the projectile), until the largest change a sweep makes to a
 * constraint's gap (normal or, with friction, tangential) is below
 * SWEEP_TOLERANCE h. */
#define MAX_SWEEPS 30
#define SWEEP_TOLERANCE 1e-6
/* The share of an interpenetration already there that a full step removes. */
#define RECOVERY 0.2
/* An interpenetration already there that is above RECOVERY_SPAN h did not come
 * from this step's approach but from a jump of the pair's geometry (a tear, an
 * element eroded beside it, a normal that turned): the pair only stops closing
 * further (an inelastic impulse: it can only take energy out). Pushing such a
 * pair apart at RECOVERY of it per step would fling its nodes at km/s (seen: a
 * torn 4-ply pack, 2 mm at 0.2 per 5e-8 s step, 6 km/s). */
#define RECOVERY_SPAN 0.05
/* A pair whose nodes are now on each other's far side by more than
 * CROSS_LIMIT of the node's shortest reference edge has crossed (a torn ply's
 * node dragged past its partner): left out. (Measured at the positions now, so
 * a pair that would cross in this step is corrected, at any gap, 0 too.) */
#define CROSS_LIMIT 0.01
/* A pair whose nodes have slid apart in plane by more than SLIP_LIMIT of the
 * node's shortest reference edge no longer faces each other: it is left out. */
#define SLIP_LIMIT 0.5
/* A node of a column in contact within NOSE_MARGIN h of the projectile's
 * surface (predicted), or one the projectile's contact pushed this step, is
 * held on the nose by the column's solve. */
#define NOSE_MARGIN 1.0
/* Fewest DOFs for which the normals take a team (as the step's passes,
 * step_threads.c: a team's start costs ~10 µs) */
#define PLY_TEAM_MIN_DOFS 16384
/* A column's constraints: at most a nose contact per ply and a pair per
 * neighbouring plies. */
#define COLUMN_MAX (2 * WFF_PLIES_MAX)
/* Projected Gauss-Seidel sweeps over a column whose pivoting did not settle
 * (a fallback: not met on the scenes measured). */
#define COLUMN_PGS_SWEEPS 200

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

static void solve_free(struct wff_ply_solve *S)
{
    if (!S)
        return;
    free(S->ring_start), free(S->ring_node), free(S->ring_corner);
    free(S->gradient), free(S->v_first), free(S->in_column), free(S->columns);
    free(S->column_start), free(S->kind), free(S->slot), free(S->a), free(S->b);
    free(S->lambda), free(S->lo), free(S->g), free(S->target), free(S->diag), free(S->off);
    free(S->normal), free(S->friction);
    free(S);
}

void wff_ply_contact_free(struct wff_pack *P)
{
    free(P->impulse);
    free(P->nose_impulse);
    free(P->touched);
    free(P->touched_list);
    free(P->on_projectile);
    free(P->normal);
    free(P->live);
    free(P->reach);
    P->normal = P->reach = NULL;
    P->live = NULL;
    P->on_projectile = NULL;
    free(P->predicted);
    free(P->facet);
    free(P->rest);
    P->rest = NULL;
    free(P->node_facets);
    free(P->node_facet_start);
    P->node_facets = P->node_facet_start = NULL;
    solve_free(P->solve);
    P->solve = NULL;
    P->facet = P->touched_list = NULL;
    P->impulse = P->nose_impulse = P->predicted = NULL;
    P->touched = NULL;
}

/* Facets per ply: triangles, then two per quad. */
static int facet_count(const struct wff_pack *P)
{
    return P->tris + 2 * P->quads;
}

/* The specimen-local nodes of facet f (ply 0's connectivity: the first
 * triangles and quads of the model's mesh are ply 0's). */
static void facet_nodes(const wff_model *m, int f, int out[3])
{
    const struct wff_pack *P = m->pack;
    if (f < P->tris) {
        const int *t = m->mesh.tri + 3 * f;
        out[0] = t[0], out[1] = t[1], out[2] = t[2];
    } else {
        int q = (f - P->tris) / 2, second = (f - P->tris) % 2;
        const int *c = m->mesh.quad + 4 * q;
        out[0] = c[0];
        out[1] = second ? c[2] : c[1];
        out[2] = second ? c[3] : c[2];
    }
    /* counter-clockwise in the reference plane, so that the normal is +z there
     * (a mesh may list an element either way round) */
    const double *xy = m->mesh.xy, *p0 = xy + 2 * out[0], *p1 = xy + 2 * out[1],
                 *p2 = xy + 2 * out[2];
    if ((p1[0] - p0[0]) * (p2[1] - p0[1]) - (p2[0] - p0[0]) * (p1[1] - p0[1]) < 0) {
        int t = out[1];
        out[1] = out[2], out[2] = t;
    }
}

/* The model's element of facet f of ply q (pack.h's order: every ply's
 * triangles, then every ply's quads). */
static inline int facet_element(const struct wff_pack *P, int q, int f)
{
    return f < P->tris ? q * P->tris + f : P->n * P->tris + q * P->quads + (f - P->tris) / 2;
}

/* Node n's position at u + s v (s = 0: now; s = Δt: predicted). */
static inline void position(const wff_model *m, int n, double s, double x[3])
{
    const double *u = m->u + D * n, *v = m->v + D * n;
    x[0] = m->mesh.xy[2 * n] + u[0] + s * v[0];
    x[1] = m->mesh.xy[2 * n + 1] + u[1] + s * v[1];
    x[2] = u[2] + s * v[2];
}

/* The rings (each specimen node first, then every other node of its facets)
 * and each of a node's facets' corners' places in its ring; -1 (err set) if
 * out of memory. */
static int build_rings(wff_model *m, struct wff_ply_solve *S, wff_error *err)
{
    const struct wff_pack *P = m->pack;
    const int nn = P->nodes, entries = P->node_facet_start[nn];
    int *stamp = malloc(sizeof(int) * (size_t)nn), *place = malloc(sizeof(int) * (size_t)nn);
    S->ring_start = calloc((size_t)nn + 1, sizeof(int));
    S->ring_corner = malloc(sizeof(int) * 3 * (size_t)(entries > 0 ? entries : 1));
    if (!stamp || !place || !S->ring_start || !S->ring_corner) {
        free(stamp), free(place);
        return wff_fail(err, "ply contact: out of memory for the rings of %d nodes", nn);
    }
    for (int pass = 0; pass < 2; pass++) {
        for (int j = 0; j < nn; j++)
            stamp[j] = -1;
        for (int i = 0; i < nn; i++) {
            int *ring = pass ? S->ring_node + S->ring_start[i] : NULL, count = 0;
            stamp[i] = i, place[i] = count;
            if (ring)
                ring[count] = i;
            count++;
            for (int a = P->node_facet_start[i]; a < P->node_facet_start[i + 1]; a++)
                for (int k = 0; k < 3; k++) {
                    const int j = P->facet[3 * P->node_facets[a] + k];
                    if (stamp[j] != i) {
                        stamp[j] = i, place[j] = count;
                        if (ring)
                            ring[count] = j;
                        count++;
                    }
                    if (pass)
                        S->ring_corner[3 * a + k] = place[j];
                }
            if (!pass)
                S->ring_start[i + 1] = count;
        }
        if (pass == 0) {
            for (int i = 0; i < nn; i++)
                S->ring_start[i + 1] += S->ring_start[i];
            S->ring_total = S->ring_start[nn];
            S->ring_node = malloc(sizeof(int) * (size_t)S->ring_total);
            if (!S->ring_node) {
                free(stamp), free(place);
                return wff_fail(err, "ply contact: out of memory for the rings of %d nodes", nn);
            }
        }
    }
    free(stamp), free(place);
    return 0;
}

static int ensure_workspace(wff_model *m, wff_error *err)
{
    struct wff_pack *P = m->pack;
    if (P->impulse)
        return 0;
    size_t slots = (size_t)(P->n - 1) * (size_t)P->nodes;
    P->impulse = calloc(3 * (size_t)m->n_nodes, sizeof(double));
    P->nose_impulse = calloc(3 * (size_t)m->n_nodes, sizeof(double));
    P->touched = calloc((size_t)m->n_nodes, 1);
    P->touched_list = malloc(sizeof(int) * (size_t)m->n_nodes);
    P->on_projectile = malloc(sizeof(int) * (size_t)m->n_nodes);
    P->normal = malloc(sizeof(double) * 3 * (size_t)m->n_nodes);
    P->live = malloc((size_t)m->n_nodes);
    P->reach = malloc(sizeof(double) * (size_t)P->nodes);
    P->predicted = malloc(sizeof(double) * 3 * (size_t)m->n_nodes);
    P->facet = malloc(sizeof(int) * 3 * (size_t)facet_count(P));
    P->rest = malloc(sizeof(double) * (slots + 1));
    if (P->on_projectile)
        for (int n = 0; n < m->n_nodes; n++)
            P->on_projectile[n] = -1;
    if (!P->impulse || !P->nose_impulse || !P->touched || !P->touched_list || !P->on_projectile || !P->normal ||
        !P->live || !P->reach || !P->predicted || !P->facet || !P->rest) {
        wff_ply_contact_free(P);
        return wff_fail(err, "ply contact: out of memory for %zu node pairs", slots);
    }
    /* each specimen node's shortest reference edge (the pairs' slip bound) */
    for (int i = 0; i < P->nodes; i++)
        P->reach[i] = INFINITY;
    for (int f = 0; f < facet_count(P); f++) {
        int *a = P->facet + 3 * f;
        facet_nodes(m, f, a);
        for (int k = 0; k < 3; k++) {
            const double *p0 = m->mesh.xy + 2 * a[k], *p1 = m->mesh.xy + 2 * a[(k + 1) % 3];
            double len = hypot(p1[0] - p0[0], p1[1] - p0[1]);
            P->reach[a[k]] = fmin(P->reach[a[k]], len);
            P->reach[a[(k + 1) % 3]] = fmin(P->reach[a[(k + 1) % 3]], len);
        }
    }
    /* each specimen node's facets (the normals' dependence on the positions) */
    const int nf = facet_count(P);
    P->node_facet_start = calloc((size_t)P->nodes + 1, sizeof(int));
    P->node_facets = malloc(sizeof(int) * 3 * (size_t)(nf > 0 ? nf : 1));
    int *cursor = malloc(sizeof(int) * ((size_t)P->nodes + 1));
    if (!P->node_facet_start || !P->node_facets || !cursor) {
        free(cursor);
        wff_ply_contact_free(P);
        return wff_fail(err, "ply contact: out of memory for the facets of %d nodes", P->nodes);
    }
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++)
            P->node_facet_start[P->facet[3 * f + k] + 1]++;
    for (int i = 0; i < P->nodes; i++)
        P->node_facet_start[i + 1] += P->node_facet_start[i];
    memcpy(cursor, P->node_facet_start, sizeof(int) * (size_t)P->nodes);
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++)
            P->node_facets[cursor[P->facet[3 * f + k]]++] = f;
    free(cursor);
    /* the solve: rings, the pairs' gradients, the constraints (a pair per slot
     * and a nose contact per node at most) */
    struct wff_ply_solve *S = calloc(1, sizeof *S);
    P->solve = S;
    if (!S || build_rings(m, S, err)) {
        wff_ply_contact_free(P);
        return S ? -1 : wff_fail(err, "ply contact: out of memory for its solve");
    }
    const size_t most = slots + (size_t)m->n_nodes;
    S->max_constraints = (int)most;
    S->gradient = malloc(sizeof(double) * 6 * ((size_t)(P->n - 1) * (size_t)S->ring_total + 1));
    S->v_first = malloc(sizeof(double) * 3 * (size_t)m->n_nodes);
    S->in_column = calloc((size_t)P->nodes, 1);
    S->columns = malloc(sizeof(int) * (size_t)P->nodes);
    S->column_start = malloc(sizeof(int) * ((size_t)P->nodes + 1));
    S->kind = malloc(most);
    S->slot = malloc(sizeof(int) * most);
    S->a = malloc(sizeof(int) * most);
    S->b = malloc(sizeof(int) * most);
    S->lambda = malloc(sizeof(double) * most);
    S->lo = malloc(sizeof(double) * most);
    S->g = malloc(sizeof(double) * most);
    S->target = malloc(sizeof(double) * most);
    S->diag = malloc(sizeof(double) * most);
    S->off = malloc(sizeof(double) * 2 * most);
    S->normal = malloc(sizeof(double) * 3 * most);
    S->friction = malloc(sizeof(double) * 3 * most);
    if (!S->gradient || !S->v_first || !S->in_column || !S->columns || !S->column_start ||
        !S->kind || !S->slot || !S->a || !S->b || !S->lambda || !S->lo || !S->g || !S->target ||
        !S->diag || !S->off || !S->normal || !S->friction) {
        wff_ply_contact_free(P);
        return wff_fail(err, "ply contact: out of memory for the solve of %zu node pairs", slots);
    }
    return 0;
}

/* Every node's normal at the predicted positions: the sum of its ply's facets'
 * normals (twice their areas: the area-weighted mean's direction), eroded
 * facets left out; live[n] 1 if node n has a facet left; the velocities at
 * this first look kept (v_first). */
static void nodal_normals(wff_model *m, double dt)
{
    struct wff_pack *P = m->pack;
    const int nf = facet_count(P), nn = P->nodes;
    const unsigned char *eroded = m->el.eroded;
    /* one ply a thread's item: a ply's facets write its own nodes only, in the
     * same order whatever the threads (the same bits) */
    int team = m->n_dofs < PLY_TEAM_MIN_DOFS ? 1 : wff_elements_team(&m->el);
    team = team > P->n ? P->n : team < 1 ? 1 : team;
#pragma omp parallel for schedule(static) num_threads(team) if (team > 1)
    for (int q = 0; q < P->n; q++) {
        double *normal = P->normal + 3 * (size_t)q * nn, *predicted = P->predicted + 3 * (size_t)q * nn;
        unsigned char *live = P->live + (size_t)q * nn;
        memset(normal, 0, sizeof(double) * 3 * (size_t)nn);
        memset(live, 0, (size_t)nn);
        double *v_first = P->solve->v_first + 3 * (size_t)q * nn;
        for (int i = 0; i < nn; i++) {
            const int node = q * nn + i;
            position(m, node, dt, predicted + 3 * i);
            memcpy(v_first + 3 * i, m->v + D * node, sizeof(double) * 3);
        }
        for (int f = 0; f < nf; f++) {
            if (eroded && eroded[facet_element(P, q, f)])
                continue;
            const int *a = P->facet + 3 * f;
            const double *x0 = predicted + 3 * a[0], *x1 = predicted + 3 * a[1],
                         *x2 = predicted + 3 * a[2];
            /* (scalars, not small arrays: stored one by one and loaded as pairs,
             * those stalled the store forwarding, 30 % of this loop) */
            const double e1x = x1[0] - x0[0], e1y = x1[1] - x0[1], e1z = x1[2] - x0[2];
            const double e2x = x2[0] - x0[0], e2y = x2[1] - x0[1], e2z = x2[2] - x0[2];
            const double nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z,
                         nz = e1x * e2y - e1y * e2x; /* (twice the area) */
            for (int k = 0; k < 3; k++) {
                double *out = normal + 3 * a[k];
                out[0] += nx, out[1] += ny, out[2] += nz;
                live[a[k]] = 1;
            }
        }
    }
}

/* The inverse mass of component c of node n: 0 if held (its support takes an
 * impulse on it). */
static inline double inverse_mass_of(const wff_model *m, int n, int c)
{
    return m->dof_kind[D * n + c] == WFF_DOF_FREE ? 1 / m->mass[D * n] : 0;
}

/* The inverse mass of node n along direction d (its free components). */
static double inverse_mass(const wff_model *m, int n, const double d[3])
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
static void give(wff_model *m, int n, const double j[3], double dt_mid, double *account)
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

/* The first ply above ply p with a facet left at node i (p + 1 unless its
 * node i is dead: through its hole), or -1. */
static inline int partner_above(const struct wff_pack *P, int p, int i)
{
    for (int q = p + 1; q < P->n; q++)
        if (P->live[(size_t)q * P->nodes + i])
            return q;
    return -1;
}

/* The upper node of slot (pair, i): node i of ply pair + 1, or of the first
 * live ply above it through its hole; -1 if none. */
static inline int upper_node(const struct wff_pack *P, int pair, int i)
{
    const int B = (pair + 1) * P->nodes + i;
    if (P->live[B])
        return B;
    const int above = partner_above(P, pair + 1, i);
    return above < 0 ? -1 : above * P->nodes + i;
}

/* A pair's look at the step's first prediction. */
struct pair_look {
    int A, B;
    double n[3];   /* unit normal N/|N| */
    double s[3];   /* in-plane offset (I − nn)(x_B − x_A) */
    double len;    /* |N| */
    double g;      /* distance − h, predicted, m */
    double now;    /* h − distance now (> 0: closer than h already), m */
};
enum { LOOK_NONE = -1, LOOK_CLEAR = 0, LOOK_PAIR = 1, LOOK_APART = 2 };

/* Slot (pair, i) at the first look (the predicted positions, the velocities
 * before the solve): LOOK_NONE (a dead node A, or nothing live above it),
 * LOOK_CLEAR (clear by more than FILTER_SHARE ROUND_OFF h: with `filter` on,
 * a squared test, no root), LOOK_APART (slid apart in plane, or crossed: left
 * out; L->g set), or LOOK_PAIR (L set). */
static int look(const wff_model *m, int pair, int i, double h, double dt, int filter,
                struct pair_look *L)
{
    const struct wff_pack *P = m->pack;
    const int A = pair * P->nodes + i;
    if (!P->live[A])
        return LOOK_NONE;
    const int B = upper_node(P, pair, i);
    if (B < 0)
        return LOOK_NONE;
    /* (in scalars: small arrays written one by one and read as pairs stalled
     * the store forwarding) */
    const double *xa = P->predicted + 3 * A, *xb = P->predicted + 3 * B;
    const double gap_x = xb[0] - xa[0], gap_y = xb[1] - xa[1], gap_z = xb[2] - xa[2];
    const double *na = P->normal + 3 * A, *nb = P->normal + 3 * B;
    double nx = na[0] + nb[0], ny = na[1] + nb[1], nz = na[2] + nb[2];
    const double len2 = nx * nx + ny * ny + nz * nz, along = gap_x * nx + gap_y * ny + gap_z * nz;
    /* clear by more than FILTER_SHARE of ROUND_OFF h (compared squared: most
     * pairs of a pack are clear) */
    if (filter && along > 0 && along * along >= FILTER_SQUARED * h * h * len2)
        return LOOK_CLEAR;
    const double len = sqrt(len2);
    if (!(len > 0))
        return LOOK_CLEAR;
    nx /= len, ny /= len, nz /= len;
    const double dist = gap_x * nx + gap_y * ny + gap_z * nz;
    const double *va = m->v + D * A, *vb = m->v + D * B;
    const double closing = (va[0] - vb[0]) * nx + (va[1] - vb[1]) * ny + (va[2] - vb[2]) * nz;
    L->A = A, L->B = B, L->len = len;
    L->n[0] = nx, L->n[1] = ny, L->n[2] = nz;
    L->s[0] = gap_x - dist * nx, L->s[1] = gap_y - dist * ny, L->s[2] = gap_z - dist * nz;
    L->g = dist - h;
    L->now = (h - dist) - dt * closing;
    const double slip = L->s[0] * L->s[0] + L->s[1] * L->s[1] + L->s[2] * L->s[2];
    const double reach = SLIP_LIMIT * P->reach[i];
    if (slip > reach * reach || h - L->now < -CROSS_LIMIT * P->reach[i])
        return LOOK_APART;
    return LOOK_PAIR;
}

/* The gradient of the pair's constraint g = (x_B − x_A)·N/|N| − h at the
 * predicted positions (N = N_A + N_B, the raw sums of the facets' normals at
 * node i of A's ply and of B's, n = N/|N|, s the in-plane offset): ±n on B
 * and A, and s·∂N/∂x_k / |N| on the nodes of those facets (for a facet's N_f =
 * e₁ × e₂: e₂ × s on its second node, s × e₁ on its third, minus both on its
 * first), into G: ply A's ring of i, then ply B's, 3 per ring node. It sums to
 * 0 (momentum kept). */
static void pair_gradient(const wff_model *m, const struct pair_look *L, int i, double *G)
{
    const struct wff_pack *P = m->pack;
    const struct wff_ply_solve *S = P->solve;
    const unsigned char *eroded = m->el.eroded;
    const int nn = P->nodes, ring = S->ring_start[i + 1] - S->ring_start[i];
    const double *s = L->s, len = L->len;
    memset(G, 0, sizeof(double) * 6 * (size_t)ring);
    for (int side = 0; side < 2; side++) {
        const int q = (side ? L->B : L->A) / nn;
        double *Gs = G + 3 * ring * side;
        for (int a = P->node_facet_start[i]; a < P->node_facet_start[i + 1]; a++) {
            const int f = P->node_facets[a];
            if (eroded && eroded[facet_element(P, q, f)])
                continue;
            const int *c = P->facet + 3 * f;
            const double *x0 = P->predicted + 3 * (q * nn + c[0]),
                         *x1 = P->predicted + 3 * (q * nn + c[1]),
                         *x2 = P->predicted + 3 * (q * nn + c[2]);
            const double e1[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
            const double e2[3] = {x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]};
            /* s·(e1 × e2): ∂/∂x1 = e2 × s, ∂/∂x2 = s × e1, ∂/∂x0 = −both */
            const double d1[3] = {(e2[1] * s[2] - e2[2] * s[1]) / len, (e2[2] * s[0] - e2[0] * s[2]) / len,
                                  (e2[0] * s[1] - e2[1] * s[0]) / len};
            const double d2[3] = {(s[1] * e1[2] - s[2] * e1[1]) / len, (s[2] * e1[0] - s[0] * e1[2]) / len,
                                  (s[0] * e1[1] - s[1] * e1[0]) / len};
            const int *r = S->ring_corner + 3 * a;
            for (int k = 0; k < 3; k++) {
                Gs[3 * r[0] + k] -= d1[k] + d2[k];
                Gs[3 * r[1] + k] += d1[k];
                Gs[3 * r[2] + k] += d2[k];
            }
        }
    }
    for (int k = 0; k < 3; k++) { /* (node i: the ring's first) */
        G[k] -= L->n[k];
        G[3 * ring + k] += L->n[k];
    }
}

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

/* Constraint c's gap now, linear in the velocities from the first look:
 * g + Δt G·(v − v_first) (m). */
static double gap_now(const wff_model *m, const struct solve_step *T, int c)
{
    const struct wff_pack *P = m->pack;
    const struct wff_ply_solve *S = P->solve;
    double sum = 0;
    if (S->kind[c] == NOSE) {
        const int n = S->a[c];
        const double *nrm = S->normal + 3 * c, *v = m->v + D * n, *v0 = S->v_first + 3 * n;
        sum = nrm[0] * (v[0] - v0[0]) + nrm[1] * (v[1] - v0[1]) + nrm[2] * (v[2] - v0[2]) -
              nrm[2] * (m->projectile.velocity - T->v_projectile);
        return S->g[c] + T->dt * sum;
    }
    const int nn = P->nodes, i = S->slot[c] % nn, start = S->ring_start[i];
    const int ring = S->ring_start[i + 1] - start;
    const double *G = gradient_of(P, S->slot[c]);
    for (int side = 0; side < 2; side++) {
        const int base = (side ? S->b[c] : S->a[c]) / nn * nn;
        const double *Gs = G + 3 * ring * side;
        for (int k = 0; k < ring; k++) {
            const int n = base + S->ring_node[start + k];
            const double *v = m->v + D * n, *v0 = S->v_first + 3 * n;
            sum += Gs[3 * k] * (v[0] - v0[0]) + Gs[3 * k + 1] * (v[1] - v0[1]) +
                   Gs[3 * k + 2] * (v[2] - v0[2]);
        }
    }
    return S->g[c] + T->dt * sum;
}

/* Σ G_c M⁻¹ G_c over the free components (and the projectile's, for a nose). */
static double self_coupling(const wff_model *m, int c)
{
    const struct wff_pack *P = m->pack;
    const struct wff_ply_solve *S = P->solve;
    if (S->kind[c] == NOSE) {
        const double *nrm = S->normal + 3 * c;
        double w = 0;
        for (int k = 0; k < 3; k++)
            w += nrm[k] * nrm[k] * inverse_mass_of(m, S->a[c], k);
        return w + nrm[2] * nrm[2] / m->projectile.mass;
    }
    const int nn = P->nodes, i = S->slot[c] % nn, start = S->ring_start[i];
    const int ring = S->ring_start[i + 1] - start;
    const double *G = gradient_of(P, S->slot[c]);
    double w = 0;
    for (int side = 0; side < 2; side++) {
        const int base = (side ? S->b[c] : S->a[c]) / nn * nn;
        for (int k = 0; k < ring; k++)
            for (int d = 0; d < 3; d++) {
                const double gk = G[3 * (ring * side + k) + d];
                w += gk * gk * inverse_mass_of(m, base + S->ring_node[start + k], d);
            }
    }
    return w;
}

/* G_c M⁻¹ G_d of two constraints of one column, c before d (a pair's ply's
 * ring shared with the pair above it; a nose's node with the pairs it is in;
 * two noses through the projectile). */
static double coupling(const wff_model *m, int c, int d)
{
    const struct wff_pack *P = m->pack;
    const struct wff_ply_solve *S = P->solve;
    const int nn = P->nodes;
    if (S->kind[c] == NOSE && S->kind[d] == NOSE)
        return S->normal[3 * c + 2] * S->normal[3 * d + 2] / m->projectile.mass;
    if (S->kind[c] == NOSE || S->kind[d] == NOSE) {
        const int nose = S->kind[c] == NOSE ? c : d, pair = nose == c ? d : c;
        const int node = S->a[nose], i = S->slot[pair] % nn;
        const int ring = S->ring_start[i + 1] - S->ring_start[i];
        const double *G = gradient_of(P, S->slot[pair]);
        const double *Gn = S->a[pair] == node ? G : S->b[pair] == node ? G + 3 * ring : NULL;
        if (!Gn)
            return 0;
        double w = 0;
        for (int k = 0; k < 3; k++) /* (the node: its ring's first) */
            w += Gn[k] * S->normal[3 * nose + k] * inverse_mass_of(m, node, k);
        return w;
    }
    if (S->b[c] / nn != S->a[d] / nn)
        return 0;
    const int i = S->slot[c] % nn, start = S->ring_start[i], ring = S->ring_start[i + 1] - start;
    const int base = S->b[c] / nn * nn;
    const double *Gc = gradient_of(P, S->slot[c]) + 3 * ring, *Gd = gradient_of(P, S->slot[d]);
    double w = 0;
    for (int k = 0; k < ring; k++)
        for (int e = 0; e < 3; e++)
            w += Gc[3 * k + e] * Gd[3 * k + e] * inverse_mass_of(m, base + S->ring_node[start + k], e);
    return w;
}

/* Constraint c's normal impulse x: x G_c on its nodes, −x n_z on the
 * projectile for a nose. */
static void apply_normal(wff_model *m, const struct solve_step *T, int c, double x)
{
    struct wff_pack *P = m->pack;
    const struct wff_ply_solve *S = P->solve;
    if (S->kind[c] == NOSE) {
        const double *nrm = S->normal + 3 * c;
        const double j[3] = {x * nrm[0], x * nrm[1], x * nrm[2]};
        give(m, S->a[c], j, T->dt_mid, P->nose_impulse);
        const double dv = -x * nrm[2] / m->projectile.mass;
        m->projectile.velocity += dv;
        P->projectile_dv += dv;
        return;
    }
    const int nn = P->nodes, i = S->slot[c] % nn, start = S->ring_start[i];
    const int ring = S->ring_start[i + 1] - start;
    const double *G = gradient_of(P, S->slot[c]);
    for (int side = 0; side < 2; side++) {
        const int base = (side ? S->b[c] : S->a[c]) / nn * nn;
        const double *Gs = G + 3 * ring * side;
        for (int k = 0; k < ring; k++) {
            const double j[3] = {x * Gs[3 * k], x * Gs[3 * k + 1], x * Gs[3 * k + 2]};
            give(m, base + S->ring_node[start + k], j, T->dt_mid, P->impulse);
        }
    }
}

/* W x on a column (K constraints; d its diagonal, o1[k] = W(k, k − 1), o2[k]
 * = W(k, k − 2)) at place k. */
static inline double band_product(int K, const double *d, const double *o1, const double *o2,
                                  const double *x, int k)
{
    double w = d[k] * x[k];
    if (k >= 1)
        w += o1[k] * x[k - 1];
    if (k >= 2)
        w += o2[k] * x[k - 2];
    if (k + 1 < K)
        w += o1[k + 1] * x[k + 1];
    if (k + 2 < K)
        w += o2[k + 2] * x[k + 2];
    return w;
}

/* Solve W_SS x = r over the places idx[0 .. ns) (ascending) of a column's
 * banded W (half-bandwidth 2): LDLᵀ, r overwritten by x. -1 if a pivot is
 * not positive (W restricted to its band is then not definite). */
static int band_solve(int ns, const int *idx, const double *d, const double *o1,
                      const double *o2, double *r)
{
    double piv[COLUMN_MAX], l1[COLUMN_MAX], l2[COLUMN_MAX];
    for (int a = 0; a < ns; a++) {
        const int k = idx[a];
        const double e1 = a >= 1 && k - idx[a - 1] == 1 ? o1[k] : a >= 1 && k - idx[a - 1] == 2 ? o2[k] : 0;
        const double e2 = a >= 2 && k - idx[a - 2] == 2 ? o2[k] : 0;
        l2[a] = a >= 2 ? e2 / piv[a - 2] : 0;
        l1[a] = a >= 1 ? (e1 - (a >= 2 ? l2[a] * piv[a - 2] * l1[a - 1] : 0)) / piv[a - 1] : 0;
        piv[a] = d[k] - (a >= 1 ? l1[a] * l1[a] * piv[a - 1] : 0) -
                 (a >= 2 ? l2[a] * l2[a] * piv[a - 2] : 0);
        if (!(piv[a] > 1e-12 * d[k]))
            return -1;
    }
    for (int a = 1; a < ns; a++)
        r[a] -= l1[a] * r[a - 1] + (a >= 2 ? l2[a] * r[a - 2] : 0);
    for (int a = 0; a < ns; a++)
        r[a] /= piv[a];
    for (int a = ns - 2; a >= 0; a--)
        r[a] -= l1[a + 1] * r[a + 1] + (a + 2 < ns ? l2[a + 2] * r[a + 2] : 0);
    return 0;
}

/* One column's constraints solved together, the rest of the pack as it is:
 * the linear complementarity problem  x ≥ lo − λ,  W x − y ≥ 0,  (λ + x −
 * lo)·(W x − y) = 0  for the impulses' change x, y = (target − gap now)/Δt the
 * change of G v each needs (W = G M⁻¹ Gᵀ restricted to the column: banded,
 * half-bandwidth 2 in the column's order, ply by ply, a nose before the pair
 * above its node); by pivoting on the set of constraints at their bound (a
 * solve of the band per pivot), projected Gauss-Seidel if that does not
 * settle. The impulses given; the largest change of a gap they make (m)
 * returned. */
static double solve_column(wff_model *m, const struct solve_step *T, int start, int K)
{
    struct wff_ply_solve *S = m->pack->solve;
    double y[COLUMN_MAX], x[COLUMN_MAX], r[COLUMN_MAX], lo[COLUMN_MAX];
    const double *d = S->diag + start;
    double o1[COLUMN_MAX], o2[COLUMN_MAX];
    int idx[COLUMN_MAX];
    unsigned char free_[COLUMN_MAX];
    const double tol_gap = 1e-3 * SWEEP_TOLERANCE * T->h; /* (of a gap, m) */
    double need = 0;
    for (int k = 0; k < K; k++) {
        const int c = start + k;
        o1[k] = S->off[2 * c], o2[k] = S->off[2 * c + 1];
        y[k] = (S->target[c] - gap_now(m, T, c)) / T->dt;
        lo[k] = S->lo[c] - S->lambda[c];
        free_[k] = lo[k] < 0 || y[k] > 0;
        x[k] = 0;
        need = fmax(need, y[k] * T->dt);
    }
    if (need <= tol_gap) { /* every constraint held: nothing to add unless one lets go */
        int any = 0;
        for (int k = 0; k < K; k++)
            any |= lo[k] < 0 && y[k] * T->dt < -tol_gap;
        if (!any)
            return 0;
    }
    int settled = 0;
    for (int pivot = 0; pivot < 4 * K + 8 && !settled; pivot++) {
        int ns = 0;
        for (int k = 0; k < K; k++) {
            if (free_[k])
                idx[ns++] = k;
            else
                x[k] = lo[k];
        }
        for (int a = 0; a < ns; a++) { /* y less the bound ones' share */
            const int k = idx[a];
            double w = y[k];
            for (int j = k - 2; j <= k + 2; j++)
                if (j >= 0 && j < K && j != k && !free_[j])
                    w -= (j < k ? (k - j == 1 ? o1[k] : o2[k]) : (j - k == 1 ? o1[j] : o2[j])) * x[j];
            r[a] = w;
        }
        if (band_solve(ns, idx, d, o1, o2, r))
            break;
        for (int a = 0; a < ns; a++)
            x[idx[a]] = r[a];
        int changed = 0;
        for (int k = 0; k < K; k++) /* below its bound: to the bound */
            if (free_[k] && x[k] < lo[k] - tol_gap / (d[k] * T->dt)) {
                free_[k] = 0;
                changed = 1;
            }
        if (changed)
            continue;
        for (int k = 0; k < K; k++) /* at its bound, closing: free */
            if (!free_[k] && (band_product(K, d, o1, o2, x, k) - y[k]) * T->dt < -tol_gap) {
                free_[k] = 1;
                changed = 1;
            }
        settled = !changed;
    }
    if (!settled) { /* projected Gauss-Seidel from nothing */
        for (int k = 0; k < K; k++)
            x[k] = 0;
        for (int sweep = 0; sweep < COLUMN_PGS_SWEEPS; sweep++)
            for (int k = 0; k < K; k++) {
                const double rest = y[k] - (band_product(K, d, o1, o2, x, k) - d[k] * x[k]);
                x[k] = fmax(lo[k], rest / d[k]);
            }
    }
    double moved = 0;
    for (int k = 0; k < K; k++) {
        if (x[k] < lo[k])
            x[k] = lo[k]; /* (within the tolerance) */
        if (x[k] == 0)
            continue;
        S->lambda[start + k] += x[k];
        apply_normal(m, T, start + k, x[k]);
        moved = fmax(moved, fabs(x[k]) * d[k] * T->dt);
    }
    return moved;
}

/* The pairs' Coulomb friction of a column, solved together: each pair's
 * accumulated friction impulse F_k (on B, −F_k on A, in its tangent plane)
 * moved by x_k so that its tangential relative velocity vt_k (B − A) stops,
 *     (w_A + w_B) x_k − w_B x_{k+1} − w_A x_{k−1} = −vt_k
 * (per component, w the inverse masses of the free components; x_{k±1} where
 * the pair above or below shares the node: a chain of plies sticking is a
 * 1-D Laplacian, which one friction update per pair and sweep passes one pair
 * a sweep), the pairs whose F then leaves the cone |F| <= μ λ slipping at its
 * edge along it and the others solved again. The largest tangential move a
 * change makes (m) returned. */
static double pair_friction(wff_model *m, const struct solve_step *T, int start, int K)
{
    struct wff_pack *P = m->pack;
    struct wff_ply_solve *S = P->solve;
    if (!(P->mu > 0))
        return 0;
    int pair[COLUMN_MAX], n = 0;
    for (int c = start; c < start + K; c++)
        if (S->kind[c] == PAIR)
            pair[n++] = c;
    if (n == 0)
        return 0;
    double vt[COLUMN_MAX][3], F[COLUMN_MAX][3], wa[COLUMN_MAX][3], wb[COLUMN_MAX][3];
    double cone[COLUMN_MAX];
    unsigned char link[COLUMN_MAX], stick[COLUMN_MAX];
    for (int k = 0; k < n; k++) {
        const int c = pair[k], A = S->a[c], B = S->b[c];
        const double *nrm = S->normal + 3 * c;
        double rel[3], along = 0;
        for (int e = 0; e < 3; e++) {
            rel[e] = m->v[D * B + e] - m->v[D * A + e];
            along += rel[e] * nrm[e];
            wa[k][e] = inverse_mass_of(m, A, e), wb[k][e] = inverse_mass_of(m, B, e);
            F[k][e] = S->friction[3 * c + e];
        }
        for (int e = 0; e < 3; e++)
            vt[k][e] = rel[e] - along * nrm[e];
        cone[k] = P->mu * fmax(S->lambda[c], 0);
        link[k] = k > 0 && S->b[pair[k - 1]] == A; /* (its A is the B of the pair below) */
        stick[k] = cone[k] > 0;
    }
    /* (a pair without a normal impulse has no friction: its F goes to 0, a known
     * change its sticking neighbours' rows take as given) */
    double next[COLUMN_MAX][3];
    for (int k = 0; k < n; k++)
        next[k][0] = next[k][1] = next[k][2] = 0;
    for (int round = 0; round <= n; round++) {
        /* each component: a tridiagonal system, the slipping pairs' rows x = their
         * cone's F less F (Thomas: the sticking rows dominate their diagonal) */
        for (int e = 0; e < 3; e++) {
            double sub[COLUMN_MAX], dia[COLUMN_MAX], sup[COLUMN_MAX], rhs[COLUMN_MAX];
            for (int k = 0; k < n; k++) {
                const double w = wa[k][e] + wb[k][e];
                if (!stick[k] || !(w > 0)) {
                    sub[k] = sup[k] = 0, dia[k] = 1;
                    rhs[k] = stick[k] ? 0 : next[k][e] - F[k][e];
                    continue;
                }
                dia[k] = w;
                sub[k] = link[k] ? -wa[k][e] : 0;
                sup[k] = k + 1 < n && link[k + 1] ? -wb[k][e] : 0;
                rhs[k] = -vt[k][e];
            }
            for (int k = 1; k < n; k++) {
                const double f = sub[k] / dia[k - 1];
                dia[k] -= f * sup[k - 1];
                rhs[k] -= f * rhs[k - 1];
            }
            for (int k = n - 1; k >= 0; k--) {
                rhs[k] = (rhs[k] - (k + 1 < n ? sup[k] * rhs[k + 1] : 0)) / dia[k];
                if (stick[k])
                    next[k][e] = F[k][e] + rhs[k];
            }
        }
        int changed = 0;
        for (int k = 0; k < n; k++) {
            if (!stick[k])
                continue;
            const double *nrm = S->normal + 3 * pair[k];
            const double along = next[k][0] * nrm[0] + next[k][1] * nrm[1] + next[k][2] * nrm[2];
            for (int e = 0; e < 3; e++)
                next[k][e] -= along * nrm[e]; /* (in its tangent plane) */
            const double size = sqrt(next[k][0] * next[k][0] + next[k][1] * next[k][1] +
                                     next[k][2] * next[k][2]);
            if (size > cone[k]) { /* slips: at the cone's edge, along it */
                for (int e = 0; e < 3; e++)
                    next[k][e] *= cone[k] / size;
                stick[k] = 0;
                changed = 1;
            }
        }
        for (int k = 0; k < n; k++)
            if (cone[k] <= 0)
                next[k][0] = next[k][1] = next[k][2] = 0; /* (no normal impulse: no friction) */
        if (!changed)
            break;
    }
    double moved = 0;
    for (int k = 0; k < n; k++) {
        const int c = pair[k];
        const double jb[3] = {next[k][0] - F[k][0], next[k][1] - F[k][1], next[k][2] - F[k][2]};
        const double change = sqrt(jb[0] * jb[0] + jb[1] * jb[1] + jb[2] * jb[2]);
        if (!(change > 0))
            continue;
        const double ja[3] = {-jb[0], -jb[1], -jb[2]};
        give(m, S->b[c], jb, T->dt_mid, P->impulse);
        give(m, S->a[c], ja, T->dt_mid, P->impulse);
        for (int e = 0; e < 3; e++)
            S->friction[3 * c + e] = next[k][e];
        const double u[3] = {jb[0] / change, jb[1] / change, jb[2] / change};
        moved = fmax(moved, change * (inverse_mass(m, S->a[c], u) + inverse_mass(m, S->b[c], u)) * T->dt);
    }
    return moved;
}

/* The nose contacts' Coulomb friction of a column against the node's
 * tangential velocity less the projectile's, |F| <= μ λ (μ the projectile's,
 * its normal impulse and F the projectile contact's and the solve's
 * together; F on the node, −F_z on the projectile): each one's accumulated
 * friction impulse F moved to the one that stops it, held within the cone
 * (stick if the cone allows). The largest tangential move a change makes (m)
 * returned. */
static double nose_friction(wff_model *m, const struct solve_step *T, int start, int K)
{
    struct wff_pack *P = m->pack;
    struct wff_ply_solve *S = P->solve;
    wff_projectile *pr = &m->projectile;
    double moved = 0;
    for (int c = start; c < start + K; c++) {
        const int nose = S->kind[c] == NOSE;
        const double mu = nose ? pr->mu : P->mu;
        if (!nose || !(mu > 0))
            continue; /* (a column's pairs: pair_friction, together) */
        const int A = S->a[c], B = S->b[c]; /* (a nose: B -1) */
        const double *nrm = S->normal + 3 * c;
        double *F = S->friction + 3 * c, rel[3], along = 0, vt[3], speed = 0, trial[3];
        for (int k = 0; k < 3; k++) {
            rel[k] = nose ? m->v[D * A + k] - (k == 2 ? pr->velocity : 0)
                          : m->v[D * B + k] - m->v[D * A + k];
            along += rel[k] * nrm[k];
        }
        for (int k = 0; k < 3; k++) {
            vt[k] = rel[k] - along * nrm[k];
            speed += vt[k] * vt[k];
        }
        speed = sqrt(speed);
        for (int k = 0; k < 3; k++)
            trial[k] = F[k];
        if (speed > 0) {
            const double t[3] = {vt[0] / speed, vt[1] / speed, vt[2] / speed};
            const double wt = nose ? inverse_mass(m, A, t) + t[2] * t[2] / pr->mass
                                   : inverse_mass(m, A, t) + inverse_mass(m, B, t);
            if (wt > 0)
                for (int k = 0; k < 3; k++)
                    trial[k] -= vt[k] / wt;
        }
        /* in the pair's tangent plane, within the cone */
        const double normal_part = trial[0] * nrm[0] + trial[1] * nrm[1] + trial[2] * nrm[2];
        for (int k = 0; k < 3; k++)
            trial[k] -= normal_part * nrm[k];
        const double size = sqrt(trial[0] * trial[0] + trial[1] * trial[1] + trial[2] * trial[2]);
        const double cone = mu * fmax(S->lambda[c] - (nose ? S->lo[c] : 0), 0);
        if (size > cone) {
            const double scale = size > 0 ? cone / size : 0;
            for (int k = 0; k < 3; k++)
                trial[k] *= scale;
        }
        const double jb[3] = {trial[0] - F[0], trial[1] - F[1], trial[2] - F[2]};
        if (jb[0] == 0 && jb[1] == 0 && jb[2] == 0)
            continue;
        const double ja[3] = {-jb[0], -jb[1], -jb[2]};
        const double change = sqrt(jb[0] * jb[0] + jb[1] * jb[1] + jb[2] * jb[2]);
        const double u[3] = {jb[0] / change, jb[1] / change, jb[2] / change};
        double w = inverse_mass(m, A, u);
        if (nose) {
            give(m, A, jb, T->dt_mid, P->nose_impulse);
            const double dv = -jb[2] / pr->mass;
            pr->velocity += dv;
            P->projectile_dv += dv;
            w += u[2] * u[2] / pr->mass;
        } else {
            give(m, B, jb, T->dt_mid, P->impulse);
            give(m, A, ja, T->dt_mid, P->impulse);
            w += inverse_mass(m, B, u);
        }
        for (int k = 0; k < 3; k++)
            F[k] = trial[k];
        /* the change's move of the tangential gap: |ΔF| w Δt along it */
        moved = fmax(moved, change * w * T->dt);
    }
    return moved;
}

/* Node n's predicted position after the solve, x + Δt v (from the first
 * look's, moved by Δt (v − v_first)). */
static inline void final_position(const wff_model *m, double dt, int n, double x[3])
{
    const struct wff_pack *P = m->pack;
    const double *x0 = P->predicted + 3 * n, *v = m->v + D * n, *v0 = P->solve->v_first + 3 * n;
    for (int k = 0; k < 3; k++)
        x[k] = x0[k] + dt * (v[k] - v0[k]);
}

/* Pair c's distance (m) at the predicted positions after the solve, along its
 * normal there (its facets' normals recomputed): what the next step's first
 * look will find, but for the next step's change of velocity. */
static double final_distance(const wff_model *m, double dt, int c)
{
    const struct wff_pack *P = m->pack;
    const struct wff_ply_solve *S = P->solve;
    const unsigned char *eroded = m->el.eroded;
    const int nn = P->nodes, i = S->slot[c] % nn;
    double N[3] = {0, 0, 0};
    for (int side = 0; side < 2; side++) {
        const int q = (side ? S->b[c] : S->a[c]) / nn;
        for (int a = P->node_facet_start[i]; a < P->node_facet_start[i + 1]; a++) {
            const int f = P->node_facets[a];
            if (eroded && eroded[facet_element(P, q, f)])
                continue;
            const int *corner = P->facet + 3 * f;
            double x0[3], x1[3], x2[3];
            final_position(m, dt, q * nn + corner[0], x0);
            final_position(m, dt, q * nn + corner[1], x1);
            final_position(m, dt, q * nn + corner[2], x2);
            const double e1[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
            const double e2[3] = {x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]};
            N[0] += e1[1] * e2[2] - e1[2] * e2[1];
            N[1] += e1[2] * e2[0] - e1[0] * e2[2];
            N[2] += e1[0] * e2[1] - e1[1] * e2[0];
        }
    }
    const double len = sqrt(N[0] * N[0] + N[1] * N[1] + N[2] * N[2]);
    double xa[3], xb[3];
    final_position(m, dt, S->a[c], xa);
    final_position(m, dt, S->b[c], xb);
    if (!(len > 0))
        return INFINITY;
    return ((xb[0] - xa[0]) * N[0] + (xb[1] - xa[1]) * N[1] + (xb[2] - xa[2]) * N[2]) / len;
}

/* Pair c's interpenetration at the positions now (m, > 0: closer than h), its
 * gap at the first look taken back by the step, linearly along its whole
 * gradient: −(g − Δt G·v), v the velocities at the first look (a pair's
 * normal turns with its facets: measured along the first look's normal alone,
 * a pair whose facets turn under it would read a depth it does not have, and
 * hold it). */
static double depth_now(const wff_model *m, const struct solve_step *T, int c)
{
    const struct wff_pack *P = m->pack;
    const struct wff_ply_solve *S = P->solve;
    const int nn = P->nodes, i = S->slot[c] % nn, start = S->ring_start[i];
    const int ring = S->ring_start[i + 1] - start;
    const double *G = gradient_of(P, S->slot[c]);
    double rate = 0;
    for (int side = 0; side < 2; side++) {
        const int base = (side ? S->b[c] : S->a[c]) / nn * nn;
        const double *Gs = G + 3 * ring * side;
        for (int k = 0; k < ring; k++) {
            const double *v = S->v_first + 3 * (base + S->ring_node[start + k]);
            rate += Gs[3 * k] * v[0] + Gs[3 * k + 1] * v[1] + Gs[3 * k + 2] * v[2];
        }
    }
    return -(S->g[c] - T->dt * rate);
}

/* The pair's target gap at the step's end (m, <= 0): 0 (contact distance h)
 * unless closer than h now; then RECOVERY of that removed per full step
 * (recovery: this step's share), above RECOVERY_SPAN h only the closing
 * stopped. */
static inline double pair_target(double now, double h, double recovery)
{
    if (now > RECOVERY_SPAN * h)
        return -now;
    if (now > 0)
        return -(1 - recovery) * now;
    return 0;
}

/* Add the constraints of column i (a pair of its in contact at the first
 * look): ply by ply, a nose contact of its node (one the projectile's contact
 * pushed this step, or within NOSE_MARGIN h of the nose), then its pair (every
 * pair of the column not left out: one clear now may be pushed into contact);
 * their couplings in the column. Returns the constraints' count so far. */
static int add_column(wff_model *m, const struct solve_step *T, const wff_projectile *nose,
                      double recovery, int i, int count)
{
    struct wff_pack *P = m->pack;
    struct wff_ply_solve *S = P->solve;
    const wff_projectile *pr = &m->projectile;
    const int nn = P->nodes, first = count;
    for (int p = 0; p < P->n; p++) {
        const int node = p * nn + i;
        if (pr->active && P->live[node]) {
            double nrm[3];
            const double gap = wff_projectile_gap(nose, P->predicted + 3 * node, nrm);
            const int c = P->on_projectile[node];
            if (c >= 0 || gap < NOSE_MARGIN * T->h) {
                S->kind[count] = NOSE;
                S->slot[count] = node;
                S->a[count] = node, S->b[count] = -1;
                memcpy(S->normal + 3 * count, nrm, sizeof nrm);
                /* the projectile's own contact gave it j: the solve may take back
                 * its normal part, not more */
                const double *j = c >= 0 ? pr->impulse + 3 * c : NULL;
                const double given = j ? j[0] * nrm[0] + j[1] * nrm[1] + j[2] * nrm[2] : 0;
                S->lo[count] = -fmax(given, 0);
                /* its friction so far: the projectile contact's, in the tangent plane */
                for (int k = 0; k < 3; k++)
                    S->friction[3 * count + k] = j ? j[k] - given * nrm[k] : 0;
                S->g[count] = gap;
                S->target[count] = 0;
                S->lambda[count] = 0;
                S->diag[count] = self_coupling(m, count);
                if (S->diag[count] > 0)
                    count++;
            }
        }
        if (p + 1 >= P->n)
            continue;
        struct pair_look L;
        if (look(m, p, i, T->h, T->dt, 0, &L) != LOOK_PAIR)
            continue;
        if (!(inverse_mass(m, L.A, L.n) + inverse_mass(m, L.B, L.n) > 0))
            continue; /* neither node can move along the normal (held): the supports take it */
        const int slot = p * nn + i;
        pair_gradient(m, &L, i, gradient_of(P, slot));
        S->kind[count] = PAIR;
        S->slot[count] = slot;
        S->a[count] = L.A, S->b[count] = L.B;
        memcpy(S->normal + 3 * count, L.n, sizeof L.n);
        S->lo[count] = 0;
        S->g[count] = L.g;
        S->target[count] = pair_target(depth_now(m, T, count), T->h, recovery);
        S->lambda[count] = 0;
        S->friction[3 * count] = S->friction[3 * count + 1] = S->friction[3 * count + 2] = 0;
        S->diag[count] = self_coupling(m, count);
        if (S->diag[count] > 0)
            count++;
    }
    for (int c = first; c < count; c++) {
        S->off[2 * c] = c - 1 >= first ? coupling(m, c - 1, c) : 0;
        S->off[2 * c + 1] = c - 2 >= first ? coupling(m, c - 2, c) : 0;
    }
    return count;
}

int wff_ply_contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    struct wff_pack *P = m->pack;
    if (!P || P->n < 2)
        return 0;
    const double started = wff_wall_seconds();
    if (!P->impulse && ensure_workspace(m, err))
        return -1;
    struct wff_ply_solve *S = P->solve;
    const int nn = P->nodes, slots = (P->n - 1) * nn;
    const double h = wff_ply_contact_distance(m);
    nodal_normals(m, dt);
    wff_projectile *pr = &m->projectile;
    for (int c = 0; pr->active && c < pr->n_contact; c++)
        P->on_projectile[pr->contact_node[c]] = c;
    const double vp_before = pr->velocity;
    P->projectile_dv = 0;
    P->contacts = 0;
    P->penetration = 0;
    P->n_touched = 0;
    P->left_out = 0;
    P->sweeps = 0;
    /* the first look: every pair (the columns with a pair in contact) */
    S->n_columns = 0;
    for (int slot = 0; slot < slots; slot++) {
        struct pair_look L;
        const int r = look(m, slot / nn, slot % nn, h, dt, 1, &L);
        double rest = 0;
        if (r == LOOK_NONE)
            P->left_out++; /* (a dead node: the live ply below pairs through it) */
        else if (r != LOOK_CLEAR) {
            const double delta = -L.g; /* > 0: closer than h */
            if (delta > ROUND_OFF * h) {
                if (r == LOOK_APART)
                    P->left_out++;
                else
                    S->in_column[slot % nn] = 1;
            }
            if (r == LOOK_PAIR)
                rest = delta;
        }
        P->rest[slot] = rest;
    }
    /* the columns' constraints */
    const double full = m->dt_factor * m->dt_stable;
    const double recovery = full > 0 && dt < full ? RECOVERY * dt / full : RECOVERY;
    const struct solve_step T = {h, dt, dt_mid, pr->velocity};
    wff_projectile nose = *pr;
    nose.tip = pr->tip + dt * pr->velocity; /* predicted */
    int count = 0;
    for (int i = 0; i < nn; i++) {
        if (!S->in_column[i])
            continue;
        S->in_column[i] = 0;
        S->columns[S->n_columns] = i;
        S->column_start[S->n_columns] = count;
        count = add_column(m, &T, &nose, recovery, i, count);
        S->n_columns++;
    }
    S->column_start[S->n_columns] = count;
    /* block Gauss-Seidel over the columns, in alternating order */
    for (int sweep = 0; sweep < MAX_SWEEPS && S->n_columns > 0; sweep++) {
        double worst = 0;
        for (int k = 0; k < S->n_columns; k++) {
            const int col = sweep % 2 ? S->n_columns - 1 - k : k;
            const int start = S->column_start[col], K = S->column_start[col + 1] - start;
            worst = fmax(worst, solve_column(m, &T, start, K));
            worst = fmax(worst, pair_friction(m, &T, start, K));
            worst = fmax(worst, nose_friction(m, &T, start, K));
        }
        P->sweeps = sweep + 1;
        if (worst <= SWEEP_TOLERANCE * h)
            break;
    }
    /* what is left: the pairs of the columns solved at the predicted
     * positions after the solve, along their normals there; the others as the
     * first look found them */
    double solved = 0, untouched = 0;
    for (int k = 0; k < S->n_columns; k++)
        S->in_column[S->columns[k]] = 1;
    for (int slot = 0; slot < slots; slot++)
        if (!S->in_column[slot % nn])
            untouched = fmax(untouched, P->rest[slot]);
    for (int c = 0; c < count; c++) {
        if (S->kind[c] != PAIR)
            continue;
        solved = fmax(solved, h - final_distance(m, dt, c));
        P->contacts += S->lambda[c] > 0;
    }
    for (int k = 0; k < S->n_columns; k++)
        S->in_column[S->columns[k]] = 0;
    P->penetration = fmax(untouched, solved);
    /* the impulses as forces over the step (their work: the book op, once every
     * part has corrected) */
    for (int t = 0; t < P->n_touched; t++) {
        const int n = P->touched_list[t];
        for (int c = 0; c < 3; c++) {
            const double j = P->impulse[3 * n + c] + P->nose_impulse[3 * n + c];
            if (j != 0) {
                m->f[D * n + c] += j / dt_mid;
                m->contact_force[D * n + c] += j / dt_mid;
            }
        }
    }
    for (int c = 0; pr->active && c < pr->n_contact; c++)
        P->on_projectile[pr->contact_node[c]] = -1;
    if (P->projectile_dv != 0) { /* the projectile's share: its momentum */
        const double dv = pr->velocity - vp_before;
        pr->force -= pr->mass * dv / dt_mid;
        pr->impulse_total -= pr->mass * dv;
    }
    P->seconds += wff_wall_seconds() - started;
    return 0;
}

double wff_ply_thickness(const wff_model *m)
{
    if (m->pack && m->pack->thickness > 0)
        return m->pack->thickness;
    return m->mat.areal_density / (WFF_PLY_FIBRE_DENSITY * WFF_PLY_FIBRE_FRACTION);
}

double wff_ply_contact_distance(const wff_model *m)
{
    double t = wff_ply_thickness(m), gap = m->pack ? m->pack->gap : t;
    return t < gap ? t : gap;
}

double wff_ply_penetration_bound(const wff_model *m)
{
    const struct wff_pack *P = m->pack;
    const double h = wff_ply_contact_distance(m);
    double reach = 0;
    for (int i = 0; P && P->reach && i < P->nodes; i++)
        reach = fmax(reach, P->reach[i]);
    return h + CROSS_LIMIT * reach;
}

/* The book op (part.h): this step's impulses' work at the final velocities,
 * j·(v^{n+½} − ½Δt_before a^n): the pairs' (their normal impulses and
 * friction) into the ply contact's dissipation; the nose contacts' the solve
 * held (normal and friction, the projectile's share at its own velocity) into
 * the projectile contact's, dissipated_friction (they are the projectile's
 * contact, solved again with the pairs: a nose contact may take back some of
 * the impulse the projectile's own correction gave, and only the two together
 * are that contact's work). The impulses cleared for the next step. */
static void ply_contact_book(wff_model *m, double dt_before, double dt_mid)
{
    struct wff_pack *P = m->pack;
    if (!P || P->n < 2 || !P->impulse)
        return;
    double pairs = 0, nose = 0;
    for (int t = 0; t < P->n_touched; t++) {
        const int n = P->touched_list[t];
        for (int c = 0; c < 3; c++) {
            const int k = D * n + c;
            const double j = P->impulse[3 * n + c], jn = P->nose_impulse[3 * n + c];
            if (j != 0)
                pairs += wff_impulse_work(m, k, j, dt_before, dt_mid);
            if (jn != 0)
                nose += wff_impulse_work(m, k, jn, dt_before, dt_mid);
            P->impulse[3 * n + c] = P->nose_impulse[3 * n + c] = 0;
        }
        P->touched[n] = 0;
    }
    P->n_touched = 0;
    const wff_projectile *pr = &m->projectile;
    if (P->projectile_dv != 0) {
        nose += wff_projectile_impulse_work(m, pr->mass * P->projectile_dv, dt_before, dt_mid);
        P->projectile_dv = 0;
    }
    P->dissipated -= pairs;
    m->dissipated_friction -= nose;
}

/* The kinetic energy the ply contact removed, J (model part). */
static double ply_contact_dissipated(const wff_model *m)
{
    return m->pack ? m->pack->dissipated : 0;
}

/* Its state for checkpoints and the adaptive step: the energy its pairs
 * removed, and the last step's measures (the values a load gives back before
 * the next step recomputes them). The rest it rebuilds every step from the
 * positions and the erosion flags. */
static int ply_contact_state_fields(wff_model *m, wff_state_field *f)
{
    struct wff_pack *P = m->pack;
    if (!P || P->n < 2)
        return 0;
    f[0] = (wff_state_field){&P->dissipated, sizeof P->dissipated, 1};
    f[1] = (wff_state_field){&P->penetration, sizeof P->penetration, 1};
    f[2] = (wff_state_field){&P->contacts, sizeof P->contacts, 1};
    f[3] = (wff_state_field){&P->left_out, sizeof P->left_out, 1};
    f[4] = (wff_state_field){&P->sweeps, sizeof P->sweeps, 1};
    return 5;
}

const wff_part_ops wff_ply_contact_part = {
    .name = "ply_contact",
    .correct = wff_ply_contact_correct,
    .book = ply_contact_book,
    .dissipated = ply_contact_dissipated,
    .state_fields = ply_contact_state_fields,
};

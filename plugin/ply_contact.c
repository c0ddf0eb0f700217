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
 * |F| <= μ λ (stick if the cone allows), after each column's normal solve:
 * the column's pairs together, then its nose contacts, a nose's step sized
 * for the stack its sticking pairs hold to its node (the pairs' friction
 * spreads a nose's change over that stack: sized for its node alone, the
 * stack of n gave back (n − 1)/n of it each sweep, and two steps in three of
 * the 8-ply pack ended at the sweeps' cap; the same fixed points either way,
 * the plain step kept: pack->nose_step_alone, and with erosion on). The
 * sweeps' slow mode was that, not the columns' coupling: the normal impulses
 * settle in a few sweeps.
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
#include "ply_solve.h"
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
                S->diag[count] = wff_ply_self_coupling(m, count);
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
        S->diag[count] = wff_ply_self_coupling(m, count);
        if (S->diag[count] > 0)
            count++;
    }
    for (int c = first; c < count; c++) {
        S->off[2 * c] = c - 1 >= first ? wff_ply_coupling(m, c - 1, c) : 0;
        S->off[2 * c + 1] = c - 2 >= first ? wff_ply_coupling(m, c - 2, c) : 0;
    }
    return count;
}

int wff_ply_contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    struct wff_pack *P = m->pack;
    if (!P || P->n < 2)
        return 0;
    const double started = wff_wall_seconds();
    if (!P->impulse && wff_ply_workspace(m, err))
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
            worst = fmax(worst, wff_ply_solve_column(m, &T, start, K));
            worst = fmax(worst, wff_ply_pair_friction(m, &T, start, K));
            worst = fmax(worst, wff_ply_nose_friction(m, &T, start, K));
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

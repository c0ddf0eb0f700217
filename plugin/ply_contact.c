/* ply_contact.c: kinematic contact between neighbouring plies of a pack
 * (include/wovenff/pack.h). Every ply is a two-sided surface of thickness t:
 * the mid-planes of plies p and p + 1 keep h = min(t, gap) apart. The plies
 * are copies of one mesh, coincident in plane at the start, so the contact is
 * node to node: node i of ply p against node i of ply p + 1 (a symmetric rule,
 * no facet search), along n, the mean of the two plies' nodal normals (area-
 * weighted facet normals at the predicted positions, continuous as the pack
 * deflects). Each step, after the projectile's correction, the pairs whose
 * predicted distance x_B − x_A (x = X + u + Δt v) along n is below h get an
 * inelastic normal impulse j_n ∇g, j_n = δ / (Δt Σ|∇_k g|²/m_k), along the
 * gradient of the pair's constraint g = (x_B − x_A)·N/|N| − h: +n on the upper
 * node, −n on the lower, and s·∂N/∂x_k / |N| on the nodes of their facets (s the
 * pair's in-plane offset; N turns with those nodes; the gradient sums to 0:
 * momentum conserved exactly; on A and B alone, along n, the impulse worked
 * against the normal's turn and put energy in: docs/model.md §23), then Coulomb friction μ against the tangential relative velocity,
 * |j_t| <= μ j_n (stick if the cone allows). A pair already closer than h now
 * has only RECOVERY of that removed per step (pushing it all out at once would
 * put energy in), and one deeper than RECOVERY_SPAN h is only stopped from
 * closing. Through a hole: a node whose facets have all eroded has no pair;
 * node i of the ply below it pairs with node i of the first ply above it that
 * has a facet left (plies p − 1 and p + 1 through ply p's hole, the same
 * contact distance h: the eroded ply is not there). Left out: a pair with a
 * fragment (a dead node with no live ply above it; the normals are of the
 * facets left), one slid apart in plane by more
 * than SLIP_LIMIT of the node's shortest edge, one that has crossed (a torn
 * ply's nodes dragged away from their partners). The pairs corrected are
 * swept again (symmetric Gauss-Seidel) until the largest correction a sweep
 * makes is below SWEEP_TOLERANCE h (a pack pushed as a chain). A component
 * held by a boundary condition takes no impulse: its support's reaction does;
 * a node the projectile pushed this step moves with it along z
 * (the projectile's mass added, its velocity and impulse updated). The impulses
 * enter f as forces j / Δt_mid; their work at the integer-step velocities,
 * negated, is the ply contact dissipation (a term of the energy balance). No
 * effect on the stable step. Limits: the pairs are fixed, so the relative
 * in-plane slip of neighbouring plies must stay small against the element
 * size (the inter-ply friction keeps it so near the impact; a ply that slides
 * by more meets its neighbour's node i still, not the node now below it);
 * plies pair with their neighbours only, or with the next live one through a
 * hole (enough while plies cannot pass each other, which the contact keeps).
 * The normals pass runs one ply a thread; the sweeps are serial. */
#include "ply_contact.h"
#include "wall_clock.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void wff_ply_contact_free(struct wff_pack *P)
{
    free(P->impulse);
    free(P->touched);
    free(P->touched_list);
    free(P->active);
    free(P->on_projectile);
    free(P->normal);
    free(P->live);
    free(P->reach);
    P->normal = P->reach = NULL;
    P->live = NULL;
    P->active = P->on_projectile = NULL;
    free(P->predicted);
    free(P->facet);
    free(P->rest);
    P->rest = NULL;
    free(P->node_facets);
    free(P->node_facet_start);
    free(P->grad_node);
    free(P->grad);
    P->node_facets = P->node_facet_start = P->grad_node = NULL;
    P->grad = NULL;
    P->facet = P->touched_list = NULL;
    P->impulse = P->predicted = NULL;
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

static int ensure_workspace(wff_model *m, wff_error *err)
{
    struct wff_pack *P = m->pack;
    if (P->impulse)
        return 0;
    size_t slots = (size_t)(P->n - 1) * (size_t)P->nodes;
    P->impulse = calloc(3 * (size_t)m->n_nodes, sizeof(double));
    P->touched = calloc((size_t)m->n_nodes, 1);
    P->touched_list = malloc(sizeof(int) * (size_t)m->n_nodes);
    P->active = malloc(sizeof(int) * (slots + 1));
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
    if (!P->impulse || !P->touched || !P->touched_list || !P->active ||
        !P->on_projectile || !P->normal || !P->live || !P->reach || !P->predicted || !P->facet || !P->rest) {
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
    if (!P->node_facet_start || !P->node_facets) {
        wff_ply_contact_free(P);
        return wff_fail(err, "ply contact: out of memory for the facets of %d nodes", P->nodes);
    }
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++)
            P->node_facet_start[P->facet[3 * f + k] + 1]++;
    int valence = 0;
    for (int i = 0; i < P->nodes; i++) {
        valence = valence > P->node_facet_start[i + 1] ? valence : P->node_facet_start[i + 1];
        P->node_facet_start[i + 1] += P->node_facet_start[i];
    }
    int *cursor = malloc(sizeof(int) * ((size_t)P->nodes + 1));
    if (!cursor) {
        wff_ply_contact_free(P);
        return wff_fail(err, "ply contact: out of memory for the facets of %d nodes", P->nodes);
    }
    memcpy(cursor, P->node_facet_start, sizeof(int) * (size_t)P->nodes);
    for (int f = 0; f < nf; f++)
        for (int k = 0; k < 3; k++)
            P->node_facets[cursor[P->facet[3 * f + k]]++] = f;
    free(cursor);
    /* a pair's gradient: the nodes of A's and B's facets (3 each, repeats merged) */
    P->grad_max = 2 * 3 * valence + 2;
    P->grad_node = malloc(sizeof(int) * (size_t)P->grad_max);
    P->grad = malloc(sizeof(double) * 3 * (size_t)P->grad_max);
    if (!P->grad_node || !P->grad) {
        wff_ply_contact_free(P);
        return wff_fail(err, "ply contact: out of memory for a pair's gradient");
    }
    return 0;
}

/* Interpenetration below ROUND_OFF h is round-off of the flat pack's
 * coordinates (z = p gap), not contact. */
#define ROUND_OFF 1e-9
/* A pair clear of contact by (1 − FILTER_SHARE ROUND_OFF) h takes the squared
 * test; between that and (1 − ROUND_OFF) h, the exact one. */
#define FILTER_SHARE 0.5
#define FILTER_SQUARED ((1 - FILTER_SHARE * ROUND_OFF) * (1 - FILTER_SHARE * ROUND_OFF))
/* Sweeps over the slots in contact after the first (Gauss-Seidel), until what
 * is left is below SWEEP_TOLERANCE h. */
#define MAX_SWEEPS 20
/* The share of an interpenetration already there that a step removes. */
#define RECOVERY 0.2
#define SWEEP_TOLERANCE 1e-6
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
/* Fewest DOFs for which the normals take a team (as the step's passes,
 * step_threads.c: a team's start costs ~10 µs) */
#define PLY_TEAM_MIN_DOFS 16384

/* The mass component c of node n moves with: its own, and the projectile's
 * along z while the projectile pushes it (this step's projectile contact): a
 * node on the nose that the next ply pushes back takes the projectile with it,
 * rather than being pushed into it. */
static inline double moving_mass(const wff_model *m, int n, int c)
{
    double mass = m->mass[D * n];
    if (c == WFF_UZ && m->pack->on_projectile[n] >= 0)
        mass += m->projectile.mass;
    return mass;
}

/* Add impulse j (3) to node n: its free components' velocities (and the
 * projectile's, moving with it), the held ones' reactions; the node's share
 * kept for the forces and work. */
static void give(wff_model *m, int n, const double j[3], double dt_mid)
{
    struct wff_pack *P = m->pack;
    for (int c = 0; c < 3; c++) {
        if (m->dof_kind[D * n + c] != WFF_DOF_FREE) {
            m->reaction[D * n + c] -= j[c] / dt_mid;
            continue;
        }
        double dv = j[c] / moving_mass(m, n, c);
        m->v[D * n + c] += dv;
        P->impulse[3 * n + c] += m->mass[D * n] * dv;
        if (c == WFF_UZ && P->on_projectile[n] >= 0) {
            m->projectile.velocity += dv;
            P->projectile_dv += dv;
        }
    }
    if (!P->touched[n]) {
        P->touched[n] = 1;
        P->touched_list[P->n_touched++] = n;
    }
}

/* The inverse mass of node n along direction d (its free components). */
static double inverse_mass(const wff_model *m, int n, const double d[3])
{
    double w = 0;
    for (int c = 0; c < 3; c++)
        if (m->dof_kind[D * n + c] == WFF_DOF_FREE)
            w += d[c] * d[c] / moving_mass(m, n, c);
    return w;
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

/* The first ply below ply p with a facet left at node i, or -1. */
static inline int partner_below(const struct wff_pack *P, int p, int i)
{
    for (int q = p - 1; q >= 0; q--)
        if (P->live[(size_t)q * P->nodes + i])
            return q;
    return -1;
}

/* Add d (3) to node `node`'s entry of the pair's gradient workspace (n entries). */
static int gradient_add(struct wff_pack *P, int n, int node, const double d[3])
{
    int k = 0;
    while (k < n && P->grad_node[k] != node)
        k++;
    if (k == n) {
        if (n == P->grad_max)
            return n; /* (cannot happen: the workspace holds every facet's nodes) */
        P->grad_node[n] = node;
        P->grad[3 * n] = P->grad[3 * n + 1] = P->grad[3 * n + 2] = 0;
        n++;
    }
    P->grad[3 * k] += d[0], P->grad[3 * k + 1] += d[1], P->grad[3 * k + 2] += d[2];
    return n;
}

/* The gradient of the pair's constraint g = (x_B − x_A)·N/|N| − h over the
 * predicted positions (N = N_A + N_B, the raw sums of the facets' normals at
 * node i of A's ply and of B's, len = |N|, n = N/len, s the pair's in-plane
 * offset (I − nn)(x_B − x_A)): ±n on B and A, and s·∂N/∂x_k / len on the nodes
 * of those facets. The nodes and the gradient in P->grad_node, P->grad; their
 * count returned. Its sum is 0 (momentum kept). */
static int pair_gradient(wff_model *m, int A, int B, int i, const double n[3], const double s[3],
                         double len)
{
    struct wff_pack *P = m->pack;
    const unsigned char *eroded = m->el.eroded;
    const int nn = P->nodes, plies[2] = {A / nn, B / nn};
    int count = 0;
    for (int side = 0; side < 2; side++) {
        const int q = plies[side];
        for (int a = P->node_facet_start[i]; a < P->node_facet_start[i + 1]; a++) {
            const int f = P->node_facets[a];
            if (eroded && eroded[facet_element(P, q, f)])
                continue;
            const int *c = P->facet + 3 * f;
            const int g0 = q * nn + c[0], g1 = q * nn + c[1], g2 = q * nn + c[2];
            const double *x0 = P->predicted + 3 * g0, *x1 = P->predicted + 3 * g1,
                         *x2 = P->predicted + 3 * g2;
            const double e1[3] = {x1[0] - x0[0], x1[1] - x0[1], x1[2] - x0[2]};
            const double e2[3] = {x2[0] - x0[0], x2[1] - x0[1], x2[2] - x0[2]};
            /* s·(e1 × e2): ∂/∂x1 = e2 × s, ∂/∂x2 = s × e1, ∂/∂x0 = −both */
            const double d1[3] = {(e2[1] * s[2] - e2[2] * s[1]) / len, (e2[2] * s[0] - e2[0] * s[2]) / len,
                                  (e2[0] * s[1] - e2[1] * s[0]) / len};
            const double d2[3] = {(s[1] * e1[2] - s[2] * e1[1]) / len, (s[2] * e1[0] - s[0] * e1[2]) / len,
                                  (s[0] * e1[1] - s[1] * e1[0]) / len};
            const double d0[3] = {-d1[0] - d2[0], -d1[1] - d2[1], -d1[2] - d2[2]};
            count = gradient_add(P, count, g0, d0);
            count = gradient_add(P, count, g1, d1);
            count = gradient_add(P, count, g2, d2);
        }
    }
    const double minus[3] = {-n[0], -n[1], -n[2]};
    count = gradient_add(P, count, B, n);
    count = gradient_add(P, count, A, minus);
    return count;
}

/* One pair: node i of ply `pair` (below, A) and of the first ply above it with
 * a facet left there (B: ply pair + 1, or one further up through a hole).
 * Returns 1 if corrected, 0 if not in contact, -1 if left out (a dead node A
 * or none above, slid apart, crossed); *rest the interpenetration h − d (m,
 * before the correction); *moved (when corrected) the part of it this
 * correction removes (m: the push-out's share of one already there only). */
static int correct_pair(wff_model *m, int pair, int i, double h, double dt, double dt_mid,
                        int apply, double *rest, double *moved)
{
    const double full = m->dt_factor * m->dt_stable;
    const double recovery = full > 0 && dt < full ? RECOVERY * dt / full : RECOVERY;
    const struct wff_pack *P = m->pack;
    const int A = pair * P->nodes + i;
    if (!P->live[A])
        return -1; /* a dead node: no pair (the live ply below pairs through it) */
    const int B = upper_node(P, pair, i);
    if (B < 0)
        return -1; /* a fragment, or nothing above: left out */
    /* (the test every pair takes in scalars: small arrays written one by one
     * and read as pairs stalled the store forwarding) */
    const double *xy_a = m->mesh.xy + 2 * A, *xy_b = m->mesh.xy + 2 * B;
    const double *ua = m->u + D * A, *ub = m->u + D * B, *va = m->v + D * A, *vb = m->v + D * B;
    const double gap_x = (xy_b[0] + ub[0] + dt * vb[0]) - (xy_a[0] + ua[0] + dt * va[0]),
                 gap_y = (xy_b[1] + ub[1] + dt * vb[1]) - (xy_a[1] + ua[1] + dt * va[1]),
                 gap_z = (ub[2] + dt * vb[2]) - (ua[2] + dt * va[2]); /* x_B − x_A predicted */
    const double *na = P->normal + 3 * A, *nb = P->normal + 3 * B;
    double nx = na[0] + nb[0], ny = na[1] + nb[1], nz = na[2] + nb[2];
    const double len2 = nx * nx + ny * ny + nz * nz, along = gap_x * nx + gap_y * ny + gap_z * nz;
    /* clear by more than FILTER_SHARE of ROUND_OFF h (compared squared, no root
     * and no division: most pairs of a pack are clear): the test below would
     * say so too, its rounding being ~1e-16 of what is compared */
    if (along > 0 && along * along >= FILTER_SQUARED * h * h * len2) {
        *rest = 0; /* (a clear pair's rest counts as 0 in the penetration measure) */
        return 0;
    }
    double len = sqrt(len2);
    if (!(len > 0))
        return 0;
    nx /= len, ny /= len, nz /= len;
    const double dist = gap_x * nx + gap_y * ny + gap_z * nz;
    double delta = h - dist; /* > 0: closer than h */
    if (delta <= ROUND_OFF * h) {
        *rest = delta;
        return 0;
    }
    const double closing = (va[0] - vb[0]) * nx + (va[1] - vb[1]) * ny + (va[2] - vb[2]) * nz;
    double nrm[3] = {nx, ny, nz};
    const double tx = gap_x - dist * nx, ty = gap_y - dist * ny, tz = gap_z - dist * nz;
    const double slip = tx * tx + ty * ty + tz * tz; /* (squared, in plane) */
    /* left out: a pair slid apart (a torn ply's node beside the shank and the
     * next ply's under the nose), a pair that has crossed */
    const double reach = SLIP_LIMIT * P->reach[i], now = delta - dt * closing; /* h − distance now */
    if (slip > reach * reach || h - now < -CROSS_LIMIT * P->reach[i])
        return -1;
    *rest = delta;
    if (!apply)
        return 0;
    /* closer than h now already: only RECOVERY of that per full step (dtfactor ×
     * the stable step; a step the travel limit shortens pushes out its share of
     * it, so the push-out's speed does not grow as the step falls), the rest of
     * the correction stops the approach (pushing it all out at once would put
     * energy in: the push-out parts the pair at up to RECOVERY RECOVERY_SPAN h /
     * the full step); above RECOVERY_SPAN h, only the approach is stopped */
    if (now > RECOVERY_SPAN * h)
        delta -= now;
    else if (now > 0)
        delta -= (1 - recovery) * now;
    if (delta <= ROUND_OFF * h)
        return 0;
    *moved = delta;
    /* the normal impulse along the gradient of the constraint g = (x_B − x_A)·n − h:
     * n is of the facets' positions, so g moves with the facets' nodes too
     * (s·∂N/∂x_k / |N|, s the in-plane offset of the pair); an impulse on A and
     * B alone, along n, works against that part and puts energy in */
    if (!(inverse_mass(m, A, nrm) + inverse_mass(m, B, nrm) > 0))
        return 0; /* neither node can move along the normal (held): the supports take it */
    const double slip_vec[3] = {tx, ty, tz};
    const int n_grad = pair_gradient(m, A, B, i, nrm, slip_vec, len);
    struct wff_pack *W = m->pack;
    double w = 0;
    for (int k = 0; k < n_grad; k++)
        for (int c = 0; c < 3; c++)
            if (m->dof_kind[D * W->grad_node[k] + c] == WFF_DOF_FREE)
                w += W->grad[3 * k + c] * W->grad[3 * k + c] / moving_mass(m, W->grad_node[k], c);
    if (!(w > 0))
        return 0;
    const double jn = delta / dt / w;
    for (int k = 0; k < n_grad; k++) {
        const double jk[3] = {jn * W->grad[3 * k], jn * W->grad[3 * k + 1], jn * W->grad[3 * k + 2]};
        give(m, W->grad_node[k], jk, dt_mid);
    }
    if (P->mu > 0) { /* friction against the tangential relative velocity after jn */
        double rel[3], along = 0, speed = 0, vt[3];
        for (int c = 0; c < 3; c++) {
            rel[c] = m->v[D * B + c] - m->v[D * A + c];
            along += rel[c] * nrm[c];
        }
        for (int c = 0; c < 3; c++) {
            vt[c] = rel[c] - along * nrm[c];
            speed += vt[c] * vt[c];
        }
        speed = sqrt(speed);
        if (speed > 0) {
            double t[3] = {vt[0] / speed, vt[1] / speed, vt[2] / speed};
            double wt = inverse_mass(m, A, t) + inverse_mass(m, B, t);
            double jt = wt > 0 ? fmin(P->mu * jn, speed / wt) : 0; /* stick if the cone allows */
            const double jb[3] = {-jt * t[0], -jt * t[1], -jt * t[2]};
            const double ja[3] = {jt * t[0], jt * t[1], jt * t[2]};
            give(m, B, jb, dt_mid);
            give(m, A, ja, dt_mid);
        }
    }
    return 1;
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

/* Every node's unit normal at the predicted positions: the area-weighted mean of its
 * ply's facets' normals, eroded facets left out; live[n] 1 if node n has a facet
 * left. */
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
        for (int i = 0; i < nn; i++)
            position(m, q * nn + i, dt, predicted + 3 * i);
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

int wff_ply_contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    struct wff_pack *P = m->pack;
    if (!P || P->n < 2)
        return 0;
    const double started = wff_wall_seconds();
    if (!P->impulse && ensure_workspace(m, err))
        return -1;
    const int nn = P->nodes;
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
    P->n_active = 0;
    /* sweep 0 over every pair, then sweeps over those corrected, then a
     * measure of what is left: over the pairs of the nodes an impulse moved
     * (the others are as sweep 0 left them, their rest kept from it) */
    P->left_out = 0;
    for (int sweep = 0; sweep <= MAX_SWEEPS; sweep++) {
        const int n = sweep == 0 ? (P->n - 1) * nn : P->n_active;
        double worst = 0;
        for (int k = 0; k < n; k++) {
            /* later sweeps alternate direction (symmetric Gauss-Seidel) */
            const int slot = sweep == 0 ? k : P->active[sweep % 2 ? P->n_active - 1 - k : k];
            double rest = 0, moved = 0;
            int r = correct_pair(m, slot / nn, slot % nn, h, dt, dt_mid, 1, &rest, &moved);
            if (sweep == 0) {
                P->rest[slot] = rest;
                P->left_out += r < 0;
            }
            if (r > 0) {
                worst = fmax(worst, moved); /* (not rest: a pair already in keeps
                                               most of that, sweep after sweep) */
                if (sweep == 0) {
                    P->active[P->n_active++] = slot;
                    P->contacts++;
                }
            }
        }
        if (sweep > 0 && worst <= SWEEP_TOLERANCE * h)
            break; /* converged */
        if (P->n_active == 0 && sweep == 0)
            break;
    }
    /* the pairs no impulse moved: as sweep 0 measured them */
    double untouched = 0;
    for (int slot = 0; slot < (P->n - 1) * nn; slot++) {
        if (P->rest[slot] <= 0 || P->touched[slot])
            continue; /* (clear, or measured again below) */
        const int upper = upper_node(P, slot / nn, slot % nn); /* (>= 0: its rest is > 0) */
        if (!P->touched[upper])
            untouched = fmax(untouched, P->rest[slot]);
    }
    P->penetration = untouched;
    for (int t = 0; t < P->n_touched; t++) {
        /* a touched node's pairs: as the lower node, and as the upper node of the
         * first live ply below it */
        const int node = P->touched_list[t], q = node / nn, i = node % nn;
        const int pairs[2] = {partner_below(P, q, i), q};
        for (int k = 0; k < 2; k++) {
            if (pairs[k] < 0 || pairs[k] >= P->n - 1)
                continue;
            double rest = 0, moved = 0;
            correct_pair(m, pairs[k], i, h, dt, dt_mid, 0, &rest, &moved);
            P->penetration = fmax(P->penetration, rest);
        }
    }
    /* the impulses as forces over the step (their work: the book op, once every
     * part has corrected) */
    for (int t = 0; t < P->n_touched; t++) {
        const int n = P->touched_list[t];
        for (int c = 0; c < 3; c++)
            if (P->impulse[3 * n + c] != 0) {
                m->f[D * n + c] += P->impulse[3 * n + c] / dt_mid;
                m->contact_force[D * n + c] += P->impulse[3 * n + c] / dt_mid;
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

/* The book op (part.h): this step's impulses' work at the final velocities,
 * j·(v^{n+½} − ½Δt_before a^n), the projectile's share (the velocity change
 * the plies gave it) at its own; the impulses cleared for the next step. */
static void ply_contact_book(wff_model *m, double dt_before, double dt_mid)
{
    struct wff_pack *P = m->pack;
    if (!P || P->n < 2 || !P->impulse)
        return;
    double work = 0;
    for (int t = 0; t < P->n_touched; t++) {
        const int n = P->touched_list[t];
        for (int c = 0; c < 3; c++) {
            const int k = D * n + c;
            const double j = P->impulse[3 * n + c];
            if (j == 0)
                continue;
            work += wff_impulse_work(m, k, j, dt_before, dt_mid);
            P->impulse[3 * n + c] = 0;
        }
        P->touched[n] = 0;
    }
    P->n_touched = 0;
    const wff_projectile *pr = &m->projectile;
    if (P->projectile_dv != 0) {
        work += wff_projectile_impulse_work(m, pr->mass * P->projectile_dv, dt_before, dt_mid);
        P->projectile_dv = 0;
    }
    P->dissipated -= work;
}

/* The kinetic energy the ply contact removed, J (model part). */
static double ply_contact_dissipated(const wff_model *m)
{
    return m->pack ? m->pack->dissipated : 0;
}

const wff_part_ops wff_ply_contact_part = {
    .name = "ply_contact",
    .correct = wff_ply_contact_correct,
    .book = ply_contact_book,
    .dissipated = ply_contact_dissipated,
};

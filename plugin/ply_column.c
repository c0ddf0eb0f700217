/* ply_column.c: the ply contact's column solve (docs/model.md §23; the
 * method is described at the head of plugin/ply_contact.c): a column's
 * constraints' gaps and couplings, the normal impulses by pivoting on the
 * band, the pairs' and the nose contacts' Coulomb friction. Called by the
 * contact's step (ply_contact.c) in its block Gauss-Seidel over the columns. */
#include "ply_solve.h"
#include "contact.h"

#include <math.h>
#include <string.h>

/* Constraint c's gap now, linear in the velocities from the first look:
 * g + Δt G·(v − v_first) (m). */
double wff_ply_gap_now(const wff_model *m, const struct solve_step *T, int c)
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
double wff_ply_self_coupling(const wff_model *m, int c)
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
double wff_ply_coupling(const wff_model *m, int c, int d)
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
void wff_ply_apply_normal(wff_model *m, const struct solve_step *T, int c, double x)
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
double wff_ply_solve_column(wff_model *m, const struct solve_step *T, int start, int K)
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
        y[k] = (S->target[c] - wff_ply_gap_now(m, T, c)) / T->dt;
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
        wff_ply_apply_normal(m, T, start + k, x[k]);
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
double wff_ply_pair_friction(wff_model *m, const struct solve_step *T, int start, int K)
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

/* Pair c sticks: its friction inside its cone (not at its edge, where the
 * pair friction leaves a pair that slips). */
static int sticks(const struct wff_pack *P, const struct wff_ply_solve *S, int c)
{
    const double *F = S->friction + 3 * c, cone = P->mu * S->lambda[c];
    const double inside = (1 - STICK_MARGIN) * cone;
    return cone > 0 && F[0] * F[0] + F[1] * F[1] + F[2] * F[2] < inside * inside;
}

/* The nose contacts of the column at node n that hold friction (a normal
 * impulse above their bound: a cone). */
static int noses_at(const wff_model *m, int start, int K, int n)
{
    const struct wff_ply_solve *S = m->pack->solve;
    int count = 0;
    for (int c = start; c < start + K; c++)
        count += S->kind[c] == NOSE && S->a[c] == n && m->projectile.mu > 0 && S->lambda[c] > S->lo[c];
    return count;
}

/* The inverse mass along unit t of node `node` and the nodes of its column
 * stuck to it through its pairs (their friction inside the cone), taken as
 * one body and shared by the nose contacts on it: k / Σ 1/w_j for k nose
 * contacts; the node's alone if one of them is held along t. The nose
 * friction's step: the pair friction passes a nose's change on to the stack
 * stuck behind its node, and the stack of n nodes gives back (n − 1)/n of the
 * node's alone each sweep (two steps in three of the 8-ply pack at the
 * sweeps' cap); sized for the stack, it stops the stack at once (each of k
 * noses on it its k-th share, or together they would overshoot it k times).
 * The solve's fixed points are the same (at one: stick, vt = 0; slip, vt
 * against F, whatever the step). */
static double stack_inverse_mass(const wff_model *m, int start, int K, int node, const double t[3])
{
    const struct wff_pack *P = m->pack;
    const struct wff_ply_solve *S = P->solve;
    const double own = inverse_mass(m, node, t);
    if (!(own > 0) || !(P->mu > 0))
        return own;
    double mass = 1 / own;
    int noses = noses_at(m, start, K, node);
    for (int dir = 0; dir < 2; dir++) { /* up the column, then down */
        int at = node;
        for (int step = 0; step < K; step++) {
            int next = -1;
            for (int c = start; c < start + K && next < 0; c++)
                if (S->kind[c] == PAIR && (dir ? S->b[c] : S->a[c]) == at && sticks(P, S, c))
                    next = dir ? S->a[c] : S->b[c];
            if (next < 0)
                break;
            const double w = inverse_mass(m, next, t);
            if (!(w > 0))
                return own;
            mass += 1 / w;
            noses += noses_at(m, start, K, next);
            at = next;
        }
    }
    return (noses > 1 ? noses : 1) / mass;
}

/* The nose contacts' Coulomb friction of a column against the node's
 * tangential velocity less the projectile's, |F| <= μ λ (μ the projectile's,
 * its normal impulse and F the projectile contact's and the solve's
 * together; F on the node, −F_z on the projectile): each one's accumulated
 * friction impulse F moved to the one that stops it, held within the cone
 * (stick if the cone allows). The largest tangential move a change makes (m)
 * returned. */
double wff_ply_nose_friction(wff_model *m, const struct solve_step *T, int start, int K)
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
            /* (a nose: its step sized for the stack stuck behind its node, or
             * for the node alone, the plain step: asked for, or with erosion on,
             * where the stack's step is not shown sound: on the 4-ply
             * perforation of tests/sh/pack_scene.sh a pair came 231 µm closer
             * than h = 209 µm with it, 135 µm plain, 145 µm plain to 400 sweeps) */
            const int stack = nose && !P->nose_step_alone && !m->el.eroded;
            const double node = stack ? stack_inverse_mass(m, start, K, A, t) : inverse_mass(m, A, t);
            const double wt = nose ? node + t[2] * t[2] / pr->mass : node + inverse_mass(m, B, t);
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

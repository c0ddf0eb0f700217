/* ply_workspace.c: the workspace of a pack's ply contact (plugin/ply_contact.c,
 * its step; plugin/ply_column.c, its column solve), made at the contact's first
 * step and freed with the pack: each ply's facets and each node's, each
 * specimen node's ring (the nodes a pair's gradient reaches), the per-node and
 * per-constraint arrays of the solve. */
#include "ply_contact.h"
#include "ply_solve.h"

#include <stdlib.h>
#include <string.h>

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

int wff_ply_workspace(wff_model *m, wff_error *err)
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

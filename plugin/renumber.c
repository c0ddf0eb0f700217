/* renumber.c: the model's own order of nodes and elements, chosen at model
 * build so that neighbours sit close in memory (the gather and scatter of
 * the force pass, the node update and the threads' element ranges touch
 * nearby cache lines): elements sorted along a Hilbert curve through their
 * centroids (triangles among triangles, quadrilaterals among
 * quadrilaterals), nodes numbered in the order those elements first use
 * them. The order depends only on the mesh (coordinates and connectivity),
 * ties broken by the given index, so the same mesh always gets the same
 * order.
 *
 * Invisible to users: every array of the model (mesh, u, v, f, masses, DOF
 * kinds, γᶠ, clamp, candidates) is in the model's order, and the functions
 * that take or return node indices, DOF vectors, element indices or element
 * values map through the permutations kept here (node_user, element_user and
 * their inverses) so that callers see the numbering of the mesh they gave.
 * Knows the mesh and the model's arrays of indices; nothing of cells,
 * elements' physics, the integrator or FreeFEM. */
#include "solver_internal.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Position along a Hilbert curve of order `bits` of the cell (x, y). */
static uint64_t hilbert_index(uint32_t x, uint32_t y, int bits)
{
    uint64_t d = 0;
    for (uint32_t s = 1u << (bits - 1); s > 0; s >>= 1) {
        uint32_t rx = (x & s) != 0, ry = (y & s) != 0;
        d += (uint64_t)s * s * ((3 * rx) ^ ry);
        if (!ry) { /* rotate the quadrant */
            if (rx) {
                x = ~x;
                y = ~y;
            }
            uint32_t t = x;
            x = y;
            y = t;
        }
    }
    return d;
}

typedef struct {
    uint64_t key;
    int index;
} keyed;

static int by_key(const void *a, const void *b)
{
    const keyed *p = a, *q = b;
    if (p->key != q->key)
        return p->key < q->key ? -1 : 1;
    return (p->index > q->index) - (p->index < q->index);
}

#define CURVE_BITS 20

/* Sort n elements of `per` nodes (conn) by the Hilbert index of their
 * centroid in the box lo + [0, span]²; order[new] = old. */
static void curve_order(const double *xy, const int *conn, int n, int per, const double lo[2],
                        double span, keyed *k, int *order)
{
    const double cells = (double)((1u << CURVE_BITS) - 1);
    for (int e = 0; e < n; e++) {
        double c[2] = {0, 0};
        for (int a = 0; a < per; a++)
            for (int j = 0; j < 2; j++)
                c[j] += xy[2 * conn[per * e + a] + j] / per;
        uint32_t ix = (uint32_t)fmin(cells, fmax(0, (c[0] - lo[0]) / span * cells));
        uint32_t iy = (uint32_t)fmin(cells, fmax(0, (c[1] - lo[1]) / span * cells));
        k[e].key = hilbert_index(ix, iy, CURVE_BITS);
        k[e].index = e;
    }
    qsort(k, (size_t)n, sizeof *k, by_key);
    for (int e = 0; e < n; e++)
        order[e] = k[e].index;
}

/* Reorder an element array (per ints each) and its regions by order. */
static void permute_elements(int *conn, int *region, int n, int per, const int *order, int *tmp)
{
    for (int e = 0; e < n; e++)
        memcpy(tmp + per * e, conn + per * order[e], sizeof(int) * (size_t)per);
    memcpy(conn, tmp, sizeof(int) * (size_t)per * (size_t)n);
    if (region) {
        for (int e = 0; e < n; e++)
            tmp[e] = region[order[e]];
        memcpy(region, tmp, sizeof(int) * (size_t)n);
    }
}

int wff_mesh_locality_order(wff_mesh *mesh, int *node_user, int *element_user, wff_error *err)
{
    int nn = mesh->n_nodes, nt = mesh->n_tris, nq = mesh->n_quads;
    size_t big = (size_t)(nn > nt + nq ? nn : nt + nq) + 1;
    keyed *k = malloc(sizeof *k * big);
    int *order = malloc(sizeof(int) * big), *renum = malloc(sizeof(int) * big);
    int *tmp = malloc(sizeof(int) * 4 * big);
    double *xy = malloc(sizeof(double) * 2 * (size_t)(nn + 1));
    if (!k || !order || !renum || !tmp || !xy) {
        free(k), free(order), free(renum), free(tmp), free(xy);
        return wff_fail(err, "out of memory ordering a mesh of %d nodes", nn);
    }
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int n = 0; n < nn; n++)
        for (int j = 0; j < 2; j++)
            lo[j] = fmin(lo[j], mesh->xy[2 * n + j]), hi[j] = fmax(hi[j], mesh->xy[2 * n + j]);
    double span = fmax(hi[0] - lo[0], hi[1] - lo[1]);
    if (!(span > 0))
        span = 1;
    /* elements along the curve */
    curve_order(mesh->xy, mesh->tri, nt, 3, lo, span, k, order);
    for (int e = 0; e < nt; e++)
        element_user[e] = order[e];
    permute_elements(mesh->tri, mesh->tri_region, nt, 3, order, tmp);
    curve_order(mesh->xy, mesh->quad, nq, 4, lo, span, k, order);
    for (int e = 0; e < nq; e++)
        element_user[nt + e] = nt + order[e];
    permute_elements(mesh->quad, mesh->quad_region, nq, 4, order, tmp);
    /* nodes in the order the elements first use them (renum[user] = model) */
    for (int n = 0; n < nn; n++)
        renum[n] = -1;
    int next = 0;
    for (int i = 0; i < 3 * nt; i++)
        if (renum[mesh->tri[i]] < 0)
            renum[mesh->tri[i]] = next++;
    for (int i = 0; i < 4 * nq; i++)
        if (renum[mesh->quad[i]] < 0)
            renum[mesh->quad[i]] = next++;
    for (int n = 0; n < nn; n++) /* (a node in no element: after the others) */
        if (renum[n] < 0)
            renum[n] = next++;
    for (int n = 0; n < nn; n++) {
        node_user[renum[n]] = n;
        xy[2 * renum[n]] = mesh->xy[2 * n];
        xy[2 * renum[n] + 1] = mesh->xy[2 * n + 1];
    }
    memcpy(mesh->xy, xy, sizeof(double) * 2 * (size_t)nn);
    for (int i = 0; i < 3 * nt; i++)
        mesh->tri[i] = renum[mesh->tri[i]];
    for (int i = 0; i < 4 * nq; i++)
        mesh->quad[i] = renum[mesh->quad[i]];
    for (int i = 0; i < 2 * mesh->n_edges; i++)
        mesh->edge[i] = renum[mesh->edge[i]];
    free(k), free(order), free(renum), free(tmp), free(xy);
    return 0;
}

void wff_model_order_free(wff_model *m)
{
    free(m->node_user);
    free(m->node_model);
    free(m->element_user);
    free(m->element_model);
    m->node_user = m->node_model = m->element_user = m->element_model = NULL;
}

int wff_model_renumber(wff_model *m, wff_error *err)
{
    size_t nn = (size_t)m->mesh.n_nodes, ne = (size_t)(m->mesh.n_tris + m->mesh.n_quads);
    m->node_user = malloc(sizeof(int) * (nn + 1));
    m->node_model = malloc(sizeof(int) * (nn + 1));
    m->element_user = malloc(sizeof(int) * (ne + 1));
    m->element_model = malloc(sizeof(int) * (ne + 1));
    if (!m->node_user || !m->node_model || !m->element_user || !m->element_model) {
        wff_model_order_free(m);
        return wff_fail(err, "out of memory for the node order of %zu nodes", nn);
    }
    if (wff_mesh_locality_order(&m->mesh, m->node_user, m->element_user, err)) {
        wff_model_order_free(m);
        return -1;
    }
    for (size_t n = 0; n < nn; n++)
        m->node_model[m->node_user[n]] = (int)n;
    for (size_t e = 0; e < ne; e++)
        m->element_model[m->element_user[e]] = (int)e;
    return 0;
}

int wff_model_user_node(const wff_model *m, int node)
{
    return m->node_user && node >= 0 ? m->node_user[node] : node;
}

int wff_model_node_of_user(const wff_model *m, int user_node)
{
    return m->node_model && user_node >= 0 ? m->node_model[user_node] : user_node;
}

int wff_model_user_element(const wff_model *m, int element)
{
    return m->element_user && element >= 0 ? m->element_user[element] : element;
}

int wff_model_element_of_user(const wff_model *m, int user_element)
{
    return m->element_model && user_element >= 0 ? m->element_model[user_element]
                                                  : user_element;
}

void wff_model_nodes_to_user(const wff_model *m, const double *model, double *user, int per)
{
    for (int n = 0; n < m->n_nodes; n++) {
        int u = wff_model_user_node(m, n);
        memcpy(user + (size_t)per * u, model + (size_t)per * n, sizeof(double) * (size_t)per);
    }
}

void wff_model_nodes_from_user(const wff_model *m, const double *user, double *model, int per)
{
    for (int n = 0; n < m->n_nodes; n++) {
        int u = wff_model_user_node(m, n);
        memcpy(model + (size_t)per * n, user + (size_t)per * u, sizeof(double) * (size_t)per);
    }
}

int wff_model_nodes_to_user_in_place(const wff_model *m, double *a, int per, wff_error *err)
{
    if (!m->node_user)
        return 0;
    size_t bytes = sizeof(double) * (size_t)per * (size_t)m->n_nodes;
    double *copy = malloc(bytes + 1);
    if (!copy)
        return wff_fail(err, "out of memory");
    memcpy(copy, a, bytes);
    wff_model_nodes_to_user(m, copy, a, per);
    free(copy);
    return 0;
}

int wff_model_elements_to_user_in_place(const wff_model *m, double *a, wff_error *err)
{
    if (!m->element_user)
        return 0;
    int ne = m->el.n_tris + m->el.n_quads;
    double *copy = malloc(sizeof(double) * (size_t)(ne + 1));
    if (!copy)
        return wff_fail(err, "out of memory");
    memcpy(copy, a, sizeof(double) * (size_t)ne);
    for (int e = 0; e < ne; e++)
        a[m->element_user[e]] = copy[e];
    free(copy);
    return 0;
}

/* "triangle 3 (nodes 4 5 9)" or "quadrilateral 2 (nodes ...)" for element e
 * of the model (triangles first, then quads), in the user's numbering, each
 * type numbered from 1. */
void wff_model_element_name(const wff_model *m, int e, char *out, size_t size)
{
    if (e < 0) {
        snprintf(out, size, "no element");
        return;
    }
    int tri = e < m->el.n_tris, ue = wff_model_user_element(m, e);
    const int *node = tri ? m->el.tri + 3 * e : m->el.quad + 4 * (e - m->el.n_tris);
    int un[4];
    for (int a = 0; a < (tri ? 3 : 4); a++)
        un[a] = wff_model_user_node(m, node[a]) + 1;
    if (tri)
        snprintf(out, size, "triangle %d (nodes %d %d %d)", ue + 1, un[0], un[1], un[2]);
    else
        snprintf(out, size, "quadrilateral %d (nodes %d %d %d %d)", ue - m->el.n_tris + 1,
                 un[0], un[1], un[2], un[3]);
}

/* mesh_check.c: defects of a loaded mesh's arrays (include/wovenff/mesh.h)
 * that no single element shows: duplicated (coincident) nodes, which leave a
 * slit in the fabric (the elements on either side are not joined), nodes in no
 * element (they would carry no mass), and elements that meet only at a vertex
 * (a hinge no woven fabric has). Each is reported with the node's coordinates.
 * Works on the arrays only: knows nothing of gmsh, materials or the solver. */
#include "wovenff/mesh_check.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Coincident nodes: within this fraction of the bounding-box diagonal. */
#define COINCIDENT_TOL 1e-9

typedef struct node_x {
    double x;
    int node;
} node_x;

static int cmp_by_x(const void *a, const void *b)
{
    double xa = ((const node_x *)a)->x, xb = ((const node_x *)b)->x;
    return (xa > xb) - (xa < xb);
}

/* Element e's node list (triangles first, then quads) and its count. */
static const int *element_nodes(const wff_mesh *m, int e, int *count)
{
    if (e < m->n_tris) {
        *count = 3;
        return m->tri + 3 * (size_t)e;
    }
    *count = 4;
    return m->quad + 4 * (size_t)(e - m->n_tris);
}

/* The 1-based name of element e: "triangle 3" or "quadrilateral 2". */
static int element_number(const wff_mesh *m, int e, const char **kind)
{
    *kind = e < m->n_tris ? "triangle" : "quadrilateral";
    return e < m->n_tris ? e + 1 : e - m->n_tris + 1;
}

/* 1 if elements a and b share an edge through node n (both have n and a
 * common node next to n in their node cycles). */
static int share_edge_at(const wff_mesh *m, int a, int b, int n)
{
    int ca, cb;
    const int *na = element_nodes(m, a, &ca), *nb = element_nodes(m, b, &cb);
    for (int i = 0; i < ca; i++) {
        if (na[i] != n)
            continue;
        int next_a[2] = {na[(i + 1) % ca], na[(i + ca - 1) % ca]};
        for (int j = 0; j < cb; j++) {
            if (nb[j] != n)
                continue;
            int next_b[2] = {nb[(j + 1) % cb], nb[(j + cb - 1) % cb]};
            for (int p = 0; p < 2; p++)
                for (int q = 0; q < 2; q++)
                    if (next_a[p] == next_b[q])
                        return 1;
        }
    }
    return 0;
}

static int find_root(int *parent, int i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

int wff_mesh_check(const wff_mesh *m, int allow_vertex_only, const char *where, wff_error *err)
{
    const int n_nodes = m->n_nodes, n_elems = m->n_tris + m->n_quads;
    if (n_nodes <= 0 || n_elems <= 0)
        return wff_fail(err, "%s: the mesh has %d nodes and %d elements", where, n_nodes,
                        n_elems);
    int *count = calloc((size_t)n_nodes + 1, sizeof *count);
    node_x *order = malloc((size_t)n_nodes * sizeof *order);
    if (!count || !order) {
        free(count);
        free(order);
        return wff_fail(err, "%s: out of memory checking the mesh", where);
    }
    int rc = 0;
    /* nodes in no element; element node indices in range */
    for (int e = 0; e < n_elems && !rc; e++) {
        int c;
        const int *nodes = element_nodes(m, e, &c);
        for (int k = 0; k < c; k++) {
            if (nodes[k] < 0 || nodes[k] >= n_nodes) {
                const char *kind;
                int number = element_number(m, e, &kind);
                rc = wff_fail(err, "%s: %s %d uses node %d; the mesh has nodes 1 to %d", where,
                              kind, number, nodes[k] + 1, n_nodes);
                break;
            }
            count[nodes[k]]++;
        }
    }
    for (int n = 0; n < n_nodes && !rc; n++)
        if (count[n] == 0)
            rc = wff_fail(err, "%s: node %d at (%.9g, %.9g) m is in no element (it would carry "
                          "no mass): remove it", where, n + 1, m->xy[2 * n], m->xy[2 * n + 1]);
    /* coincident nodes: sorted by x, compared within the tolerance */
    if (!rc) {
        double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
        for (int n = 0; n < n_nodes; n++)
            for (int d = 0; d < 2; d++) {
                lo[d] = fmin(lo[d], m->xy[2 * n + d]);
                hi[d] = fmax(hi[d], m->xy[2 * n + d]);
            }
        double tol = COINCIDENT_TOL * hypot(hi[0] - lo[0], hi[1] - lo[1]);
        for (int n = 0; n < n_nodes; n++)
            order[n] = (node_x){m->xy[2 * n], n};
        qsort(order, (size_t)n_nodes, sizeof *order, cmp_by_x);
        for (int i = 0; i < n_nodes && !rc; i++) {
            const int ni = order[i].node;
            const double *a = m->xy + 2 * ni;
            for (int j = i + 1; j < n_nodes; j++) {
                const int nj = order[j].node;
                const double *b = m->xy + 2 * nj;
                if (b[0] - a[0] > tol)
                    break;
                if (fabs(b[1] - a[1]) <= tol) {
                    int p = ni < nj ? ni : nj, q = ni < nj ? nj : ni;
                    rc = wff_fail(err, "%s: nodes %d and %d coincide at (%.9g, %.9g) m "
                                  "(within %.3g m): a duplicated node leaves a slit in the "
                                  "fabric (the elements on either side are not joined); merge "
                                  "them (gmsh: Coherence Mesh)", where, p + 1, q + 1, a[0],
                                  a[1], tol);
                    break;
                }
            }
        }
    }
    /* elements meeting only at a vertex: the elements around each node must be
     * joined through edges around it */
    if (!rc && !allow_vertex_only) {
        int *start = malloc(((size_t)n_nodes + 1) * sizeof *start);
        int *fill = malloc((size_t)n_nodes * sizeof *fill);
        int total = 0;
        for (int n = 0; n < n_nodes; n++)
            total += count[n];
        int *incident = malloc((size_t)total * sizeof *incident);
        int *parent = malloc((size_t)total * sizeof *parent);
        if (!start || !fill || !incident || !parent) {
            rc = wff_fail(err, "%s: out of memory checking the mesh", where);
        } else {
            start[0] = 0;
            for (int n = 0; n < n_nodes; n++) {
                start[n + 1] = start[n] + count[n];
                fill[n] = start[n];
            }
            for (int e = 0; e < n_elems; e++) {
                int c;
                const int *nodes = element_nodes(m, e, &c);
                for (int k = 0; k < c; k++)
                    incident[fill[nodes[k]]++] = e;
            }
            for (int n = 0; n < n_nodes && !rc; n++) {
                int s = start[n], k = count[n];
                for (int i = 0; i < k; i++)
                    parent[s + i] = s + i;
                for (int i = 0; i < k; i++)
                    for (int j = i + 1; j < k; j++)
                        if (share_edge_at(m, incident[s + i], incident[s + j], n)) {
                            int ri = find_root(parent, s + i), rj = find_root(parent, s + j);
                            if (ri != rj)
                                parent[ri] = rj;
                        }
                for (int i = 1; i < k; i++)
                    if (find_root(parent, s + i) != find_root(parent, s)) {
                        const char *kind_a, *kind_b;
                        int a = element_number(m, incident[s], &kind_a);
                        int b = element_number(m, incident[s + i], &kind_b);
                        rc = wff_fail(err, "%s: %s %d and %s %d meet only at node %d, "
                                      "(%.9g, %.9g) m, without a shared edge: the fabric would "
                                      "hinge there; mesh it with shared edges, or allow it with "
                                      "the mesh setting vertex_only=1", where, kind_a, a,
                                      kind_b, b, n + 1, m->xy[2 * n], m->xy[2 * n + 1]);
                        break;
                    }
            }
        }
        free(start);
        free(fill);
        free(incident);
        free(parent);
    }
    free(count);
    free(order);
    return rc;
}

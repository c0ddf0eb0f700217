/* Membrane elements: the set-up, not on the per-step path (compiled once,
 * not a kernel): each element's reference geometry (shape-function gradients,
 * areas or Gauss weights, sizes), the force pass's element-vertex slots and
 * each node's list of them in element order, the static amplitudes' per-point
 * storage. See include/wovenff/membrane.h. */
#include "wovenff/membrane.h"
#include "membrane_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define D WFF_DOFS_PER_NODE

static double dist(const double *X, int a, int b)
{
    return hypot(X[2 * a] - X[2 * b], X[2 * a + 1] - X[2 * b + 1]);
}

/* The force pass's element-vertex slots (zero: an element the pass skips, e.g.
 * eroded, keeps zeros there), each referenced node's slots in ascending element
 * order (triangles, then quads), the per-block energy sums. 0, or -1 out of
 * memory. */
static int slots_init(wff_elements *el, int n_nodes)
{
    const int n_tris = el->n_tris, n_quads = el->n_quads;
    const size_t n_slots = 3 * (size_t)n_tris + 4 * (size_t)n_quads;
    const int n_blocks = (n_tris + WFF_BLOCK - 1) / WFF_BLOCK + (n_quads + WFF_BLOCK - 1) / WFF_BLOCK;
    el->slot = calloc(D * (n_slots ? n_slots : 1), sizeof(double));
    el->block_sums = calloc(WFF_BLOCK_SUMS * (size_t)(n_blocks ? n_blocks : 1), sizeof(double));
    int *count = calloc((size_t)n_nodes + 1, sizeof(int));
    el->node_slot = malloc(sizeof(int) * (n_slots ? n_slots : 1));
    if (!el->slot || !el->block_sums || !count || !el->node_slot) {
        free(count);
        return -1;
    }
    for (size_t s = 0; s < n_slots; s++)
        count[s < 3 * (size_t)n_tris ? el->tri[s] : el->quad[s - 3 * (size_t)n_tris]]++;
    int used = 0;
    for (int n = 0; n < n_nodes; n++)
        used += count[n] > 0;
    el->n_gather = used;
    el->node_list = malloc(sizeof(int) * (size_t)(used ? used : 1));
    el->node_slot_start = malloc(sizeof(int) * ((size_t)used + 1));
    int *cursor = malloc(sizeof(int) * ((size_t)n_nodes + 1));
    if (!el->node_list || !el->node_slot_start || !cursor) {
        free(count);
        free(cursor);
        return -1;
    }
    int k = 0, start = 0;
    for (int n = 0; n < n_nodes; n++) {
        cursor[n] = start;
        if (count[n] == 0)
            continue;
        el->node_list[k] = n;
        el->node_slot_start[k++] = start;
        start += count[n];
    }
    el->node_slot_start[used] = start;
    el->gather_begin = 0;
    el->gather_end = used;
    /* slots in ascending order: the triangles' (3e + b), then the quads' */
    for (size_t s = 0; s < n_slots; s++) {
        const int n = s < 3 * (size_t)n_tris ? el->tri[s] : el->quad[s - 3 * (size_t)n_tris];
        el->node_slot[cursor[n]++] = (int)s;
    }
    free(count);
    free(cursor);
    return 0;
}

int wff_elements_init(wff_elements *el, const double *X, int n_tris, const int *tri,
                      int n_quads, const int *quad, wff_error *err)
{
    memset(el, 0, sizeof *el);
    el->n_tris = n_tris;
    el->n_quads = n_quads;
    el->tri = tri;
    el->quad = quad;
    el->tri_grad = malloc(sizeof(double) * 6 * (size_t)(n_tris ? n_tris : 1));
    el->tri_area = malloc(sizeof(double) * (size_t)(n_tris ? n_tris : 1));
    el->quad_grad = malloc(sizeof(double) * 32 * (size_t)(n_quads ? n_quads : 1));
    el->quad_weight = malloc(sizeof(double) * 4 * (size_t)(n_quads ? n_quads : 1));
    el->size = malloc(sizeof(double) * (size_t)(n_tris + n_quads + 1));
    if (!el->tri_grad || !el->tri_area || !el->quad_grad || !el->quad_weight || !el->size) {
        wff_elements_free(el);
        return wff_fail(err, "out of memory for %d triangles and %d quads", n_tris, n_quads);
    }
    for (int e = 0; e < n_tris; e++) {
        const int *n = tri + 3 * e;
        double x0 = X[2 * n[0]], y0 = X[2 * n[0] + 1];
        double x1 = X[2 * n[1]] - x0, y1 = X[2 * n[1] + 1] - y0;
        double x2 = X[2 * n[2]] - x0, y2 = X[2 * n[2] + 1] - y0;
        double twice = x1 * y2 - x2 * y1;
        if (!(twice > 0)) {
            wff_elements_free(el);
            return wff_fail(err, "triangle %d (nodes %d %d %d): area %.3g m^2 is not positive",
                            e + 1, n[0] + 1, n[1] + 1, n[2] + 1, 0.5 * twice);
        }
        double *g = el->tri_grad + 6 * e;
        g[0] = (y1 - y2) / twice, g[1] = (x2 - x1) / twice; /* node 0 */
        g[2] = y2 / twice, g[3] = -x2 / twice;              /* node 1 */
        g[4] = -y1 / twice, g[5] = x1 / twice;              /* node 2 */
        el->tri_area[e] = 0.5 * twice;
        double longest = fmax(dist(X, n[0], n[1]), fmax(dist(X, n[1], n[2]), dist(X, n[2], n[0])));
        el->size[e] = twice / longest; /* smallest altitude */
    }
    int max_node = -1;
    for (int i = 0; i < 3 * n_tris; i++)
        max_node = tri[i] > max_node ? tri[i] : max_node;
    for (int i = 0; i < 4 * n_quads; i++)
        max_node = quad[i] > max_node ? quad[i] : max_node;
    el->n_dofs = D * (max_node + 1);
    el->team_min_tris = WFF_TEAM_MIN_TRIS;
#ifdef _OPENMP
    /* OpenMP's maximum, or the processors if more (OMP_NUM_THREADS=1 in the
     * environment must not stop a model that asks for 2) */
    el->max_threads = omp_get_max_threads();
    if (omp_get_num_procs() > el->max_threads)
        el->max_threads = omp_get_num_procs();
#else
    el->max_threads = 1;
#endif
    if (el->max_threads > WFF_MAX_THREADS)
        el->max_threads = WFF_MAX_THREADS;
    el->n_threads = 1; /* threads are asked for (wff_elements_set_threads): on a shared
                          machine a busy second core makes a team slower than one */
    if (slots_init(el, max_node + 1)) {
        wff_elements_free(el);
        return wff_fail(err, "out of memory for the force slots of %d triangles and %d quads",
                        n_tris, n_quads);
    }
    for (int e = 0; e < n_quads; e++) {
        const int *n = quad + 4 * e;
        double area = 0;
        for (int q = 0; q < 4; q++) {
            double grad[4][2];
            double det = quad_gradients(X, n, gauss_1d * quad_gauss[q][0],
                                        gauss_1d * quad_gauss[q][1], grad);
            if (!(det > 0)) {
                wff_elements_free(el);
                return wff_fail(err, "quadrilateral %d (nodes %d %d %d %d): Jacobian %.3g at "
                                "Gauss point %d is not positive (inverted or degenerate)",
                                e + 1, n[0] + 1, n[1] + 1, n[2] + 1, n[3] + 1, det, q + 1);
            }
            memcpy(el->quad_grad + 32 * e + 8 * q, grad, sizeof grad);
            el->quad_weight[4 * e + q] = det;
            area += det;
        }
        double diag = fmax(dist(X, n[0], n[2]), dist(X, n[1], n[3]));
        el->size[n_tris + e] = area / diag;
    }
    return 0;
}

void wff_elements_free(wff_elements *el)
{
    free(el->tri_grad);
    free(el->tri_area);
    free(el->quad_grad);
    free(el->quad_weight);
    free(el->size);
    free(el->slot);
    free(el->block_sums);
    free(el->node_slot);
    free(el->node_slot_start);
    free(el->node_list);
    free(el->point_dA);
    free(el->eroded);
    free(el->block_run);
    free(el->block_count);
    el->block_run = el->block_count = NULL;
    el->point_dA = NULL;
    el->eroded = NULL;
    el->tri_grad = el->tri_area = el->quad_grad = el->quad_weight = el->size = NULL;
    el->slot = el->block_sums = NULL;
    el->node_slot = el->node_slot_start = el->node_list = NULL;
    el->n_gather = el->gather_begin = el->gather_end = 0;
}

int wff_elements_set_threads(wff_elements *el, int n_threads, wff_error *err)
{
    if (n_threads < 1 || n_threads > el->max_threads)
        return wff_fail(err, "threads = %d: must be 1 to %d (OpenMP's maximum or the "
                        "processors here, the larger; set OMP_NUM_THREADS for more)", n_threads, el->max_threads);
    el->n_threads = n_threads;
    return 0;
}

int wff_elements_static_amplitudes(wff_elements *el, wff_element_material *em,
                                   const double dA0[2], wff_error *err)
{
    size_t n = (size_t)(WFF_TRI_POINTS * el->n_tris + WFF_QUAD_POINTS * el->n_quads);
    if (!el->point_dA) {
        el->point_dA = malloc(2 * sizeof(double) * (n ? n : 1));
        if (!el->point_dA)
            return wff_fail(err, "out of memory for static amplitudes at %zu points", n);
    }
    for (size_t i = 0; i < n; i++) {
        el->point_dA[2 * i] = dA0[0];
        el->point_dA[2 * i + 1] = dA0[1];
    }
    em->static_amplitudes = 1;
    return 0;
}

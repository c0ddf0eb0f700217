/* Structured rectangle meshes for the C tests, see test_meshes.h. */
#include "test_meshes.h"
#include "rng.h"
#include "wovenff/pack.h"
#include "wovenff/renumber.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void add_group(wff_mesh *m, int dim, int tag, const char *name)
{
    wff_mesh_group *g = &m->groups[m->n_groups++];
    g->dim = dim;
    g->tag = tag;
    snprintf(g->name, sizeof g->name, "%s", name);
}

int test_mesh_rect(const test_rect *r, wff_mesh *mesh)
{
    memset(mesh, 0, sizeof *mesh);
    if (r->nx < 1 || r->ny < 1 || !(r->x1 > r->x0) || !(r->y1 > r->y0) || r->jitter < 0 ||
        r->jitter >= 0.5)
        return -1;
    int nx = r->nx, ny = r->ny, cells = nx * ny;
    int quads = r->type == TEST_MESH_QUAD;
    mesh->n_nodes = (nx + 1) * (ny + 1);
    mesh->n_quads = quads ? cells : 0;
    mesh->n_tris = quads ? 0 : 2 * cells;
    mesh->n_edges = 2 * (nx + ny);
    mesh->xy = malloc(sizeof(double) * 2 * (size_t)mesh->n_nodes);
    mesh->tri = malloc(sizeof(int) * (3 * (size_t)mesh->n_tris + 1));
    mesh->tri_region = malloc(sizeof(int) * ((size_t)mesh->n_tris + 1));
    mesh->quad = malloc(sizeof(int) * (4 * (size_t)mesh->n_quads + 1));
    mesh->quad_region = malloc(sizeof(int) * ((size_t)mesh->n_quads + 1));
    mesh->edge = malloc(sizeof(int) * 2 * (size_t)mesh->n_edges);
    mesh->edge_label = malloc(sizeof(int) * (size_t)mesh->n_edges);
    mesh->groups = malloc(sizeof(wff_mesh_group) * 5);
    if (!mesh->xy || !mesh->tri || !mesh->tri_region || !mesh->quad || !mesh->quad_region ||
        !mesh->edge || !mesh->edge_label || !mesh->groups) {
        wff_mesh_free(mesh);
        return -1;
    }
    double hx = (r->x1 - r->x0) / nx, hy = (r->y1 - r->y0) / ny;
    rng g = {r->seed ? r->seed : 0x9e3779b97f4a7c15ULL};
    for (int j = 0; j <= ny; j++)
        for (int i = 0; i <= nx; i++) {
            double *p = mesh->xy + 2 * (j * (nx + 1) + i);
            /* exact end points; interior by fraction */
            p[0] = i == nx ? r->x1 : r->x0 + (r->x1 - r->x0) * i / nx;
            p[1] = j == ny ? r->y1 : r->y0 + (r->y1 - r->y0) * j / ny;
            if (r->jitter > 0 && i > 0 && i < nx && j > 0 && j < ny) {
                p[0] += r->jitter * hx * rng_uniform(&g, -1, 1);
                p[1] += r->jitter * hy * rng_uniform(&g, -1, 1);
            }
        }
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            int c = j * nx + i;
            int n0 = j * (nx + 1) + i, n1 = n0 + 1, n2 = n1 + nx + 1, n3 = n0 + nx + 1;
            if (quads) {
                int *q = mesh->quad + 4 * c;
                q[0] = n0, q[1] = n1, q[2] = n2, q[3] = n3;
                mesh->quad_region[c] = TEST_FABRIC;
                continue;
            }
            int *t = mesh->tri + 6 * c;
            if (r->alternate && (i + j) % 2) { /* diagonal 1-3 */
                t[0] = n0, t[1] = n1, t[2] = n3;
                t[3] = n1, t[4] = n2, t[5] = n3;
            } else { /* diagonal 0-2 */
                t[0] = n0, t[1] = n1, t[2] = n2;
                t[3] = n0, t[4] = n2, t[5] = n3;
            }
            mesh->tri_region[2 * c] = mesh->tri_region[2 * c + 1] = TEST_FABRIC;
        }
    /* boundary edges, counter-clockwise around the rectangle */
    int e = 0;
    for (int i = 0; i < nx; i++, e++) {
        mesh->edge[2 * e] = i, mesh->edge[2 * e + 1] = i + 1;
        mesh->edge_label[e] = TEST_BOTTOM;
    }
    for (int j = 0; j < ny; j++, e++) {
        mesh->edge[2 * e] = j * (nx + 1) + nx, mesh->edge[2 * e + 1] = (j + 1) * (nx + 1) + nx;
        mesh->edge_label[e] = TEST_RIGHT;
    }
    for (int i = nx; i > 0; i--, e++) {
        mesh->edge[2 * e] = ny * (nx + 1) + i, mesh->edge[2 * e + 1] = ny * (nx + 1) + i - 1;
        mesh->edge_label[e] = TEST_TOP;
    }
    for (int j = ny; j > 0; j--, e++) {
        mesh->edge[2 * e] = j * (nx + 1), mesh->edge[2 * e + 1] = (j - 1) * (nx + 1);
        mesh->edge_label[e] = TEST_LEFT;
    }
    add_group(mesh, 1, TEST_LEFT, "left");
    add_group(mesh, 1, TEST_RIGHT, "right");
    add_group(mesh, 1, TEST_BOTTOM, "bottom");
    add_group(mesh, 1, TEST_TOP, "top");
    add_group(mesh, 2, TEST_FABRIC, "fabric");
    return 0;
}

int test_model_rect(wff_model *m, const test_rect *r, const char *material, wff_error *err)
{
    wff_mesh mesh;
    if (test_mesh_rect(r, &mesh))
        return wff_fail(err, "test mesh %dx%d: invalid or out of memory", r->nx, r->ny);
    return wff_model_create_from_mesh(m, &mesh, material, err);
}

int test_model_struck(wff_model *m, int n, const char *material, int plies, double gap,
                      wff_error *err)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, n, n, TEST_MESH_TRI, 1, 0.2, 7};
    wff_mesh mesh;
    if (test_mesh_rect(&r, &mesh))
        return wff_fail(err, "test mesh %dx%d: invalid or out of memory", n, n);
    if (wff_model_create_ordered(m, &mesh, material, 1, err))
        return -1;
    if (plies > 0 && wff_model_set_plies(m, plies, gap, err))
        return -1;
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int g = 0; g < 4; g++)
        for (int c = WFF_UX; c <= WFF_UZ; c++)
            if (wff_model_fix_group(m, edges[g], c, err) < 0)
                return -1;
    return wff_model_set_projectile(m, 0.0025, 0.002, 60, 0.2, err) ? -1 : 0;
}

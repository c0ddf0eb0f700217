/* mesh_arrays.c: what the rest of the core does with a loaded mesh (the
 * arrays of include/wovenff/mesh.h): free it, find a physical group's tag by
 * name, its extent (bounding box, edge lengths), and give the triangle twin
 * FreeFEM needs (each quad split along its 0-2 diagonal). Knows nothing of gmsh (mesh.c reads the files), materials
 * or the solver. */
#include "wovenff/mesh_arrays.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void wff_mesh_free(wff_mesh *mesh)
{
    if (!mesh)
        return;
    free(mesh->xy);
    free(mesh->tri);
    free(mesh->tri_region);
    free(mesh->quad);
    free(mesh->quad_region);
    free(mesh->edge);
    free(mesh->edge_label);
    free(mesh->groups);
    memset(mesh, 0, sizeof *mesh);
}

int wff_mesh_group_tag(const wff_mesh *mesh, int dim, const char *name)
{
    if (!mesh || !name)
        return -1;
    for (int i = 0; i < mesh->n_groups; i++)
        if (mesh->groups[i].dim == dim && strcmp(mesh->groups[i].name, name) == 0)
            return mesh->groups[i].tag;
    return -1;
}

void wff_mesh_triangulate(const wff_mesh *mesh, int *tri_out, int *region_out)
{
    if (mesh->n_tris > 0) {
        memcpy(tri_out, mesh->tri, 3 * (size_t)mesh->n_tris * sizeof *tri_out);
        memcpy(region_out, mesh->tri_region, (size_t)mesh->n_tris * sizeof *region_out);
    }
    int *t = tri_out + 3 * (size_t)mesh->n_tris;
    int *r = region_out + mesh->n_tris;
    for (int q = 0; q < mesh->n_quads; q++) {
        const int *v = &mesh->quad[4 * q];
        t[0] = v[0], t[1] = v[1], t[2] = v[2];
        t[3] = v[0], t[4] = v[2], t[5] = v[3];
        t += 6;
        r[0] = r[1] = mesh->quad_region[q];
        r += 2;
    }
}

void wff_mesh_extent(const wff_mesh *mesh, double box[4], double *shortest_edge,
                     double *mean_edge)
{
    box[0] = box[2] = INFINITY;
    box[1] = box[3] = -INFINITY;
    for (int i = 0; i < mesh->n_nodes; i++) {
        double x = mesh->xy[2 * i], y = mesh->xy[2 * i + 1];
        box[0] = fmin(box[0], x);
        box[1] = fmax(box[1], x);
        box[2] = fmin(box[2], y);
        box[3] = fmax(box[3], y);
    }
    double shortest = INFINITY, sum = 0;
    long count = 0;
    for (int kind = 0; kind < 2; kind++) {
        int n = kind ? mesh->n_quads : mesh->n_tris, corners = kind ? 4 : 3;
        const int *node = kind ? mesh->quad : mesh->tri;
        for (int e = 0; e < n; e++)
            for (int c = 0; c < corners; c++) {
                int a = node[corners * e + c], b = node[corners * e + (c + 1) % corners];
                double length = hypot(mesh->xy[2 * a] - mesh->xy[2 * b],
                                      mesh->xy[2 * a + 1] - mesh->xy[2 * b + 1]);
                shortest = fmin(shortest, length);
                sum += length;
                count++;
            }
    }
    *shortest_edge = count ? shortest : 0;
    *mean_edge = count ? sum / (double)count : 0;
}

/* wovenff — a mesh as plain arrays (struct wff_mesh: nodes, triangles,
 * quadrilaterals, labelled edges, named groups) and what is done with a
 * loaded mesh's arrays (plugin/mesh_arrays.c). Reading and generating a mesh
 * is wovenff/mesh.h's, which includes this. */
#ifndef WOVENFF_MESH_ARRAYS_H
#define WOVENFF_MESH_ARRAYS_H

#ifdef __cplusplus
extern "C" {
#endif

#define WFF_MESH_NAME_MAX 64

/* A physical group of the mesh file (curves: dim 1, surfaces: dim 2). */
typedef struct wff_mesh_group {
    int dim;
    int tag;
    char name[WFF_MESH_NAME_MAX];
} wff_mesh_group;

typedef struct wff_mesh {
    int n_nodes;
    double *xy;          /* 2*n_nodes reference coordinates X, Y in m */
    int n_tris;
    int *tri;            /* 3*n_tris node indices, 0-based, counter-clockwise */
    int *tri_region;     /* physical surface tag of each triangle (0 if none) */
    int n_quads;
    int *quad;           /* 4*n_quads node indices, 0-based, counter-clockwise */
    int *quad_region;
    int n_edges;         /* line elements of physical curves (wovenff/mesh.h) */
    int *edge;           /* 2*n_edges node indices */
    int *edge_label;     /* physical curve tag of each edge */
    int n_groups;
    wff_mesh_group *groups;
} wff_mesh;

void wff_mesh_free(wff_mesh *mesh);

/* Label of the physical group named `name` of dimension dim, or -1. */
int wff_mesh_group_tag(const wff_mesh *mesh, int dim, const char *name);

/* The mesh's size, for checks of its unit against a scene's lengths: the
 * bounding box (box: X min, X max, Y min, Y max, m) and the shortest and mean
 * element edge, m (each element's edges, a shared edge once per element). */
void wff_mesh_extent(const wff_mesh *mesh, double box[4], double *shortest_edge,
                     double *mean_edge);

/* Triangle twin: 3*(n_tris + 2*n_quads) indices into tri_out (caller-sized),
 * regions into region_out; triangles first, then each quad as (0,1,2),(0,2,3). */
void wff_mesh_triangulate(const wff_mesh *mesh, int *tri_out, int *region_out);

#ifdef __cplusplus
}
#endif
#endif

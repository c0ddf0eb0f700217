/* wovenff — planar membrane meshes read or generated through gmsh's C API.
 *
 * wff_mesh_load() opens a gmsh `.geo` (and meshes it in 2-D, with size
 * parameters) or reads a `.msh` of any version gmsh reads (MSH2/MSH4, ASCII
 * or binary). The physics keeps triangles and quadrilaterals as they are;
 * wff_mesh_triangulate() gives the triangle twin FreeFEM needs (each quad
 * split in two along its diagonal 0-2, same vertex numbering).
 *
 * Checks, each an error naming the file and the element or group at fault:
 * missing or unreadable file, no 2-D elements, an element type other than
 * 3-node triangle or 4-node quadrilateral, a node off the z = 0 plane,
 * a zero-area or non-convex (inverted) element. Clockwise elements are
 * reordered counter-clockwise (orientation in a flat mesh is a convention,
 * not a defect). */
#ifndef WOVENFF_MESH_H
#define WOVENFF_MESH_H

#include "wovenff/error.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WFF_MESH_NAME_MAX 64
#define WFF_MESH_SETTINGS_MAX 16

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
    int n_edges;         /* boundary line elements that belong to a physical curve */
    int *edge;           /* 2*n_edges node indices */
    int *edge_label;     /* physical curve tag of each edge */
    int n_groups;
    wff_mesh_group *groups;
} wff_mesh;

/* Numbers handed to a .geo before it is read (gmsh ONELAB parameters, seen
 * by `DefineConstant[name = default]`), e.g. {"h_min", 1e-3}. */
typedef struct wff_mesh_setting {
    char name[WFF_MESH_NAME_MAX];
    double value;
} wff_mesh_setting;

typedef struct wff_mesh_options {
    int n_settings;
    wff_mesh_setting settings[WFF_MESH_SETTINGS_MAX];
    int recombine;       /* 1: ask gmsh for quadrilaterals when meshing a .geo */
    double size_factor;  /* gmsh Mesh.MeshSizeFactor for a .geo; 0 means 1 */
} wff_mesh_options;

/* Load or generate a mesh. On failure *mesh is empty (nothing to free) and
 * err says why. The caller owns the arrays: free with wff_mesh_free(). */
int wff_mesh_load(const char *path, const wff_mesh_options *options, wff_mesh *mesh,
                  wff_error *err);

void wff_mesh_free(wff_mesh *mesh);

/* Label of the physical group named `name` of dimension dim, or -1. */
int wff_mesh_group_tag(const wff_mesh *mesh, int dim, const char *name);

/* Triangle twin: 3*(n_tris + 2*n_quads) indices into tri_out (caller-sized),
 * regions into region_out; triangles first, then each quad as (0,1,2),(0,2,3). */
void wff_mesh_triangulate(const wff_mesh *mesh, int *tri_out, int *region_out);

#ifdef __cplusplus
}
#endif
#endif

/* wovenff — meshes given by arrays (a FreeFEM mesh handed over by the
 * binding, a FreeFEM-format .msh) and FreeFEM labels as groups.
 *
 * Groups from labels: every boundary-edge label N is a dim-1 group, named
 * "label_N" unless the settings name it; every triangle region label R is a
 * dim-2 group, named "region_R" unless named. Settings (one line, pairs
 * separated by spaces):
 *     names=1:clamp,2:sym_x     boundary labels 1 and 2 named "clamp", "sym_x"
 *     regions=0:ply             region label 0 named "ply"
 * A name given to a label the mesh does not have is an error, so is a name
 * used twice in one dimension or any other setting.
 *
 * A label number resolves (wff_mesh_label_group) to the dim-1 group with that
 * tag, else to the dim-2 group with that tag (gmsh physical tags count as
 * labels: a curve tag is looked up before a surface tag). */
#ifndef WOVENFF_MESH_LABELS_H
#define WOVENFF_MESH_LABELS_H

#include "wovenff/error.h"
#include "wovenff/mesh_arrays.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A triangle mesh in arrays, borrowed (the caller keeps them): 0-based. */
typedef struct wff_mesh_arrays {
    int n_nodes;
    const double *xy;        /* 2*n_nodes, m */
    int n_tris;
    const int *tri;          /* 3*n_tris */
    const int *tri_region;   /* n_tris region labels */
    int n_edges;
    const int *edge;         /* 2*n_edges */
    const int *edge_label;   /* n_edges boundary labels */
} wff_mesh_arrays;

/* Copy arrays into *mesh (same node numbering; the caller frees it with
 * wff_mesh_free) with wff_mesh_load's checks: finite coordinates, node
 * indices in range, no node outside every triangle (it would carry no mass),
 * no zero-area triangle (area <= 1e-12 diagonal^2). Clockwise triangles are
 * made counter-clockwise (nodes 1 and 2 swapped). Groups from the labels and
 * `settings` (above; NULL or "" for none). Errors name the triangle (1-based,
 * as FreeFEM's .msh numbers them), node or label. On failure *mesh is empty. */
int wff_mesh_from_arrays(const wff_mesh_arrays *in, const char *settings, wff_mesh *mesh,
                         wff_error *err);

/* Replace mesh's groups by those of its labels and `settings` (above). */
int wff_mesh_label_groups(wff_mesh *mesh, const char *settings, wff_error *err);

/* Name of the group a label number resolves to (above), or NULL with an error
 * naming the labels the mesh has. */
const char *wff_mesh_label_group(const wff_mesh *mesh, long label, wff_error *err);

/* 1 if the file starts like FreeFEM's savemesh .msh (first line: three
 * whole numbers "nv nt nbe"), 0 otherwise (gmsh's .msh starts "$MeshFormat"). */
int wff_mesh_is_freefem_msh(const char *path);

/* Read a FreeFEM-format .msh (savemesh: "nv nt nbe", nv lines "x y label",
 * nt lines "i j k region", nbe lines "i j label", 1-based) with
 * wff_mesh_from_arrays's checks and groups (settings as above). Errors name
 * the file and line. */
int wff_mesh_load_freefem(const char *path, const char *settings, wff_mesh *mesh,
                          wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

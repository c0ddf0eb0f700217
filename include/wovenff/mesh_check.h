/* wovenff — the checks of a mesh's arrays no single element shows
 * (plugin/mesh_check.c). */
#ifndef WOVENFF_MESH_CHECK_H
#define WOVENFF_MESH_CHECK_H

#include "wovenff/error.h"
#include "wovenff/mesh_arrays.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Defects no single element shows (plugin/mesh_check.c), each an error naming
 * `where` (the file), the nodes or elements and the coordinates: an element
 * node index out of range, a node in no element (it would carry no mass),
 * two nodes that coincide (within 1e-9 of the bounding-box diagonal: a slit in
 * the fabric), and, unless allow_vertex_only, elements that meet only at a
 * vertex (no shared edge around the node: a hinge). wff_mesh_load runs it
 * (with the setting vertex_only), and so does wff_model_create_from_mesh (for
 * meshes given as arrays; vertex-only contacts there are the caller's to
 * check). */
int wff_mesh_check(const wff_mesh *mesh, int allow_vertex_only, const char *where,
                   wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

/* wovenff — the model's own order of nodes and elements (plugin/renumber.c).
 *
 * At build a model renumbers its mesh so that neighbours sit close in memory
 * (elements along a Hilbert curve through their centroids, nodes in the
 * order those elements first use them); the order depends only on the mesh.
 * The model's arrays (m->mesh, u, v, f, mass, dof_kind, state, clamp and
 * contact node lists, dt_worst_element) are in that order; every function of
 * the API that takes or returns node indices, DOF or node vectors, element
 * indices or element values speaks the numbering of the mesh the caller gave
 * (the "user" numbering), and so do error messages. These calls convert
 * between the two (identity when the order is kept: wff_model_create_ordered
 * with renumber 0). */
#ifndef WOVENFF_RENUMBER_H
#define WOVENFF_RENUMBER_H

#include "wovenff/solver.h"

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Create as wff_model_create_from_mesh; renumber 0 keeps the mesh's own
 * order (what wff_model_create_from_mesh does), 1 renumbers (what
 * wff_model_create and the FreeFEM binding's wovenffModel(mesh Th, ...) do). */
int wff_model_create_ordered(wff_model *m, wff_mesh *mesh, const char *material_path,
                             int renumber, wff_error *err);

/* Reorder a mesh in place (nodes, elements, regions, edges' nodes);
 * node_user[model node] = the given node, element_user[model element] = the
 * given element (triangles first, then quads; each type stays in its
 * range). */
int wff_mesh_locality_order(wff_mesh *mesh, int *node_user, int *element_user, wff_error *err);

/* Index conversions, 0-based (a negative index is returned as it is). */
int wff_model_user_node(const wff_model *m, int node);
int wff_model_node_of_user(const wff_model *m, int user_node);
int wff_model_user_element(const wff_model *m, int element);
int wff_model_element_of_user(const wff_model *m, int user_element);

/* Arrays of `per` values a node (5: DOF vectors) between the orders (out
 * must not alias in), and in place (-1 with err if out of memory). */
void wff_model_nodes_to_user(const wff_model *m, const double *model, double *user, int per);
void wff_model_nodes_from_user(const wff_model *m, const double *user, double *model, int per);
int wff_model_nodes_to_user_in_place(const wff_model *m, double *a, int per, wff_error *err);
/* One value per element (triangles, then quads) to the user's order, in place. */
int wff_model_elements_to_user_in_place(const wff_model *m, double *a, wff_error *err);

/* "triangle 3 (nodes 4 5 9)" / "quadrilateral 2 (nodes ...)" for model
 * element e in the user's numbering (1-based within its type). */
void wff_model_element_name(const wff_model *m, int e, char *out, size_t size);

#ifdef __cplusplus
}
#endif
#endif

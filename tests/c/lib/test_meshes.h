/* In-memory structured meshes for the C tests (no gmsh): a rectangle of
 * nx × ny cells as quadrilaterals or triangles, physical curves "left",
 * "right", "bottom", "top" (dim 1, boundary edges counter-clockwise around
 * the domain) and the surface "fabric" (dim 2). Node (i, j) is j (nx+1) + i. */
#ifndef WFF_TEST_MESHES_H
#define WFF_TEST_MESHES_H

#include "wovenff/mesh.h"
#include "wovenff/solver.h"

#include <stdint.h>

enum { TEST_MESH_TRI = 0, TEST_MESH_QUAD = 1 };

typedef struct test_rect {
    double x0, x1, y0, y1;
    int nx, ny;
    int type;          /* TEST_MESH_TRI or TEST_MESH_QUAD */
    int alternate;     /* triangles: alternate the diagonal cell by cell */
    double jitter;     /* interior nodes moved by up to jitter × cell size in x and y */
    uint64_t seed;     /* for the jitter (0: a fixed default) */
} test_rect;

/* Curve tags: left 1, right 2, bottom 3, top 4; surface "fabric" tag 10. */
enum { TEST_LEFT = 1, TEST_RIGHT = 2, TEST_BOTTOM = 3, TEST_TOP = 4, TEST_FABRIC = 10 };

/* Fill mesh (malloc'ed arrays, free with wff_mesh_free). Returns 0, or -1 when
 * out of memory or the description is invalid (mesh is then empty). */
int test_mesh_rect(const test_rect *r, wff_mesh *mesh);

/* A model on that mesh with the given material file; -1 with err set. */
int test_model_rect(wff_model *m, const test_rect *r, const char *material, wff_error *err);

/* The struck square of the pack tests: a 6 cm square of n x n cells of
 * triangles (alternate diagonals, jitter 0.2, seed 7) of `material`,
 * renumbered (as the binding's models are); plies (0: none) at gap; the four
 * edges fixed in u_x u_y u_z; a projectile of radius 2.5 mm and 2 g at 60 m/s,
 * 0.2 mm from the fabric. -1 with err set. */
int test_model_struck(wff_model *m, int n, const char *material, int plies, double gap,
                      wff_error *err);

#endif

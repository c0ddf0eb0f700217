/* wovenff — planar membrane meshes read or generated through gmsh's C API.
 *
 * wff_mesh_load() opens a gmsh `.geo` (and meshes it in 2-D, with size
 * parameters) or reads a `.msh` of any version gmsh reads (MSH2/MSH4, ASCII
 * or binary). The physics keeps triangles and quadrilaterals as they are;
 * wff_mesh_triangulate() gives the triangle twin FreeFEM needs (each quad
 * split in two along its diagonal 0-2, same vertex numbering).
 *
 * What is kept: if the file has physical surfaces, the 2-D elements of those
 * (gmsh's rule for saving), else all 2-D elements; region = physical surface
 * tag, 0 without one. Nodes: those of the kept elements, numbered 0.. in
 * increasing gmsh node tag. Edges: the line elements of every physical curve
 * (boundary or interface), labelled with its tag, once per curve they belong
 * to; line elements outside physical curves are ignored.
 *
 * Checks, each an error naming the file and the element or group at fault:
 * missing or unreadable file, gmsh read or meshing errors (gmsh's message),
 * no 2-D elements, an element type other than 3-node triangle or 4-node
 * quadrilateral, a surface in two physical surfaces, an edge node that is in
 * no kept 2-D element (it would carry no mass), a node off the z = 0 plane
 * (|z| > 1e-9 bounding-box diagonal), a zero-area element (area <= 1e-12
 * diagonal^2), a non-convex or inverted quadrilateral. 2-D elements are named
 * by 1-based position among the kept ones and gmsh element tag. Clockwise
 * elements are reordered counter-clockwise (orientation in a flat mesh is a
 * convention, not a defect; quads keep node 0, so the 0-2 diagonal stays).
 *
 * gmsh is one global session per process: wff_mesh_load() initialises and
 * finalises it (so it must not run while the caller has its own gmsh session,
 * nor from two threads at once), keeps it silent, and restores the process
 * locale gmshInitialize() changes. */
#ifndef WOVENFF_MESH_H
#define WOVENFF_MESH_H

#include "wovenff/error.h"
#include "wovenff/mesh_arrays.h"
#include "wovenff/mesh_check.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WFF_MESH_SETTINGS_MAX 16

/* Numbers handed to a .geo before it is read, e.g. {"h_min", 1e-3}, as gmsh
 * ONELAB parameters. gmsh 4.8.4 passes a ONELAB number only to a
 * DefineConstant that names it:
 *     DefineConstant[ h_min = {0.002, Name "h_min"} ];
 * The plain form `DefineConstant[ h_min = 0.002 ];` (or `If(!Exists(h_min))`)
 * sees only command-line `-setnumber` values, which this gmsh keeps for the
 * rest of the process (there is no gmshParserSetNumber yet): not used. A
 * setting that no DefineConstant of the file reads is an error (a misspelt
 * name would otherwise be ignored); settings are ignored for a .msh. */
typedef struct wff_mesh_setting {
    char name[WFF_MESH_NAME_MAX];
    double value;
} wff_mesh_setting;

typedef struct wff_mesh_options {
    int n_settings;
    wff_mesh_setting settings[WFF_MESH_SETTINGS_MAX];
    int recombine;       /* 1: quadrilaterals when meshing a .geo (Mesh.RecombineAll;
                            "simple full-quad" recombination unless the file sets
                            Mesh.RecombinationAlgorithm): all quads */
    double size_factor;  /* gmsh Mesh.MeshSizeFactor for a .geo; 0 leaves the
                            file's value (default 1). Both override the file. */
    int allow_vertex_only; /* 1: elements meeting only at a vertex are accepted
                              (setting vertex_only=1); 0: an error (wff_mesh_check) */
} wff_mesh_options;

/* Load or generate a mesh (path ends in .geo or .msh; options may be NULL:
 * no settings, the file's own mesh options). On failure *mesh is empty
 * (nothing to free) and err says why. The caller owns the arrays: free with
 * wff_mesh_free(). */
int wff_mesh_load(const char *path, const wff_mesh_options *options, wff_mesh *mesh,
                  wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

/* Meshes from arrays and FreeFEM's .msh (include/wovenff/mesh_labels.h): the
 * checks (zero-area, indices, unused vertices), clockwise triangles reordered,
 * labels as groups and names=/regions=, label lookup, and wff_mesh_load
 * telling FreeFEM's format from gmsh's. Files under $WFF_TEST_TMP. */
#include "check.h"
#include "test_tmp.h"
#include "wovenff/mesh.h"
#include "wovenff/mesh_labels.h"

#include <stdlib.h>
#include <string.h>

static char tmp_dir[512];

/* unit square, 4 vertices, 2 triangles (the second clockwise), 4 edges */
static const double sq_xy[] = {0, 0, 1, 0, 1, 1, 0, 1};
static const int sq_tri[] = {0, 1, 2, 0, 3, 2};
static const int sq_region[] = {5, 6};
static const int sq_edge[] = {0, 1, 1, 2, 2, 3, 3, 0};
static const int sq_label[] = {1, 2, 3, 4};

static wff_mesh_arrays square_arrays(void)
{
    wff_mesh_arrays a = {4, sq_xy, 2, sq_tri, sq_region, 4, sq_edge, sq_label};
    return a;
}

static void test_arrays(check_state *st)
{
    wff_mesh_arrays a = square_arrays();
    wff_mesh m;
    wff_error err;
    CHECK(st, wff_mesh_from_arrays(&a, "names=1:clamp,3:top regions=6:patch", &m, &err) == 0,
          "%s", err.message);
    CHECK(st, m.n_nodes == 4 && m.n_tris == 2 && m.n_edges == 4 && m.n_quads == 0, "sizes");
    CHECK(st, m.tri[3] == 0 && m.tri[4] == 2 && m.tri[5] == 3, "clockwise triangle reordered: "
          "%d %d %d", m.tri[3], m.tri[4], m.tri[5]);
    CHECK(st, m.n_groups == 6, "4 boundary + 2 region groups, got %d", m.n_groups);
    CHECK(st, wff_mesh_group_tag(&m, 1, "clamp") == 1 && wff_mesh_group_tag(&m, 1, "label_2") == 2,
          "boundary names");
    CHECK(st, wff_mesh_group_tag(&m, 2, "region_5") == 5 && wff_mesh_group_tag(&m, 2, "patch") == 6,
          "region names");
    const char *g = wff_mesh_label_group(&m, 3, &err);
    CHECK(st, g && strcmp(g, "top") == 0, "label 3 -> top");
    g = wff_mesh_label_group(&m, 6, &err); /* no boundary 6: the region */
    CHECK(st, g && strcmp(g, "patch") == 0, "label 6 -> patch");
    CHECK(st, wff_mesh_label_group(&m, 9, &err) == NULL && strstr(err.message, "no label 9") &&
          strstr(err.message, "1 (clamp)") && strstr(err.message, "6 (patch)"), "%s", err.message);
    wff_mesh_free(&m);

    /* errors, each naming what is at fault */
    CHECK(st, wff_mesh_from_arrays(&a, "names=7:x", &m, &err) < 0 &&
          strstr(err.message, "boundary label 7") && strstr(err.message, "1 2 3 4"), "%s",
          err.message);
    CHECK(st, m.n_nodes == 0 && m.xy == NULL, "empty on failure");
    CHECK(st, wff_mesh_from_arrays(&a, "regions=1:x", &m, &err) < 0 &&
          strstr(err.message, "region label 1"), "%s", err.message);
    CHECK(st, wff_mesh_from_arrays(&a, "names=1:a,2:a", &m, &err) < 0 &&
          strstr(err.message, "'a'"), "%s", err.message);
    CHECK(st, wff_mesh_from_arrays(&a, "names=1:label_2", &m, &err) < 0 &&
          strstr(err.message, "label_2"), "%s", err.message);
    CHECK(st, wff_mesh_from_arrays(&a, "names=1", &m, &err) < 0 &&
          strstr(err.message, "LABEL:NAME"), "%s", err.message);
    CHECK(st, wff_mesh_from_arrays(&a, "size=2", &m, &err) < 0 &&
          strstr(err.message, "unknown setting"), "%s", err.message);

    double flat_xy[] = {0, 0, 1, 0, 2, 0, 0, 1};
    int flat_tri[] = {0, 1, 3, 0, 1, 2};
    wff_mesh_arrays b = {4, flat_xy, 2, flat_tri, sq_region, 0, sq_edge, sq_label};
    CHECK(st, wff_mesh_from_arrays(&b, "", &m, &err) < 0 && strstr(err.message, "triangle 2") &&
          strstr(err.message, "zero-area"), "%s", err.message);
    int out_tri[] = {0, 1, 2, 0, 2, 4};
    b = square_arrays();
    b.tri = out_tri;
    CHECK(st, wff_mesh_from_arrays(&b, "", &m, &err) < 0 && strstr(err.message, "triangle 2") &&
          strstr(err.message, "vertex index 5"), "%s", err.message);
    double five_xy[] = {0, 0, 1, 0, 1, 1, 0, 1, 3, 3};
    b = square_arrays();
    b.n_nodes = 5;
    b.xy = five_xy;
    CHECK(st, wff_mesh_from_arrays(&b, "", &m, &err) < 0 && strstr(err.message, "vertex 5") &&
          strstr(err.message, "no triangle"), "%s", err.message);
    double nan_xy[] = {0, 0, 1, 0, 1, NAN, 0, 1};
    b = square_arrays();
    b.xy = nan_xy;
    CHECK(st, wff_mesh_from_arrays(&b, "", &m, &err) < 0 && strstr(err.message, "vertex 3"),
          "%s", err.message);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        exit(2);
    }
    fputs(text, f);
    fclose(f);
}

static void test_freefem_file(check_state *st)
{
    char path[600], gpath[600];
    test_tmp_path(tmp_dir, "square.msh", path, sizeof path);
    /* as FreeFEM's savemesh writes square(1, 1) */
    write_file(path, "4 2 4\n0 0 4\n1 0 2\n0 1 4\n1 1 2\n1 2 4 0\n1 4 3 0\n"
                     "1 2 1\n2 4 2\n4 3 3\n3 1 4\n");
    CHECK(st, wff_mesh_is_freefem_msh(path) == 1, "recognised");
    wff_mesh m;
    wff_error err;
    CHECK(st, wff_mesh_load(path, NULL, &m, &err) == 0, "wff_mesh_load: %s", err.message);
    CHECK(st, m.n_nodes == 4 && m.n_tris == 2 && m.n_edges == 4, "sizes %d %d %d", m.n_nodes,
          m.n_tris, m.n_edges);
    CHECK(st, m.xy[2] == 1 && m.xy[3] == 0 && m.tri[0] == 0 && m.tri[1] == 1 && m.tri[2] == 3,
          "vertices and triangles as in the file");
    CHECK(st, wff_mesh_group_tag(&m, 1, "label_3") == 3 && wff_mesh_group_tag(&m, 2, "region_0") == 0,
          "labels as groups");
    wff_mesh_free(&m);
    CHECK(st, wff_mesh_load_freefem(path, "names=2:right", &m, &err) == 0, "%s", err.message);
    CHECK(st, wff_mesh_group_tag(&m, 1, "right") == 2, "named");
    wff_mesh_free(&m);

    write_file(path, "4 2 4\n0 0 4\n1 0 2\n0 1 4\n1 1 2\n1 2 4 0\n1 4 x 0\n");
    CHECK(st, wff_mesh_load(path, NULL, &m, &err) < 0 && strstr(err.message, "line 7") &&
          strstr(err.message, "square.msh"), "%s", err.message);
    write_file(path, "4 2 4\n0 0 4\n1 0 2\n0 1 4\n1 1 2\n1 2 4 0\n1 4 3.5 0\n1 2 1\n2 4 2\n"
                     "4 3 3\n3 1 4\n");
    CHECK(st, wff_mesh_load(path, NULL, &m, &err) < 0 && strstr(err.message, "line 7") &&
          strstr(err.message, "whole number"), "%s", err.message);

    /* gmsh's format is not taken for FreeFEM's */
    test_tmp_path(tmp_dir, "gmsh.msh", gpath, sizeof gpath);
    write_file(gpath, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");
    CHECK(st, wff_mesh_is_freefem_msh(gpath) == 0, "gmsh .msh not FreeFEM's");
}

int main(void)
{
    check_state st = {0, 0};
    if (test_tmp_dir("test_mesh_labels", tmp_dir, sizeof tmp_dir))
        return 2;
    test_arrays(&st);
    test_freefem_file(&st);
    test_tmp_remove(tmp_dir);
    return check_summary(&st, "test_mesh_labels");
}

/* Mesh defects no single element shows (plugin/mesh_check.c, issue 11 item 7):
 * duplicated (coincident) nodes, nodes in no element, elements that meet only
 * at a vertex; each reported with the coordinates, through the array path
 * (wff_model_create_from_mesh, as for meshes built in code or by FreeFEM) and
 * the file path (wff_mesh_load of small MSH 2.2 files written here), and the
 * setting vertex_only=1 that accepts vertex-only contacts. Also a truncated
 * and an empty .msh file: a clear error, no crash. */
#include "check.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "wovenff/mesh.h"
#include "wovenff/options.h"
#include "wovenff/solver.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"

/* Expect create_from_mesh to fail with every needle in the message. */
static void expect_model_error(check_state *st, wff_mesh *mesh, const char *what,
                               const char *n1, const char *n2, const char *n3)
{
    wff_model m;
    wff_error err = {{0}};
    int rc = wff_model_create_from_mesh(&m, mesh, KEVLAR, &err);
    CHECK(st, rc == -1, "%s: accepted", what);
    if (rc == 0)
        wff_model_free(&m);
    const char *needles[] = {n1, n2, n3};
    for (int i = 0; i < 3; i++)
        if (needles[i])
            CHECK(st, strstr(err.message, needles[i]) != NULL, "%s: message '%s' lacks '%s'",
                  what, err.message, needles[i]);
    printf("  %s: %s\n", what, err.message);
}

/* A 2 x 1 quad strip on [0, 2] x [0, 1]: nodes (i, j) = 3 j + i. */
static int strip(wff_mesh *mesh)
{
    test_rect r = {0, 2, 0, 1, 2, 1, TEST_MESH_QUAD, 0, 0, 0};
    return test_mesh_rect(&r, mesh);
}

/* One more node at (x, y) (returns its index). */
static int add_node(wff_mesh *mesh, double x, double y)
{
    mesh->xy = realloc(mesh->xy, 2 * (size_t)(mesh->n_nodes + 1) * sizeof *mesh->xy);
    mesh->xy[2 * mesh->n_nodes] = x;
    mesh->xy[2 * mesh->n_nodes + 1] = y;
    return mesh->n_nodes++;
}

static void array_cases(check_state *st)
{
    wff_mesh mesh;
    /* the strip as it is: accepted */
    if (strip(&mesh) == 0) {
        wff_model m;
        wff_error err;
        int rc = wff_model_create_from_mesh(&m, &mesh, KEVLAR, &err);
        CHECK(st, rc == 0, "clean strip: %s", rc ? err.message : "");
        if (rc == 0)
            wff_model_free(&m);
    }
    /* a slit: the second quad uses a copy of node 1 (1, 0) */
    if (strip(&mesh) == 0) {
        int copy = add_node(&mesh, 1, 0);
        for (int k = 0; k < 4; k++)
            if (mesh.quad[4 + k] == 1)
                mesh.quad[4 + k] = copy;
        expect_model_error(st, &mesh, "duplicated node", "nodes 2 and 7 coincide", "(1, 0) m",
                           "slit");
    }
    /* a node in no element */
    if (strip(&mesh) == 0) {
        add_node(&mesh, 5, 7);
        expect_model_error(st, &mesh, "unreferenced node", "node 7 at (5, 7) m",
                           "in no element", NULL);
    }
    /* an element node index out of range */
    if (strip(&mesh) == 0) {
        mesh.quad[2] = 99;
        expect_model_error(st, &mesh, "node out of range", "quadrilateral 1 uses node 100",
                           "nodes 1 to 6", NULL);
    }
    /* vertex-only: two triangles sharing node 0 only */
    {
        wff_mesh v = {0};
        double xy[] = {0, 0, 1, 0, 0, 1, -1, 0, 0, -1};
        int tri[] = {0, 1, 2, 0, 3, 4};
        v.n_nodes = 5;
        v.xy = malloc(sizeof xy);
        memcpy(v.xy, xy, sizeof xy);
        v.n_tris = 2;
        v.tri = malloc(sizeof tri);
        memcpy(v.tri, tri, sizeof tri);
        v.tri_region = calloc(2, sizeof(int));
        wff_error err = {{0}};
        int rc = wff_mesh_check(&v, 0, "bowtie", &err);
        CHECK(st, rc == -1 && strstr(err.message, "triangle 1 and triangle 2 meet only at node 1")
                  && strstr(err.message, "(0, 0) m") && strstr(err.message, "vertex_only=1"),
              "vertex-only contact refused: %s", err.message);
        printf("  vertex-only: %s\n", err.message);
        CHECK(st, wff_mesh_check(&v, 1, "bowtie", &err) == 0, "vertex_only allows it: %s",
              err.message);
        wff_mesh_free(&v);
    }
}

static int write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f)
        return -1;
    fputs(text, f);
    return fclose(f);
}

/* Two unit squares side by side as 4 triangles, MSH 2.2; `right_x1` names the
 * node the right square uses at (1, 0)/(1, 1): 2/3 joined, 7/8 duplicated. */
static void square_pair_msh(char *out, size_t size, int duplicated)
{
    snprintf(out, size,
             "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
             "$Nodes\n8\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 2 0 0\n6 2 1 0\n"
             "7 1 0 0\n8 1 1 0\n$EndNodes\n"
             "$Elements\n4\n1 2 2 1 1 1 2 3\n2 2 2 1 1 1 3 4\n3 2 2 1 1 %d 5 6\n"
             "4 2 2 1 1 %d 6 %d\n$EndElements\n",
             duplicated ? 7 : 2, duplicated ? 7 : 2, duplicated ? 8 : 3);
}

static void file_cases(check_state *st)
{
    char dir[512], path[700], text[1024];
    if (test_tmp_dir("test_mesh_defects", dir, sizeof dir))
        return;
    wff_mesh mesh;
    wff_error err = {{0}};
    /* joined: accepted (gmsh drops the two unused nodes 7, 8 of the file) */
    test_tmp_path(dir, "joined.msh", path, sizeof path);
    square_pair_msh(text, sizeof text, 0);
    write_text(path, text);
    int rc = wff_mesh_load(path, NULL, &mesh, &err);
    CHECK(st, rc == 0 && mesh.n_nodes == 6, "joined squares: %s", rc ? err.message : "");
    if (rc == 0)
        wff_mesh_free(&mesh);
    /* duplicated nodes 7, 8 at (1, 0), (1, 1): a slit */
    test_tmp_path(dir, "slit.msh", path, sizeof path);
    square_pair_msh(text, sizeof text, 1);
    write_text(path, text);
    rc = wff_mesh_load(path, NULL, &mesh, &err);
    CHECK(st, rc == -1 && strstr(err.message, "slit.msh") && strstr(err.message, "coincide at (1, ")
              && strstr(err.message, "slit"), "duplicated nodes in a .msh: %s", err.message);
    printf("  .msh with a slit: %s\n", err.message);
    /* two triangles meeting at a vertex; allowed with vertex_only=1 */
    test_tmp_path(dir, "bowtie.msh", path, sizeof path);
    write_text(path, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                     "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 -1 0 0\n5 0 -1 0\n$EndNodes\n"
                     "$Elements\n2\n1 2 2 1 1 1 2 3\n2 2 2 1 1 1 4 5\n$EndElements\n");
    rc = wff_mesh_load(path, NULL, &mesh, &err);
    CHECK(st, rc == -1 && strstr(err.message, "meet only at node") &&
              strstr(err.message, "(0, 0) m"), "vertex-only .msh: %s", err.message);
    wff_mesh_options opt;
    CHECK(st, wff_mesh_options_parse("vertex_only=1", &opt, &err) == 0 && opt.allow_vertex_only,
          "setting vertex_only=1: %s", err.message);
    rc = wff_mesh_load(path, &opt, &mesh, &err);
    CHECK(st, rc == 0, "vertex-only .msh with vertex_only=1: %s", rc ? err.message : "");
    if (rc == 0)
        wff_mesh_free(&mesh);
    /* truncated and empty files: an error naming the file, no crash */
    test_tmp_path(dir, "truncated.msh", path, sizeof path);
    square_pair_msh(text, sizeof text, 0);
    text[strlen(text) / 2] = '\0';
    write_text(path, text);
    rc = wff_mesh_load(path, NULL, &mesh, &err);
    CHECK(st, rc == -1 && strstr(err.message, "truncated.msh"), "truncated .msh: %s",
          err.message);
    printf("  truncated .msh: %s\n", err.message);
    test_tmp_path(dir, "empty.msh", path, sizeof path);
    write_text(path, "");
    rc = wff_mesh_load(path, NULL, &mesh, &err);
    CHECK(st, rc == -1 && strstr(err.message, "empty.msh"), "empty .msh: %s", err.message);
    printf("  empty .msh: %s\n", err.message);
    test_tmp_remove(dir);
}

int main(void)
{
    check_state st = {0, 0};
    array_cases(&st);
    file_cases(&st);
    return check_summary(&st, "test_mesh_defects");
}

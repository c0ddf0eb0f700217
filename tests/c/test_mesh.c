/* Meshes through gmsh: the .geo files of meshes/, every MSH flavour, the
 * triangle twin, and each rejected input (message names file and fault).
 * Files are written under $WFF_TEST_TMP (else a fresh directory in /tmp). */
#define _GNU_SOURCE
#include "check.h"
#include "test_tmp.h"
#include "wovenff/mesh.h"

#include <dirent.h>
#include <gmshc.h>
#include <locale.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define BALLISTIC "meshes/ballistic_quarter.geo"
#define STRIP "meshes/strip.geo"

static char tmp_dir[512];

static void tmp_path(char *out, size_t size, const char *name)
{
    test_tmp_path(tmp_dir, name, out, size);
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

static wff_mesh_options opts(int recombine, double size_factor)
{
    wff_mesh_options o;
    memset(&o, 0, sizeof o);
    o.recombine = recombine;
    o.size_factor = size_factor;
    return o;
}

static void add_setting(wff_mesh_options *o, const char *name, double value)
{
    snprintf(o->settings[o->n_settings].name, WFF_MESH_NAME_MAX, "%s", name);
    o->settings[o->n_settings++].value = value;
}

static int load_ok(check_state *st, const char *path, const wff_mesh_options *o, wff_mesh *m)
{
    wff_error e = {{0}};
    int rc = wff_mesh_load(path, o, m, &e);
    CHECK(st, rc == 0, "%s: %s", path, e.message);
    return rc == 0;
}

static double signed_area(const wff_mesh *m, const int *v, int n)
{
    double a = 0;
    for (int k = 0; k < n; k++) {
        const double *p = &m->xy[2 * v[k]], *q = &m->xy[2 * v[(k + 1) % n]];
        a += 0.5 * (p[0] * q[1] - p[1] * q[0]);
    }
    return a;
}

/* Sum of element areas; checks counter-clockwise, convex quads, indices in
 * range and every node used by some element. */
static double check_sane(check_state *st, const wff_mesh *m, const char *what)
{
    char *used = calloc((size_t)m->n_nodes + 1, 1);
    int bad_index = 0, bad_area = 0, bad_convex = 0;
    double total = 0;
    for (int pass = 0; pass < 2; pass++) {
        int n = pass ? 4 : 3, count = pass ? m->n_quads : m->n_tris;
        const int *conn = pass ? m->quad : m->tri;
        for (int e = 0; e < count; e++) {
            const int *v = &conn[n * e];
            int ok = 1;
            for (int k = 0; k < n; k++) {
                if (v[k] < 0 || v[k] >= m->n_nodes)
                    ok = 0;
                else
                    used[v[k]] = 1;
            }
            if (!ok) {
                bad_index++;
                continue;
            }
            double a = signed_area(m, v, n);
            bad_area += !(a > 0);
            total += a;
            if (n == 4)
                for (int k = 0; k < 4; k++) {
                    const double *p0 = &m->xy[2 * v[k]], *p1 = &m->xy[2 * v[(k + 1) % 4]],
                                 *p2 = &m->xy[2 * v[(k + 3) % 4]];
                    double c = (p1[0] - p0[0]) * (p2[1] - p0[1]) - (p1[1] - p0[1]) * (p2[0] - p0[0]);
                    bad_convex += !(c > 0);
                }
        }
    }
    int unused = 0;
    for (int i = 0; i < m->n_nodes; i++)
        unused += !used[i];
    free(used);
    CHECK(st, bad_index == 0, "%s: %d elements with node indices out of range", what, bad_index);
    CHECK(st, bad_area == 0, "%s: %d elements not counter-clockwise", what, bad_area);
    CHECK(st, bad_convex == 0, "%s: %d non-convex quad corners", what, bad_convex);
    CHECK(st, unused == 0, "%s: %d of %d nodes in no element", what, unused, m->n_nodes);
    for (int i = 0; i < m->n_edges; i++)
        CHECK(st, m->edge[2 * i] >= 0 && m->edge[2 * i] < m->n_nodes &&
                      m->edge[2 * i + 1] >= 0 && m->edge[2 * i + 1] < m->n_nodes,
              "%s: edge %d out of range", what, i);
    return total;
}

static double region_area(const wff_mesh *m, int region)
{
    double a = 0;
    for (int e = 0; e < m->n_tris; e++)
        if (m->tri_region[e] == region)
            a += signed_area(m, &m->tri[3 * e], 3);
    for (int e = 0; e < m->n_quads; e++)
        if (m->quad_region[e] == region)
            a += signed_area(m, &m->quad[4 * e], 4);
    return a;
}

static int edges_with_label(const wff_mesh *m, int label)
{
    int n = 0;
    for (int i = 0; i < m->n_edges; i++)
        n += m->edge_label[i] == label;
    return n;
}

static int is_empty(const wff_mesh *m)
{
    return !m->n_nodes && !m->xy && !m->n_tris && !m->tri && !m->tri_region && !m->n_quads &&
           !m->quad && !m->quad_region && !m->n_edges && !m->edge && !m->edge_label &&
           !m->n_groups && !m->groups;
}

static int same_ints(const int *a, const int *b, int n)
{
    return n == 0 || memcmp(a, b, (size_t)n * sizeof *a) == 0;
}

static int same_mesh(const wff_mesh *a, const wff_mesh *b)
{
    if (a->n_nodes != b->n_nodes || a->n_tris != b->n_tris || a->n_quads != b->n_quads ||
        a->n_edges != b->n_edges || a->n_groups != b->n_groups)
        return 0;
    for (int i = 0; i < 2 * a->n_nodes; i++)
        if (fabs(a->xy[i] - b->xy[i]) > 1e-15)
            return 0;
    for (int i = 0; i < a->n_groups; i++)
        if (a->groups[i].dim != b->groups[i].dim || a->groups[i].tag != b->groups[i].tag ||
            strcmp(a->groups[i].name, b->groups[i].name) != 0)
            return 0;
    return same_ints(a->tri, b->tri, 3 * a->n_tris) &&
           same_ints(a->tri_region, b->tri_region, a->n_tris) &&
           same_ints(a->quad, b->quad, 4 * a->n_quads) &&
           same_ints(a->quad_region, b->quad_region, a->n_quads) &&
           same_ints(a->edge, b->edge, 2 * a->n_edges) &&
           same_ints(a->edge_label, b->edge_label, a->n_edges);
}

static void test_ballistic(check_state *st)
{
    wff_mesh m;
    wff_mesh_options o = opts(0, 0);
    if (!load_ok(st, BALLISTIC, &o, &m))
        return;
    const char *curves[] = {"sym_x", "sym_y", "clamp_edge", "outer"};
    int tag[4];
    for (int i = 0; i < 4; i++) {
        tag[i] = wff_mesh_group_tag(&m, 1, curves[i]);
        CHECK(st, tag[i] > 0, "curve group %s missing", curves[i]);
        CHECK(st, edges_with_label(&m, tag[i]) > 0, "no edges in %s", curves[i]);
    }
    int fabric = wff_mesh_group_tag(&m, 2, "fabric"), clamp = wff_mesh_group_tag(&m, 2, "clamp");
    CHECK(st, fabric > 0 && clamp > 0 && fabric != clamp, "surface groups %d %d", fabric, clamp);
    CHECK(st, m.n_groups == 6, "%d groups", m.n_groups);
    CHECK(st, wff_mesh_group_tag(&m, 2, "sym_x") == -1, "sym_x is a curve, not a surface");
    CHECK(st, wff_mesh_group_tag(&m, 1, "nothing") == -1, "unknown group");
    CHECK(st, m.n_quads == 0 && m.n_tris >= 2000 && m.n_tris <= 2600, "default: %d tris %d quads",
          m.n_tris, m.n_quads);
    double area = check_sane(st, &m, "ballistic");
    CHECK_CLOSE(st, area, 0.04, 1e-12, 0, "ballistic total area");
    /* the arc is polygonal: the disk is slightly smaller than pi R^2 / 4 */
    double disk = 0.25 * M_PI * 0.127 * 0.127;
    CHECK_CLOSE(st, region_area(&m, fabric), disk, 2e-3, 0, "fabric area");
    CHECK_CLOSE(st, region_area(&m, fabric) + region_area(&m, clamp), 0.04, 1e-12, 0,
                "fabric + clamp area");
    /* every edge lies on its curve */
    int off = 0;
    for (int i = 0; i < m.n_edges; i++)
        for (int k = 0; k < 2; k++) {
            double x = m.xy[2 * m.edge[2 * i + k]], y = m.xy[2 * m.edge[2 * i + k] + 1];
            int l = m.edge_label[i];
            if ((l == tag[0] && fabs(x) > 1e-12) || (l == tag[1] && fabs(y) > 1e-12) ||
                (l == tag[2] && fabs(hypot(x, y) - 0.127) > 1e-9) ||
                (l == tag[3] && fabs(x - 0.2) > 1e-12 && fabs(y - 0.2) > 1e-12))
                off++;
        }
    CHECK(st, off == 0, "%d edge nodes off their curve", off);
    /* fabric elements inside r <= R, clamp outside */
    int wrong = 0;
    for (int e = 0; e < m.n_tris; e++) {
        double cx = 0, cy = 0;
        for (int k = 0; k < 3; k++) {
            cx += m.xy[2 * m.tri[3 * e + k]] / 3;
            cy += m.xy[2 * m.tri[3 * e + k] + 1] / 3;
        }
        int inside = hypot(cx, cy) < 0.127;
        wrong += inside != (m.tri_region[e] == fabric);
    }
    CHECK(st, wrong == 0, "%d triangles in the wrong region", wrong);
    /* graded: triangles at the impact point far smaller than in the clamp */
    double a_centre = 0, a_clamp = 0;
    int n_centre = 0, n_clamp = 0;
    for (int e = 0; e < m.n_tris; e++) {
        const int *v = &m.tri[3 * e];
        double a = signed_area(&m, v, 3);
        int at_origin = 0;
        for (int k = 0; k < 3; k++)
            at_origin |= m.xy[2 * v[k]] == 0 && m.xy[2 * v[k] + 1] == 0;
        if (at_origin)
            a_centre += a, n_centre++;
        if (m.tri_region[e] == clamp)
            a_clamp += a, n_clamp++;
    }
    CHECK(st, n_centre > 0 && n_clamp > 0 && a_centre / n_centre < 0.1 * a_clamp / n_clamp,
          "grading: %d triangles at (0,0), mean area %g; clamp mean %g", n_centre,
          n_centre ? a_centre / n_centre : 0, n_clamp ? a_clamp / n_clamp : 0);
    int n_default = m.n_tris;
    wff_mesh_free(&m);
    CHECK(st, is_empty(&m), "wff_mesh_free leaves an empty mesh");

    /* size factor: about 1/f^2 times the triangles */
    const double factors[] = {2, 0.5, 0.25};
    int n_f[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++) {
        o = opts(0, factors[i]);
        if (!load_ok(st, BALLISTIC, &o, &m))
            continue;
        n_f[i] = m.n_tris;
        double ratio = (double)n_f[i] / n_default * factors[i] * factors[i];
        CHECK(st, ratio > 0.6 && ratio < 1.4, "size factor %g: %d triangles (default %d)",
              factors[i], n_f[i], n_default);
        CHECK_CLOSE(st, check_sane(st, &m, "ballistic scaled"), 0.04, 1e-12, 0, "scaled area");
        wff_mesh_free(&m);
    }

    /* ONELAB settings reach the DefineConstant of the .geo ... */
    o = opts(0, 0);
    add_setting(&o, "h_min", 0.004);
    if (load_ok(st, BALLISTIC, &o, &m)) {
        CHECK(st, m.n_tris < n_default, "h_min 0.004: %d triangles, default %d", m.n_tris,
              n_default);
        wff_mesh_free(&m);
    }
    o = opts(0, 0);
    add_setting(&o, "h_min", 0.0015);
    add_setting(&o, "h_max", 0.004);
    if (load_ok(st, BALLISTIC, &o, &m)) {
        CHECK(st, m.n_tris > n_default, "h_max 0.004: %d triangles, default %d", m.n_tris,
              n_default);
        wff_mesh_free(&m);
    }
    /* ... and do not outlive the call (gmsh keeps ONELAB across sessions) */
    o = opts(0, 0);
    if (load_ok(st, BALLISTIC, &o, &m)) {
        CHECK(st, m.n_tris == n_default, "defaults again: %d triangles, first %d", m.n_tris,
              n_default);
        wff_mesh_free(&m);
    }
    /* a .geo may reject its parameters with Error(): a clean failure */
    o = opts(0, 0);
    add_setting(&o, "h_min", -1);
    wff_error e = {{0}};
    CHECK(st, wff_mesh_load(BALLISTIC, &o, &m, &e) == -1 && strstr(e.message, BALLISTIC) &&
                  strstr(e.message, "h_min"),
          "negative h_min: %s", e.message);
    CHECK(st, is_empty(&m), "failed load leaves an empty mesh");

    /* recombined: quads, still covering the square */
    o = opts(1, 0);
    if (load_ok(st, BALLISTIC, &o, &m)) {
        CHECK(st, m.n_quads > 500 && m.n_tris < m.n_quads / 10, "recombined: %d quads %d tris",
              m.n_quads, m.n_tris);
        CHECK_CLOSE(st, check_sane(st, &m, "ballistic quads"), 0.04, 1e-12, 0, "quad area");
        wff_mesh_free(&m);
    }
}

static void test_strip(check_state *st)
{
    const double L = 0.254, W = 0.0254;
    wff_mesh m;
    wff_mesh_options o = opts(0, 0);
    if (load_ok(st, STRIP, &o, &m)) {
        CHECK(st, m.n_quads == 640 && m.n_tris == 0 && m.n_nodes == 65 * 11,
              "strip: %d quads %d tris %d nodes", m.n_quads, m.n_tris, m.n_nodes);
        CHECK_CLOSE(st, check_sane(st, &m, "strip"), L * W, 1e-12, 0, "strip area");
        const char *names[] = {"left", "right", "bottom", "top"};
        const int want[] = {10, 10, 64, 64};
        for (int i = 0; i < 4; i++) {
            int t = wff_mesh_group_tag(&m, 1, names[i]);
            CHECK(st, t > 0 && edges_with_label(&m, t) == want[i], "%s: tag %d, %d edges",
                  names[i], t, edges_with_label(&m, t));
        }
        int s = wff_mesh_group_tag(&m, 2, "strip");
        CHECK(st, s > 0, "strip surface group");
        int other = 0;
        for (int q = 0; q < m.n_quads; q++)
            other += m.quad_region[q] != s;
        CHECK(st, other == 0, "%d quads outside region 'strip'", other);
        double xmax = 0, ymax = 0;
        for (int i = 0; i < m.n_nodes; i++) {
            xmax = fmax(xmax, m.xy[2 * i]);
            ymax = fmax(ymax, m.xy[2 * i + 1]);
        }
        CHECK_CLOSE(st, xmax, L, 1e-14, 0, "strip length");
        CHECK_CLOSE(st, ymax, W, 1e-14, 0, "strip width");

        /* triangle twin: 2 per quad, same nodes, same area */
        int nt = m.n_tris + 2 * m.n_quads;
        int *tri = malloc(3 * (size_t)nt * sizeof *tri), *reg = malloc((size_t)nt * sizeof *reg);
        wff_mesh_triangulate(&m, tri, reg);
        wff_mesh twin = m;
        twin.tri = tri;
        twin.tri_region = reg;
        twin.n_tris = nt;
        twin.n_quads = 0;
        CHECK_CLOSE(st, check_sane(st, &twin, "strip twin"), L * W, 1e-12, 0, "twin area");
        int bad = 0;
        for (int q = 0; q < m.n_quads; q++) {
            const int *v = &m.quad[4 * q], *t = &tri[6 * q];
            bad += t[0] != v[0] || t[1] != v[1] || t[2] != v[2] || t[3] != v[0] ||
                   t[4] != v[2] || t[5] != v[3] || reg[2 * q] != s || reg[2 * q + 1] != s;
        }
        CHECK(st, bad == 0, "%d quads split wrongly", bad);
        free(tri);
        free(reg);
        wff_mesh_free(&m);
    }
    o = opts(0, 0);
    add_setting(&o, "quads", 0);
    if (load_ok(st, STRIP, &o, &m)) {
        CHECK(st, m.n_tris == 1280 && m.n_quads == 0 && m.n_nodes == 715,
              "strip quads=0: %d tris %d quads", m.n_tris, m.n_quads);
        CHECK_CLOSE(st, check_sane(st, &m, "strip tris"), L * W, 1e-12, 0, "strip tri area");
        wff_mesh_free(&m);
    }
    o = opts(1, 0); /* recombine keeps the structured quads as they are */
    add_setting(&o, "nx", 8);
    add_setting(&o, "ny", 3);
    add_setting(&o, "length", 1);
    if (load_ok(st, STRIP, &o, &m)) {
        CHECK(st, m.n_quads == 24 && m.n_tris == 0, "strip 8x3: %d quads %d tris", m.n_quads,
              m.n_tris);
        CHECK_CLOSE(st, check_sane(st, &m, "strip 8x3"), W, 1e-12, 0, "strip 8x3 area");
        wff_mesh_free(&m);
    }
    /* a misspelt setting is an error, not silently ignored */
    o = opts(0, 0);
    add_setting(&o, "n_x", 8);
    wff_error e = {{0}};
    CHECK(st, wff_mesh_load(STRIP, &o, &m, &e) == -1 && strstr(e.message, STRIP) &&
                  strstr(e.message, "'n_x'") && strstr(e.message, "not a parameter"),
          "misspelt setting: %s", e.message);
    CHECK(st, is_empty(&m), "failed load leaves an empty mesh");
}

/* A .geo with a triangle part, a quad part, a surface outside every physical
 * group, and one curve in two physical curves; saved by gmsh in several MSH
 * flavours, all of which must load to the same arrays as the .geo. */
static const char MIXED_GEO[] =
    "Point(1) = {0, 0, 0, 0.3}; Point(2) = {1, 0, 0, 0.3}; Point(3) = {2, 0, 0, 0.3};\n"
    "Point(4) = {2, 1, 0, 0.3}; Point(5) = {1, 1, 0, 0.3}; Point(6) = {0, 1, 0, 0.3};\n"
    "Point(7) = {0, 1.5, 0, 0.3}; Point(8) = {2, 1.5, 0, 0.3};\n"
    "Line(1) = {1, 2}; Line(2) = {2, 5}; Line(3) = {5, 6}; Line(4) = {6, 1};\n"
    "Line(5) = {2, 3}; Line(6) = {3, 4}; Line(7) = {4, 5};\n"
    "Line(8) = {6, 7}; Line(9) = {7, 8}; Line(10) = {8, 4};\n"
    "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
    "Curve Loop(2) = {5, 6, 7, -2}; Plane Surface(2) = {2};\n"
    "Curve Loop(3) = {-3, -7, -10, -9, -8}; Plane Surface(3) = {3};\n"
    "Transfinite Curve {5, 7} = 5; Transfinite Curve {2, 6} = 4;\n"
    "Transfinite Surface {2}; Recombine Surface {2};\n"
    "Physical Curve(\"bottom\", 11) = {1, 5};\n"
    "Physical Curve(\"left\", 12) = {4};\n"
    "Physical Curve(\"west\", 13) = {4};\n"
    "Physical Surface(\"tri_part\", 7) = {1};\n"
    "Physical Surface(\"quad_part\", 8) = {2};\n";

static void write_msh(const char *geo, const char *out, double version, int binary)
{
    int ierr = 0;
    gmshInitialize(0, NULL, 0, &ierr);
    gmshOptionSetNumber("General.Terminal", 0, &ierr);
    gmshOpen(geo, &ierr);
    gmshModelMeshGenerate(2, &ierr);
    gmshOptionSetNumber("Mesh.MshFileVersion", version, &ierr);
    gmshOptionSetNumber("Mesh.Binary", binary, &ierr);
    gmshWrite(out, &ierr);
    gmshFinalize(&ierr);
}

static void test_msh_flavours(check_state *st)
{
    char geo[600];
    tmp_path(geo, sizeof geo, "mixed.geo");
    write_file(geo, MIXED_GEO);
    wff_mesh ref;
    wff_mesh_options o = opts(0, 0);
    if (!load_ok(st, geo, &o, &ref))
        return;
    CHECK(st, ref.n_tris > 10 && ref.n_quads == 12, "mixed: %d tris %d quads", ref.n_tris,
          ref.n_quads);
    CHECK_CLOSE(st, check_sane(st, &ref, "mixed"), 2.0, 1e-12, 0, "mixed area (top excluded)");
    CHECK_CLOSE(st, region_area(&ref, 7), 1.0, 1e-12, 0, "tri_part area");
    CHECK_CLOSE(st, region_area(&ref, 8), 1.0, 1e-12, 0, "quad_part area");
    int above = 0;
    for (int i = 0; i < ref.n_nodes; i++)
        above += ref.xy[2 * i + 1] > 1 + 1e-12;
    CHECK(st, above == 0, "%d nodes of the unphysical surface kept", above);
    /* curve 4 is in both 'left' and 'west': its edges come once per group */
    CHECK(st, edges_with_label(&ref, 12) > 0 &&
                  edges_with_label(&ref, 12) == edges_with_label(&ref, 13),
          "left %d west %d edges", edges_with_label(&ref, 12), edges_with_label(&ref, 13));
    CHECK(st, edges_with_label(&ref, 11) > 0, "bottom edges");
    CHECK(st, ref.n_edges == edges_with_label(&ref, 11) + 2 * edges_with_label(&ref, 12),
          "only physical curves give edges (%d)", ref.n_edges);

    const struct { const char *name; double version; int binary; } flavours[] = {
        {"mixed_v2_ascii.msh", 2.2, 0},
        {"mixed_v2_binary.msh", 2.2, 1},
        {"mixed_v4_ascii.msh", 4.1, 0},
        {"mixed_v4_binary.msh", 4.1, 1},
    };
    for (size_t i = 0; i < sizeof flavours / sizeof flavours[0]; i++) {
        char path[600];
        tmp_path(path, sizeof path, flavours[i].name);
        write_msh(geo, path, flavours[i].version, flavours[i].binary);
        wff_mesh m;
        if (!load_ok(st, path, &o, &m))
            continue;
        CHECK(st, same_mesh(&m, &ref), "%s differs from the .geo mesh (%d/%d nodes, %d/%d tris, "
              "%d/%d quads, %d/%d edges)", flavours[i].name, m.n_nodes, ref.n_nodes, m.n_tris,
              ref.n_tris, m.n_quads, ref.n_quads, m.n_edges, ref.n_edges);
        wff_mesh_free(&m);
    }

    /* triangle twin of a mixed mesh: triangles first, then 2 per quad */
    int nt = ref.n_tris + 2 * ref.n_quads;
    int *tri = malloc(3 * (size_t)nt * sizeof *tri), *reg = malloc((size_t)nt * sizeof *reg);
    wff_mesh_triangulate(&ref, tri, reg);
    CHECK(st, same_ints(tri, ref.tri, 3 * ref.n_tris) &&
                  same_ints(reg, ref.tri_region, ref.n_tris),
          "twin starts with the triangles");
    wff_mesh twin = ref;
    twin.tri = tri;
    twin.tri_region = reg;
    twin.n_tris = nt;
    twin.n_quads = 0;
    CHECK_CLOSE(st, check_sane(st, &twin, "mixed twin"), 2.0, 1e-12, 0, "twin area");
    CHECK_CLOSE(st, region_area(&twin, 8), 1.0, 1e-12, 0, "twin quad_part area");
    free(tri);
    free(reg);
    wff_mesh_free(&ref);
}

/* Hand-written MSH2 files (node tags sparse on purpose). */
static const char MSH2_HEAD[] = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";

static void msh2(char *path, size_t size, const char *name, const char *nodes,
                 const char *elements)
{
    tmp_path(path, size, name);
    char text[4096];
    snprintf(text, sizeof text, "%s$Nodes\n%s$EndNodes\n$Elements\n%s$EndElements\n", MSH2_HEAD,
             nodes, elements);
    write_file(path, text);
}

/* Unit square as two triangles and a quad beside it, one clockwise each;
 * node 99 is used by nothing; tags are sparse. */
static void test_orientation(check_state *st)
{
    char path[600];
    msh2(path, sizeof path, "clockwise.msh",
         "7\n10 0 0 0\n20 1 0 0\n30 1 1 0\n40 0 1 0\n50 2 0 0\n60 2 1 0\n99 5 5 0\n",
         "4\n"
         "1 1 2 0 1 10 20\n"              /* a line outside any physical curve */
         "2 2 2 0 1 10 40 30\n"           /* clockwise */
         "3 2 2 0 1 10 20 30\n"           /* counter-clockwise */
         "7 3 2 0 2 20 30 60 50\n");      /* clockwise quad */
    wff_mesh m;
    wff_mesh_options o = opts(0, 0);
    if (!load_ok(st, path, &o, &m))
        return;
    CHECK(st, m.n_nodes == 6 && m.n_tris == 2 && m.n_quads == 1 && m.n_edges == 0 &&
                  m.n_groups == 0,
          "clockwise.msh: %d nodes %d tris %d quads %d edges %d groups", m.n_nodes, m.n_tris,
          m.n_quads, m.n_edges, m.n_groups);
    if (m.n_nodes == 6 && m.n_tris == 2 && m.n_quads == 1) {
        CHECK_CLOSE(st, check_sane(st, &m, "clockwise"), 2.0, 1e-14, 0, "clockwise area");
        /* nodes numbered in tag order: 10 -> 0, 20 -> 1, ..., 60 -> 5 */
        CHECK(st, m.xy[2 * 4] == 2 && m.xy[2 * 4 + 1] == 0 && m.xy[2 * 5 + 1] == 1,
              "node order follows tags");
        /* clockwise triangle 10 40 30 -> 10 30 40; quad 20 30 60 50 -> 20 50 60 30 */
        CHECK(st, m.tri[0] == 0 && m.tri[1] == 2 && m.tri[2] == 3, "tri %d %d %d", m.tri[0],
              m.tri[1], m.tri[2]);
        CHECK(st, m.quad[0] == 1 && m.quad[1] == 4 && m.quad[2] == 5 && m.quad[3] == 2,
              "quad %d %d %d %d", m.quad[0], m.quad[1], m.quad[2], m.quad[3]);
        CHECK(st, m.tri_region[0] == 0 && m.quad_region[0] == 0, "no physical: region 0");
    }
    wff_mesh_free(&m);
}

static void expect_fail(check_state *st, const char *path, const wff_mesh_options *o,
                        const char *word1, const char *word2)
{
    wff_mesh m;
    memset(&m, 0x5a, sizeof m); /* must come back empty whatever it held */
    wff_error e = {{0}};
    int rc = wff_mesh_load(path, o, &m, &e);
    CHECK(st, rc == -1, "%s: loaded, expected an error with '%s'", path, word1);
    if (rc == 0) {
        wff_mesh_free(&m);
        return;
    }
    CHECK(st, is_empty(&m), "%s: mesh not empty after failure", path);
    CHECK(st, strstr(e.message, path) != NULL, "message does not name %s: %s", path, e.message);
    CHECK(st, strstr(e.message, word1) != NULL, "message lacks '%s': %s", word1, e.message);
    CHECK(st, !word2 || strstr(e.message, word2) != NULL, "message lacks '%s': %s", word2,
          e.message);
}

static int open_fds(void)
{
    DIR *d = opendir("/proc/self/fd");
    if (!d)
        return -1;
    int n = 0;
    while (readdir(d))
        n++;
    closedir(d);
    return n;
}

static void test_errors(check_state *st)
{
    int fds = open_fds();
    wff_mesh_options o = opts(0, 0);
    char path[600];
    const char *square = "4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n";

    tmp_path(path, sizeof path, "no_such_mesh.msh");
    expect_fail(st, path, &o, "cannot read", "No such file");
    tmp_path(path, sizeof path, "no_such_mesh.geo");
    expect_fail(st, path, &o, "cannot read", NULL);
    expect_fail(st, "meshes/strip.txt", &o, "expected .geo or .msh", NULL);

    tmp_path(path, sizeof path, "truncated.msh");
    write_file(path, "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0\n");
    expect_fail(st, path, &o, "could not read", NULL);
    tmp_path(path, sizeof path, "garbage.msh");
    write_file(path, "this is not a mesh\n\x01\x02\xff\xfe\n");
    expect_fail(st, path, &o, "could not read", NULL);

    tmp_path(path, sizeof path, "syntax.geo");
    write_file(path, "Point(1) = {0, 0, 0, 1};\nLine(1) = {1, 2;\n");
    expect_fail(st, path, &o, "syntax error", "line 2");
    tmp_path(path, sizeof path, "unknown_variable.geo");
    write_file(path, "Point(1) = {0, 0, 0, h};\n");
    expect_fail(st, path, &o, "Unknown variable", NULL);
    /* a meshing error is raised inside gmsh's OpenMP region: must not abort */
    tmp_path(path, sizeof path, "open_loop.geo");
    write_file(path, "Point(1) = {0, 0, 0, 1}; Point(2) = {1, 0, 0, 1}; Point(3) = {0, 1, 0, 1};\n"
                     "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};\n"
                     "Curve Loop(1) = {1, 2}; Plane Surface(1) = {1};\n");
    expect_fail(st, path, &o, "could not mesh", NULL);
    tmp_path(path, sizeof path, "lines_only.geo");
    write_file(path, "Point(1) = {0, 0, 0, 1}; Point(2) = {1, 0, 0, 1}; Line(1) = {1, 2};\n");
    expect_fail(st, path, &o, "no 2-D elements", NULL);

    msh2(path, sizeof path, "tri6.msh",
         "6\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0.5 0 0\n5 0.5 0.5 0\n6 0 0.5 0\n",
         "1\n17 9 2 0 1 1 2 3 4 5 6\n");
    expect_fail(st, path, &o, "Triangle 6", "gmsh type 9");
    msh2(path, sizeof path, "quad9.msh",
         "9\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 .5 0 0\n6 1 .5 0\n7 .5 1 0\n8 0 .5 0\n"
         "9 .5 .5 0\n",
         "1\n1 10 2 0 1 1 2 3 4 5 6 7 8 9\n");
    expect_fail(st, path, &o, "Quadrilateral 9", "gmsh type 10");
    msh2(path, sizeof path, "lines.msh", square, "2\n1 1 2 1 1 1 2\n2 1 2 1 1 2 3\n");
    expect_fail(st, path, &o, "no 2-D elements", NULL);
    msh2(path, sizeof path, "off_plane.msh", "4\n1 0 0 0\n2 1 0 0\n3 1 1 0.25\n4 0 1 0\n",
         "2\n5 2 2 0 1 1 2 3\n6 2 2 0 1 1 3 4\n");
    expect_fail(st, path, &o, "not in the z = 0 plane", "element 1 (gmsh tag 5)");
    msh2(path, sizeof path, "flat_tri.msh", "4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 2 0 0\n",
         "2\n1 2 2 0 1 1 2 3\n8 2 2 0 1 1 2 4\n");
    expect_fail(st, path, &o, "zero-area element", "element 2 (gmsh tag 8)");
    msh2(path, sizeof path, "bowtie.msh", square, "1\n4 3 2 0 1 1 3 2 4\n");
    expect_fail(st, path, &o, "non-convex or inverted quadrilateral", "gmsh tag 4");
    msh2(path, sizeof path, "arrow.msh", "4\n1 0 0 0\n2 1 0.5 0\n3 0 1 0\n4 0.5 0.5 0\n",
         "1\n1 3 2 0 1 1 2 3 4\n");
    expect_fail(st, path, &o, "non-convex or inverted quadrilateral", NULL);
    /* MSH2 stores an element once per physical group: one surface, two groups */
    msh2(path, sizeof path, "two_regions.msh", square,
         "4\n1 2 2 1 1 1 2 3\n2 2 2 1 1 1 3 4\n3 2 2 2 1 1 2 3\n4 2 2 2 1 1 3 4\n");
    expect_fail(st, path, &o, "surface 1 belongs to 2 physical surfaces", NULL);
    /* an edge of a physical curve off the 2-D mesh: its node would have no mass */
    msh2(path, sizeof path, "stray_edge.msh",
         "5\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 3 3 0\n",
         "2\n1 2 2 1 1 1 2 3\n2 1 2 4 2 3 5\n");
    expect_fail(st, path, &o, "in no 2-D element", "node 5");

    /* bad options */
    wff_mesh_options bad = opts(0, -1);
    expect_fail(st, STRIP, &bad, "size_factor", NULL);
    bad = opts(0, 0);
    bad.n_settings = WFF_MESH_SETTINGS_MAX + 1;
    expect_fail(st, STRIP, &bad, "mesh settings", NULL);
    wff_error e = {{0}};
    CHECK(st, wff_mesh_load(NULL, &o, &(wff_mesh){0}, &e) == -1, "NULL path");

    /* after all that, gmsh still parses a good file correctly, and no file
     * was left open */
    wff_mesh m;
    if (load_ok(st, STRIP, &o, &m)) {
        CHECK(st, m.n_quads == 640, "strip after errors: %d quads", m.n_quads);
        wff_mesh_free(&m);
    }
    CHECK(st, open_fds() == fds, "%d file descriptors open, %d before", open_fds(), fds);
}

/* Nothing on stdout or stderr from gmsh on success; locale untouched. */
static void test_quiet(check_state *st)
{
    char log_path[600];
    tmp_path(log_path, sizeof log_path, "gmsh_output.txt");
    char locale_before[256];
    snprintf(locale_before, sizeof locale_before, "%s", setlocale(LC_ALL, NULL));
    fflush(stdout);
    fflush(stderr);
    int out = dup(1), err = dup(2);
    FILE *f = fopen(log_path, "w");
    if (!f || out < 0 || err < 0) {
        CHECK(st, 0, "cannot redirect output to %s", log_path);
        return;
    }
    dup2(fileno(f), 1);
    dup2(fileno(f), 2);
    wff_mesh m1, m2;
    wff_error e1 = {{0}}, e2 = {{0}};
    wff_mesh_options o = opts(1, 0);
    int rc1 = wff_mesh_load(STRIP, &o, &m1, &e1);
    o.size_factor = 0.25; /* ~19k quads: gmsh's default quad algorithm would print here */
    int rc2 = wff_mesh_load(BALLISTIC, &o, &m2, &e2);
    fflush(stdout);
    fflush(stderr);
    dup2(out, 1);
    dup2(err, 2);
    close(out);
    close(err);
    fclose(f);
    struct stat sb;
    long size = stat(log_path, &sb) == 0 ? (long)sb.st_size : -1;
    CHECK(st, rc1 == 0 && rc2 == 0, "quiet loads: %s %s", e1.message, e2.message);
    CHECK(st, size == 0, "gmsh printed %ld bytes (see %s)", size, log_path);
    CHECK(st, strcmp(locale_before, setlocale(LC_ALL, NULL)) == 0, "locale changed to %s",
          setlocale(LC_ALL, NULL));
    if (rc1 == 0)
        wff_mesh_free(&m1);
    if (rc2 == 0) {
        CHECK(st, m2.n_quads > 15000 && m2.n_tris == 0, "quads at size factor 0.25: %d quads "
              "%d tris", m2.n_quads, m2.n_tris);
        wff_mesh_free(&m2);
    }
}

int main(void)
{
    check_state st = {0, 0};
    if (test_tmp_dir("test_mesh", tmp_dir, sizeof tmp_dir))
        return 2;
    test_quiet(&st);
    test_ballistic(&st);
    test_strip(&st);
    test_msh_flavours(&st);
    test_orientation(&st);
    test_errors(&st);
    if (st.failures == 0) /* keep the files of a failing run for a look */
        test_tmp_remove(tmp_dir);
    else
        fprintf(stderr, "test_mesh: files kept in %s\n", tmp_dir);
    return check_summary(&st, "test_mesh");
}

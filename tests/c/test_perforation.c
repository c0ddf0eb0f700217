/* The shot's verdict (plugin/perforation.c, include/wovenff/perforation.h) on
 * states set by hand: a 100 mm square of King plain weave with failure, held on
 * its edges, its elements eroded by setting the flags, its yarns torn by setting
 * their damage, its nodes moved by setting u; no step is taken. Checked:
 *   1. at rest, the nose on the fabric: undecided, nothing holed;
 *   2. a hole wider than the nose, the nose past the plane: perforated while the
 *      projectile moves on, stopped when it has turned back; without a
 *      projectile: an error;
 *   3. a hole smaller than the nose (4 mm): holed, but the nose through it only once
 *      its rear is past the rim (the footprint's held nodes);
 *   4. an island left in the hole (not held to the edges) riding on the nose
 *      over the shot line: not the ply, perforated;
 *   5. held fabric lifted ahead of the tip over the shot line: in the way while
 *      intact (or within a ply's thickness of the tip when torn); lifted further
 *      and held only through torn elements, a shred: perforated;
 *   6. a pack of two plies: perforated only when both are holed and passed;
 *      the values by name (perforation, plies_holed, plies_through) and the ply
 *      keys holed, through agree with the call;
 *   7. a pack's ply apex once yarns have torn: of the part held through intact
 *      elements (a torn flap pulled 300 mm out is not the ply's deflection). */
#include "check.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "wovenff/cell_ops.h"
#include "wovenff/pack.h"
#include "wovenff/perforation.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

static const double radius = 6.35e-3;          /* m, the nose */
static const double axis[2] = {1.3e-3, 0.7e-3}; /* m, inside an element */

/* Element e's centroid distance from the axis in the reference plane. */
static double centre_distance(const wff_model *m, int e)
{
    const int nt = m->el.n_tris;
    const int *c = e < nt ? m->el.tri + 3 * e : m->el.quad + 4 * (e - nt);
    int k = e < nt ? 3 : 4;
    double x = 0, y = 0;
    for (int j = 0; j < k; j++) {
        x += m->mesh.xy[2 * c[j]] / k;
        y += m->mesh.xy[2 * c[j] + 1] / k;
    }
    return hypot(x - axis[0], y - axis[1]);
}

/* Node n's distance from the axis in the reference plane. */
static double node_distance(const wff_model *m, int n)
{
    return hypot(m->mesh.xy[2 * n] - axis[0], m->mesh.xy[2 * n + 1] - axis[1]);
}

/* Erode the elements (of ply `ply`, -1 every ply) whose centroid is within rho of the axis. */
static void erode_within(wff_model *m, double rho, int ply)
{
    for (int e = 0; e < m->el.n_tris + m->el.n_quads; e++)
        if (centre_distance(m, e) <= rho && (ply < 0 || wff_model_element_ply(m, e) == ply)) {
            if (!m->el.eroded[e])
                m->n_eroded++;
            m->el.eroded[e] = 1;
        }
}

/* Family 0 ruptured (damage 1) at every point of every element: all torn. */
static void tear_all(wff_model *m)
{
    int k = wff_cell_damage_state(m->mat.cell, 0);
    size_t points = wff_elements_point_count(&m->el);
    for (size_t q = 0; q < points; q++)
        m->state[(size_t)m->n_state * q + (size_t)k] = 1;
}

/* u_z = z for the nodes within rho of the axis (ply `ply`'s; -1 every node). */
static void lift_within(wff_model *m, double rho, double z, int ply)
{
    for (int n = 0; n < m->n_nodes; n++)
        if (node_distance(m, n) <= rho && (ply < 0 || wff_model_node_ply(m, n) == ply))
            m->u[D * n + WFF_UZ] = z;
}

static int verdict(check_state *st, const wff_model *m, wff_perforation *out, const char *what)
{
    wff_error err;
    int rc = wff_model_perforation(m, out, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    return rc == 0 ? out->verdict : -2;
}

/* A held square with a projectile at the axis, nose tip at z = 0 moving on. */
static int make(check_state *st, wff_model *m, const char *material, int plies)
{
    const test_rect square = {-0.05, 0.05, -0.05, 0.05, 20, 20, TEST_MESH_TRI, 1, 0, 0};
    wff_error err;
    int rc = test_model_rect(m, &square, material, &err);
    if (rc == 0 && plies > 1)
        rc = wff_model_set_plies(m, plies, 0.3e-3, &err);
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int g = 0; g < 4 && rc >= 0; g++)
        for (int c = WFF_UX; c <= WFF_UZ && rc >= 0; c++)
            rc = wff_model_fix_group(m, edges[g], c, &err);
    if (rc >= 0)
        rc = wff_model_set_impact_point(m, axis[0], axis[1], &err);
    if (rc >= 0)
        rc = wff_model_set_projectile(m, radius, 0.1, 50, 0.2, &err);
    CHECK(st, rc >= 0, "the model: %s", err.message);
    CHECK(st, rc < 0 || m->el.eroded, "the material with failure: erosion on");
    return rc < 0 || !m->el.eroded ? -1 : 0;
}

static void check_single(check_state *st, const char *material)
{
    wff_model m;
    wff_perforation v;
    if (make(st, &m, material, 1))
        return;
    double t;
    wff_error err;
    wff_model_pack_value(&m, "ply_thickness", &t, &err);
    /* 1 */
    CHECK(st, verdict(st, &m, &v, "at rest") == WFF_VERDICT_UNDECIDED && v.plies_holed == 0,
          "at rest: verdict %d, holed %d", v.verdict, v.plies_holed);
    /* 2: a hole of 10 mm radius, the nose 20 mm past the plane */
    erode_within(&m, 10e-3, -1);
    m.projectile.tip = 20e-3;
    CHECK(st, verdict(st, &m, &v, "hole, past") == WFF_VERDICT_PERFORATED && v.holed[0] && v.through[0],
          "a wide hole, the nose past: verdict %d, holed %d, through %d", v.verdict, v.holed[0],
          v.through[0]);
    m.projectile.velocity = -1;
    CHECK(st, verdict(st, &m, &v, "hole, back") == WFF_VERDICT_STOPPED,
          "turned back: verdict %d", v.verdict);
    m.projectile.velocity = 0;
    CHECK(st, verdict(st, &m, &v, "hole, still") == WFF_VERDICT_STOPPED, "at rest: verdict %d",
          v.verdict);
    m.projectile.velocity = 50;
    wff_model_free(&m);
    /* 3: a hole of 4 mm (every element over the axis: a triangle's points lie within 3.7 mm of
     * its centroid here): holed; through once the rear (tip - r) is past the rim at z = 0 */
    if (make(st, &m, material, 1))
        return;
    erode_within(&m, 4e-3, -1);
    m.projectile.tip = 3e-3; /* rear at -3.35 mm: the rim (z = 0) about the nose */
    CHECK(st, verdict(st, &m, &v, "small hole") == WFF_VERDICT_UNDECIDED && v.holed[0] && !v.through[0],
          "a small hole, the nose in it: verdict %d, holed %d, through %d", v.verdict, v.holed[0],
          v.through[0]);
    m.projectile.tip = radius + 1e-3; /* rear 1 mm past the rim */
    CHECK(st, verdict(st, &m, &v, "small hole, past") == WFF_VERDICT_PERFORATED,
          "a small hole, the rear past its rim: verdict %d", v.verdict);
    /* 4: an island within 2.5 mm left live (a ring 2.5-10 mm eroded), on the nose's tip */
    for (int e = 0; e < m.el.n_tris + m.el.n_quads; e++) {
        double d = centre_distance(&m, e);
        int want = d > 2.5e-3 && d <= 10e-3;
        m.n_eroded += want - m.el.eroded[e];
        m.el.eroded[e] = (unsigned char)want;
    }
    int island = 0;
    for (int e = 0; e < m.el.n_tris + m.el.n_quads; e++)
        island += !m.el.eroded[e] && centre_distance(&m, e) <= 2.5e-3;
    lift_within(&m, 3e-3, 20e-3, -1);
    m.projectile.tip = 20e-3;
    CHECK(st, island > 0 && verdict(st, &m, &v, "island") == WFF_VERDICT_PERFORATED,
          "an island (%d elements) not held, riding on the nose: verdict %d", island, v.verdict);
    wff_model_free(&m);
    /* 5: held fabric lifted ahead of the tip over the shot line, nothing eroded */
    if (make(st, &m, material, 1))
        return;
    m.projectile.tip = 0;
    lift_within(&m, 8e-3, 20e-3, -1);
    CHECK(st, verdict(st, &m, &v, "intact ahead") == WFF_VERDICT_UNDECIDED && !v.holed[0],
          "intact fabric 20 mm ahead: verdict %d, holed %d", v.verdict, v.holed[0]);
    tear_all(&m);
    CHECK(st, verdict(st, &m, &v, "torn ahead") == WFF_VERDICT_PERFORATED && v.holed[0],
          "torn fabric 20 mm ahead (a shred): verdict %d, holed %d", v.verdict, v.holed[0]);
    lift_within(&m, 8e-3, 0.5 * t, -1);
    CHECK(st, verdict(st, &m, &v, "torn on the nose") == WFF_VERDICT_UNDECIDED && !v.holed[0],
          "torn fabric half a ply's thickness (%g m) ahead, on the nose: verdict %d", 0.5 * t,
          v.verdict);
    wff_model_free(&m);
    /* no projectile */
    const test_rect small = {0, 0.01, 0, 0.01, 2, 2, TEST_MESH_TRI, 0, 0, 0};
    if (test_model_rect(&m, &small, material, &err) == 0) {
        CHECK(st, wff_model_perforation(&m, &v, &err) == -1 && strstr(err.message, "no projectile"),
              "no projectile: '%s'", err.message);
        wff_model_free(&m);
    }
}

static void check_pack(check_state *st, const char *material)
{
    wff_model m;
    wff_perforation v;
    wff_error err;
    if (make(st, &m, material, 2))
        return;
    m.projectile.tip = 20e-3;
    erode_within(&m, 10e-3, 0);
    double by_name, holed0, through1;
    CHECK(st, verdict(st, &m, &v, "ply 0 holed") == WFF_VERDICT_UNDECIDED && v.holed[0] && !v.holed[1] &&
              v.plies_holed == 1,
          "ply 0 holed, ply 1 whole: verdict %d, holed %d %d", v.verdict, v.holed[0], v.holed[1]);
    erode_within(&m, 10e-3, 1);
    CHECK(st, verdict(st, &m, &v, "both holed") == WFF_VERDICT_PERFORATED && v.plies_through == 2,
          "both holed: verdict %d, through %d", v.verdict, v.plies_through);
    CHECK(st, wff_model_value(&m, "perforation", &by_name, &err) == 0 && by_name == v.verdict,
          "perforation by name %g, the call %d", by_name, v.verdict);
    CHECK(st, wff_model_value(&m, "plies_holed", &by_name, &err) == 0 && by_name == 2,
          "plies_holed by name %g", by_name);
    CHECK(st, wff_model_ply_value(&m, 0, "holed", &holed0, &err) == 0 && holed0 == 1 &&
              wff_model_ply_value(&m, 1, "through", &through1, &err) == 0 && through1 == 1,
          "ply keys holed %g, through %g", holed0, through1);
    wff_model_free(&m);
    /* 7: ply 1's centre torn and pulled 300 mm out; its apex is of the intact part */
    if (make(st, &m, material, 2))
        return;
    int k = wff_cell_damage_state(m.mat.cell, 0), torn = 0;
    for (int e = 0; e < m.el.n_tris + m.el.n_quads; e++) {
        if (wff_model_element_ply(&m, e) != 1 || centre_distance(&m, e) > 12e-3)
            continue;
        size_t first = e < m.el.n_tris ? (size_t)WFF_TRI_POINTS * (size_t)e
                                       : (size_t)WFF_TRI_POINTS * (size_t)m.el.n_tris +
                                             (size_t)WFF_QUAD_POINTS * (size_t)(e - m.el.n_tris);
        m.state[(size_t)m.n_state * first + (size_t)k] = 1; /* one point ruptured */
        torn++;
    }
    double gap = 0.3e-3, apex;
    lift_within(&m, 4e-3, gap + 0.3, 1);
    CHECK(st, torn > 0 && wff_model_ply_value(&m, 1, "apex", &apex, &err) == 0 && apex < 0.01,
          "a torn flap of ply 1 pulled 300 mm out (%d torn elements): apex %g m", torn, apex);
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    char dir[400], path[512];
    if (test_tmp_dir("test_perforation", dir, sizeof dir))
        return 1;
    test_tmp_path(dir, "kevlar_failure.txt", path, sizeof path);
    CHECK(&st, test_tmp_copy_replacing(KEVLAR, path, "failure = 0", "failure = 1\n") == 1,
          "%s has a line 'failure = 0'", KEVLAR);
    check_single(&st, path);
    check_pack(&st, path);
    test_tmp_remove(dir);
    return check_summary(&st, "test_perforation");
}

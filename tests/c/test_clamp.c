/* The friction clamp (docs/model.md §15, docs/clamp.md): a 50 x 10 mm strip
 * (16 x 2 cells of triangles) held at its left end by the clamp, pulled at
 * its right end, with u_y = 0 on its bottom edge (a symmetry line, as in the
 * ballistic quarter model):
 *
 *   1. a node of the clamp on the symmetry line is held by friction along it
 *      (it used to be skipped, so that the quarter model's clamped symmetry
 *      lines slid freely): a weak pull sticks, a strong pull slides at 2 mu N;
 *   2. the clamping force is shared by the clamp's own area (a node on the
 *      clamp's boundary gets no force for the area of the free fabric next to
 *      it), and only inside the plates' bounds (wff_model_clamp_bounds);
 *   3. the out-of-plane reaction of a clamped node presses it on one face
 *      (clamp_edge_reaction 1): the friction limit grows by mu |R_z|;
 *   4. the ballistic mesh's frame (plates' extent, staple line) and h_clamp
 *      (clamp-region size) parameters.
 * Each check can fail: it compares against a force or a slip computed by hand. */
#include "check.h"
#include "test_meshes.h"
#include "test_ramp.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

typedef struct pull_result {
    double slip;       /* largest in-plane displacement of a clamped node, m */
    double corner_slip; /* that of the clamped node on the symmetry line y = 0, m */
    double load_slip;  /* mean pull-end reaction while the clamp slides, N */
    double normal_sum; /* Σ clamp.normal_force, N */
    int ok;
} pull_result;

/* The strip: "left" in the friction clamp (N, mu), "bottom" u_y = 0, "right"
 * pulled along x by a smooth ramp to `pull` m, then held. */
static void pull_run(check_state *st, double N, double mu, double pull, pull_result *out)
{
    memset(out, 0, sizeof *out);
    test_rect r = {0, 0.05, 0, 0.01, 16, 2, TEST_MESH_TRI, 1, 0, 0};
    wff_model m;
    wff_error err;
    if (test_model_rect(&m, &r, KEVLAR, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    int rc = wff_model_fix_group(&m, "bottom", WFF_UY, &err) < 0 ||
             wff_model_clamp_friction(&m, "left", N, mu, &err) != 3;
    CHECK(st, rc == 0, "set-up: %s", err.message);
    for (int i = 0; i < m.clamp.n; i++)
        out->normal_sum += m.clamp.normal_force[i];
    const int corner = 0; /* node (0, 0): clamped and on the symmetry line */
    const double V = 1.5, t_ramp = 0.1e-3, block = 5e-6;
    const double t_cruise = pull / V - t_ramp, t_move = 2 * t_ramp + t_cruise, t_hold = 0.2e-3;
    int n_slip = 0;
    double prev_slip = 0;
    while (rc == 0 && m.time < t_move + t_hold) {
        double t = m.time + 0.5 * block, v = test_ramp_velocity(t, V, t_ramp, t_cruise);
        rc = wff_model_prescribe_group(&m, "right", WFF_UX, v, &err) < 0 ||
             wff_model_advance(&m, m.time + block, 10000000, &err);
        CHECK(st, rc == 0, "pull, N %g: %s", N, rc ? err.message : "");
        if (rc)
            break;
        double slip = 0, load;
        for (int i = 0; i < m.clamp.n; i++) {
            int n = m.clamp.node[i];
            slip = fmax(slip, hypot(m.u[D * n], m.u[D * n + 1]));
        }
        out->corner_slip = fmax(out->corner_slip, fabs(m.u[D * corner]));
        wff_model_group_reaction(&m, "right", WFF_UX, &load, &err);
        if (t > t_ramp && t < t_ramp + t_cruise && slip > prev_slip + 0.5 * V * block) {
            out->load_slip += load;
            n_slip++;
        }
        prev_slip = slip;
        out->slip = fmax(out->slip, slip);
    }
    if (n_slip)
        out->load_slip /= n_slip;
    out->ok = rc == 0;
    wff_model_free(&m);
}

static void check_symmetry_line(check_state *st)
{
    const double mu = 0.3, pull = 0.5e-3; /* 1 % of the strip */
    wff_material mat;
    wff_error err;
    wff_biaxial_state s = {.stretch = {1, 1}};
    if (wff_material_load(KEVLAR, &mat, &err) || wff_uniaxial_static(&mat, 0, 1.01, &s, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    const double load = s.resultant[0] * 0.01; /* static load at 1 %, N */
    const double N_stick = 5 * load / (2 * mu), N_slip = 0.25 * load / (2 * mu);
    pull_result a, b;
    pull_run(st, N_stick, mu, pull, &a);
    pull_run(st, N_slip, mu, pull, &b);
    printf("1. clamp node on a symmetry line (u_y = 0), strip pulled %.2f mm (static load "
           "%.2f N): weak pull (2 mu N = 5 x the load): slip %.3g m (corner %.3g m); strong "
           "pull (0.25 x): load while sliding %.3f N = %.3f x 2 mu N\n", 1e3 * pull, load,
           a.slip, a.corner_slip, b.load_slip, b.load_slip / (2 * mu * N_slip));
    CHECK(st, a.ok && b.ok, "both pulls ran");
    CHECK(st, fabs(a.normal_sum - N_stick) <= 1e-12 * N_stick, "force sum %.17g vs %g",
          a.normal_sum, N_stick);
    /* the corner node holds a quarter of the force (half the area of the middle
     * node): without friction along the symmetry line it slides at once */
    CHECK(st, a.slip < 1e-12 && a.corner_slip < 1e-12,
          "weak pull sticks, also on the symmetry line: slip %g m, corner %g m", a.slip,
          a.corner_slip);
    CHECK(st, b.slip > 0.25 * pull, "strong pull slides: %g m", b.slip);
    CHECK(st, b.load_slip > 0 && fabs(b.load_slip / (2 * mu * N_slip) - 1) < 0.15,
          "sliding load %g N vs 2 mu N %g N (the corner's share counts)", b.load_slip,
          2 * mu * N_slip);
}


/* 2. The strip (16 x 2 cells, diagonals all one way, 3.125 mm square cells)
 * with its right half x >= 25 mm made a second physical surface "clamp": a
 * node inside it is a corner of 6 triangles (area h²), a node on its boundary
 * x = 25 mm inside the strip of 3 of them (h²/2), whatever the free fabric
 * beside it adds to its lumped mass. */
static void check_force_sharing(check_state *st)
{
    const int nx = 16, ny = 2;
    const double length = 0.05, width = 0.00625, h = length / nx, N = 10, mu = 0.3;
    test_rect r = {0, length, 0, width, nx, ny, TEST_MESH_TRI, 0, 0, 0};
    wff_mesh mesh;
    wff_model m;
    wff_error err;
    if (test_mesh_rect(&r, &mesh)) {
        CHECK(st, 0, "test mesh");
        return;
    }
    for (int e = 0; e < mesh.n_tris; e++) {
        const int *t = mesh.tri + 3 * e;
        double xc = (mesh.xy[2 * t[0]] + mesh.xy[2 * t[1]] + mesh.xy[2 * t[2]]) / 3;
        if (xc > 0.5 * length)
            mesh.tri_region[e] = 20;
    }
    wff_mesh_group *g = realloc(mesh.groups, sizeof *g * (size_t)(mesh.n_groups + 1));
    if (!g) {
        wff_mesh_free(&mesh);
        CHECK(st, 0, "out of memory");
        return;
    }
    mesh.groups = g;
    g[mesh.n_groups] = (wff_mesh_group){.dim = 2, .tag = 20};
    snprintf(g[mesh.n_groups].name, sizeof g[0].name, "clamp");
    mesh.n_groups++;
    if (wff_model_create_from_mesh(&m, &mesh, KEVLAR, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    int n = wff_model_clamp_friction(&m, "clamp", N, mu, &err);
    CHECK(st, n == (nx / 2 + 1) * (ny + 1), "clamped nodes: %d: %s", n, err.message);
    const int boundary = 1 * (nx + 1) + nx / 2;  /* node (8, 1): x = 25 mm, mid-width */
    const int inside = 1 * (nx + 1) + nx / 2 + 2; /* node (10, 1) */
    double share[2] = {0, 0}, sum = 0;
    for (int i = 0; i < m.clamp.n; i++) {
        sum += m.clamp.normal_force[i];
        if (m.clamp.node[i] == boundary)
            share[0] = m.clamp.normal_force[i];
        if (m.clamp.node[i] == inside)
            share[1] = m.clamp.normal_force[i];
    }
    const double area = 0.5 * length * width; /* the clamp's area */
    printf("2. force shared by the clamp's area: %d nodes, boundary node %.6g N (want %.6g), "
           "inside %.6g N (want %.6g), sum %.12g N\n", n, share[0], N * 0.5 * h * h / area,
           share[1], N * h * h / area, sum);
    CHECK(st, fabs(sum - N) <= 1e-12 * N, "force sum %.17g vs %g", sum, N);
    CHECK_CLOSE(st, share[1], N * h * h / area, 1e-12, 0, "inside node: N h^2 / area");
    CHECK_CLOSE(st, share[0], N * 0.5 * h * h / area, 1e-12, 0,
                "boundary node: half an inside node (its free side does not count)");
    /* pressed only within 40 mm of (0, 0): the sum stays N, nodes beyond get
     * none, those within keep their proportions (one common factor) */
    double *before = malloc(sizeof(double) * (size_t)m.clamp.n);
    if (!before) {
        CHECK(st, 0, "out of memory");
        wff_model_free(&m);
        return;
    }
    memcpy(before, m.clamp.normal_force, sizeof(double) * (size_t)m.clamp.n);
    int rc = wff_model_set_option(&m, "clamp_radius", 0.04, &err);
    CHECK(st, rc == 0, "clamp_radius: %s", rc ? err.message : "");
    double inner = 0, outer = 0, factor = 0, worst = 0;
    int n_inner = 0;
    for (int i = 0; i < m.clamp.n; i++) {
        const double *p = m.mesh.xy + 2 * m.clamp.node[i];
        if (hypot(p[0], p[1]) > 0.04) {
            outer += fabs(m.clamp.normal_force[i]);
            continue;
        }
        inner += m.clamp.normal_force[i];
        n_inner++;
        double f = m.clamp.normal_force[i] / before[i];
        if (factor == 0)
            factor = f;
        worst = fmax(worst, fabs(f / factor - 1));
    }
    free(before);
    CHECK(st, fabs(inner - N) <= 1e-12 * N && outer == 0 && n_inner == 5 * (ny + 1),
          "within the radius (%d nodes): %.17g N, beyond %g N", n_inner, inner, outer);
    CHECK(st, factor > 1 && worst < 1e-12, "one factor %g for the nodes within (spread %g)",
          factor, worst);
    rc = wff_model_set_option(&m, "clamp_radius", 0.001, &err);
    CHECK(st, rc != 0, "a radius with no clamped node inside is an error");
    double after = 0;
    for (int i = 0; i < m.clamp.n; i++)
        after += m.clamp.normal_force[i];
    CHECK(st, fabs(after - N) <= 1e-12 * N, "the failed setting left the force as it was: %g",
          after);
    wff_model_free(&m);
}

/* 3. The strip turned rigidly by 45° about its clamped end (u_x = X (cos θ − 1),
 * u_z = X sin θ: no strain) and pulled along itself: the clamp holds the
 * strip's tension T against u_z with R_z = T sin θ, so it slides when
 * T cos θ = μ (2N + T sin θ), i.e. at an x load 2 μ N / (1 − μ) with
 * clamp_edge_reaction 1, and at 2 μ N without. */
static double tilted_sliding_load(check_state *st, double N, double mu, int edge_reaction)
{
    const double length = 0.05, theta = M_PI / 4, pull = 0.5e-3;
    test_rect r = {0, length, 0, 0.01, 16, 2, TEST_MESH_TRI, 1, 0, 0};
    wff_model m;
    wff_error err;
    if (test_model_rect(&m, &r, KEVLAR, &err)) {
        CHECK(st, 0, "%s", err.message);
        return 0;
    }
    int rc = wff_model_clamp_friction(&m, "left", N, mu, &err) != 3 ||
             wff_model_set_option(&m, "clamp_edge_reaction", edge_reaction, &err);
    CHECK(st, rc == 0, "set-up: %s", err.message);
    for (int n = 0; n < m.n_nodes; n++) {
        double X = m.mesh.xy[2 * n];
        m.u[D * n + WFF_UX] = X * (cos(theta) - 1);
        m.u[D * n + WFF_UZ] = X * sin(theta);
    }
    const double V = 0.75, t_ramp = 0.1e-3, block = 5e-6, t_cruise = pull / V - t_ramp;
    double load = 0, prev_slip = 0;
    int n_slip = 0;
    while (rc == 0 && m.time < t_ramp + t_cruise) {
        double t = m.time + 0.5 * block, v = test_ramp_velocity(t, V, t_ramp, t_cruise);
        rc = wff_model_prescribe_group(&m, "right", WFF_UX, v * cos(theta), &err) < 0 ||
             wff_model_prescribe_group(&m, "right", WFF_UZ, v * sin(theta), &err) < 0 ||
             wff_model_advance(&m, m.time + block, 10000000, &err);
        CHECK(st, rc == 0, "tilted pull: %s", rc ? err.message : "");
        if (rc)
            break;
        double slip = 0, rx;
        for (int i = 0; i < m.clamp.n; i++)
            slip = fmax(slip, fabs(m.u[D * m.clamp.node[i]]));
        wff_model_group_reaction(&m, "right", WFF_UX, &rx, &err);
        if (t > t_ramp && slip > prev_slip + 0.5 * V * cos(theta) * block) {
            load += rx;
            n_slip++;
        }
        prev_slip = slip;
    }
    CHECK(st, n_slip > 10, "the tilted strip slid in the clamp (%d blocks)", n_slip);
    wff_model_free(&m);
    return n_slip ? load / n_slip : 0;
}

static void check_edge_reaction(check_state *st)
{
    const double N = 5, mu = 0.3;
    double with = tilted_sliding_load(st, N, mu, 1), without = tilted_sliding_load(st, N, mu, 0);
    printf("3. strip at 45 deg pulled along itself: x load while sliding %.3f N with "
           "clamp_edge_reaction (2 mu N / (1 - mu) = %.3f N), %.3f N without (2 mu N = %.3f N)\n",
           with, 2 * mu * N / (1 - mu), without, 2 * mu * N);
    CHECK(st, fabs(with / (2 * mu * N / (1 - mu)) - 1) < 0.1,
          "with the reaction: %g N vs 2 mu N / (1 - mu) = %g N", with, 2 * mu * N / (1 - mu));
    CHECK(st, fabs(without / (2 * mu * N) - 1) < 0.1, "without: %g N vs 2 mu N = %g N", without,
          2 * mu * N);
}

/* 4. meshes/ballistic_quarter.geo with frame = 0.1525 (coarse): the clamp is
 * the fabric under the frames (R <= r, |x|, |y| <= frame), the margin the rest
 * of the square, the staple line the frame's outer edge; the clamp's area is
 * frame² − π R² / 4 to the mesh's chordal error. With h_clamp the clamp region
 * is finer (the opening's triangles change only along the arc). */
static double region_area(const wff_mesh *mesh, int tag)
{
    double area = 0;
    for (int e = 0; e < mesh->n_tris; e++) {
        if (mesh->tri_region[e] != tag)
            continue;
        const int *t = mesh->tri + 3 * e;
        const double *a = mesh->xy + 2 * t[0], *b = mesh->xy + 2 * t[1];
        const double *c = mesh->xy + 2 * t[2];
        area += 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
    }
    return area;
}

static void check_frame_mesh(check_state *st)
{
    const double R = 0.127, L = 0.2, frame = 0.1525;
    wff_mesh_options o = {.n_settings = 1, .size_factor = 2};
    snprintf(o.settings[0].name, sizeof o.settings[0].name, "frame");
    o.settings[0].value = frame;
    wff_mesh mesh;
    wff_error err;
    if (wff_mesh_load("meshes/ballistic_quarter.geo", &o, &mesh, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    int clamp = wff_mesh_group_tag(&mesh, 2, "clamp");
    int margin = wff_mesh_group_tag(&mesh, 2, "margin");
    int staples = wff_mesh_group_tag(&mesh, 1, "staples");
    CHECK(st, clamp >= 0 && margin >= 0 && staples >= 0, "groups clamp %d, margin %d, staples %d",
          clamp, margin, staples);
    double a_clamp = region_area(&mesh, clamp), a_margin = region_area(&mesh, margin);
    double want_clamp = frame * frame - M_PI * R * R / 4, want_margin = L * L - frame * frame;
    int n_staple_edges = 0, off_line = 0;
    for (int e = 0; e < mesh.n_edges; e++) {
        if (mesh.edge_label[e] != staples)
            continue;
        n_staple_edges++;
        for (int k = 0; k < 2; k++) {
            const double *p = mesh.xy + 2 * mesh.edge[2 * e + k];
            off_line += fabs(fmax(p[0], p[1]) - frame) > 1e-12;
        }
    }
    printf("4. frame mesh (coarse, frame %.4f m): %d triangles, clamp %.6g m^2 (want %.6g), "
           "margin %.6g m^2 (want %.6g), %d staple edges\n", frame, mesh.n_tris, a_clamp,
           want_clamp, a_margin, want_margin, n_staple_edges);
    /* the opening's polygon is inside the arc (~13 chords): 0.3 % more clamp */
    double a_fabric = region_area(&mesh, wff_mesh_group_tag(&mesh, 2, "fabric"));
    CHECK(st, fabs(a_clamp / want_clamp - 1) < 5e-3, "clamp area %g vs %g", a_clamp, want_clamp);
    CHECK(st, fabs((a_clamp + a_fabric) / (frame * frame) - 1) < 1e-12,
          "opening and clamp fill the frame's square: %.15g vs %.15g", a_clamp + a_fabric,
          frame * frame);
    CHECK(st, fabs(a_margin / want_margin - 1) < 1e-12, "margin area %g vs %g", a_margin,
          want_margin);
    CHECK(st, n_staple_edges >= 4 && off_line == 0, "staple line: %d edges, %d nodes off it",
          n_staple_edges, off_line);
    int n_plain = mesh.n_tris;
    wff_mesh_free(&mesh);
    /* h_clamp: more triangles, only in the clamp region */
    wff_mesh_options h = {.n_settings = 1, .size_factor = 2};
    snprintf(h.settings[0].name, sizeof h.settings[0].name, "h_clamp");
    h.settings[0].value = 0.004;
    wff_mesh fine, plain;
    wff_mesh_options none = {.size_factor = 2};
    if (wff_mesh_load("meshes/ballistic_quarter.geo", &h, &fine, &err) ||
        wff_mesh_load("meshes/ballistic_quarter.geo", &none, &plain, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    int fab_f = wff_mesh_group_tag(&fine, 2, "fabric");
    int fab_p = wff_mesh_group_tag(&plain, 2, "fabric");
    int n_fab[2] = {0, 0}, n_all[2] = {fine.n_tris, plain.n_tris};
    for (int e = 0; e < fine.n_tris; e++)
        n_fab[0] += fine.tri_region[e] == fab_f;
    for (int e = 0; e < plain.n_tris; e++)
        n_fab[1] += plain.tri_region[e] == fab_p;
    printf("   h_clamp 0.004 (x 2): %d triangles (%d in the opening) vs %d (%d); with the frame "
           "%d\n", n_all[0], n_fab[0], n_all[1], n_fab[1], n_plain);
    CHECK(st, n_all[0] - n_fab[0] > 3 * (n_all[1] - n_fab[1]),
          "the clamp region is refined: %d vs %d triangles", n_all[0] - n_fab[0],
          n_all[1] - n_fab[1]);
    CHECK(st, abs(n_fab[0] - n_fab[1]) <= n_fab[1] / 10, "the opening hardly: %d vs %d",
          n_fab[0], n_fab[1]);
    wff_mesh_free(&fine);
    wff_mesh_free(&plain);
}

int main(void)
{
    check_state st = {0, 0};
    check_symmetry_line(&st);
    check_force_sharing(&st);
    check_edge_reaction(&st);
    check_frame_mesh(&st);
    return check_summary(&st, "test_clamp");
}

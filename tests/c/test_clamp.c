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
 *      (clamp_edge_reaction 1): the friction limit grows by mu |R_z|.
 * Each check can fail: it compares against a force or a slip computed by hand. */
#include "check.h"
#include "test_meshes.h"
#include "test_ramp.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"

#include <math.h>
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

int main(void)
{
    check_state st = {0, 0};
    check_symmetry_line(&st);
    return check_summary(&st, "test_clamp");
}

/* Bad input to the solver's C API is refused with a message naming the
 * value (docs/limits.md, "Errors"): a projectile placed inside the fabric
 * (naming the node and the depth), a negative mass, speed or radius, solver
 * settings out of range, an unknown setting, a group the mesh lacks; the
 * energy split per mechanism adds up to the stored energy; and a state gone
 * bad (NaN, a collapsed element, a projectile through the fabric) stops the
 * run with the time, the step, the element and the quantity. */
#include "check.h"
#include "test_meshes.h"
#include "wovenff/solver.h"

#include <math.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"

static void expect(check_state *st, int rc, const wff_error *err, const char *want,
                   const char *what)
{
    CHECK(st, rc != 0, "%s: accepted", what);
    CHECK(st, strstr(err->message, want) != NULL, "%s: message '%s' lacks '%s'", what,
          err->message, want);
    printf("  %-22s %s\n", what, err->message);
}

int main(void)
{
    check_state st = {0, 0};
    test_rect r = {-0.02, 0.02, -0.02, 0.02, 8, 8, TEST_MESH_TRI, 1, 0, 0};
    wff_model m;
    wff_error err;
    if (test_model_rect(&m, &r, KEVLAR, &err)) {
        CHECK(&st, 0, "%s", err.message);
        return check_summary(&st, "test_solver_input");
    }
    int rc = wff_model_place_projectile(&m, 0, &err);
    expect(&st, rc, &err, "no projectile to place", "place before set");
    rc = wff_model_set_projectile(&m, 6.35e-3, -0.01, 20, 0.3, &err);
    expect(&st, rc, &err, "projectile mass -0.01 kg must be > 0", "negative mass");
    rc = wff_model_set_projectile(&m, 6.35e-3, 0.01, -1, 0.3, &err);
    expect(&st, rc, &err, "projectile velocity -1 m/s must be >= 0", "negative speed");
    rc = wff_model_set_projectile(&m, 0, 0.01, 20, 0.3, &err);
    expect(&st, rc, &err, "projectile radius 0 m must be > 0", "zero radius");
    rc = wff_model_set_projectile(&m, 6.35e-3, 0.01, NAN, 0.3, &err);
    expect(&st, rc, &err, "projectile velocity nan m/s", "NaN speed");
    rc = wff_model_set_projectile(&m, 6.35e-3, 0.01, 20, 0.3, &err);
    CHECK(&st, rc == 0, "%s", err.message);
    rc = wff_model_place_projectile(&m, 1e-3, &err);
    expect(&st, rc, &err, "projectile starts inside the fabric: node ", "tip 1 mm inside");
    CHECK(&st, strstr(err.message, "is 0.001 m inside the projectile") != NULL,
          "names the depth: %s", err.message);
    CHECK(&st, m.projectile.tip == 0, "a refused placement leaves the tip: %g", m.projectile.tip);
    /* a stand-off in front of the fabric is fine */
    rc = wff_model_place_projectile(&m, -2e-3, &err);
    CHECK(&st, rc == 0 && m.projectile.tip == -2e-3, "a stand-off of 2 mm: %s", err.message);
    rc = wff_model_set_option(&m, "dtfactor", 2.5, &err);
    expect(&st, rc, &err, "dtfactor = 2.5: must be in (0, 2]", "dtfactor 2.5");
    rc = wff_model_set_option(&m, "dtfactor", 0, &err);
    expect(&st, rc, &err, "dtfactor = 0: must be in (0, 2]", "dtfactor 0");
    rc = wff_model_set_option(&m, "dtinterval", 0.5, &err);
    expect(&st, rc, &err, "dtinterval = 0.5", "dtinterval 0.5");
    rc = wff_model_set_option(&m, "threadz", 1, &err);
    expect(&st, rc, &err, "unknown solver setting 'threadz'", "unknown setting");
    rc = wff_model_fix_group(&m, "clamp", 0, &err) < 0;
    expect(&st, rc, &err, "no physical group named 'clamp' in the mesh (groups: left, right, "
           "bottom, top, fabric)", "missing group");

    /* energy split: sums to the stored energy (after a few steps) */
    rc = wff_model_set_option(&m, "symmetry", 4, &err);
    for (int c = 0; c < 3 && rc == 0; c++)
        rc = wff_model_fix_group(&m, "left", c, &err) < 0;
    rc = rc || wff_model_place_projectile(&m, 0, &err) || wff_model_advance(&m, 1, 100, &err);
    CHECK(&st, rc == 0, "%s", err.message);
    double mech[WFF_MECH_MAX], sum = 0;
    int n = wff_model_energy_split(&m, mech);
    wff_energies e;
    wff_model_energies(&m, &e);
    for (int k = 0; k < n; k++)
        sum += mech[k];
    printf("  energy split: %d mechanisms,", n);
    for (int k = 0; k < n; k++)
        printf(" %s %.4e", m.mat.cell->mech_names[k], mech[k]);
    printf(" J; sum %.10e, stored %.10e J\n", sum, e.internal);
    CHECK(&st, n == m.mat.cell->n_mech && n > 0, "mechanisms: %d", n);
    CHECK(&st, fabs(sum - e.internal) <= 1e-9 * fabs(e.internal) && e.internal > 0,
          "split sums to the stored energy (x symmetry): %.12g vs %.12g", sum, e.internal);
    wff_model_free(&m);

    /* a state gone bad stops the run naming time, step, element and quantity */
    static const struct { const char *what, *want; } bad[] = {
        {"NaN displacement", "NaN or infinite displacement, amplitude, stress or energy"},
        {"fabric crushed", "degenerate deformation (yarns collapsed or parallel: inverted "
                               "element)"},
        {"through the fabric", "the projectile has passed through the fabric"},
    };
    for (int k = 0; k < 3; k++) {
        if (test_model_rect(&m, &r, KEVLAR, &err)) {
            CHECK(&st, 0, "%s", err.message);
            break;
        }
        rc = wff_model_set_projectile(&m, 6.35e-3, 0.01, 20, 0, &err) ||
             wff_model_advance(&m, 1, 10, &err);
        CHECK(&st, rc == 0, "%s", err.message);
        int centre = wff_model_nearest_node(&m, 0, 0);
        double *u = m.u + WFF_DOFS_PER_NODE * centre;
        if (k == 0)
            u[2] = NAN;
        else if (k == 1) /* the fabric crushed onto the line y = z = 0, at rest: the
                          * weft yarns have zero length */
            for (int n = 0; n < m.n_nodes; n++) {
                m.u[WFF_DOFS_PER_NODE * n + 1] = -m.mesh.xy[2 * n + 1];
                m.u[WFF_DOFS_PER_NODE * n + 2] = 0;
                for (int c = 0; c < 3; c++)
                    m.v[WFF_DOFS_PER_NODE * n + c] = 0;
            }
        else /* 4 mm behind the nose tip, under its axis */
            u[2] = m.projectile.tip - 4e-3;
        rc = wff_model_advance(&m, 1, 10, &err);
        expect(&st, rc, &err, bad[k].want, bad[k].what);
        CHECK(&st, strstr(err.message, "t = ") && strstr(err.message, "(step 1"),
              "%s: names the time and step: %s", bad[k].what, err.message);
        if (k < 2)
            CHECK(&st, strstr(err.message, "triangle ") && strstr(err.message, "(nodes "),
                  "%s: names the element: %s", bad[k].what, err.message);
        wff_model_free(&m);
    }
    return check_summary(&st, "test_solver_input");
}

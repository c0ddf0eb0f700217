/* Contact with held nodes (docs/model.md §14, issue 11 item 7): a projectile
 * meets fabric nodes whose DOFs are fixed (clamped) exactly as it meets free
 * ones: it is stopped, the supports take the contact force (their reactions
 * sum to minus the force on the projectile), the projectile's lost kinetic
 * energy is dissipated by the inelastic contact and the balance closes; the
 * impulse the projectile received (impulse_total) equals its momentum change.
 * Meshes built in code (tests/c/lib/test_meshes.c). */
#include "check.h"
#include "test_meshes.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdio.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define NOSE_RADIUS 6.35e-3

/* A square fixed in u_x, u_y, u_z everywhere (group "fabric"), or only along
 * its edges with the projectile aimed at an edge node (fabric_held = 0). */
static void held_case(check_state *st, int fabric_held, const char *what)
{
    test_rect r = {-0.02, 0.02, -0.02, 0.02, 8, 8, TEST_MESH_TRI, 1, 0, 0};
    wff_model m;
    wff_error err;
    if (test_model_rect(&m, &r, KEVLAR, &err)) {
        CHECK(st, 0, "%s: %s", what, err.message);
        return;
    }
    const char *groups[] = {"fabric", "left", "right", "bottom", "top"};
    int first = fabric_held ? 0 : 1, last = fabric_held ? 0 : 4;
    for (int g = first; g <= last; g++)
        for (int c = WFF_UX; c <= WFF_UZ; c++)
            CHECK(st, wff_model_fix_group(&m, groups[g], c, &err) > 0, "%s: fix: %s", what,
                  err.message);
    const double M = 0.002, V = 10;
    CHECK(st, wff_model_set_projectile(&m, NOSE_RADIUS, M, V, 0, &err) == 0, "%s: %s", what,
          err.message);
    if (!fabric_held) { /* aim at the left edge's middle node (-0.02, 0): held */
        m.projectile.axis[0] = -0.02;
        m.projectile.axis[1] = 0;
    }
    int rc = wff_model_advance(&m, 2e-5, 1000000, &err);
    CHECK(st, rc == 0, "%s: advance: %s", what, rc ? err.message : "");
    if (rc == 0) {
        /* stopped at the first contact: less than 1e-9 of its speed is left */
        CHECK(st, fabs(m.projectile.velocity) < 1e-9 * V,
              "%s: the projectile is stopped by held nodes (%g m/s left)", what,
              m.projectile.velocity);
        CHECK(st, m.projectile.tip < 1e-9, "%s: the tip stays at the fabric (z = %g m)", what,
              m.projectile.tip);
        double momentum_change = M * (V - m.projectile.velocity);
        CHECK(st, fabs(m.projectile.impulse_total - momentum_change) <= 1e-12 * M * V,
              "%s: impulse %.12g N s = momentum change %.12g", what,
              m.projectile.impulse_total, momentum_change);
        wff_energies e;
        wff_model_energies(&m, &e);
        CHECK(st, fabs(e.dissipated_friction - 0.5 * M * V * V) < 1e-9 * 0.5 * M * V * V,
              "%s: the contact dissipates the impact energy: %g of %g J", what,
              e.dissipated_friction, 0.5 * M * V * V);
        CHECK(st, fabs(e.error) < 1e-9, "%s: energy balance closes: error %g", what, e.error);
        printf("  %s: projectile %.3g m/s after %ld steps, impulse %.6g N s, dissipated %.6g J,"
               " energy error %.2e\n", what, m.projectile.velocity, m.step,
               m.projectile.impulse_total, e.dissipated_friction, e.error);
    }
    /* the supports' reaction is the contact force at the step of the impact */
    wff_model m2;
    if (test_model_rect(&m2, &r, KEVLAR, &err) == 0) {
        for (int g = first; g <= last; g++)
            for (int c = WFF_UX; c <= WFF_UZ; c++)
                wff_model_fix_group(&m2, groups[g], c, &err);
        wff_model_set_projectile(&m2, NOSE_RADIUS, M, V, 0, &err);
        if (!fabric_held) {
            m2.projectile.axis[0] = -0.02;
            m2.projectile.axis[1] = 0;
        }
        rc = wff_model_advance(&m2, 0, 1, &err); /* the start: first half step with contact */
        CHECK(st, rc == 0, "%s: start: %s", what, rc ? err.message : "");
        double rz = 0;
        const char *sum_group = fabric_held ? "fabric" : "left";
        CHECK(st, wff_model_group_reaction(&m2, sum_group, WFF_UZ, &rz, &err) > 0, "%s: %s",
              what, err.message);
        CHECK(st, m2.projectile.force > 0 && fabs(rz + m2.projectile.force) <=
                  1e-9 * m2.projectile.force,
              "%s: reactions %.6g N = -(contact force %.6g N)", what, rz,
              m2.projectile.force);
        wff_model_free(&m2);
    }
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    held_case(&st, 1, "all nodes held");
    held_case(&st, 0, "clamped edge node");
    return check_summary(&st, "test_contact_fixed");
}

/* The physical invariants (plugin/invariants.c, wff_model_invariants):
 *   1. a 2-ply pack struck at 60 m/s holds them all, step after step (every
 *      dissipation >= 0, the projectile no faster than the energy given);
 *   2. each one broken by hand is named with its value: a negative shear
 *      dissipation, the contacts' and friction's sum negative (a part's
 *      included; one account negative with the sum positive passes), a projectile
 *      given more kinetic energy than the run had; the message says nothing
 *      when they hold. */
#include "check.h"
#include "plies.h"
#include "solver_internal.h"
#include "test_meshes.h"
#include "wovenff/pack.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"

/* The pack tests' struck square (test_meshes.h), 2 plies 0.3 mm apart. */
static int struck_pack(check_state *st, wff_model *m)
{
    wff_error err;
    if (test_model_struck(m, 12, KEVLAR, 2, 3e-4, &err)) {
        CHECK(st, 0, "model: %s", err.message);
        return -1;
    }
    return 0;
}

static void holds_in_a_run(check_state *st)
{
    wff_model m;
    if (struck_pack(st, &m))
        return;
    wff_error err;
    char text[512];
    int worst = 0, rc = 0;
    for (int k = 0; k < 40 && rc == 0; k++) { /* 40 x 20 steps: contact and ply contact */
        rc = wff_model_advance(&m, 1e9, 20, &err);
        worst = fmax(worst, wff_model_invariants(&m, text, sizeof text));
    }
    CHECK(st, rc == 0, "advance: %s", rc ? err.message : "");
    double ply = NAN;
    wff_model_pack_value(&m, "ply_contact_dissipated", &ply, &err);
    printf("  2 plies struck at 60 m/s, 800 steps: invariants violated %d (ply contact "
           "dissipated %.4g J, the ply contact's contacts %s)\n", worst, ply,
           ply > 0 ? "made" : "none");
    CHECK(st, worst == 0, "a run breaks an invariant: %s", text);
    CHECK(st, ply > 0, "the ply contact never acted (dissipated %g J): the check is empty", ply);
    CHECK(st, text[0] == 0, "message when the invariants hold: '%s'", text);

    /* 2. each broken by hand, one at a time */
    char name[64];
    double saved = m.dissipated_shear;
    m.dissipated_shear = -1e-3;
    int n = wff_model_invariants(&m, text, sizeof text);
    CHECK(st, n == 1 && strstr(text, "dissipated_shear, -0.001 J, is negative"),
          "negative shear dissipation: %d, '%s'", n, text);
    m.dissipated_shear = saved;

    saved = m.pack->dissipated;
    m.pack->dissipated = -0.25 / m.symmetry_factor;
    n = wff_model_invariants(&m, text, sizeof text);
    snprintf(name, sizeof name, "ply_contact_dissipated -0.25 J");
    CHECK(st, n == 1 && strstr(text, name), "negative ply contact dissipation: %d, '%s'", n, text);
    printf("  named: '%s'\n", text);
    /* the projectile's contact negative, the ply contact's more positive: the
     * accounts' split of a node both act on, not energy put in */
    const double friction = m.dissipated_friction;
    m.dissipated_friction = -1e-3 / m.symmetry_factor;
    m.pack->dissipated = 2e-3 / m.symmetry_factor;
    n = wff_model_invariants(&m, text, sizeof text);
    CHECK(st, n == 0, "the contacts' sum positive, the projectile's negative: %d, '%s'", n, text);
    m.pack->dissipated = -2e-3 / m.symmetry_factor;
    n = wff_model_invariants(&m, text, sizeof text);
    CHECK(st, n == 1 && strstr(text, "-0.003 J, is negative"), "the contacts' sum negative: %d, '%s'",
          n, text);
    m.dissipated_friction = friction;
    m.pack->dissipated = saved;

    saved = m.projectile.velocity;
    wff_energies e;
    wff_model_energies(&m, &e);
    /* a projectile at twice the striking speed holds 4x the impact energy */
    m.projectile.velocity = 120;
    n = wff_model_invariants(&m, text, sizeof text);
    CHECK(st, n == 1 && strstr(text, "the projectile's kinetic energy"),
          "projectile faster than it struck: %d, '%s'", n, text);
    printf("  named: '%s'\n", text);
    m.projectile.velocity = saved;
    n = wff_model_invariants(&m, text, sizeof text);
    CHECK(st, n == 0, "restored: %d, '%s'", n, text);
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    holds_in_a_run(&st);
    return check_summary(&st, "test_invariants");
}

/* The ply contact's column solve, the nose friction's step sized for the
 * stack stuck behind its node (plugin/ply_column.c, stack_inverse_mass)
 * against the plain step sized for the node alone (pack->nose_step_alone),
 * on a 4-ply impact with friction (the stack held on the nose):
 *   1. to 0.05 ms each way: fewer sweeps in all, no more steps ending at the
 *      cap;
 *   2. one step from the same state, at the plain run's four slowest steps
 *      short of the cap: both solves end at the same velocities, every node's
 *      and the projectile's (times the step: a gap), within what the plain
 *      one's stopping rule leaves (a sweep moving no gap by more than
 *      SWEEP_TOLERANCE h, its change shrinking by (n − 1)/n a sweep: at most
 *      (n − 1) SWEEP_TOLERANCE h left, the fast one's less; both together
 *      under n SWEEP_TOLERANCE h), the fast one in fewer sweeps (the plain
 *      one not stopped by the cap, or it would be no reference). */
#include "check.h"
#include "plies.h"
#include "ply_solve.h"
#include "test_meshes.h"
#include "wovenff/pack.h"
#include "wovenff/renumber.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdio.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define PLIES 4
#define THICKNESS 0.21e-3

/* A 4-ply square pack, edges held, struck at 150 m/s by a nose of radius
 * 8 mm (as test_ply_contact's 8-ply impact); the nose step `alone` or not. */
static int pack(check_state *st, wff_model *m, int alone)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, 10, 10, TEST_MESH_TRI, 1, 0.2, 11};
    wff_mesh mesh;
    wff_error err;
    int rc = test_mesh_rect(&r, &mesh) || wff_model_create_ordered(m, &mesh, KEVLAR, 1, &err);
    if (rc) {
        CHECK(st, 0, "model: %s", err.message);
        return -1;
    }
    rc = wff_model_set_plies(m, PLIES, THICKNESS, &err) ||
         wff_model_set_option(m, "ply_thickness", THICKNESS, &err);
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int g = 0; g < 4 && rc == 0; g++)
        for (int c = WFF_UX; c <= WFF_UZ && rc == 0; c++)
            rc = wff_model_fix_group(m, edges[g], c, &err) < 0;
    if (rc == 0)
        rc = wff_model_set_projectile(m, 0.008, 0.004, 150, 0.2, &err);
    CHECK(st, rc == 0, "pack: %s", err.message);
    if (rc) {
        wff_model_free(m);
        return -1;
    }
    m->pack->nose_step_alone = alone;
    return 0;
}

/* 2. Both models `steps` plain steps on, then one step each way (step
 * steps + 1). */
static void one_step(check_state *st, long steps, int *fewer, int *compared)
{
    wff_model a, b;
    wff_error err;
    if (pack(st, &a, 1))
        return;
    if (pack(st, &b, 1)) {
        wff_model_free(&a);
        return;
    }
    int rc = 0;
    for (long k = 0; k < steps && rc == 0; k++) {
        double dt;
        rc = wff_model_step(&a, &dt, &err) || wff_model_step(&b, &dt, &err);
    }
    b.pack->nose_step_alone = 0;
    double dt_a = 0, dt_b = 0;
    if (rc == 0)
        rc = wff_model_step(&a, &dt_a, &err) || wff_model_step(&b, &dt_b, &err);
    CHECK(st, rc == 0, "step %ld: %s", steps, err.message);
    if (rc == 0) {
        const double h = THICKNESS; /* (the contact distance: gap = t) */
        double apart = fabs(a.projectile.velocity - b.projectile.velocity) * dt_a;
        for (int n = 0; n < a.n_nodes; n++)
            for (int c = 0; c < 3; c++)
                apart = fmax(apart, fabs(a.v[D * n + c] - b.v[D * n + c]) * dt_a);
        const int plain = a.pack->sweeps, fast = b.pack->sweeps;
        printf("  step %ld: %d sweeps plain, %d with the stack's step; the solutions %.3g h apart "
               "(bound %g h)\n", steps + 1, plain, fast, apart / h, PLIES * SWEEP_TOLERANCE);
        CHECK(st, dt_a == dt_b, "step %ld: the steps differ (%g, %g s)", steps + 1, dt_a, dt_b);
        CHECK(st, plain < MAX_SWEEPS, "step %ld: the plain solve stopped at the cap (%d sweeps): "
              "no reference", steps + 1, plain);
        CHECK(st, apart <= PLIES * SWEEP_TOLERANCE * h,
              "step %ld: the solutions %.3g h apart (a node's or the projectile's velocity "
              "change over the step), above %g h", steps + 1, apart / h, PLIES * SWEEP_TOLERANCE);
        *fewer += fast < plain;
        *compared += 1;
    }
    wff_model_free(&a);
    wff_model_free(&b);
}

/* 1. The first 0.05 ms each way: the sweeps in all, the steps at the cap;
 * each step's sweeps into `each` (up to `most` steps). */
static void run(check_state *st, int alone, long *sweeps, long *capped, long *steps, int *each, long most)
{
    wff_model m;
    wff_error err;
    *sweeps = *capped = *steps = 0;
    if (pack(st, &m, alone))
        return;
    while (m.time < 0.05e-3) {
        double dt;
        if (wff_model_step(&m, &dt, &err)) {
            CHECK(st, 0, "run: %s", err.message);
            break;
        }
        if (*steps < most)
            each[*steps] = m.pack->sweeps;
        *sweeps += m.pack->sweeps;
        *capped += m.pack->sweeps >= MAX_SWEEPS;
        *steps += 1;
    }
    wff_model_free(&m);
}

#define MOST_STEPS 4096
#define COMPARED 4

int main(void)
{
    check_state st = {0, 0};
    static int each[MOST_STEPS], ignored[MOST_STEPS];
    long sweeps[2], capped[2], steps[2];
    run(&st, 1, &sweeps[0], &capped[0], &steps[0], each, MOST_STEPS);
    run(&st, 0, &sweeps[1], &capped[1], &steps[1], ignored, MOST_STEPS);
    printf("  to 0.05 ms: plain %ld sweeps in %ld steps (%.3g a step), %ld at the cap of %d; the "
           "stack's step %ld in %ld (%.3g), %ld at the cap\n", sweeps[0], steps[0],
           (double)sweeps[0] / fmax(steps[0], 1), capped[0], MAX_SWEEPS, sweeps[1], steps[1],
           (double)sweeps[1] / fmax(steps[1], 1), capped[1]);
    CHECK(&st, sweeps[1] < sweeps[0] && capped[1] <= capped[0],
          "the stack's step: %ld sweeps, %ld at the cap (plain: %ld, %ld)", sweeps[1], capped[1],
          sweeps[0], capped[0]);
    /* 2. at the plain run's slowest steps short of the cap (where the stack's
     * step matters) */
    int fewer = 0, compared = 0;
    for (int k = 0; k < COMPARED; k++) {
        long slowest = -1;
        for (long s = 0; s < steps[0] && s < MOST_STEPS; s++)
            if (each[s] < MAX_SWEEPS && (slowest < 0 || each[s] > each[slowest]))
                slowest = s;
        if (slowest < 0)
            break;
        each[slowest] = MAX_SWEEPS; /* (taken) */
        one_step(&st, slowest, &fewer, &compared);
    }
    CHECK(&st, compared == COMPARED && fewer == compared,
          "the stack's step took fewer sweeps at %d of %d steps", fewer, compared);
    return check_summary(&st, "test_ply_sweeps");
}

/* Threads through a whole step: the ballistic quarter model with a friction
 * clamp and the projectile's contact with friction, big enough that every
 * threaded pass (force pass and its reduction, position and velocity
 * updates, clamp friction, kinetic energies, contact candidates, stable
 * step) splits into parts. Checks:
 *   1. 2 threads repeat bit for bit (u, v, every energy) over the run;
 *   2. 1 and 2 threads agree to round-off (1e-12 relative on u, v and the
 *      energies) over 60 steps (the force sums' order differs between the
 *      counts; the round-off grows with the steps through the contact's and
 *      clamp's stick/slip: v 5.7e-13 at 60 steps, 1.2e-12 at 100 here);
 *   3. the energies of one state are the same bits with 1 and 2 threads
 *      (the passes' parts are fixed by the item count, not the threads);
 *   4. the default thread count ("threads" = 0: the cores this process may
 *      use, or OMP_NUM_THREADS) resolves to a count >= 1 that the model
 *      reports.
 * OpenMP may be limited to 1 thread here (OMP_NUM_THREADS=1): the model asks
 * for its team explicitly; the test says when 2 threads could not run. */
#include "check.h"
#include "wovenff/options.h"
#include "wovenff/solver.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#define STEPS 60

typedef struct run {
    double *u, *v;
    wff_energies e;
    double tip, speed;
    int n_dofs, clamped, candidates;
} run;

static int make_model(wff_model *m, wff_error *err)
{
    wff_mesh_options opt;
    const double F_pre[4] = {1.003963, 0, 0, 1.013476}, dA0[2] = {-9.311e-6, -23.748e-6};
    if (wff_mesh_options_parse("size_factor=0.55", &opt, err) ||
        wff_model_create(m, "meshes/ballistic_quarter.geo", &opt,
                         "freefem_scripts/materials/kevlar_s706.txt", err))
        return -1;
    if (wff_model_set_preload(m, F_pre, dA0, err) || wff_model_fix_group(m, "sym_x", 0, err) < 0 ||
        wff_model_fix_group(m, "sym_y", 1, err) < 0 ||
        wff_model_clamp_friction(m, "clamp", 1000, 0.5, err) < 0 ||
        wff_model_set_projectile(m, 6.35e-3, 0.026, 60, 0.3, err))
        return -1;
    m->el.team_min_tris = 0; /* a team on this mesh too: the threaded passes are under test */
    return 0;
}

/* STEPS steps with `threads` (0: the default count); the state at the end. */
static int run_steps(check_state *st, int threads, run *out)
{
    wff_model m;
    wff_error err;
    if (make_model(&m, &err) || wff_model_set_option(&m, "threads", threads, &err) ||
        wff_model_advance(&m, 1e9, STEPS, &err)) {
        CHECK(st, 0, "%d threads: %s", threads, err.message);
        return -1;
    }
    out->n_dofs = m.n_dofs;
    out->u = malloc(sizeof(double) * (size_t)m.n_dofs);
    out->v = malloc(sizeof(double) * (size_t)m.n_dofs);
    memcpy(out->u, m.u, sizeof(double) * (size_t)m.n_dofs);
    memcpy(out->v, m.v, sizeof(double) * (size_t)m.n_dofs);
    wff_model_energies(&m, &out->e);
    out->tip = m.projectile.tip;
    out->speed = m.projectile.velocity;
    out->clamped = m.clamp.n;
    out->candidates = m.projectile.n_candidates;
    printf("  %d threads (asked %d): %d nodes, %d elements, %d clamped, %d contact candidates, "
           "energy error %.3e, friction %.6e J\n", m.el.n_threads, threads, m.n_nodes,
           m.el.n_tris, m.clamp.n, m.projectile.n_candidates, out->e.error,
           out->e.dissipated_friction);
    wff_model_free(&m);
    return 0;
}

static double max_rel(const double *a, const double *b, int n)
{
    double scale = 0, diff = 0;
    for (int i = 0; i < n; i++) {
        scale = fmax(scale, fabs(b[i]));
        diff = fmax(diff, fabs(a[i] - b[i]));
    }
    return scale > 0 ? diff / scale : diff;
}

static const double *energy_fields(const wff_energies *e, double out[9])
{
    double f[9] = {e->kinetic_inplane, e->kinetic_transverse, e->kinetic_amplitude,
                   e->kinetic_projectile, e->internal, e->dissipated_shear,
                   e->dissipated_friction, e->external_work, e->reference};
    memcpy(out, f, sizeof f);
    return out;
}

static void free_run(run *r)
{
    free(r->u);
    free(r->v);
}

int main(void)
{
    check_state st = {0, 0};
    int team = 0;
#pragma omp parallel num_threads(2)
    {
#pragma omp single
        team = omp_get_num_threads();
    }
    printf("OpenMP: max threads %d, processors %d, a team of 2 asked gets %d\n",
           omp_get_max_threads(), omp_get_num_procs(), team);
    run one, two, again, dflt;
    if (run_steps(&st, 1, &one))
        return check_summary(&st, "test_threads");
    /* big enough that the passes over DOFs take a team (TEAM_MIN_DOFS, step_threads.c) */
    CHECK(&st, one.n_dofs >= 16384, "%d DOFs: too few for the threaded passes", one.n_dofs);
    CHECK(&st, one.clamped >= 256 && one.candidates > 0 && one.e.dissipated_friction > 0,
          "the run exercises the clamp's parts and the contact: %d clamped, %d candidates",
          one.clamped, one.candidates);
    if (team < 2) {
        printf("  OpenMP gives 1 thread here: the 2-thread checks are skipped\n");
        free_run(&one);
        return check_summary(&st, "test_threads");
    }
    if (run_steps(&st, 2, &two) || run_steps(&st, 2, &again))
        return check_summary(&st, "test_threads");
    /* 1. bit for bit */
    double et[9], ea[9], e1[9];
    energy_fields(&two.e, et);
    energy_fields(&again.e, ea);
    energy_fields(&one.e, e1);
    CHECK(&st, memcmp(two.u, again.u, sizeof(double) * (size_t)two.n_dofs) == 0,
          "2 threads: u repeats bit for bit");
    CHECK(&st, memcmp(two.v, again.v, sizeof(double) * (size_t)two.n_dofs) == 0,
          "2 threads: v repeats bit for bit");
    CHECK(&st, memcmp(et, ea, sizeof et) == 0 && two.e.error == again.e.error,
          "2 threads: every energy repeats bit for bit");
    CHECK(&st, two.tip == again.tip && two.speed == again.speed,
          "2 threads: the projectile repeats bit for bit");
    /* 2. 1 vs 2 threads bit for bit: every node sums its elements' slots in element
     * order whatever thread computed them, the energies go block by block in order
     * (before that, the threads' force buffers summed in thread order: u 2.8e-15,
     * v 8.7e-14 of the largest apart) */
    double du = max_rel(two.u, one.u, one.n_dofs), dv = max_rel(two.v, one.v, one.n_dofs);
    printf("  1 vs 2 threads: u %.2e, v %.2e (relative to the largest)\n", du, dv);
    CHECK(&st, memcmp(two.u, one.u, sizeof(double) * (size_t)one.n_dofs) == 0,
          "u: 1 vs 2 threads differ by %.3g", du);
    CHECK(&st, memcmp(two.v, one.v, sizeof(double) * (size_t)one.n_dofs) == 0,
          "v: 1 vs 2 threads differ by %.3g", dv);
    CHECK(&st, memcmp(et, e1, sizeof et) == 0 && two.e.error == one.e.error,
          "every energy: 1 vs 2 threads bit for bit");
    CHECK(&st, two.tip == one.tip && two.speed == one.speed,
          "the projectile: 1 vs 2 threads bit for bit (%.17g, %.17g m/s)", two.speed, one.speed);
    /* 3. the default count */
    wff_model m;
    wff_error err;
    if (make_model(&m, &err) == 0) {
        int rc = wff_model_set_option(&m, "threads", 0, &err);
        CHECK(&st, rc == 0 && m.el.n_threads >= 1 && m.el.n_threads == wff_default_threads(),
              "threads = 0: the default count %d (model %d): %s", wff_default_threads(),
              m.el.n_threads, rc ? err.message : "");
        printf("  threads = 0: %d threads\n", m.el.n_threads);
        /* the kinetic-energy pass sums by parts fixed by the node count: the same
         * bits with 1 and 2 threads on one state */
        wff_energies k2, k1;
        if (wff_model_set_option(&m, "threads", 2, &err) == 0 &&
            wff_model_advance(&m, 1e9, 10, &err) == 0) {
            wff_model_energies(&m, &k2);
            wff_model_set_option(&m, "threads", 1, &err);
            wff_model_energies(&m, &k1);
            CHECK(&st, memcmp(&k1, &k2, sizeof k1) == 0,
                  "energies of one state: 1 and 2 threads give the same bits");
        } else
            CHECK(&st, 0, "%s", err.message);
        wff_model_free(&m);
    }
    if (run_steps(&st, 0, &dflt) == 0) {
        if (wff_default_threads() == 2)
            CHECK(&st, memcmp(dflt.u, two.u, sizeof(double) * (size_t)two.n_dofs) == 0,
                  "the default (2 here) is the 2-thread run, bit for bit");
        free_run(&dflt);
    }
    free_run(&one);
    free_run(&two);
    free_run(&again);
    return check_summary(&st, "test_threads");
}

/* The kernel variants (include/wovenff/kernel.h) give the same answers:
 *   - requests: auto picks the widest this CPU runs, names select, an unknown
 *     name or one this CPU cannot run is a clear error, also through the
 *     environment variable WOVENFF_KERNEL at model creation;
 *   - each variant this CPU runs has its own build of every cell (its own
 *     code), which passes the whole cell suite (fast paths = evaluate());
 *   - on a model, the blocked fast path = the plain path under each variant,
 *     with dynamic and with static amplitudes;
 *   - the ballistic quarter model, 150 steps with the projectile in contact
 *     under each variant: forces, energies, projectile and stable step equal
 *     the baseline's to round-off. */
#include "cell_suite.h"
#include "test_meshes.h"
#include "wovenff/kernel.h"
#include "wovenff/material.h"
#include "wovenff/options.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

static int contains(const char *s, const char *part) { return strstr(s, part) != NULL; }

static void check_requests(check_state *st)
{
    const wff_kernel *k, *widest = NULL;
    wff_error err;
    CHECK(st, wff_kernel_count() == 3, "three variants (got %d)", wff_kernel_count());
    CHECK(st, strcmp(wff_kernel_name(wff_kernel_at(0)), "baseline") == 0, "baseline first");
    CHECK(st, wff_kernel_at(wff_kernel_count()) == NULL && wff_kernel_at(-1) == NULL,
          "no variant outside the table");
    for (int i = 0; i < wff_kernel_count(); i++) {
        const wff_kernel *v = wff_kernel_at(i);
        if (wff_kernel_runs_here(v))
            widest = v;
        int rc = wff_kernel_select(wff_kernel_name(v), &k, &err);
        if (wff_kernel_runs_here(v))
            CHECK(st, rc == 0 && k == v, "'%s' selects itself", wff_kernel_name(v));
        else /* e.g. avx512 on an AVX2 machine */
            CHECK(st, rc == -1 && contains(err.message, wff_kernel_isa(v)) &&
                          contains(err.message, "lacks"),
                  "'%s' on a CPU without it: %s", wff_kernel_name(v), err.message);
        printf("  kernel %-8s %-22s %s\n", wff_kernel_name(v), wff_kernel_isa(v),
               wff_kernel_runs_here(v) ? "runs here" : "not on this CPU");
    }
    CHECK(st, widest != NULL, "this CPU runs the baseline");
    CHECK(st, wff_kernel_select("auto", &k, &err) == 0 && k == widest, "auto = the widest");
    CHECK(st, wff_kernel_select(NULL, &k, &err) == 0 && k == widest, "NULL = auto");
    CHECK(st, wff_kernel_select("", &k, &err) == 0 && k == widest, "\"\" = auto");
    CHECK(st, wff_kernel_select("avx3", &k, &err) == -1 && k == NULL &&
                  contains(err.message, "'avx3'") && contains(err.message, "unknown") &&
                  contains(err.message, "auto baseline avx2 avx512"),
          "unknown name: %s", err.message);

    /* at model creation, from the environment */
    test_rect r = {0, 0.02, 0, 0.02, 4, 4, TEST_MESH_TRI, 0, 0, 0};
    wff_model m;
    setenv("WOVENFF_KERNEL", "sse9", 1);
    int rc = test_model_rect(&m, &r, KEVLAR, &err);
    CHECK(st, rc == -1 && contains(err.message, "WOVENFF_KERNEL") && contains(err.message, "sse9"),
          "a bad WOVENFF_KERNEL stops model creation: %s", rc ? err.message : "created");
    if (rc == 0)
        wff_model_free(&m);
    setenv("WOVENFF_KERNEL", "baseline", 1);
    rc = test_model_rect(&m, &r, KEVLAR, &err);
    CHECK(st, rc == 0 && strcmp(wff_material_kernel(&m.mat), "baseline") == 0,
          "WOVENFF_KERNEL=baseline: %s", rc ? err.message : wff_material_kernel(&m.mat));
    if (rc == 0)
        wff_model_free(&m);
    unsetenv("WOVENFF_KERNEL");
    rc = test_model_rect(&m, &r, KEVLAR, &err);
    CHECK(st, rc == 0 && widest && strcmp(wff_material_kernel(&m.mat), wff_kernel_name(widest)) == 0,
          "unset: the widest, %s", rc ? err.message : wff_material_kernel(&m.mat));
    if (rc == 0)
        wff_model_free(&m);

    /* a cell table made at run time has no variant builds: auto keeps it, a name refuses */
    wff_material mat;
    if (wff_material_load(KEVLAR, &mat, &err) == 0) {
        wff_cell_type copy = *mat.cell;
        mat.cell = &copy;
        CHECK(st, wff_kernel_apply(&mat, "auto", &err) == 0 && mat.cell == &copy &&
                      strcmp(wff_material_kernel(&mat), "baseline") == 0,
              "auto keeps a cell built into no variant");
        CHECK(st, wff_kernel_apply(&mat, "baseline", &err) == -1 && mat.cell == &copy &&
                      contains(err.message, "no build"),
              "a named variant refuses it: %s", err.message);
    }
}

/* Each runnable variant's cells: their own code, and the whole suite passes. */
static void check_cells(check_state *st)
{
    static const cell_case cases[] = {
        {KEVLAR, "tests/data/king_symmetric.txt", 30e-6, 1},
        {"tests/data/king_flow_n3.txt", NULL, 30e-6, 1},
        {"freefem_scripts/materials/kevlar_basket.txt", "tests/data/basket_symmetric.txt", 30e-6, 1},
        {"freefem_scripts/materials/kevlar_linear.txt", "tests/data/linear_symmetric.txt", 0, 1},
    };
    for (int i = 0; i < wff_kernel_count(); i++) {
        const wff_kernel *k = wff_kernel_at(i);
        if (!wff_kernel_runs_here(k))
            continue;
        for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
            wff_material base, mat;
            wff_error err;
            int rc = wff_material_load(cases[c].material, &base, &err);
            CHECK(st, rc == 0, "%s", err.message);
            if (rc)
                continue;
            mat = base;
            rc = wff_kernel_apply(&mat, wff_kernel_name(k), &err);
            CHECK(st, rc == 0 && wff_kernel_of_cell(mat.cell) == k &&
                          strcmp(mat.cell->name, base.cell->name) == 0,
                  "%s: the %s build of %s", cases[c].material, wff_kernel_name(k),
                  base.cell->name);
            if (rc)
                continue;
            if (i > 0) /* not the baseline's code */
                CHECK(st, mat.cell != base.cell && mat.cell->evaluate != base.cell->evaluate &&
                              (!base.cell->evaluate_tri_block ||
                               mat.cell->evaluate_tri_block != base.cell->evaluate_tri_block),
                      "%s: the %s cell has code of its own", cases[c].material, wff_kernel_name(k));
            int before = st->failures;
            cell_suite_check(st, &cases[c], &mat);
            CHECK(st, st->failures == before, "%s: the cell suite under kernel %s",
                  cases[c].material, wff_kernel_name(k));
        }
    }
}

/* Blocked fast path vs plain path under each variant, on a bumpy state. */
static void check_fast_paths(check_state *st)
{
    for (int i = 0; i < wff_kernel_count(); i++) {
        const wff_kernel *k = wff_kernel_at(i);
        if (!wff_kernel_runs_here(k))
            continue;
        test_rect r = {0, 0.04, 0, 0.03, 12, 10, TEST_MESH_TRI, 1, 0.2, 4242}; /* 240 triangles */
        wff_model m;
        wff_error err;
        int rc = test_model_rect(&m, &r, KEVLAR, &err);
        CHECK(st, rc == 0, "%s", err.message);
        if (rc)
            continue;
        rc = wff_kernel_apply(&m.mat, wff_kernel_name(k), &err);
        CHECK(st, rc == 0 && strcmp(wff_material_kernel(&m.mat), wff_kernel_name(k)) == 0,
              "model on %s: %s", wff_kernel_name(k), rc ? err.message : "");
        const double F_pre[4] = {1.00396, 0, 0, 1.0135}, dA0[2] = {-9.3e-6, -23.8e-6};
        wff_model_set_preload(&m, F_pre, dA0, &err);
        for (int n = 0; n < m.n_nodes; n++) {
            double x = m.mesh.xy[2 * n], y = m.mesh.xy[2 * n + 1];
            m.u[D * n] = 0.05 * y + 1e-4 * sin(300 * x);
            m.u[D * n + 2] = 2e-3 * sin(100 * x) * cos(80 * y);
            m.u[D * n + 3] += -15e-6 * cos(200 * y);
            m.u[D * n + 4] += 5e-6 * sin(150 * x);
        }
        size_t nq = (size_t)(3 * m.el.n_tris), nd = (size_t)m.n_dofs;
        double *f_ref = calloc(nd, sizeof(double)), *f_fast = calloc(nd, sizeof(double));
        double *g_ref = malloc(nq * sizeof(double)), *g_fast = malloc(nq * sizeof(double));
        for (size_t q = 0; q < nq; q++)
            g_ref[q] = g_fast[q] = 0.01 * (double)(q % 5);
        wff_force_totals t_ref, t_fast;
        m.em.reference_path = 1;
        wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, g_ref, 1e-7, f_ref, &t_ref);
        m.em.reference_path = 0;
        wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, g_fast, 1e-7, f_fast, &t_fast);
        double scale = 0, diff = 0, gdiff = 0;
        for (size_t j = 0; j < nd; j++) {
            scale = fmax(scale, fabs(f_ref[j]));
            diff = fmax(diff, fabs(f_fast[j] - f_ref[j]));
        }
        for (size_t q = 0; q < nq; q++)
            gdiff = fmax(gdiff, fabs(g_fast[q] - g_ref[q]));
        printf("  %-8s blocked vs plain: forces %.2e of %.3g, gamma_f %.2e\n", wff_kernel_name(k),
               diff / scale, scale, gdiff);
        CHECK(st, t_ref.bad_element < 0 && t_fast.bad_element < 0, "%s: no bad element",
              wff_kernel_name(k));
        CHECK(st, scale > 0 && diff <= 1e-12 * scale, "%s: blocked path forces differ by %.3g of %.3g",
              wff_kernel_name(k), diff, scale);
        CHECK(st, gdiff <= 1e-14, "%s: gamma_f differs by %.3g", wff_kernel_name(k), gdiff);
        CHECK_CLOSE(st, t_fast.internal_energy, t_ref.internal_energy, 1e-12, 0,
                    "blocked path energy");
        free(f_ref);
        free(f_fast);
        free(g_ref);
        free(g_fast);
        wff_model_free(&m);
    }
}

/* What a run leaves, for comparison between variants. */
typedef struct run_result {
    double *u, *v, *f, *gamma_f;
    size_t nd, nq;
    wff_energies e;
    double tip, velocity, force, dt_stable;
    long step;
} run_result;

/* The ballistic quarter model (as bench/kernel_speed.c sets it up) on a coarse
 * mesh, `steps` steps on kernel `name`; 0 or -1. */
static int ballistic_run(const char *name, long steps, run_result *out, wff_error *err)
{
    wff_mesh_options opt;
    wff_model m;
    memset(out, 0, sizeof *out);
    if (wff_mesh_options_parse("size_factor=1.5", &opt, err) ||
        wff_model_create(&m, "meshes/ballistic_quarter.geo", &opt, KEVLAR, err))
        return -1;
    const double F_pre[4] = {1.003963, 0, 0, 1.013476}, dA0[2] = {-9.311e-6, -23.748e-6};
    int rc = wff_kernel_apply(&m.mat, name, err) || wff_model_set_preload(&m, F_pre, dA0, err) ||
             wff_model_fix_group(&m, "sym_x", 0, err) < 0 ||
             wff_model_fix_group(&m, "sym_y", 1, err) < 0 ||
             wff_model_fix_group(&m, "clamp", 0, err) < 0 ||
             wff_model_fix_group(&m, "clamp", 1, err) < 0 ||
             wff_model_fix_group(&m, "clamp", 2, err) < 0 ||
             wff_model_set_projectile(&m, 6.35e-3, 0.026, 22, 0.3, err) ||
             wff_model_advance(&m, 1e9, steps, err);
    if (rc == 0 && strcmp(wff_material_kernel(&m.mat), name) != 0)
        rc = wff_fail(err, "the model runs kernel %s, not %s", wff_material_kernel(&m.mat), name);
    if (rc == 0) {
        out->nd = (size_t)m.n_dofs;
        out->nq = (size_t)(3 * m.el.n_tris + 4 * m.el.n_quads);
        out->u = malloc(out->nd * sizeof(double));
        out->v = malloc(out->nd * sizeof(double));
        out->f = malloc(out->nd * sizeof(double));
        out->gamma_f = malloc(out->nq * sizeof(double));
        memcpy(out->u, m.u, out->nd * sizeof(double));
        memcpy(out->v, m.v, out->nd * sizeof(double));
        memcpy(out->f, m.f, out->nd * sizeof(double));
        memcpy(out->gamma_f, m.state, out->nq * sizeof(double));
        wff_model_energies(&m, &out->e);
        out->tip = m.projectile.tip;
        out->velocity = m.projectile.velocity;
        out->force = m.projectile.force;
        out->dt_stable = m.dt_stable;
        out->step = m.step;
    }
    wff_model_free(&m);
    return rc ? -1 : 0;
}

static void run_free(run_result *r)
{
    free(r->u);
    free(r->v);
    free(r->f);
    free(r->gamma_f);
}

/* largest |a − b| over n, relative to the largest |b| */
static double relative_gap(const double *a, const double *b, size_t n)
{
    double scale = 0, gap = 0;
    for (size_t i = 0; i < n; i++) {
        scale = fmax(scale, fabs(b[i]));
        gap = fmax(gap, fabs(a[i] - b[i]));
    }
    return scale > 0 ? gap / scale : gap;
}

/* Static amplitudes (a Newton solve per point, blocked with the cell's tangent):
 * under each variant the blocked path = the plain path, and both = the
 * baseline's plain path, one pass on a sheared, stretched state. */
static int static_pass(const char *kernel, int plain, double *f, size_t nd, double *energy,
                       wff_error *err)
{
    test_rect r = {0, 0.02, 0, 0.01, 12, 6, TEST_MESH_TRI, 1, 0.2, 7};
    wff_model m;
    if (test_model_rect(&m, &r, KEVLAR, err))
        return -1;
    const double F_pre[4] = {1.003963, 0, 0, 1.013476}, dA0[2] = {-9.311e-6, -23.748e-6};
    int rc = wff_kernel_apply(&m.mat, kernel, err) || wff_model_set_preload(&m, F_pre, dA0, err) ||
             wff_model_set_option(&m, "static_amplitudes", 1, err) || (size_t)m.n_dofs != nd;
    if (rc == 0) {
        for (int n = 0; n < m.n_nodes; n++) {
            double x = m.mesh.xy[2 * n], y = m.mesh.xy[2 * n + 1];
            m.u[D * n] = 0.02 * (0.3 * y + 0.002 * sin(400 * x));
            m.u[D * n + 1] = 0.004 * x * cos(300 * y);
            m.u[D * n + 2] = 4e-4 * sin(300 * x) * cos(250 * y);
        }
        m.em.reference_path = plain;
        wff_force_totals t;
        memset(f, 0, nd * sizeof(double));
        wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, m.state, 1e-6, f, &t);
        *energy = t.internal_energy;
        if (t.bad_element >= 0)
            rc = wff_fail(err, "element %d failed (status %d)", t.bad_element, t.bad_status);
    }
    wff_model_free(&m);
    return rc ? -1 : 0;
}

static void check_static_paths(check_state *st)
{
    const size_t nd = (size_t)D * 13 * 7; /* the 12 x 6 rectangle's nodes */
    double *ref = calloc(nd, sizeof(double)), *plain = calloc(nd, sizeof(double));
    double *blocked = calloc(nd, sizeof(double)), e_ref = 0, e_plain = 0, e_blocked = 0;
    wff_error err;
    int rc = static_pass("baseline", 1, ref, nd, &e_ref, &err);
    CHECK(st, rc == 0, "static amplitudes, baseline plain path: %s", err.message);
    for (int i = 0; rc == 0 && i < wff_kernel_count(); i++) {
        const wff_kernel *k = wff_kernel_at(i);
        if (!wff_kernel_runs_here(k))
            continue;
        const char *name = wff_kernel_name(k);
        int rp = static_pass(name, 1, plain, nd, &e_plain, &err);
        CHECK(st, rp == 0, "static amplitudes, %s plain path: %s", name, err.message);
        int rb = static_pass(name, 0, blocked, nd, &e_blocked, &err);
        CHECK(st, rb == 0, "static amplitudes, %s blocked path: %s", name, err.message);
        if (rp || rb)
            continue;
        double own = relative_gap(blocked, plain, nd), cross = relative_gap(blocked, ref, nd);
        printf("  %-8s static amplitudes: blocked vs plain %.1e, vs the baseline's plain %.1e\n",
               name, own, cross);
        CHECK(st, own <= 1e-11 && cross <= 1e-11,
              "%s: static blocked forces differ by %.3g (plain) / %.3g (baseline)", name, own,
              cross);
        CHECK_CLOSE(st, e_blocked, e_ref, 1e-11, 0, "static energy against the baseline's");
    }
    free(ref);
    free(plain);
    free(blocked);
}

static void check_ballistic(check_state *st)
{
    const long steps = 150;
    const double tol = 1e-9; /* round-off (FMA, libmvec's atan/exp) grown over 150 steps */
    run_result base;
    wff_error err;
    int rc = ballistic_run("baseline", steps, &base, &err);
    CHECK(st, rc == 0, "baseline run: %s", err.message);
    if (rc)
        return;
    CHECK(st, base.step == steps && base.force > 0 && base.e.internal > 0,
          "the projectile is in contact and the fabric loaded (step %ld, force %g N)", base.step,
          base.force);
    for (int i = 1; i < wff_kernel_count(); i++) {
        const wff_kernel *k = wff_kernel_at(i);
        if (!wff_kernel_runs_here(k))
            continue;
        run_result run;
        const char *name = wff_kernel_name(k);
        rc = ballistic_run(name, steps, &run, &err);
        CHECK(st, rc == 0, "%s run: %s", name, err.message);
        if (rc)
            continue;
        double gu = relative_gap(run.u, base.u, base.nd), gv = relative_gap(run.v, base.v, base.nd);
        double gf = relative_gap(run.f, base.f, base.nd);
        double gg = relative_gap(run.gamma_f, base.gamma_f, base.nq);
        printf("  %-8s vs baseline after %ld steps: u %.1e v %.1e f %.1e gamma_f %.1e, "
               "internal energy %.1e, projectile force %.1e\n", name, steps, gu, gv, gf, gg,
               fabs(run.e.internal / base.e.internal - 1), fabs(run.force / base.force - 1));
        CHECK(st, run.step == base.step && run.nd == base.nd, "%s: same steps and mesh", name);
        CHECK(st, gu <= tol && gv <= tol && gf <= tol && gg <= tol,
              "%s: state and forces differ from the baseline's: u %g v %g f %g gamma_f %g", name,
              gu, gv, gf, gg);
        CHECK_CLOSE(st, run.e.internal, base.e.internal, tol, 0, "internal energy");
        CHECK_CLOSE(st, run.e.kinetic_transverse, base.e.kinetic_transverse, tol, 0,
                    "transverse kinetic energy");
        CHECK_CLOSE(st, run.e.kinetic_amplitude, base.e.kinetic_amplitude, tol, 0,
                    "amplitude kinetic energy");
        CHECK_CLOSE(st, run.e.dissipated_shear, base.e.dissipated_shear, tol, 1e-12,
                    "shear dissipation");
        CHECK_CLOSE(st, run.e.error, base.e.error, 1e-6, 1e-9, "energy balance error");
        CHECK_CLOSE(st, run.force, base.force, tol, 0, "projectile force");
        CHECK_CLOSE(st, run.velocity, base.velocity, tol, 0, "projectile velocity");
        CHECK_CLOSE(st, run.tip, base.tip, tol, 0, "projectile tip");
        CHECK_CLOSE(st, run.dt_stable, base.dt_stable, 1e-12, 0, "stable step");
        run_free(&run);
    }
    run_free(&base);
}

int main(void)
{
    check_state st = {0, 0};
    check_requests(&st);
    check_cells(&st);
    check_fast_paths(&st);
    check_static_paths(&st);
    check_ballistic(&st);
    return check_summary(&st, "test_kernels");
}

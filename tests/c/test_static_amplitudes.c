/* Static amplitudes (docs/model.md §13): the per-point Newton with the cell's
 * exact amplitude tangent. The blocked triangle path (tri_block_static_forces)
 * gives the plain reference path's forces, energies, balanced amplitudes and
 * γᶠ to round-off over several passes; the Newton is warm-started (a repeated
 * pass takes one tangent per point) and balances every point; a cell without
 * the tangent ops (finite-difference default) gives the same balance; a Newton that
 * cannot converge stops the run naming the element, the point, the residual
 * left and the iterations spent (a singular tangent: one; a wrong one: the
 * bound). Knows the elements and the model, not the cells' internals. */
#include "check.h"
#include "test_meshes.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/membrane.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

static const test_rect RECT = {0, 0.02, 0, 0.01, 12, 6, TEST_MESH_TRI, 1, 0.2, 7};

/* A model on RECT with static amplitudes, deformed non-uniformly by `amount`,
 * γᶠ varied; the preload's amplitudes as the first guess. */
static int static_model(wff_model *m, const char *material, wff_error *err)
{
    if (test_model_rect(m, &RECT, material, err))
        return -1;
    const double F_pre[4] = {1.003963, 0, 0, 1.013476}, dA0[2] = {-9.311e-6, -23.748e-6};
    if (wff_model_set_preload(m, F_pre, dA0, err) ||
        wff_model_set_option(m, "static_amplitudes", 1, err))
        return -1;
    for (int q = 0; q < 3 * m->el.n_tris + 4 * m->el.n_quads; q++)
        m->state[q] = 0.002 * (q % 5);
    return 0;
}

static void deform(wff_model *m, double amount)
{
    for (int n = 0; n < m->n_nodes; n++) {
        double x = m->mesh.xy[2 * n], y = m->mesh.xy[2 * n + 1];
        m->u[D * n] = amount * (0.3 * y + 0.002 * sin(400 * x));
        m->u[D * n + 1] = amount * 0.2 * x * cos(300 * y);
        m->u[D * n + 2] = amount * 0.02 * sin(300 * x) * cos(250 * y);
    }
}

static double max_abs_diff(const double *a, const double *b, size_t n, double *scale)
{
    double d = 0, s = 0;
    for (size_t i = 0; i < n; i++) {
        d = fmax(d, fabs(a[i] - b[i]));
        s = fmax(s, fabs(b[i]));
    }
    *scale = s;
    return d;
}

/* Blocked vs plain over passes that move the state (γᶠ advanced, the points'
 * amplitudes carried from pass to pass), then warm start and balance. */
static void check_block_vs_plain(check_state *st)
{
    wff_model a, b;
    wff_error err;
    int rc = static_model(&a, KEVLAR, &err);
    CHECK(st, rc == 0, "%s", err.message);
    rc = rc || static_model(&b, KEVLAR, &err);
    CHECK(st, rc == 0, "%s", err.message);
    if (rc)
        return;
    a.em.reference_path = 1; /* plain: tri_forces_static, wff_balance_point */
    size_t nd = (size_t)a.n_dofs, np = (size_t)(3 * a.el.n_tris);
    double *fa = calloc(nd, sizeof(double)), *fb = calloc(nd, sizeof(double));
    double worst_f = 0, worst_dA = 0, worst_gf = 0, worst_W = 0;
    long iterations_first = 0;
    for (int pass = 0; pass < 6; pass++) {
        deform(&a, 0.01 * (pass + 1));
        deform(&b, 0.01 * (pass + 1));
        wff_force_totals ta, tb;
        memset(fa, 0, sizeof(double) * nd);
        memset(fb, 0, sizeof(double) * nd);
        wff_elements_forces(&a.el, &a.em, a.mesh.xy, a.u, a.state, 1e-6, fa, &ta);
        wff_elements_forces(&b.el, &b.em, b.mesh.xy, b.u, b.state, 1e-6, fb, &tb);
        CHECK(st, ta.bad_element < 0 && tb.bad_element < 0,
              "pass %d: bad element %d / %d (status %d / %d)", pass, ta.bad_element,
              tb.bad_element, ta.bad_status, tb.bad_status);
        double s;
        worst_f = fmax(worst_f, max_abs_diff(fb, fa, nd, &s) / s);
        worst_dA = fmax(worst_dA, max_abs_diff(b.el.point_dA, a.el.point_dA, 2 * np, &s) / s);
        worst_gf = fmax(worst_gf, max_abs_diff(b.state, a.state, np, &s) / s);
        worst_W = fmax(worst_W, fabs(tb.internal_energy - ta.internal_energy) /
                                    fabs(ta.internal_energy));
        CHECK(st, ta.amplitude_iterations >= (long)np &&
                      ta.amplitude_iterations <= WFF_BALANCE_MAX_ITERATIONS * (long)np,
              "pass %d: %ld Newton iterations for %zu points", pass, ta.amplitude_iterations, np);
        if (pass == 0)
            iterations_first = ta.amplitude_iterations;
    }
    printf("  blocked vs plain static path: forces %.1e, amplitudes %.1e, gamma_f %.1e, "
           "energy %.1e; first pass %.2f Newton iterations per point\n", worst_f, worst_dA,
           worst_gf, worst_W, (double)iterations_first / (double)np);
    CHECK(st, worst_f <= 1e-11, "blocked static forces differ from the plain path by %.3g",
          worst_f);
    CHECK(st, worst_dA <= 1e-11, "blocked static amplitudes differ by %.3g", worst_dA);
    CHECK(st, worst_gf <= 1e-11, "blocked static gamma_f differs by %.3g", worst_gf);
    CHECK(st, worst_W <= 1e-11, "blocked static energy differs by %.3g", worst_W);
    CHECK(st, iterations_first >= 2 * (long)np, "a deformed first pass needs Newton steps (%ld)",
          iterations_first);

    /* warm start: the same state again converges at the first tangent, both paths */
    for (int path = 0; path < 2; path++) {
        wff_model *m = path ? &b : &a;
        wff_force_totals t;
        memset(fa, 0, sizeof(double) * nd);
        wff_elements_forces(&m->el, &m->em, m->mesh.xy, m->u, m->state, 0, fa, &t);
        CHECK(st, t.bad_element < 0 && t.amplitude_iterations == (long)np,
              "%s path: a repeated pass takes one tangent per point (%ld for %zu)",
              path ? "blocked" : "plain", t.amplitude_iterations, np);
    }
    /* every point balanced: |R| tiny against the compaction force's scale */
    double worst_R = 0, scale_R = 0, pitch0[2], amplitude0[2];
    b.mat.cell->reference_geometry(b.mat.params, pitch0, amplitude0);
    for (int e = 0; e < b.el.n_tris; e++) {
        double F[6], dA_c[2];
        wff_point_result r;
        /* F of the (linear) triangle, the preload applied */
        wff_element_center_state(&b.el, b.mesh.xy, b.u, e, F, dA_c);
        double Fe[6];
        for (int i = 0; i < 3; i++) {
            Fe[2 * i] = F[2 * i] * b.em.F_pre[0] + F[2 * i + 1] * b.em.F_pre[2];
            Fe[2 * i + 1] = F[2 * i] * b.em.F_pre[1] + F[2 * i + 1] * b.em.F_pre[3];
        }
        for (int q = 0; q < 3; q++) {
            wff_material_evaluate(&b.mat, Fe, b.el.point_dA + 6 * e + 2 * q, b.state + (3 * e + q) * b.n_state,
                                  0, &r);
            worst_R = fmax(worst_R, fmax(fabs(r.residual[0]), fabs(r.residual[1])));
            /* F_I (diag 4) per cell area 4 p1⁰ p2⁰ */
            scale_R = fmax(scale_R, r.diag[4] / (4 * pitch0[0] * pitch0[1]));
        }
    }
    printf("  balance: largest |R| %.2e N/m^2 against F_I/area %.2e\n", worst_R, scale_R);
    CHECK(st, worst_R <= 1e-9 * scale_R, "static points balanced: |R| %g of %g", worst_R, scale_R);
    free(fa);
    free(fb);
    wff_model_free(&a);
    wff_model_free(&b);
}

/* A cell without the tangent ops gets the finite-difference default: the same
 * balance (to the Newton tolerance) as with the exact tangent. */
static void check_default_tangent(check_state *st)
{
    wff_model a, b;
    wff_error err;
    int rc = static_model(&a, KEVLAR, &err) || static_model(&b, KEVLAR, &err);
    CHECK(st, rc == 0, "%s", err.message);
    if (rc)
        return;
    wff_cell_type bare = *b.mat.cell;
    bare.amplitude_tangent = NULL;
    bare.amplitude_tangent_block = NULL;
    b.mat.cell = &bare;
    size_t nd = (size_t)a.n_dofs, np = (size_t)(3 * a.el.n_tris);
    double *fa = calloc(nd, sizeof(double)), *fb = calloc(nd, sizeof(double));
    wff_force_totals ta, tb;
    deform(&a, 0.02);
    deform(&b, 0.02);
    wff_elements_forces(&a.el, &a.em, a.mesh.xy, a.u, a.state, 0, fa, &ta);
    wff_elements_forces(&b.el, &b.em, b.mesh.xy, b.u, b.state, 0, fb, &tb);
    double sf, sa;
    double df = max_abs_diff(fb, fa, nd, &sf) / sf;
    double da = max_abs_diff(b.el.point_dA, a.el.point_dA, 2 * np, &sa);
    printf("  default (finite-difference) tangent: forces %.1e, amplitudes %.1e m from the exact "
           "tangent's; %.2f vs %.2f iterations per point\n", df, da,
           (double)tb.amplitude_iterations / (double)np, (double)ta.amplitude_iterations / (double)np);
    CHECK(st, ta.bad_element < 0 && tb.bad_element < 0, "default tangent: bad element %d / %d",
          ta.bad_element, tb.bad_element);
    CHECK(st, df <= 1e-9 && da <= 1e-12, "default tangent: forces %.3g, amplitudes %.3g m off",
          df, da);
    free(fa);
    free(fb);
    wff_model_free(&a);
    wff_model_free(&b);
}

/* Tangents that make Newton fail: singular (zero), and four times too stiff
 * (quarter steps: linear convergence, too slow for the bound). */
static int zero_tangent(const void *params, const double F[6], const double dA[2], const double *gf,
                        double residual[2], double tangent[4])
{
    int rc = wff_cell_find("king_plain")->amplitude_tangent(params, F, dA, gf, residual, tangent);
    for (int i = 0; i < 4; i++)
        tangent[i] = 0;
    return rc;
}

static int stiff_tangent(const void *params, const double F[6], const double dA[2], const double *gf,
                         double residual[2], double tangent[4])
{
    int rc = wff_cell_find("king_plain")->amplitude_tangent(params, F, dA, gf, residual, tangent);
    for (int i = 0; i < 4; i++)
        tangent[i] *= 4;
    return rc;
}

static int stiff_tangent_block(const void *params, wff_tangent_block *blk)
{
    int rc = wff_cell_find("king_plain")->amplitude_tangent_block(params, blk);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < WFF_BLOCK; j++)
            blk->tangent[i][j] *= 4;
    return rc;
}

static void check_failure(check_state *st, const char *what, wff_cell_type *cell,
                          int expect_iterations)
{
    wff_model m;
    wff_error err;
    int rc = static_model(&m, KEVLAR, &err);
    CHECK(st, rc == 0, "%s", err.message);
    if (rc)
        return;
    *cell = *m.mat.cell;
    cell->amplitude_tangent = what[0] == 'z' ? zero_tangent : stiff_tangent;
    cell->amplitude_tangent_block = what[0] == 'b' ? stiff_tangent_block : NULL;
    m.mat.cell = cell;
    deform(&m, 0.02);
    size_t nd = (size_t)m.n_dofs;
    double *f = calloc(nd, sizeof(double));
    wff_force_totals t;
    wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, m.state, 0, f, &t);
    CHECK(st, t.bad_element >= 0 && t.bad_status == WFF_POINT_UNBALANCED,
          "%s tangent: element %d, status %d", what, t.bad_element, t.bad_status);
    CHECK(st, t.bad_iterations == expect_iterations && t.bad_residual > 0 &&
                  isfinite(t.bad_residual),
          "%s tangent: %d iterations (want %d), residual %g", what, t.bad_iterations,
          expect_iterations, t.bad_residual);
    /* a run stops with the element, point, residual and iterations named */
    rc = wff_model_advance(&m, 1, 1, &err);
    char want[64];
    snprintf(want, sizeof want, "after %d Newton steps", expect_iterations);
    CHECK(st, rc != 0 && strstr(err.message, "unbalanced") && strstr(err.message, want) &&
                  strstr(err.message, "quadrature point") && strstr(err.message, "|R|"),
          "%s tangent: the run's error names it: %s", what, rc ? err.message : "(no error)");
    printf("  %s tangent: %s\n", what, rc ? err.message : "(no error)");
    free(f);
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    check_block_vs_plain(&st);
    check_default_tangent(&st);
    wff_cell_type zero, stiff, block;
    check_failure(&st, "zero (singular)", &zero, 1);
    check_failure(&st, "stiff (4x, plain)", &stiff, WFF_BALANCE_MAX_ITERATIONS);
    check_failure(&st, "blocked stiff (4x)", &block, WFF_BALANCE_MAX_ITERATIONS);
    return check_summary(&st, "test_static_amplitudes");
}

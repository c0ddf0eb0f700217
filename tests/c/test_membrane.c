/* Membrane elements (docs/model.md §8): patch test with and without preload,
 * lumped masses, and a degenerate or non-finite state stopping the run. */
#include "check.h"
#include "test_meshes.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

static int diag_index(const wff_material *mat, const char *name)
{
    for (int d = 0; d < mat->cell->n_diag; d++)
        if (strcmp(mat->cell->diag_names[d], name) == 0)
            return d;
    return -1;
}

/* Reference area of the mesh, from the element geometry. */
static double mesh_area(const wff_model *m)
{
    double area = 0;
    for (int e = 0; e < m->el.n_tris; e++)
        area += m->el.tri_area[e];
    for (int q = 0; q < 4 * m->el.n_quads; q++)
        area += m->el.quad_weight[q];
    return area;
}

/* 1. Uniform F (in-plane stretch and shear, out-of-plane tilt), balanced
 * uniform amplitudes: interior nodes carry no net force, amplitude forces
 * vanish, boundary nodes carry −Σ P_mesh n |e|/2 over their edges, with
 * P_mesh = P(F F_pre) F_preᵀ / det F_pre. */
static void patch_case(check_state *st, int type, const double *F_pre, const char *what)
{
    test_rect r = {-0.02, 0.03, -0.01, 0.015, 7, 5, type, 1, 0.25, 12345};
    wff_model m;
    wff_error err;
    int rc = test_model_rect(&m, &r, KEVLAR, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    if (rc)
        return;
    double Fp[4] = {1, 0, 0, 1}, dA[2] = {0, 0};
    if (F_pre) {
        double dA0[2] = {-9.3e-6, -23.8e-6};
        memcpy(Fp, F_pre, sizeof Fp);
        memcpy(dA, dA0, sizeof dA);
        rc = wff_model_set_preload(&m, Fp, dA0, &err);
        CHECK(st, rc == 0, "%s: %s", what, err.message);
    }
    const double F[6] = {1.012, 0.021, -0.008, 0.994, 0.035, -0.027};
    double Fe[6], Jp = Fp[0] * Fp[3] - Fp[1] * Fp[2];
    for (int i = 0; i < 3; i++) {
        Fe[2 * i] = F[2 * i] * Fp[0] + F[2 * i + 1] * Fp[2];
        Fe[2 * i + 1] = F[2 * i] * Fp[1] + F[2 * i + 1] * Fp[3];
    }
    rc = wff_balance_amplitudes(&m.mat, Fe, wff_rest_state, dA, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    wff_point_result pr;
    rc = wff_material_evaluate(&m.mat, Fe, dA, wff_rest_state, 0, &pr);
    CHECK(st, rc == WFF_POINT_OK, "%s: evaluate at F_eff", what);
    double Pm[6];
    for (int i = 0; i < 3; i++) {
        Pm[2 * i] = (pr.stress[2 * i] * Fp[0] + pr.stress[2 * i + 1] * Fp[1]) / Jp;
        Pm[2 * i + 1] = (pr.stress[2 * i] * Fp[2] + pr.stress[2 * i + 1] * Fp[3]) / Jp;
    }
    for (int n = 0; n < m.n_nodes; n++) {
        double X = m.mesh.xy[2 * n], Y = m.mesh.xy[2 * n + 1];
        double *u = m.u + D * n;
        u[0] = (F[0] - 1) * X + F[1] * Y;
        u[1] = F[2] * X + (F[3] - 1) * Y;
        u[2] = F[4] * X + F[5] * Y;
        u[3] = dA[0];
        u[4] = dA[1];
    }
    memset(m.f, 0, sizeof(double) * (size_t)m.n_dofs);
    wff_force_totals t;
    wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, m.state, 0, m.f, &t);
    CHECK(st, t.bad_element < 0, "%s: element %d failed", what, t.bad_element);

    /* exact boundary resultants */
    double *want = calloc(3 * (size_t)m.n_nodes, sizeof(double));
    unsigned char *boundary = calloc((size_t)m.n_nodes, 1);
    double longest = 0, pmax = 0;
    for (int e = 0; e < m.mesh.n_edges; e++) {
        int a = m.mesh.edge[2 * e], b = m.mesh.edge[2 * e + 1];
        /* edges run counter-clockwise: outward n |e| = (dy, −dx) */
        double nl[2] = {m.mesh.xy[2 * b + 1] - m.mesh.xy[2 * a + 1],
                        -(m.mesh.xy[2 * b] - m.mesh.xy[2 * a])};
        longest = fmax(longest, hypot(nl[0], nl[1]));
        for (int i = 0; i < 3; i++) {
            double half = 0.5 * (Pm[2 * i] * nl[0] + Pm[2 * i + 1] * nl[1]);
            want[3 * a + i] -= half;
            want[3 * b + i] -= half;
        }
        boundary[a] = boundary[b] = 1;
    }
    for (int i = 0; i < 6; i++)
        pmax = fmax(pmax, fabs(Pm[i]));
    double scale = pmax * longest; /* force on one boundary edge */
    double fi = diag_index(&m.mat, "F_I") >= 0 ? pr.diag[diag_index(&m.mat, "F_I")] : 0;
    double cell_area = m.mat.yarn_spacing[0] * m.mat.yarn_spacing[1];
    double amp_scale = fabs(fi) / cell_area * longest * longest / Jp;
    double worst_in = 0, worst_bd = 0, worst_amp = 0;
    int interior = 0;
    for (int n = 0; n < m.n_nodes; n++) {
        const double *f = m.f + D * n;
        for (int i = 0; i < 3; i++) {
            double d = fabs(f[i] - want[3 * n + i]);
            if (boundary[n])
                worst_bd = fmax(worst_bd, d);
            else
                worst_in = fmax(worst_in, d);
        }
        interior += !boundary[n];
        worst_amp = fmax(worst_amp, fmax(fabs(f[3]), fabs(f[4])));
    }
    double area = mesh_area(&m);
    printf("  patch %-24s |P| %.4g N/m, F_I %.4f N; interior %d nodes |f| %.2e, boundary "
           "error %.2e, amplitude |f| %.2e (relative)\n", what, pmax, fi, interior,
           worst_in / scale, worst_bd / scale, worst_amp / amp_scale);
    CHECK(st, interior > 10, "%s: interior nodes %d", what, interior);
    CHECK(st, pmax > 100 && fabs(Pm[4]) > 1 && fabs(Pm[5]) > 1,
          "%s: a real, out-of-plane stress state: |P| %g, P31 %g, P32 %g", what, pmax, Pm[4],
          Pm[5]);
    CHECK(st, worst_in <= 1e-10 * scale, "%s: interior net force %g (scale %g N)", what,
          worst_in, scale);
    CHECK(st, worst_bd <= 1e-10 * scale, "%s: boundary force off by %g (scale %g N)", what,
          worst_bd, scale);
    CHECK(st, worst_amp <= 1e-10 * amp_scale, "%s: amplitude force %g (scale %g N)", what,
          worst_amp, amp_scale);
    CHECK_CLOSE(st, t.internal_energy, pr.energy * area / Jp, 1e-12, 0, "patch energy");
    CHECK(st, t.dissipated == 0, "%s: dt = 0 dissipates nothing: %g", what, t.dissipated);
    free(want);
    free(boundary);
    wff_model_free(&m);
}

static void check_patch(check_state *st)
{
    const double F_pre[4] = {1.00396, 0, 0, 1.0135};
    patch_case(st, TEST_MESH_TRI, NULL, "jittered triangles");
    patch_case(st, TEST_MESH_QUAD, NULL, "jittered quads");
    patch_case(st, TEST_MESH_TRI, F_pre, "triangles, preload");
    patch_case(st, TEST_MESH_QUAD, F_pre, "quads, preload");
}

/* 5. Lumped masses: amplitude masses are 1/6 of the displacement masses at
 * every node; the total is ρ_A × area / det F_pre. */
static void masses_case(check_state *st, int type, const char *what)
{
    test_rect r = {0, 0.04, 0, 0.03, 6, 5, type, 1, 0.2, 777};
    wff_model m;
    wff_error err;
    int rc = test_model_rect(&m, &r, KEVLAR, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    if (rc)
        return;
    const double F_pre[4] = {1.00396, 0.002, -0.001, 1.0135}, dA0[2] = {-9.3e-6, -23.8e-6};
    double Jp = F_pre[0] * F_pre[3] - F_pre[1] * F_pre[2];
    double *before = malloc(sizeof(double) * (size_t)m.n_dofs);
    for (int pass = 0; pass < 2; pass++) {
        double J = pass ? Jp : 1, total = 0;
        int bad = 0;
        for (int n = 0; n < m.n_nodes; n++) {
            const double *mn = m.mass + D * n;
            total += mn[0];
            bad += !(mn[0] > 0) || mn[1] != mn[0] || mn[2] != mn[0] ||
                   fabs(mn[3] - mn[0] / 6) > 1e-15 * mn[0] || mn[4] != mn[3];
            if (pass)
                bad += fabs(mn[0] - before[D * n] / Jp) > 1e-14 * mn[0];
        }
        CHECK(st, bad == 0, "%s: %d nodes with wrong masses (pass %d)", what, bad, pass);
        CHECK_CLOSE(st, total, 0.181 * 0.04 * 0.03 / J, 1e-12, 0, "total displacement mass");
        if (!pass) {
            memcpy(before, m.mass, sizeof(double) * (size_t)m.n_dofs);
            rc = wff_model_set_preload(&m, F_pre, dA0, &err);
            CHECK(st, rc == 0, "%s: %s", what, err.message);
        }
    }
    free(before);
    wff_model_free(&m);
}

static void check_masses(check_state *st)
{
    masses_case(st, TEST_MESH_TRI, "triangles");
    masses_case(st, TEST_MESH_QUAD, "quads");
}

static int contains(const char *s, const char *part) { return strstr(s, part) != NULL; }

/* 8. A collapsed triangle (all three nodes moved onto the line y = 0, its
 * yarn directions parallel) stops the run with t, step, element type and
 * number; so do NaN displacements and NaN amplitudes. */
static void check_degenerate(check_state *st)
{
    for (int when = 0; when < 2; when++) {
        test_rect r = {0, 0.02, 0, 0.02, 4, 4, TEST_MESH_TRI, 0, 0, 0};
        wff_model m;
        wff_error err;
        int rc = test_model_rect(&m, &r, KEVLAR, &err);
        CHECK(st, rc == 0, "%s", err.message);
        if (rc)
            return;
        if (when) { /* healthy steps first */
            rc = wff_model_advance(&m, 1, 3, &err);
            CHECK(st, rc == 0 && m.step == 3, "healthy start: %s", rc ? err.message : "");
        }
        int e = 2 * (2 * 4 + 1); /* lower triangle of cell (1, 2): number 19 */
        for (int a = 0; a < 3; a++) {
            int n = m.mesh.tri[3 * e + a];
            m.u[D * n + 1] = -m.mesh.xy[2 * n + 1];
            m.v[D * n + 1] = 0;
            m.dof_kind[D * n + 1] = WFF_DOF_FIXED; /* keeps y = 0 exact */
        }
        rc = wff_model_advance(&m, 1, 10, &err);
        char number[32];
        snprintf(number, sizeof number, "triangle %d ", e + 1);
        printf("  collapsed triangle (%s): %s\n", when ? "mid-run" : "at the start",
               rc ? err.message : "not detected");
        CHECK(st, rc == -1, "collapsed triangle not detected (%s)", when ? "mid-run" : "start");
        CHECK(st, rc == -1 && contains(err.message, "t = ") && contains(err.message, "step") &&
                      contains(err.message, number),
              "message names time, step and %s: %s", number, err.message);
        wff_model_free(&m);
    }
    for (int c = 0; c < 2; c++) {
        test_rect r = {0, 0.02, 0, 0.02, 4, 4, TEST_MESH_QUAD, 0, 0, 0};
        wff_model m;
        wff_error err;
        int rc = test_model_rect(&m, &r, KEVLAR, &err);
        CHECK(st, rc == 0, "%s", err.message);
        if (rc)
            return;
        rc = wff_model_advance(&m, 1, 5, &err);
        CHECK(st, rc == 0, "healthy start: %s", rc ? err.message : "");
        int n = 12; /* interior node (2, 2); its first quad is number 6 */
        m.u[D * n + (c ? WFF_DA1 : WFF_UX)] = NAN;
        rc = wff_model_advance(&m, 1, 10, &err);
        printf("  NaN in %s: %s\n", c ? "dA1" : "ux", rc ? err.message : "not detected");
        CHECK(st, rc == -1 && contains(err.message, "t = ") && contains(err.message, "step") &&
                      contains(err.message, "quadrilateral 6 ") && contains(err.message, "NaN") &&
                      !contains(err.message, "degenerate"),
              "NaN in %s stops the run: %s", c ? "dA1" : "ux", rc ? err.message : "no error");
        wff_model_free(&m);
    }
}

/* The mesh-summed energy split adds up to the force pass's stored energy, and
 * the fast triangle path gives the reference path's forces to round-off. */
static void split_and_fast_case(check_state *st, int type, const char *what)
{
    test_rect r = {0, 0.04, 0, 0.03, 6, 5, type, 1, 0.2, 4242};
    wff_model m;
    wff_error err;
    int rc = test_model_rect(&m, &r, KEVLAR, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    if (rc)
        return;
    const double F_pre[4] = {1.00396, 0, 0, 1.0135}, dA0[2] = {-9.3e-6, -23.8e-6};
    wff_model_set_preload(&m, F_pre, dA0, &err);
    for (int n = 0; n < m.n_nodes; n++) { /* a bumpy, sheared, compacted state */
        double x = m.mesh.xy[2 * n], y = m.mesh.xy[2 * n + 1];
        m.u[D * n] = 0.05 * y + 1e-4 * sin(300 * x);
        m.u[D * n + 2] = 2e-3 * sin(100 * x) * cos(80 * y);
        m.u[D * n + 3] += -15e-6 * cos(200 * y);
        m.u[D * n + 4] += 5e-6 * sin(150 * x);
    }
    for (int q = 0; q < 3 * m.el.n_tris + 4 * m.el.n_quads; q++)
        m.state[q] = 0.01 * (q % 5);
    double *f_ref = calloc((size_t)m.n_dofs, sizeof(double));
    double *f_fast = calloc((size_t)m.n_dofs, sizeof(double));
    double *gf_copy = malloc(sizeof(double) * (size_t)(3 * m.el.n_tris + 4 * m.el.n_quads));
    memcpy(gf_copy, m.state, sizeof(double) * (size_t)(3 * m.el.n_tris + 4 * m.el.n_quads));
    wff_force_totals t_ref, t_fast;
    m.em.reference_path = 1;
    wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, m.state, 0, f_ref, &t_ref);
    m.em.reference_path = 0;
    wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, gf_copy, 0, f_fast, &t_fast);
    double scale = 0, diff = 0;
    for (int i = 0; i < m.n_dofs; i++) {
        scale = fmax(scale, fabs(f_ref[i]));
        diff = fmax(diff, fabs(f_fast[i] - f_ref[i]));
    }
    CHECK(st, t_ref.bad_element < 0 && t_fast.bad_element < 0, "%s: no bad element", what);
    CHECK(st, diff <= 1e-12 * scale, "%s: fast path forces differ by %.3g of %.3g", what, diff,
          scale);
    CHECK_CLOSE(st, t_fast.internal_energy, t_ref.internal_energy, 1e-12, 0, "fast path energy");
    double mech[WFF_MECH_MAX], sum = 0;
    wff_elements_energy_split(&m.el, &m.em, m.mesh.xy, m.u, m.state, mech);
    int active = 0;
    for (int k = 0; k < m.mat.cell->n_mech; k++) {
        sum += mech[k];
        active += mech[k] != 0;
    }
    CHECK(st, active == m.mat.cell->n_mech, "%s: %d of %d mechanisms hold energy", what, active,
          m.mat.cell->n_mech);
    CHECK_CLOSE(st, sum, t_ref.internal_energy, 1e-12, 0, "energy split sums to the stored energy");
    free(f_ref);
    free(f_fast);
    free(gf_copy);
    wff_model_free(&m);
}

static void check_split_and_fast(check_state *st)
{
    split_and_fast_case(st, TEST_MESH_TRI, "triangles");
    split_and_fast_case(st, TEST_MESH_QUAD, "quads");
}

/* Amplitude knobs: (a) static amplitudes reproduce the balanced dynamic state
 * under a uniform F and set no amplitude step limit; (b) the amplitude-mass
 * factor scales the amplitude masses only, and the amplitude step limit by its
 * square root. */
static void check_amplitude_knobs(check_state *st)
{
    test_rect r = {0, 0.04, 0, 0.03, 6, 5, TEST_MESH_TRI, 1, 0.2, 99};
    wff_model m;
    wff_error err;
    int rc = test_model_rect(&m, &r, KEVLAR, &err);
    CHECK(st, rc == 0, "%s", err.message);
    if (rc)
        return;
    const double F[6] = {1.012, 0.03, 0.0, 1.004, 0.0, 0.0};
    double dA[2] = {0, 0};
    rc = wff_balance_amplitudes(&m.mat, F, wff_rest_state, dA, &err);
    CHECK(st, rc == 0, "%s", err.message);
    for (int n = 0; n < m.n_nodes; n++) {
        double X = m.mesh.xy[2 * n], Y = m.mesh.xy[2 * n + 1];
        m.u[D * n] = (F[0] - 1) * X + F[1] * Y;
        m.u[D * n + 1] = F[2] * X + (F[3] - 1) * Y;
        m.u[D * n + 3] = dA[0];
        m.u[D * n + 4] = dA[1];
    }
    size_t nd = (size_t)m.n_dofs;
    double *f_dyn = calloc(nd, sizeof(double)), *f_sta = calloc(nd, sizeof(double));
    wff_force_totals t_dyn, t_sta;
    wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, m.state, 0, f_dyn, &t_dyn);
    int worst_dyn;
    double dt_dyn = wff_elements_stable_step(&m.el, &m.em, m.mesh.xy, m.u, &worst_dyn);
    const double guess[2] = {0, 0};
    rc = wff_elements_static_amplitudes(&m.el, &m.em, guess, &err);
    CHECK(st, rc == 0, "%s", err.message);
    wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, m.state, 0, f_sta, &t_sta);
    double scale = 0, diff = 0, amp = 0, point_err = 0;
    for (size_t i = 0; i < nd; i++) {
        scale = fmax(scale, fabs(f_dyn[i]));
        if (i % D < 3)
            diff = fmax(diff, fabs(f_sta[i] - f_dyn[i]));
        else
            amp = fmax(amp, fabs(f_sta[i]));
    }
    for (int q = 0; q < 3 * m.el.n_tris; q++)
        for (int k = 0; k < 2; k++)
            point_err = fmax(point_err, fabs(m.el.point_dA[2 * q + k] - dA[k]));
    printf("  static amplitudes: points within %.2e m of the balance, forces differ by %.2e of %.3g\n",
           point_err, diff / scale, scale);
    CHECK(st, point_err < 1e-12, "static amplitudes solve the balance: %g m off", point_err);
    CHECK(st, diff <= 1e-8 * scale, "static = balanced dynamic forces: %g of %g", diff, scale);
    CHECK(st, amp == 0, "no amplitude forces in static mode: %g", amp);
    CHECK_CLOSE(st, t_sta.internal_energy, t_dyn.internal_energy, 1e-9, 0, "static energy");
    /* the split and the element-centre evaluation read the points' own amplitudes: move the
     * nodal ones away and nothing may change */
    for (int n = 0; n < m.n_nodes; n++)
        m.u[D * n + 3] = m.u[D * n + 4] = 7e-6;
    double mech[WFF_MECH_MAX], split = 0;
    wff_elements_energy_split(&m.el, &m.em, m.mesh.xy, m.u, m.state, mech);
    for (int k = 0; k < m.mat.cell->n_mech; k++)
        split += mech[k];
    CHECK_CLOSE(st, split, t_sta.internal_energy, 1e-9, 0, "static: split = stored energy");
    wff_point_result centre;
    wff_element_center_eval(&m.el, &m.em, m.mesh.xy, m.u, m.state, 0, &centre);
    CHECK(st, fabs(centre.residual[0]) < 1e-6 * fabs(centre.diag[4]) / 5.58e-7,
          "static: the element centre is balanced (R1 %g)", centre.residual[0]);
    for (int n = 0; n < m.n_nodes; n++) {
        m.u[D * n + 3] = dA[0];
        m.u[D * n + 4] = dA[1];
    }
    int worst_sta;
    double dt_sta = wff_elements_stable_step(&m.el, &m.em, m.mesh.xy, m.u, &worst_sta);
    CHECK(st, dt_sta > 1.5 * dt_dyn, "static amplitudes lift the amplitude step limit: %g vs %g",
          dt_sta, dt_dyn);
    m.em.static_amplitudes = 0;

    /* mass factor */
    double *before = malloc(sizeof(double) * nd);
    memcpy(before, m.mass, sizeof(double) * nd);
    m.em.amplitude_mass_factor = 4;
    wff_elements_masses(&m.el, &m.em, m.n_nodes, m.mass);
    int bad = 0;
    for (size_t i = 0; i < nd; i++)
        bad += i % D < 3 ? m.mass[i] != before[i] : fabs(m.mass[i] - 4 * before[i]) > 1e-15 * m.mass[i];
    CHECK(st, bad == 0, "mass factor 4 scales only the amplitude masses (%d wrong)", bad);
    int worst4;
    double dt4 = wff_elements_stable_step(&m.el, &m.em, m.mesh.xy, m.u, &worst4);
    printf("  stable step: dynamic %.3g s, static %.3g s, mass factor 4 %.3g s\n", dt_dyn, dt_sta,
           dt4);
    CHECK(st, dt4 > dt_dyn * 1.2 && dt4 <= 2.0000001 * dt_dyn,
          "mass factor 4 raises the amplitude-limited step by at most 2: %g vs %g", dt4, dt_dyn);
    free(before);
    free(f_dyn);
    free(f_sta);
    wff_model_free(&m);
}

/* Threads: the force pass with 2 threads gives the 1-thread forces to
 * round-off, and the same bits on every run with 2. */
static void check_threads(check_state *st)
{
    test_rect r = {0, 0.2, 0, 0.1, 40, 20, TEST_MESH_TRI, 1, 0.2, 5}; /* 1600 triangles */
    wff_model m;
    wff_error err;
    int rc = test_model_rect(&m, &r, KEVLAR, &err);
    CHECK(st, rc == 0, "%s", err.message);
    if (rc)
        return;
    if (m.el.max_threads < 2) {
        printf("  threads: OpenMP offers 1 thread here; the 2-thread check is skipped\n");
        wff_model_free(&m);
        return;
    }
    for (int n = 0; n < m.n_nodes; n++) {
        double x = m.mesh.xy[2 * n], y = m.mesh.xy[2 * n + 1];
        m.u[D * n] = 0.01 * x + 1e-4 * sin(200 * y);
        m.u[D * n + 2] = 1e-3 * sin(60 * x) * sin(90 * y);
        m.u[D * n + 3] = -10e-6 * (1 + sin(50 * x));
        m.u[D * n + 4] = -20e-6;
    }
    size_t nd = (size_t)m.n_dofs, nq = (size_t)(3 * m.el.n_tris);
    double *f1 = calloc(nd, sizeof(double)), *f2 = calloc(nd, sizeof(double)), *f3 = calloc(nd, sizeof(double));
    double *g1 = malloc(nq * sizeof(double)), *g2 = malloc(nq * sizeof(double)), *g3 = malloc(nq * sizeof(double));
    for (size_t q = 0; q < nq; q++)
        g1[q] = g2[q] = g3[q] = 0.001 * (double)(q % 7);
    wff_force_totals t1, t2, t3;
    wff_elements_set_threads(&m.el, 1, &err);
    wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, g1, 1e-7, f1, &t1);
    wff_elements_set_threads(&m.el, 2, &err);
    m.el.team_min_tris = 0; /* a team on this small mesh too: the threaded pass is under test */
    wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, g2, 1e-7, f2, &t2);
    wff_elements_forces(&m.el, &m.em, m.mesh.xy, m.u, g3, 1e-7, f3, &t3);
    double scale = 0, diff = 0;
    for (size_t i = 0; i < nd; i++) {
        scale = fmax(scale, fabs(f1[i]));
        diff = fmax(diff, fabs(f2[i] - f1[i]));
    }
    printf("  threads: 2 vs 1 thread forces differ by %.2e of %.3g\n", diff / scale, scale);
    CHECK(st, diff <= 1e-12 * scale, "2 threads = 1 thread to round-off: %g of %g", diff, scale);
    CHECK_CLOSE(st, t2.internal_energy, t1.internal_energy, 1e-12, 0, "energy with 2 threads");
    CHECK(st, memcmp(g1, g2, nq * sizeof(double)) == 0, "gamma_f updated identically");
    CHECK(st, memcmp(f2, f3, nd * sizeof(double)) == 0 && t2.internal_energy == t3.internal_energy,
          "2 threads give the same bits twice");
    CHECK(st, wff_elements_set_threads(&m.el, m.el.max_threads + 1, &err) == -1 &&
                  strstr(err.message, "threads"), "too many threads refused: %s", err.message);
    free(f1);
    free(f2);
    free(f3);
    free(g1);
    free(g2);
    free(g3);
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    check_patch(&st);
    check_masses(&st);
    check_degenerate(&st);
    check_split_and_fast(&st);
    check_amplitude_knobs(&st);
    check_threads(&st);
    return check_summary(&st, "test_membrane");
}

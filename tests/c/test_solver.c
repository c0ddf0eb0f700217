/* Explicit solver (docs/model.md §14): momentum and energy conservation, quarter
 * model against the full one, tri against quad strips and strips against
 * the static uniaxial balance. */
#include "check.h"
#include "rng.h"
#include "test_meshes.h"
#include "test_ramp.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define ELASTIC "tests/data/king_elastic.txt"
#define D WFF_DOFS_PER_NODE
#define NOSE_RADIUS 6.35e-3

static int make(check_state *st, wff_model *m, const test_rect *r, const char *material)
{
    wff_error err;
    int rc = test_model_rect(m, r, material, &err);
    CHECK(st, rc == 0, "%s", err.message);
    return rc;
}

static int fix_edges(check_state *st, wff_model *m, const char *const *groups, int n_groups,
                     int c0, int c1)
{
    wff_error err;
    for (int g = 0; g < n_groups; g++)
        for (int c = c0; c <= c1; c++)
            if (wff_model_fix_group(m, groups[g], c, &err) < 0) {
                CHECK(st, 0, "%s", err.message);
                return -1;
            }
    return 0;
}

static int advance(check_state *st, wff_model *m, double t_end, long steps, const char *what)
{
    wff_error err;
    int rc = wff_model_advance(m, t_end, steps, &err);
    CHECK(st, rc == 0, "%s: %s", what, rc ? err.message : "");
    return rc;
}

/* Σ m v over the fabric (v is the half-step velocity) and Σ m |v|. */
static void momentum(const wff_model *m, double p[3], double *scale)
{
    p[0] = p[1] = p[2] = 0;
    *scale = 0;
    for (int n = 0; n < m->n_nodes; n++)
        for (int i = 0; i < 3; i++) {
            p[i] += m->mass[D * n + i] * m->v[D * n + i];
            *scale += m->mass[D * n + i] * fabs(m->v[D * n + i]);
        }
}

/* 2a. Free square, random displacements and velocities: Σ m v is conserved. */
static void momentum_free(check_state *st, int type, const char *what)
{
    test_rect r = {-0.02, 0.02, -0.02, 0.02, 8, 8, type, 1, 0.2, 99};
    wff_model m;
    if (make(st, &m, &r, KEVLAR))
        return;
    wff_rng g = {2024};
    for (int n = 0; n < m.n_nodes; n++) {
        double *u = m.u + D * n, *v = m.v + D * n;
        u[0] = wff_rng_uniform(&g, -1, 1) * 2e-5;
        u[1] = wff_rng_uniform(&g, -1, 1) * 2e-5;
        u[2] = wff_rng_uniform(&g, -1, 1) * 2e-4;
        u[3] = wff_rng_uniform(&g, -3, 1) * 1e-6;
        u[4] = wff_rng_uniform(&g, -3, 1) * 1e-6;
        for (int i = 0; i < 3; i++)
            v[i] = wff_rng_uniform(&g, -1, 1);
        v[3] = wff_rng_uniform(&g, -1, 1) * 0.01;
        v[4] = wff_rng_uniform(&g, -1, 1) * 0.01;
    }
    double p0[3], p1[3], s0, s1;
    momentum(&m, p0, &s0);
    if (advance(st, &m, 1, 200, what) == 0) {
        momentum(&m, p1, &s1);
        double worst = 0;
        for (int i = 0; i < 3; i++)
            worst = fmax(worst, fabs(p1[i] - p0[i]));
        printf("  momentum, free %-10s 200 steps: |dP| / sum m|v| = %.2e (P0 = %.3e %.3e %.3e)\n",
               what, worst / s0, p0[0], p0[1], p0[2]);
        CHECK(st, worst <= 1e-13 * s0, "%s: momentum drift %g, scale %g", what, worst, s0);
    }
    wff_model_free(&m);
}

/* 2b. Projectile (μ = 0.3) on a free fabric: z momentum of fabric and projectile. */
static void momentum_projectile(check_state *st)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, 12, 12, TEST_MESH_TRI, 1, 0.2, 5};
    wff_model m;
    if (make(st, &m, &r, KEVLAR))
        return;
    wff_error err;
    double M = 0.01, V = 20;
    int rc = wff_model_set_projectile(&m, NOSE_RADIUS, M, V, 0.3, &err);
    CHECK(st, rc == 0, "%s", err.message);
    double p[3], s, worst = 0;
    for (int block = 0; block < 4 && rc == 0; block++) {
        rc = advance(st, &m, 1, 100, "projectile on free fabric");
        momentum(&m, p, &s);
        worst = fmax(worst, fabs(p[2] + m.projectile.mass * m.projectile.velocity - M * V));
    }
    wff_energies e;
    wff_model_energies(&m, &e);
    printf("  momentum, projectile mu 0.3 on free fabric, %ld steps: |dPz| / MV = %.2e; "
           "projectile %.3f m/s, friction dissipated %.3e J, energy error %.2e\n", m.step,
           worst / (M * V), m.projectile.velocity, e.dissipated_friction, e.error);
    CHECK(st, m.projectile.velocity < V, "the projectile touched the fabric (slowed to %g m/s)",
          m.projectile.velocity);
    CHECK(st, e.dissipated_friction > 0, "friction acted: %g J", e.dissipated_friction);
    CHECK(st, worst <= 1e-13 * M * V, "z momentum drift %g of %g", worst, M * V);
    wff_model_free(&m);
}

/* 3. Clamped square hit by a light projectile (μ = 0, 0.5 g at 20 m/s, so
 * the fabric takes a real share): the energy balance holds within 0.5 % of
 * the reference at every block end, and also within 0.5 % of the energy the
 * fabric holds (catches first-order bookkeeping errors in the contact); with
 * shear flow on, energy is dissipated and the balance still holds. */
static void energy_case(check_state *st, const char *material, int type, const char *what,
                        int expect_flow)
{
    test_rect r = {-0.05, 0.05, -0.05, 0.05, 20, 20, type, 1, 0, 0};
    wff_model m;
    if (make(st, &m, &r, material))
        return;
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    wff_error err;
    if (fix_edges(st, &m, edges, 4, WFF_UX, WFF_UZ))
        goto done;
    double M = 0.0005, V = 20;
    int rc = wff_model_set_projectile(&m, NOSE_RADIUS, M, V, 0, &err);
    CHECK(st, rc == 0, "%s", err.message);
    double worst = 0, worst_fabric = 0, fabric = 0;
    wff_energies e;
    for (int block = 1; block <= 10 && rc == 0; block++) {
        rc = advance(st, &m, block * 0.02e-3, 1000000, what);
        wff_model_energies(&m, &e);
        fabric = e.kinetic_inplane + e.kinetic_transverse + e.kinetic_amplitude + e.internal;
        double absolute = fabs(e.error) * e.reference;
        worst = fmax(worst, fabs(e.error));
        worst_fabric = fmax(worst_fabric, absolute / fabric);
        CHECK(st, fabs(e.error) < 0.005, "%s: energy error %.3g at t = %g s", what, e.error,
              m.time);
        CHECK(st, absolute < 0.005 * fabric, "%s: energy error %.3g J, fabric holds %.3g J at "
              "t = %g s", what, absolute, fabric, m.time);
    }
    printf("  energy %-19s %ld steps to %.2g s: max |error| %.2e of the reference, %.2e of the "
           "fabric's energy; fabric holds %.1f%% of %.3f J (internal %.3e, kinetic %.3e J), "
           "contact and friction %.3e J, shear dissipated %.3e J, projectile %.2f m/s\n",
           what, m.step, m.time, worst, worst_fabric, 100 * fabric / (0.5 * M * V * V),
           0.5 * M * V * V, e.internal,
           e.kinetic_inplane + e.kinetic_transverse + e.kinetic_amplitude,
           e.dissipated_friction, e.dissipated_shear, m.projectile.velocity);
    CHECK(st, fabric > 0.1 * 0.5 * M * V * V, "%s: the fabric takes a real share: %g J", what,
          fabric);
    if (expect_flow)
        CHECK(st, e.dissipated_shear > 0, "%s: shear flow dissipates: %g J", what,
              e.dissipated_shear);
    else
        CHECK(st, e.dissipated_shear == 0, "%s: elastic: %g J", what, e.dissipated_shear);
done:
    wff_model_free(&m);
}

static void check_energy(check_state *st)
{
    energy_case(st, ELASTIC, TEST_MESH_QUAD, "elastic, quads", 0);
    energy_case(st, ELASTIC, TEST_MESH_TRI, "elastic, triangles", 0);
    energy_case(st, KEVLAR, TEST_MESH_QUAD, "shear flow, quads", 1);
}

/* 4. Quarter model with symmetry conditions against the full square. */
static void check_quarter(check_state *st)
{
    const double L = 0.04, M = 0.02, V = 20, mu = 0.3;
    const int n = 8; /* cells per half side */
    test_rect rf = {-L, L, -L, L, 2 * n, 2 * n, TEST_MESH_QUAD, 0, 0, 0};
    test_rect rq = {0, L, 0, L, n, n, TEST_MESH_QUAD, 0, 0, 0};
    wff_model full, quarter;
    if (make(st, &full, &rf, KEVLAR))
        return;
    if (make(st, &quarter, &rq, KEVLAR)) {
        wff_model_free(&full);
        return;
    }
    static const char *const all[] = {"left", "right", "bottom", "top"};
    static const char *const outer[] = {"right", "top"};
    wff_error err;
    int rc = fix_edges(st, &full, all, 4, WFF_UX, WFF_UZ) ||
             fix_edges(st, &quarter, outer, 2, WFF_UX, WFF_UZ) ||
             wff_model_fix_group(&quarter, "left", WFF_UX, &err) < 0 ||
             wff_model_fix_group(&quarter, "bottom", WFF_UY, &err) < 0 ||
             wff_model_set_option(&quarter, "symmetry", 4, &err) ||
             wff_model_set_projectile(&full, NOSE_RADIUS, M, V, mu, &err) ||
             wff_model_set_projectile(&quarter, NOSE_RADIUS, M, V, mu, &err); /* whole mass */
    CHECK(st, rc == 0, "quarter/full setup: %s", err.message);
    int af = wff_model_nearest_node(&full, 0, 0), aq = wff_model_nearest_node(&quarter, 0, 0);
    CHECK(st, full.mesh.xy[2 * af] == 0 && full.mesh.xy[2 * af + 1] == 0 && aq == 0,
          "apex nodes at the origin");
    double worst_u = 0, worst_e = 0, uz = 0;
    for (int block = 0; block < 8 && rc == 0; block++) {
        if (advance(st, &full, 1, 50, "full") || advance(st, &quarter, 1, 50, "quarter"))
            break;
        uz = full.u[D * af + 2];
        worst_u = fmax(worst_u, fabs(quarter.u[D * aq + 2] - uz) / fabs(uz));
        wff_energies ef, eq;
        wff_model_energies(&full, &ef);
        wff_model_energies(&quarter, &eq);
        double a[] = {ef.kinetic_inplane, ef.kinetic_transverse, ef.kinetic_amplitude,
                      ef.kinetic_projectile, ef.internal, ef.dissipated_shear,
                      ef.dissipated_friction};
        double b[] = {eq.kinetic_inplane, eq.kinetic_transverse, eq.kinetic_amplitude,
                      eq.kinetic_projectile, eq.internal, eq.dissipated_shear,
                      eq.dissipated_friction};
        for (int i = 0; i < 7; i++)
            worst_e = fmax(worst_e, fabs(a[i] - b[i]) / (0.5 * M * V * V));
        CHECK(st, fabs(full.time - quarter.time) <= 1e-12 * full.time, "same time: %.17g %.17g",
              full.time, quarter.time);
    }
    wff_energies ef;
    wff_model_energies(&full, &ef);
    printf("  quarter vs full (%dx%d quads vs %dx%d), %ld steps: apex uz %.4e m, max relative "
           "difference %.2e; energies differ by %.2e of the impact energy (internal %.3e J, "
           "friction %.3e J)\n", 2 * n, 2 * n, n, n, full.step, uz, worst_u, worst_e,
           ef.internal, ef.dissipated_friction);
    CHECK(st, uz > 1e-4, "the apex moved: %g m", uz);
    CHECK(st, ef.dissipated_friction > 0, "contact off the axis (friction): %g J",
          ef.dissipated_friction);
    CHECK(st, worst_u < 1e-8, "apex uz quarter vs full: %g", worst_u);
    CHECK(st, worst_e < 1e-8, "energies quarter vs full: %g", worst_e);
    wff_model_free(&full);
    wff_model_free(&quarter);
}

/* A strip pulled along `family` (0: x, "right" moves; 1: y, "top" moves):
 * the fixed end holds the pulled component and u_z, one corner node holds
 * the other in-plane component, so the strip may contract freely. Smooth
 * velocity ramp up and down to `strain`, then held; the load per width, the
 * stretch and the nodal amplitudes in the middle third are averaged over the
 * hold. */
typedef struct strip_result {
    double load;        /* reaction per reference width, N/m */
    double strain;      /* nominal: end displacement / length */
    double dA[2];       /* middle-third nodal mean, m */
    double strain_mid;  /* between the nodes at L/4 and 3L/4 */
    double load_spread; /* (max − min)/mean of the load over the hold */
    long steps;
} strip_result;

static int strip_run(check_state *st, int type, int family, double strain, strip_result *out)
{
    const double length = 0.05, width = 0.01;
    const int nl = 16, nw = 2; /* cells along and across; nl divisible by 4 */
    test_rect r = family == 0 ? (test_rect){0, length, 0, width, nl, nw, type, 1, 0, 0}
                              : (test_rect){0, width, 0, length, nw, nl, type, 1, 0, 0};
    wff_model m;
    if (make(st, &m, &r, KEVLAR))
        return -1;
    const char *fixed = family ? "bottom" : "left", *moved = family ? "top" : "right";
    int along = family ? WFF_UY : WFF_UX, across = family ? WFF_UX : WFF_UY;
    wff_error err;
    int rc = wff_model_fix_group(&m, fixed, along, &err) < 0 ||
             wff_model_fix_group(&m, fixed, WFF_UZ, &err) < 0;
    CHECK(st, rc == 0, "%s", err.message);
    m.dof_kind[D * 0 + across] = WFF_DOF_FIXED; /* corner node (0, 0) */
    /* v(t): (1 − cos) ramp over t_ramp, cruise at V, ramp down, hold */
    const double V = 1.5, t_ramp = 0.3e-3, block = 5e-6;
    const double t_cruise = strain * length / V - t_ramp, t_move = 2 * t_ramp + t_cruise;
    const double t_hold = 0.25e-3;
    int samples = 0;
    double load_min = INFINITY, load_max = -INFINITY;
    memset(out, 0, sizeof *out);
    while (rc == 0 && m.time < t_move + t_hold) {
        double t = m.time + 0.5 * block, v = test_ramp_velocity(t, V, t_ramp, t_cruise);
        if (wff_model_prescribe_group(&m, moved, along, v, &err) < 0) {
            CHECK(st, 0, "%s", err.message);
            rc = -1;
            break;
        }
        if ((rc = advance(st, &m, m.time + block, 1000000, "strip")) != 0)
            break;
        if (m.time < t_move + 0.2 * t_hold)
            continue;
        double load;
        wff_model_group_reaction(&m, moved, along, &load, &err);
        load /= width;
        double dA[2] = {0, 0};
        int count = 0;
        for (int n = 0; n < m.n_nodes; n++) {
            double X = m.mesh.xy[2 * n + family];
            if (X < length / 3 || X > 2 * length / 3)
                continue;
            dA[0] += m.u[D * n + WFF_DA1];
            dA[1] += m.u[D * n + WFF_DA2];
            count++;
        }
        double mid = 0;
        for (int k = 0; k <= nw; k++) { /* nodes k across, at L/4 and 3L/4 along */
            int a = family ? (nl / 4) * (nw + 1) + k : k * (nl + 1) + nl / 4;
            int b = family ? (3 * nl / 4) * (nw + 1) + k : k * (nl + 1) + 3 * nl / 4;
            mid += (m.u[D * b + along] - m.u[D * a + along]) /
                   (m.mesh.xy[2 * b + family] - m.mesh.xy[2 * a + family]) / (nw + 1);
        }
        out->strain_mid += mid;
        out->load += load;
        out->dA[0] += dA[0] / count;
        out->dA[1] += dA[1] / count;
        load_min = fmin(load_min, load);
        load_max = fmax(load_max, load);
        samples++;
    }
    if (rc == 0 && samples > 0) {
        out->load /= samples;
        out->dA[0] /= samples;
        out->dA[1] /= samples;
        out->strain_mid /= samples;
        out->load_spread = (load_max - load_min) / out->load;
        /* end displacement: every node of the moved edge has the same */
        int corner = family ? m.n_nodes - 1 : nl;
        out->strain = m.u[D * corner + along] / length;
        out->steps = m.step;
    }
    wff_model_free(&m);
    return rc || samples == 0 ? -1 : 0;
}

/* 6. and 7. */
static void check_strips(check_state *st)
{
    const double strain = 0.018;
    wff_material mat;
    wff_error err;
    if (wff_material_load(KEVLAR, &mat, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    strip_result quad[2], tri;
    for (int family = 0; family < 2; family++) {
        if (strip_run(st, TEST_MESH_QUAD, family, strain, &quad[family]))
            return;
        const strip_result *q = &quad[family];
        wff_biaxial_state s = {.stretch = {1, 1}};
        int rc = wff_uniaxial_static(&mat, family, 1 + q->strain, &s, &err);
        CHECK(st, rc == 0, "%s", err.message);
        double P = s.resultant[family];
        printf("  strip %s, quads, %ld steps, nominal strain %.4f%% (middle %.4f%%): load %.2f "
               "N/m (static %.2f, ratio %.4f, spread over hold %.2f%%); dA1 %.3f um (static "
               "%.3f, ratio %.4f), dA2 %.3f um (static %.3f, ratio %.4f)\n",
               family ? "weft" : "warp", q->steps, 100 * q->strain, 100 * q->strain_mid, q->load,
               P, q->load / P, 100 * q->load_spread, 1e6 * q->dA[0],
               1e6 * s.dA[0], q->dA[0] / s.dA[0], 1e6 * q->dA[1], 1e6 * s.dA[1],
               q->dA[1] / s.dA[1]);
        CHECK(st, fabs(q->strain - strain) < 0.02 * strain, "reached strain %g", q->strain);
        CHECK(st, fabs(q->strain_mid / q->strain - 1) < 0.02, "uniform middle: strain %g",
              q->strain_mid);
        CHECK(st, fabs(q->load / P - 1) < 0.02, "load vs static: %g", q->load / P);
        CHECK(st, fabs(q->dA[0] / s.dA[0] - 1) < 0.02, "dA1 vs static: %g", q->dA[0] / s.dA[0]);
        CHECK(st, fabs(q->dA[1] / s.dA[1] - 1) < 0.02, "dA2 vs static: %g", q->dA[1] / s.dA[1]);
    }
    if (strip_run(st, TEST_MESH_TRI, 0, strain, &tri))
        return;
    printf("  strip warp, triangles, %ld steps, nominal strain %.4f%%: load %.2f N/m, ratio to "
           "quads %.4f\n", tri.steps, 100 * tri.strain, tri.load, tri.load / quad[0].load);
    CHECK(st, fabs(tri.load / quad[0].load - 1) < 0.02, "tri vs quad load: %g",
          tri.load / quad[0].load);
}

/* Solver knobs change what they should and only that: a clamped square
 * struck by a light projectile, run with each knob against the default. */
typedef struct knob_run { double apex[20]; double dt, energy_error; long steps; int ok; } knob_run;

static knob_run knob_case(check_state *st, const char *key, double value, const char *material)
{
    knob_run out = {{0}, 0, 0, 0, 0};
    test_rect r = {-0.05, 0.05, -0.05, 0.05, 16, 16, TEST_MESH_TRI, 1, 0, 0};
    wff_model m;
    if (make(st, &m, &r, material))
        return out;
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    wff_error err;
    const double F_pre[4] = {1.003963, 0, 0, 1.013476}, dA0[2] = {-9.311e-6, -23.748e-6};
    int rc = wff_model_set_preload(&m, F_pre, dA0, &err);
    if (!rc)
        rc = fix_edges(st, &m, edges, 4, WFF_UX, WFF_UZ);
    if (!rc)
        rc = wff_model_set_projectile(&m, NOSE_RADIUS, 0.0005, 20, 0.3, &err);
    if (!rc && key)
        rc = wff_model_set_option(&m, key, value, &err);
    CHECK(st, rc == 0, "knob %s = %g: %s", key ? key : "none", value, rc ? err.message : "");
    int apex = wff_model_nearest_node(&m, 0, 0);
    for (int k = 0; k < 20 && rc == 0; k++) {
        rc = advance(st, &m, (k + 1) * 0.01e-3, 1000000, key ? key : "default");
        out.apex[k] = m.u[D * apex + WFF_UZ];
    }
    wff_energies e;
    wff_model_energies(&m, &e);
    out.dt = m.dt;
    out.steps = m.step;
    out.energy_error = e.error;
    out.ok = rc == 0;
    if (key && strcmp(key, "static_amplitudes") == 0 && value == 1) {
        double amp_v = 0;
        for (int n = 0; n < m.n_nodes; n++)
            amp_v = fmax(amp_v, fmax(fabs(m.v[D * n + 3]), fabs(m.v[D * n + 4])));
        CHECK(st, amp_v == 0, "static amplitudes: nodal amplitude DOFs stay at rest (%g)", amp_v);
    }
    wff_model_free(&m);
    return out;
}

static double apex_diff(const knob_run *a, const knob_run *b)
{
    double d = 0, s = 0;
    for (int k = 0; k < 20; k++) {
        d = fmax(d, fabs(a->apex[k] - b->apex[k]));
        s = fmax(s, fabs(b->apex[k]));
    }
    return d / s;
}

static void check_knobs(check_state *st)
{
    knob_run base = knob_case(st, NULL, 0, KEVLAR);
    knob_run all = knob_case(st, "contact_search", 0, KEVLAR);
    knob_run thr = knob_case(st, "threads", 1, KEVLAR);
    knob_run mass = knob_case(st, "amplitude_mass_factor", 10, KEVLAR);
    knob_run sta = knob_case(st, "static_amplitudes", 1, KEVLAR);
    knob_run fac = knob_case(st, "dtfactor", 0.4, KEVLAR);
    printf("  knobs: apex at 0.2 ms %.4g mm; vs default: contact everywhere %.1e, mass x10 %.2e "
           "(dt %.3g vs %.3g s), static amplitudes %.2e (dt %.3g s), dtfactor 0.4 %.2e\n",
           1e3 * base.apex[19], apex_diff(&all, &base), apex_diff(&mass, &base), mass.dt, base.dt,
           apex_diff(&sta, &base), sta.dt, apex_diff(&fac, &base));
    CHECK(st, base.ok && all.ok && thr.ok && mass.ok && sta.ok && fac.ok, "all knob runs ran");
    CHECK(st, apex_diff(&all, &base) == 0 && all.steps == base.steps,
          "searching every node for contact changes nothing but the cost");
    CHECK(st, apex_diff(&thr, &base) == 0, "threads = 1 is the default");
    CHECK(st, mass.dt > 1.3 * base.dt, "heavier amplitudes allow a longer step: %g vs %g", mass.dt,
          base.dt);
    CHECK(st, sta.dt > 1.3 * base.dt, "static amplitudes lift the amplitude step limit: %g vs %g",
          sta.dt, base.dt);
    CHECK(st, fabs(fac.dt / base.dt - 0.5) < 0.05, "dtfactor 0.4 halves the 0.8 step: %g",
          fac.dt / base.dt);
    /* approximations stay close to the default answer, but are not it */
    CHECK(st, apex_diff(&mass, &base) > 0 && apex_diff(&mass, &base) < 0.05,
          "mass factor 10 changes the apex a little: %g", apex_diff(&mass, &base));
    /* static amplitudes are a different model (no crimp inertia): how far it is
     * from the paper's is measured by make bench (6 % on this small square),
     * here only that it is the same impact: the same apex to within half */
    CHECK(st, apex_diff(&sta, &base) > 0 && apex_diff(&sta, &base) < 0.5,
          "static amplitudes give a different but comparable apex: %g", apex_diff(&sta, &base));
    CHECK(st, apex_diff(&fac, &base) < 0.01, "a smaller step agrees: %g", apex_diff(&fac, &base));
    CHECK(st, fabs(mass.energy_error) < 0.005 && fabs(sta.energy_error) < 0.005,
          "energy balance holds with the knobs: %g, %g", mass.energy_error, sta.energy_error);
}

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int main(void)
{
    check_state st = {0, 0};
    double t0 = seconds();
    momentum_free(&st, TEST_MESH_TRI, "triangles");
    momentum_free(&st, TEST_MESH_QUAD, "quads");
    momentum_projectile(&st);
    double t1 = seconds();
    check_energy(&st);
    double t2 = seconds();
    check_quarter(&st);
    double t3 = seconds();
    check_strips(&st);
    double t4 = seconds();
    check_knobs(&st);
    printf("  timings: momentum %.2f s, energy %.2f s, quarter %.2f s, strips %.2f s\n", t1 - t0,
           t2 - t1, t3 - t2, t4 - t3);
    return check_summary(&st, "test_solver");
}

/* The projectile (docs/model.md §16): each nose shape's penetration and
 * normal against the exact geometry; a flat nose on a pretensioned membrane
 * takes every node under its face at the first contact; the energy balance of
 * an impact with each shape, off the centre; the whole-specimen convention
 * (masses and clamp forces divided by the symmetry in any order of calls,
 * axes off the symmetry planes refused); and the contracts (preload,
 * symmetry, shape and impact point after the first step, a second
 * projectile, fixed against prescribed DOFs, advancing to NaN, inf or
 * backwards). */
#include "check.h"
#include "rng.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define ELASTIC "tests/data/king_elastic.txt"
#define D WFF_DOFS_PER_NODE
#define R_NOSE 6.35e-3
#define R_EDGE 1.5e-3

static const double kPi = 3.14159265358979323846;

/* One sample: a surface point S with outward normal n; S − δn must give δ
 * and n, S + δn nothing. */
static void check_sample(check_state *st, const wff_projectile *p, const double S[3],
                         const double n[3], double delta, const char *what, double *worst)
{
    double in[3], out[3], nrm[3] = {0, 0, 0};
    for (int i = 0; i < 3; i++) {
        in[i] = S[i] - delta * n[i];
        out[i] = S[i] + delta * n[i];
    }
    double got = wff_projectile_penetration(p, in, nrm);
    double err = fabs(got - delta);
    for (int i = 0; i < 3; i++)
        err = fmax(err, R_NOSE * fabs(nrm[i] - n[i]));
    *worst = fmax(*worst, err);
    CHECK(st, err <= 1e-12 * R_NOSE, "%s: at (%g, %g, %g) penetration %.12g (want %.12g), normal "
          "(%g, %g, %g) (want %g, %g, %g)", what, in[0], in[1], in[2], got, delta, nrm[0],
          nrm[1], nrm[2], n[0], n[1], n[2]);
    double none = wff_projectile_penetration(p, out, nrm);
    CHECK(st, none == 0, "%s: a point outside at (%g, %g, %g) is %g m inside", what, out[0],
          out[1], out[2], none);
}

static void check_shapes(check_state *st)
{
    wff_projectile p;
    memset(&p, 0, sizeof p);
    p.radius = R_NOSE;
    p.tip = -2e-3;
    p.axis[0] = 0.013, p.axis[1] = -0.007;
    wff_rng g = {77};
    double worst[3] = {0, 0, 0};
    for (int k = 0; k < 400; k++) {
        double psi = wff_rng_uniform(&g, 0, 2 * kPi), c = cos(psi), s = sin(psi);
        double phi = wff_rng_uniform(&g, 0.01, 0.5 * kPi - 0.01); /* from the axis */
        double below = wff_rng_uniform(&g, 0.1, 3) * R_NOSE;      /* along the shank */
        double S[3], n[3];
        /* hemisphere: the nose (centre a radius behind the tip), the shank */
        p.nose = WFF_NOSE_HEMISPHERE, p.edge_radius = 0;
        double cz = p.tip - R_NOSE;
        n[0] = sin(phi) * c, n[1] = sin(phi) * s, n[2] = cos(phi);
        for (int i = 0; i < 3; i++)
            S[i] = (i < 2 ? p.axis[i] : cz) + R_NOSE * n[i];
        check_sample(st, &p, S, n, wff_rng_uniform(&g, 0.01, 0.45) * R_NOSE, "hemisphere nose",
                     &worst[0]);
        double nr[3] = {c, s, 0}, Sr[3] = {p.axis[0] + R_NOSE * c, p.axis[1] + R_NOSE * s,
                                           cz - below};
        check_sample(st, &p, Sr, nr, wff_rng_uniform(&g, 0.01, 0.45) * R_NOSE,
                     "hemisphere shank", &worst[0]);
        /* sphere: any direction, the back half too */
        p.nose = WFF_NOSE_SPHERE;
        double th = acos(wff_rng_uniform(&g, -0.99, 0.99));
        double ns[3] = {sin(th) * c, sin(th) * s, cos(th)}, Ss[3];
        for (int i = 0; i < 3; i++)
            Ss[i] = (i < 2 ? p.axis[i] : cz) + R_NOSE * ns[i];
        check_sample(st, &p, Ss, ns, wff_rng_uniform(&g, 0.01, 0.95) * R_NOSE, "sphere",
                     &worst[1]);
        /* flat: the face (ρ <= a at z = tip), the edge torus, the shank */
        p.nose = WFF_NOSE_FLAT, p.edge_radius = R_EDGE;
        double a = R_NOSE - R_EDGE, zc = p.tip - R_EDGE, rho = wff_rng_uniform(&g, 0, 0.95) * a;
        double nf[3] = {0, 0, 1}, Sf[3] = {p.axis[0] + rho * c, p.axis[1] + rho * s, p.tip};
        /* nearest the face while deeper than the edge's distance to the side */
        check_sample(st, &p, Sf, nf, wff_rng_uniform(&g, 0.01, 0.99) * (R_EDGE + a - rho),
                     "flat face", &worst[2]);
        double nt[3] = {sin(phi) * c, sin(phi) * s, cos(phi)}, St[3];
        St[0] = p.axis[0] + a * c + R_EDGE * nt[0];
        St[1] = p.axis[1] + a * s + R_EDGE * nt[1];
        St[2] = zc + R_EDGE * nt[2];
        check_sample(st, &p, St, nt, wff_rng_uniform(&g, 0.01, 0.99) * R_EDGE, "flat edge torus",
                     &worst[2]);
        double Sk[3] = {p.axis[0] + R_NOSE * c, p.axis[1] + R_NOSE * s, zc - below};
        /* (deeper than the edge and `below` together, the face is nearer) */
        check_sample(st, &p, Sk, nr, wff_rng_uniform(&g, 0.01, 0.99) *
                     fmin(R_NOSE, R_EDGE + below), "flat shank", &worst[2]);
    }
    /* the flat face's own points: inside by the depth below the face */
    p.nose = WFF_NOSE_FLAT;
    double x[3] = {p.axis[0], p.axis[1], p.tip - 1e-4}, nrm[3];
    CHECK_CLOSE(st, wff_projectile_penetration(&p, x, nrm), 1e-4, 1e-12, 1e-3, "flat, on axis");
    printf("  shapes, 400 samples each: largest error hemisphere %.2e m, sphere %.2e m, flat "
           "%.2e m\n", worst[0], worst[1], worst[2]);
}

/* A clamped square (edges fixed) of side 2h with n x n cells. */
static int clamped_square(check_state *st, wff_model *m, double h, int n, int type,
                          const char *material)
{
    test_rect r = {-h, h, -h, h, n, n, type, 1, 0, 0};
    wff_error err;
    int rc = test_model_rect(m, &r, material, &err);
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int e = 0; e < 4 && rc == 0; e++)
        for (int c = 0; c < 3 && rc == 0; c++)
            rc = wff_model_fix_group(m, edges[e], c, &err) < 0;
    CHECK(st, rc == 0, "clamped square: %s", err.message);
    return rc;
}

/* A flat nose on a pretensioned membrane: at the first contact (the start's
 * half step), every node under the flat face moves with the projectile and
 * nodes beyond its reach do not move; a hemisphere there takes the node under
 * its tip only. */
static void check_flat_first_contact(check_state *st)
{
    const double X = 0.004, Y = -0.003, V = 20;
    for (int nose = WFF_NOSE_HEMISPHERE; nose <= WFF_NOSE_FLAT; nose++) {
        wff_model m;
        if (clamped_square(st, &m, 0.03, 60, TEST_MESH_TRI, KEVLAR))
            return;
        wff_error err;
        const double F_pre[4] = {1.004, 0, 0, 1.013}, dA0[2] = {-9.3e-6, -23.7e-6};
        int rc = wff_model_set_preload(&m, F_pre, dA0, &err) ||
                 wff_model_set_projectile_shape(&m, nose, R_EDGE, &err) ||
                 wff_model_set_impact_point(&m, X, Y, &err) ||
                 wff_model_set_projectile(&m, R_NOSE, 0.01, V, 0, &err) ||
                 wff_model_advance(&m, 1, 0, &err); /* the start only: one contact pass */
        CHECK(st, rc == 0, "flat first contact: %s", err.message);
        if (rc) {
            wff_model_free(&m);
            return;
        }
        int under = 0, moved = 0, wrong = 0, far_moved = 0;
        double fabric_pz = 0, vz_min = INFINITY, vz_max = 0;
        double a = nose == WFF_NOSE_FLAT ? R_NOSE - R_EDGE : 0;
        for (int k = 0; k < m.n_nodes; k++) {
            double rho = hypot(m.mesh.xy[2 * k] - X, m.mesh.xy[2 * k + 1] - Y);
            double vz = m.v[D * k + 2];
            fabric_pz += m.mass[D * k + 2] * vz;
            if (vz > 0.5 * V)
                moved++;
            if (nose == WFF_NOSE_FLAT ? rho < a : rho < 1e-9) {
                under++;
                if (!(vz > 0.5 * V))
                    wrong++;
                vz_min = fmin(vz_min, vz), vz_max = fmax(vz_max, vz);
            } else if (rho > R_NOSE + 1e-3 && fabs(vz) > 1e-6 * V) {
                far_moved++;
            }
        }
        printf("  first contact, %s nose at (%g, %g): %d nodes under the face, %d moving with "
               "the projectile (%g m/s), projectile force %.4g N\n", wff_nose_name(nose), X, Y,
               under, moved, m.projectile.velocity, m.projectile.force);
        CHECK(st, wrong == 0, "%s: %d of %d nodes under the face not taken along", 
              wff_nose_name(nose), wrong, under);
        CHECK(st, far_moved == 0, "%s: %d nodes beyond the nose moved", wff_nose_name(nose),
              far_moved);
        /* the pattern: the impulses move the face's nodes with the projectile, all
         * at its speed (within the few m/s·kg it loses node by node), and the
         * fabric's momentum is what the projectile lost */
        CHECK_CLOSE(st, fabric_pz, 0.01 * (V - m.projectile.velocity), 1e-9, 1e-12,
                    "first contact: fabric momentum = projectile's loss");
        CHECK(st, vz_max - vz_min <= 0.01 * V && vz_min >= m.projectile.velocity * (1 - 1e-9),
              "%s: face nodes at the projectile's speed: %g..%g m/s (projectile %g)",
              wff_nose_name(nose), vz_min, vz_max, m.projectile.velocity);
        if (nose == WFF_NOSE_FLAT)
            CHECK(st, under > 20 && moved >= under && moved < under + 40,
                  "flat: the face's %d nodes and few more (%d) move", under, moved);
        else
            CHECK(st, moved <= 1, "hemisphere: only the node under the tip moves (%d)", moved);
        wff_model_free(&m);
    }
}

/* Energy balance of an impact (0.5 g at 20 m/s on a clamped square) with each
 * shape, off the centre. */
static void check_energy(check_state *st)
{
    const double M = 0.0005, V = 20;
    for (int nose = 0; nose < 3; nose++) {
        wff_model m;
        if (clamped_square(st, &m, 0.05, 20, TEST_MESH_QUAD, ELASTIC))
            return;
        wff_error err;
        int rc = wff_model_set_projectile(&m, R_NOSE, M, V, 0.3, &err) ||
                 wff_model_set_projectile_shape(&m, nose, R_EDGE, &err) ||
                 wff_model_set_impact_point(&m, 0.011, -0.006, &err);
        CHECK(st, rc == 0, "%s", err.message);
        double worst = 0, fabric = 0;
        wff_energies e;
        for (int block = 1; block <= 10 && rc == 0; block++) {
            rc = wff_model_advance(&m, block * 0.02e-3, 1000000, &err);
            CHECK(st, rc == 0, "%s nose: %s", wff_nose_name(nose), err.message);
            wff_model_energies(&m, &e);
            worst = fmax(worst, fabs(e.error));
            fabric = e.kinetic_inplane + e.kinetic_transverse + e.kinetic_amplitude + e.internal;
        }
        printf("  energy, %-10s nose at (0.011, -0.006), %ld steps: max |error| %.2e; fabric "
               "holds %.1f%%, contact and friction %.3e J, projectile %.2f m/s\n",
               wff_nose_name(nose), m.step, worst, 100 * fabric / (0.5 * M * V * V),
               e.dissipated_friction, m.projectile.velocity);
        CHECK(st, worst < 0.005, "%s nose: energy error %.3g", wff_nose_name(nose), worst);
        CHECK(st, fabric > 0.1 * 0.5 * M * V * V, "%s nose: the fabric takes a share: %g J",
              wff_nose_name(nose), fabric);
        int apex = wff_model_nearest_node(&m, 0.011, -0.006), centre = wff_model_nearest_node(&m, 0, 0);
        CHECK(st, m.u[D * apex + 2] > m.u[D * centre + 2], "%s nose: the fabric is deepest under "
              "the impact point (%g m there, %g at the centre)", wff_nose_name(nose),
              m.u[D * apex + 2], m.u[D * centre + 2]);
        wff_model_free(&m);
    }
}

/* Whole-specimen values in any order: a quarter model given the whole mass
 * and clamp force before or after its symmetry is the same model, step for
 * step; an axis off the symmetry planes is refused in either order. */
static void check_symmetry(check_state *st)
{
    const double M = 0.02, V = 20, N = 400;
    wff_model a, b;
    test_rect rq = {0, 0.04, 0, 0.04, 8, 8, TEST_MESH_QUAD, 0, 0, 0};
    wff_error err;
    if (test_model_rect(&a, &rq, KEVLAR, &err) || test_model_rect(&b, &rq, KEVLAR, &err)) {
        CHECK(st, 0, "%s", err.message);
        return;
    }
    int rc = wff_model_set_option(&a, "symmetry", 4, &err) ||
             wff_model_fix_group(&a, "left", WFF_UX, &err) < 0 ||
             wff_model_fix_group(&a, "bottom", WFF_UY, &err) < 0 ||
             wff_model_clamp_friction(&a, "right", N, 0.3, &err) < 0 ||
             wff_model_set_projectile(&a, R_NOSE, M, V, 0.3, &err);
    CHECK(st, rc == 0, "symmetry first: %s", err.message);
    rc = wff_model_set_projectile(&b, R_NOSE, M, V, 0.3, &err) ||
         wff_model_clamp_friction(&b, "right", N, 0.3, &err) < 0 ||
         wff_model_fix_group(&b, "bottom", WFF_UY, &err) < 0 ||
         wff_model_fix_group(&b, "left", WFF_UX, &err) < 0 ||
         wff_model_set_option(&b, "symmetry", 4, &err);
    CHECK(st, rc == 0, "symmetry last: %s", err.message);
    CHECK(st, a.projectile.mass == M / 4 && b.projectile.mass == M / 4,
          "modelled projectile mass M/4: %g, %g", a.projectile.mass, b.projectile.mass);
    double fa = 0, fb = 0;
    for (int i = 0; i < a.clamp.n; i++)
        fa += a.clamp.normal_force[i], fb += b.clamp.normal_force[i];
    CHECK_CLOSE(st, fa, N / 4, 1e-13, 1, "clamp force on the quarter (symmetry first)");
    CHECK(st, a.clamp.n == b.clamp.n && memcmp(a.clamp.normal_force, b.clamp.normal_force,
          sizeof(double) * (size_t)a.clamp.n) == 0, "the same clamp forces in both orders");
    if (wff_model_advance(&a, 1, 200, &err) || wff_model_advance(&b, 1, 200, &err))
        CHECK(st, 0, "%s", err.message);
    CHECK(st, memcmp(a.u, b.u, sizeof(double) * (size_t)a.n_dofs) == 0 &&
          a.projectile.velocity == b.projectile.velocity,
          "the same run in both orders, bit for bit (projectile %.17g, %.17g m/s)",
          a.projectile.velocity, b.projectile.velocity);
    wff_energies ea;
    wff_model_energies(&a, &ea);
    /* (read at the integer step, the velocity here is the half step's: they differ by
     * ~1e-6; a missing symmetry factor would be 4x) */
    CHECK_CLOSE(st, ea.kinetic_projectile, 0.5 * M * a.projectile.velocity * a.projectile.velocity,
                1e-4, 1e-9, "projectile kinetic energy read: the whole projectile's");
    /* after the start: symmetry, shape and impact point are fixed */
    CHECK(st, wff_model_set_option(&a, "symmetry", 1, &err) != 0 &&
          strstr(err.message, "before the first step"), "symmetry after the start: %s",
          err.message);
    CHECK(st, wff_model_set_projectile_shape(&a, WFF_NOSE_FLAT, 1e-3, &err) != 0,
          "shape after the start refused");
    CHECK(st, wff_model_set_impact_point(&a, 0, 0, &err) != 0, "impact point after the start refused");
    wff_model_free(&a);
    wff_model_free(&b);
    /* axes off the symmetry planes */
    for (int order = 0; order < 2; order++) {
        wff_model q;
        if (test_model_rect(&q, &rq, KEVLAR, &err))
            return;
        if (order == 0) {
            rc = wff_model_set_option(&q, "symmetry", 4, &err) ||
                 wff_model_set_impact_point(&q, 0.01, 0, &err);
        } else {
            rc = wff_model_set_impact_point(&q, 0.01, 0, &err) ||
                 wff_model_set_option(&q, "symmetry", 4, &err);
        }
        CHECK(st, rc != 0 && strstr(err.message, "(0.01, 0)") &&
              strstr(err.message, "symmetry 4") && strstr(err.message, "x = 0"),
              "quarter model, axis at (0.01, 0), order %d: %s", order, rc ? err.message : "");
        CHECK(st, q.symmetry_factor == (order == 0 ? 4 : 1) &&
              q.projectile.axis[0] == (order == 0 ? 0 : 0.01), "nothing changed on refusal");
        rc = wff_model_set_option(&q, "symmetry", 2, &err);
        CHECK(st, rc == 0 || order == 0, "half model struck on y = 0: %s", err.message);
        if (order == 0) {
            rc = wff_model_set_option(&q, "symmetry", 2, &err) ||
                 wff_model_set_impact_point(&q, 0.01, 0, &err);
            CHECK(st, rc == 0, "half model struck on y = 0: %s", err.message);
        }
        rc = wff_model_set_impact_point(&q, 0.01, 0.01, &err);
        CHECK(st, rc != 0 && strstr(err.message, "symmetry 2"),
              "half model struck off both planes: %s", rc ? err.message : "accepted");
        wff_model_free(&q);
    }
}

static void check_contracts(check_state *st)
{
    wff_model m;
    if (clamped_square(st, &m, 0.02, 8, TEST_MESH_TRI, KEVLAR))
        return;
    wff_error err;
    const double F_pre[4] = {1.01, 0, 0, 1.01}, dA0[2] = {0, 0};
    /* fixed against prescribed: an error naming the node, nothing changed */
    int rc = wff_model_prescribe_group(&m, "left", WFF_UX, 1, &err);
    CHECK(st, rc < 0 && strstr(err.message, "fixed already") && strstr(err.message, "node"),
          "prescribing a fixed DOF: %s", rc < 0 ? err.message : "accepted");
    CHECK(st, m.dof_kind[D * 0] == WFF_DOF_FIXED && m.v_prescribed[D * 0] == 0,
          "the fixed DOF stays fixed");
    CHECK(st, wff_model_fix_group(&m, "left", WFF_UX, &err) > 0, "fixing again: %s",
          err.message);
    rc = wff_model_prescribe_group(&m, "fabric", WFF_DA1, 0.1, &err); /* a free DOF: fine */
    CHECK(st, rc > 0, "prescribing a free DOF: %s", err.message);
    CHECK(st, wff_model_prescribe_group(&m, "fabric", WFF_DA1, 0.2, &err) > 0 &&
          m.v_prescribed[D * 5 + WFF_DA1] == 0.2, "prescribing again: the new velocity");
    rc = wff_model_fix_group(&m, "top", WFF_DA1, &err);
    CHECK(st, rc < 0 && strstr(err.message, "prescribed already"),
          "fixing a prescribed DOF: %s", rc < 0 ? err.message : "accepted");
    rc = wff_model_fix_group(&m, "fabric", WFF_DA1, &err);
    CHECK(st, rc < 0, "fixing a prescribed DOF (surface)");
    wff_model_free(&m);

    if (clamped_square(st, &m, 0.02, 8, TEST_MESH_TRI, KEVLAR))
        return;
    rc = wff_model_prescribe_group(&m, "fabric", WFF_UX, 0.0, &err);
    CHECK(st, rc < 0, "prescribing a surface whose edge nodes are fixed: refused");
    CHECK(st, m.dof_kind[D * (9 * 4 + 4)] == WFF_DOF_FREE, "nothing changed on refusal");
    rc = wff_model_set_projectile(&m, R_NOSE, 0.01, 20, 0, &err);
    CHECK(st, rc == 0, "%s", err.message);
    rc = wff_model_set_projectile(&m, R_NOSE, 0.02, 30, 0, &err);
    CHECK(st, rc != 0 && strstr(err.message, "second projectile") && m.projectile.mass == 0.01,
          "a second projectile: %s", rc ? err.message : "accepted");
    /* advancing: NaN, inf, backwards are errors; to the current time does nothing */
    rc = wff_model_advance(&m, NAN, 10, &err);
    CHECK(st, rc != 0 && strstr(err.message, "finite"), "advance to NaN: %s", err.message);
    rc = wff_model_advance(&m, INFINITY, 10, &err);
    CHECK(st, rc != 0 && m.step == 0, "advance to inf: %s", err.message);
    CHECK(st, wff_model_advance(&m, 1, 5, &err) == 0 && m.step == 5, "5 steps");
    double t = m.time;
    long step = m.step;
    rc = wff_model_advance(&m, 0.5 * t, 10, &err);
    CHECK(st, rc != 0 && strstr(err.message, "cannot go back") && m.step == step,
          "advance backwards: %s", rc ? err.message : "accepted");
    CHECK(st, wff_model_advance(&m, t, 10, &err) == 0 && m.step == step && m.time == t,
          "advance to the current time: nothing");
    rc = wff_model_set_preload(&m, F_pre, dA0, &err);
    CHECK(st, rc != 0 && strstr(err.message, "before the first step"),
          "a preload after the first step: %s", rc ? err.message : "accepted");
    CHECK(st, m.em.F_pre[0] == 1, "the preload unchanged");
    wff_model_free(&m);

    /* a friction clamp on nodes whose u_z is prescribed */
    if (clamped_square(st, &m, 0.02, 8, TEST_MESH_TRI, KEVLAR))
        return;
    test_rect r = {-0.02, 0.02, -0.02, 0.02, 8, 8, TEST_MESH_TRI, 1, 0, 0};
    wff_model_free(&m);
    if (test_model_rect(&m, &r, KEVLAR, &err) == 0) {
        rc = wff_model_prescribe_group(&m, "left", WFF_UZ, 1, &err) > 0 &&
             wff_model_clamp_friction(&m, "left", 100, 0.3, &err) < 0;
        CHECK(st, rc && strstr(err.message, "prescribed"), "clamp on prescribed u_z: %s",
              err.message);
        rc = wff_model_clamp_friction(&m, "right", 100, 0.3, &err) > 0 &&
             wff_model_prescribe_group(&m, "right", WFF_UZ, 1, &err) < 0;
        CHECK(st, rc && strstr(err.message, "clamp"), "prescribing a clamped u_z: %s",
              err.message);
        wff_model_free(&m);
    }
}

/* A checkpoint of a flat nose off the centre loads into the same model and is
 * refused, saying the nose or impact point differs, by another. */
static void check_checkpoint(check_state *st)
{
    char dir[512], path[600];
    if (test_tmp_dir("projectile", dir, sizeof dir))
        return;
    test_tmp_path(dir, "flat.ckpt", path, sizeof path);
    wff_model m[3];
    const int nose[3] = {WFF_NOSE_FLAT, WFF_NOSE_FLAT, WFF_NOSE_FLAT};
    const double x[3] = {0.004, 0.004, 0.003};
    wff_error err;
    for (int k = 0; k < 3; k++) {
        if (clamped_square(st, &m[k], 0.02, 10, TEST_MESH_TRI, KEVLAR))
            return;
        int rc = wff_model_set_projectile_shape(&m[k], nose[k], R_EDGE, &err) ||
                 wff_model_set_impact_point(&m[k], x[k], 0, &err) ||
                 wff_model_set_projectile(&m[k], R_NOSE, 0.01, 20, 0.3, &err);
        CHECK(st, rc == 0, "%s", err.message);
    }
    int rc = wff_model_advance(&m[0], 1, 30, &err) || wff_model_save(&m[0], path, &err);
    CHECK(st, rc == 0, "%s", err.message);
    CHECK(st, wff_model_load_state(&m[1], path, &err) == 0 && m[1].step == 30 &&
          memcmp(m[1].u, m[0].u, sizeof(double) * (size_t)m[0].n_dofs) == 0,
          "the same model loads the checkpoint: %s", err.message);
    rc = wff_model_load_state(&m[2], path, &err);
    CHECK(st, rc != 0 && strstr(err.message, "impact point"),
          "another impact point refused: %s", rc ? err.message : "loaded");
    for (int k = 0; k < 3; k++)
        wff_model_free(&m[k]);
    test_tmp_remove(dir);
}

int main(void)
{
    check_state st = {0, 0};
    check_shapes(&st);
    check_flat_first_contact(&st);
    check_energy(&st);
    check_symmetry(&st);
    check_contracts(&st);
    check_checkpoint(&st);
    return check_summary(&st, "test_projectile");
}

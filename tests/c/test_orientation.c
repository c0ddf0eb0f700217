/* Ply orientation (include/wovenff/membrane.h, docs/model.md "Ply
 * orientation"): the warp E1 at θ to the mesh's x axis, the cell seeing
 * F_mesh R(θ) F_pre and its stress going back through R(θ)ᵀ.
 *
 *   1. forces at θ = 30° are −dE/du (central differences) on a jittered,
 *      randomly deformed mesh with a preload, triangles and quads, and the
 *      cell's fast paths give the plain path's forces to round-off;
 *   2. the rotated patch test: a stretch along the direction at θ of a mesh
 *      whose warp is at θ gives the yarn tensions, stretches and W of the
 *      stretch along x at θ = 0, element by element, to round-off; the
 *      stable step at rest does not depend on θ;
 *   3. θ = 90° equals θ = 0 with the warp and weft parameters swapped (a copy
 *      of the material text with every `_1` key's value exchanged with its
 *      `_2` partner), on a struck run: u to round-off, amplitudes mapped;
 *   4. θ = 0 set explicitly (and 360°) is the run without orientation, bit
 *      for bit;
 *   5. a struck run at θ = 30° conserves energy as the one at 0;
 *   6. bad input: a non-finite angle, a change after the run started, a
 *      checkpoint of another orientation. */
#include "check.h"
#include "rng.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"
#include "wovenff/state.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE
#define R_NOSE 6.35e-3

static const double kDeg = 3.14159265358979323846 / 180;
static char tmpdir[512];

/* Stored energy (J) and forces (into f, zeroed first) with the state held. */
static double force_pass(wff_model *m, const double *u, double *f, int *bad)
{
    wff_force_totals t;
    memset(f, 0, sizeof(double) * (size_t)m->n_dofs);
    wff_elements_forces(&m->el, &m->em, m->mesh.xy, u, m->state, 0, f, &t);
    *bad = t.bad_element;
    return t.internal_energy;
}

/* 1. f = −dE/du at θ = 30°, preload with shear, random state; fast = plain. */
static void consistency_case(check_state *st, int type, const char *what)
{
    test_rect r = {-0.01, 0.012, -0.008, 0.009, 5, 4, type, 1, 0.25, 777};
    wff_model m;
    wff_error err;
    const double F_pre[4] = {1.004, 0.002, -0.001, 1.013}, dA0[2] = {-9.3e-6, -23.8e-6};
    int rc = test_model_rect(&m, &r, KEVLAR, &err) ||
             wff_model_set_preload(&m, F_pre, dA0, &err) ||
             wff_model_set_orientation(&m, 30 * kDeg, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    if (rc)
        return;
    wff_rng g = {20240607};
    for (int n = 0; n < m.n_nodes; n++) {
        m.u[D * n + 0] += wff_rng_uniform(&g, -1, 1) * 2e-5;
        m.u[D * n + 1] += wff_rng_uniform(&g, -1, 1) * 2e-5;
        m.u[D * n + 2] += wff_rng_uniform(&g, -1, 1) * 2e-4;
        m.u[D * n + 3] += wff_rng_uniform(&g, -1, 1) * 3e-6;
        m.u[D * n + 4] += wff_rng_uniform(&g, -1, 1) * 3e-6;
    }
    for (size_t i = 0; i < (size_t)m.n_state * (3 * m.el.n_tris + 4 * m.el.n_quads); i++)
        m.state[i] = wff_rng_uniform(&g, -0.02, 0.02); /* γᶠ: held (dt = 0) */
    size_t nd = (size_t)m.n_dofs;
    double *f = malloc(nd * sizeof(double)), *fr = malloc(nd * sizeof(double));
    double *u = malloc(nd * sizeof(double)), *scratch = malloc(nd * sizeof(double));
    memcpy(u, m.u, nd * sizeof(double));
    int bad;
    force_pass(&m, u, f, &bad);
    CHECK(st, bad < 0, "%s: element %d failed", what, bad);
    m.em.reference_path = 1; /* the plain evaluate() everywhere */
    force_pass(&m, u, fr, &bad);
    m.em.reference_path = 0;
    double fbig[2] = {0, 0}, fast_diff[2] = {0, 0};
    for (size_t i = 0; i < nd; i++) {
        int amp = i % D >= 3;
        fbig[amp] = fmax(fbig[amp], fabs(fr[i]));
        fast_diff[amp] = fmax(fast_diff[amp], fabs(f[i] - fr[i]));
    }
    double worst[2] = {0, 0};
    int checked = 0;
    for (size_t i = 0; i < nd; i++) {
        if (m.dof_kind[i] != WFF_DOF_FREE)
            continue;
        int amp = i % D >= 3;
        double h = amp ? 1e-10 : i % D == 2 ? 1e-8 : 1e-9;
        u[i] = m.u[i] + h;
        double Ep = force_pass(&m, u, scratch, &bad);
        u[i] = m.u[i] - h;
        double Em = force_pass(&m, u, scratch, &bad);
        u[i] = m.u[i];
        double dE = (Ep - Em) / (2 * h);
        worst[amp] = fmax(worst[amp], fabs(f[i] + dE) / fbig[amp]);
        checked++;
    }
    printf("  %-10s theta 30 deg: %d DOFs, |f + dE/du| / max|f|: displacements %.2e, "
           "amplitudes %.2e; fast - plain path %.2e, %.2e (relative)\n", what, checked,
           worst[0], worst[1], fast_diff[0] / fbig[0], fast_diff[1] / fbig[1]);
    CHECK(st, fbig[0] > 1e-3 && fbig[1] > 1e-6, "%s: a stressed state: |f| %g N, %g N", what,
          fbig[0], fbig[1]);
    CHECK(st, worst[0] < 1e-6 && worst[1] < 1e-6, "%s: forces against -dE/du: %g, %g", what,
          worst[0], worst[1]);
    CHECK(st, fast_diff[0] <= 1e-12 * fbig[0] && fast_diff[1] <= 1e-12 * fbig[1],
          "%s: fast path against the plain one: %g, %g (relative)", what,
          fast_diff[0] / fbig[0], fast_diff[1] / fbig[1]);
    free(f);
    free(fr);
    free(u);
    free(scratch);
    wff_model_free(&m);
}

/* 2. A uniform F_0 at θ = 0 against Q F_0 R(θ)ᵀ at θ (Q the rotation by θ about
 * z: the stretch along x becomes the stretch along (cos θ, sin θ)); the cell
 * sees Q F_0 F_pre against F_0 F_pre, the same tensions by objectivity. */
static void set_uniform(wff_model *m, const double F[6], const double dA[2])
{
    for (int n = 0; n < m->n_nodes; n++) {
        double X = m->mesh.xy[2 * n], Y = m->mesh.xy[2 * n + 1];
        double *u = m->u + D * n;
        u[0] = (F[0] - 1) * X + F[1] * Y;
        u[1] = F[2] * X + (F[3] - 1) * Y;
        u[2] = F[4] * X + F[5] * Y;
        u[3] = dA[0];
        u[4] = dA[1];
    }
}

static void patch_case(check_state *st, int type, double theta_deg, const double F0[6],
                       const char *what)
{
    test_rect r = {-0.02, 0.03, -0.01, 0.015, 7, 5, type, 1, 0.25, 4242};
    const double F_pre[4] = {1.00396, 0, 0, 1.0135}, dA0[2] = {-9.3e-6, -23.8e-6};
    wff_model a, b;
    wff_error err;
    int rc = test_model_rect(&a, &r, KEVLAR, &err) || wff_model_set_preload(&a, F_pre, dA0, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    if (rc)
        return;
    rc = test_model_rect(&b, &r, KEVLAR, &err) || wff_model_set_preload(&b, F_pre, dA0, &err) ||
         wff_model_set_option(&b, "orientation", theta_deg, &err);
    CHECK(st, rc == 0, "%s: %s", what, err.message);
    if (rc) {
        wff_model_free(&a);
        return;
    }
    double t = theta_deg * kDeg, c = cos(t), s = sin(t);
    /* F_b = Q F0 Rᵀ, Q = [c −s 0; s c 0; 0 0 1], R = [c −s; s c] */
    double QF[6], Fb[6];
    for (int j = 0; j < 2; j++) {
        QF[j] = c * F0[j] - s * F0[2 + j];
        QF[2 + j] = s * F0[j] + c * F0[2 + j];
        QF[4 + j] = F0[4 + j];
    }
    for (int i = 0; i < 3; i++) {
        Fb[2 * i] = QF[2 * i] * c - QF[2 * i + 1] * s;     /* (QF Rᵀ)_i1 */
        Fb[2 * i + 1] = QF[2 * i] * s + QF[2 * i + 1] * c; /* (QF Rᵀ)_i2 */
    }
    const double dA[2] = {-8e-6, -21e-6};
    set_uniform(&a, F0, dA);
    set_uniform(&b, Fb, dA);
    static const char *const names[] = {"T1", "T2", "lambda1", "lambda2", "shear_angle", "W"};
    int n_el = a.el.n_tris + a.el.n_quads;
    double *va = malloc(sizeof(double) * (size_t)n_el), *vb = malloc(sizeof(double) * (size_t)n_el);
    double worst = 0, t1 = 0;
    for (int k = 0; k < 6; k++) {
        rc = wff_model_element_values(&a, names[k], va, &err) ||
             wff_model_element_values(&b, names[k], vb, &err);
        CHECK(st, rc == 0, "%s: %s", what, err.message);
        if (rc)
            break;
        double scale = 0, diff = 0;
        for (int e = 0; e < n_el; e++) {
            scale = fmax(scale, fabs(va[e]));
            diff = fmax(diff, fabs(va[e] - vb[e]));
        }
        if (k == 0)
            t1 = va[0];
        /* (the shear angle is 0 in the uniaxial case: against 1 rad) */
        double rel = diff / fmax(scale, k == 4 ? 1 : 1e-12);
        worst = fmax(worst, rel);
        CHECK(st, rel <= 1e-12, "%s: %s differs by %g (relative; scale %g)", what, names[k],
              rel, scale);
    }
    int wa, wb;
    double dta = wff_elements_stable_step(&a.el, &a.em, a.mesh.xy, a.u, &wa);
    double dtb = wff_elements_stable_step(&b.el, &b.em, b.mesh.xy, b.u, &wb);
    printf("  patch %-26s theta %g deg: T1 %.4f N; largest difference of T1 T2 lambda1 "
           "lambda2 shear_angle W %.2e (relative); stable step %.6g / %.6g us\n", what,
           theta_deg, t1, worst, 1e6 * dta, 1e6 * dtb);
    CHECK(st, fabs(t1) > 1, "%s: the yarns carry tension: T1 %g N", what, t1);
    CHECK_CLOSE(st, dtb, dta, 1e-12, 0, "stable step at theta against 0");
    free(va);
    free(vb);
    wff_model_free(&a);
    wff_model_free(&b);
}

static void check_patch(check_state *st)
{
    const double stretch_x[6] = {1.02, 0, 0, 1, 0, 0};
    const double general[6] = {1.012, 0.021, -0.008, 0.994, 0.035, -0.027};
    patch_case(st, TEST_MESH_TRI, 30, stretch_x, "uniaxial, triangles");
    patch_case(st, TEST_MESH_QUAD, 30, stretch_x, "uniaxial, quads");
    patch_case(st, TEST_MESH_TRI, -57, general, "general F, triangles");
    patch_case(st, TEST_MESH_QUAD, 135, general, "general F, quads");
}

/* A copy of material `path` with every `_1` key's value exchanged with its
 * `_2` partner, at out. */
static int swapped_material(const char *path, const char *out, wff_error *err)
{
    char *text, *swapped = NULL;
    if (wff_read_text_file(path, "material", WFF_MATERIAL_FILE_MAX, &text, err))
        return -1;
    char keys[2048];
    wff_material_text_keys(text, keys, sizeof keys);
    const char *k[WFF_KV_MAX];
    char store[WFF_KV_MAX][2][WFF_KV_VALUE_MAX], names[WFF_KV_MAX][WFF_KV_KEY_MAX];
    int n = 0;
    for (char *key = strtok(keys, ", "); key; key = strtok(NULL, ", ")) {
        size_t len = strlen(key);
        if (len < 3 || strcmp(key + len - 2, "_1") != 0 || n + 2 > WFF_KV_MAX)
            continue;
        char partner[WFF_KV_KEY_MAX];
        snprintf(partner, sizeof partner, "%.*s_2", (int)(len - 2), key);
        const char *b1, *e1, *b2, *e2;
        int line;
        if (!wff_material_text_find(text, key, &b1, &e1, &line) ||
            !wff_material_text_find(text, partner, &b2, &e2, &line))
            continue;
        snprintf(names[n], sizeof names[n], "%s", key);
        snprintf(store[n][0], sizeof store[n][0], "%.*s", (int)(e2 - b2), b2);
        snprintf(names[n + 1], sizeof names[n + 1], "%s", partner);
        snprintf(store[n + 1][0], sizeof store[n + 1][0], "%.*s", (int)(e1 - b1), b1);
        n += 2;
    }
    for (int i = 0; i < n; i++)
        k[i] = names[i];
    const char *v[WFF_KV_MAX];
    for (int i = 0; i < n; i++)
        v[i] = store[i][0];
    int rc = n < 8 ? wff_fail(err, "%s: only %d family keys to swap", path, n)
                   : wff_material_text_replace(text, path, n, k, v, &swapped, err);
    if (rc == 0) {
        FILE *fp = fopen(out, "w");
        rc = !fp || fputs(swapped, fp) < 0 || fclose(fp) != 0 ? wff_fail(err, "cannot write %s",
                                                                        out)
                                                              : 0;
    }
    free(text);
    free(swapped);
    return rc;
}

/* A clamped square of side 2h (edges fixed), n x n cells, preloaded, struck
 * at (x0, y0) by 0.5 g at 20 m/s, at orientation theta_deg (NAN: not set). */
static int struck(check_state *st, wff_model *m, const char *material, int type,
                  const double F_pre[4], const double dA0[2], double theta_deg)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, 16, 16, type, 1, 0.2, 99};
    wff_error err;
    int rc = test_model_rect(m, &r, material, &err);
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int e = 0; e < 4 && rc == 0; e++)
        for (int c = 0; c < 3 && rc == 0; c++)
            rc = wff_model_fix_group(m, edges[e], c, &err) < 0;
    if (rc == 0)
        rc = wff_model_set_preload(m, F_pre, dA0, &err) ||
             (!isnan(theta_deg) && wff_model_set_option(m, "orientation", theta_deg, &err)) ||
             wff_model_set_impact_point(m, 0.004, -0.003, &err) ||
             wff_model_set_projectile(m, R_NOSE, 0.0005, 20, 0.2, &err);
    CHECK(st, rc == 0, "struck model: %s", err.message);
    return rc;
}

static int run_to(check_state *st, wff_model *m, double t_end, double *worst_error)
{
    wff_error err;
    *worst_error = 0;
    for (int block = 1; block <= 10; block++) {
        if (wff_model_advance(m, block * t_end / 10, 10000000, &err)) {
            CHECK(st, 0, "advance: %s", err.message);
            return -1;
        }
        wff_energies e;
        wff_model_energies(m, &e);
        *worst_error = fmax(*worst_error, fabs(e.error));
    }
    return 0;
}

/* 3. θ = 90° against θ = 0 with the families swapped. */
static void check_quarter_turn(check_state *st)
{
    char swapped[1024];
    test_tmp_path(tmpdir, "kevlar_swapped.txt", swapped, sizeof swapped);
    wff_error err;
    int rc = swapped_material(KEVLAR, swapped, &err);
    CHECK(st, rc == 0, "swapped material: %s", err.message);
    if (rc)
        return;
    const double F_pre[4] = {1.004, 0, 0, 1.013}, dA0[2] = {-9.3e-6, -23.7e-6};
    const double F_sw[4] = {1.013, 0, 0, 1.004}, dA_sw[2] = {-23.7e-6, -9.3e-6};
    for (int type = TEST_MESH_TRI; type <= TEST_MESH_QUAD; type++) {
        wff_model a, b;
        if (struck(st, &a, KEVLAR, type, F_pre, dA0, 90))
            return;
        if (struck(st, &b, swapped, type, F_sw, dA_sw, NAN)) {
            wff_model_free(&a);
            return;
        }
        double ea, eb;
        if (run_to(st, &a, 0.06e-3, &ea) || run_to(st, &b, 0.06e-3, &eb)) {
            wff_model_free(&a);
            wff_model_free(&b);
            return;
        }
        double scale[5] = {0}, diff[5] = {0};
        for (int n = 0; n < a.n_nodes; n++)
            for (int c = 0; c < D; c++) {
                int cb = c == 3 ? 4 : c == 4 ? 3 : c; /* the warp's amplitude is b's weft's */
                double x = a.u[D * n + c], y = b.u[D * n + cb];
                scale[c] = fmax(scale[c], fabs(y));
                diff[c] = fmax(diff[c], fabs(x - y));
            }
        double worst = 0;
        for (int c = 0; c < D; c++)
            worst = fmax(worst, diff[c] / scale[c]);
        printf("  theta 90 deg against the swapped material, %s, %ld / %ld steps: apex %.4f mm, "
               "|du| / max|u|: ux %.1e uy %.1e uz %.1e dA1 %.1e dA2 %.1e; projectile %.6f / "
               "%.6f m/s\n", type ? "quads" : "triangles", a.step, b.step, 1e3 * scale[2],
               diff[0] / scale[0], diff[1] / scale[1], diff[2] / scale[2], diff[3] / scale[3],
               diff[4] / scale[4], a.projectile.velocity, b.projectile.velocity);
        CHECK(st, a.step == b.step, "the same steps: %ld, %ld", a.step, b.step);
        CHECK(st, scale[2] > 1e-4, "the fabric is struck: apex %g m", scale[2]);
        CHECK(st, worst <= 1e-9, "theta 90 against swapped: u differs by %g (relative)", worst);
        CHECK_CLOSE(st, a.projectile.velocity, b.projectile.velocity, 1e-10, 1,
                    "projectile velocity");
        wff_model_free(&a);
        wff_model_free(&b);
    }
}

/* 4 and 5: θ = 0 set explicitly, and 360°, against not set (bit for bit); the
 * energy balance at 30°. */
static void check_zero_and_energy(check_state *st)
{
    const double F_pre[4] = {1.004, 0, 0, 1.013}, dA0[2] = {-9.3e-6, -23.7e-6};
    wff_model plain, zero, full, turned;
    if (struck(st, &plain, KEVLAR, TEST_MESH_TRI, F_pre, dA0, NAN))
        return;
    if (struck(st, &zero, KEVLAR, TEST_MESH_TRI, F_pre, dA0, 0) ||
        struck(st, &full, KEVLAR, TEST_MESH_TRI, F_pre, dA0, 360) ||
        struck(st, &turned, KEVLAR, TEST_MESH_TRI, F_pre, dA0, 30))
        return;
    CHECK(st, memcmp(zero.em.F_pre, F_pre, sizeof F_pre) == 0 &&
                  memcmp(full.em.F_pre, F_pre, sizeof F_pre) == 0,
          "theta 0 and 360: the element map is the preload itself");
    double e_plain, e_zero, e_full, e_turned;
    const double t_end = 0.1e-3;
    if (run_to(st, &plain, t_end, &e_plain) || run_to(st, &zero, t_end, &e_zero) ||
        run_to(st, &full, t_end, &e_full) || run_to(st, &turned, t_end, &e_turned))
        return;
    size_t nd = (size_t)plain.n_dofs * sizeof(double);
    CHECK(st, memcmp(plain.u, zero.u, nd) == 0 && memcmp(plain.v, zero.v, nd) == 0 &&
                  plain.step == zero.step && e_plain == e_zero,
          "theta 0 set: bit for bit the run without orientation");
    CHECK(st, memcmp(plain.u, full.u, nd) == 0 && plain.step == full.step,
          "theta 360: bit for bit the run at 0");
    int apex_plain = wff_model_nearest_node(&plain, 0.004, -0.003);
    int apex_turned = wff_model_nearest_node(&turned, 0.004, -0.003);
    printf("  struck run to %g ms: theta 0 (set, and 360) bit for bit the plain run; largest "
           "|energy error| theta 0 %.3e, theta 30 %.3e; apex %.4f / %.4f mm\n", 1e3 * t_end,
           e_plain, e_turned, 1e3 * plain.u[D * apex_plain + 2],
           1e3 * turned.u[D * apex_turned + 2]);
    CHECK(st, e_plain < 0.005 && e_turned < 0.005, "energy error: theta 0 %g, theta 30 %g",
          e_plain, e_turned);
    CHECK(st, turned.u[D * apex_turned + 2] > 1e-4, "theta 30: the fabric is struck");
    wff_model_free(&plain);
    wff_model_free(&zero);
    wff_model_free(&full);
    wff_model_free(&turned);
}

static int contains(const char *s, const char *part) { return strstr(s, part) != NULL; }

/* 6. Bad input. */
static void check_bad_input(check_state *st)
{
    const double F_pre[4] = {1.004, 0, 0, 1.013}, dA0[2] = {-9.3e-6, -23.7e-6};
    wff_model m;
    if (struck(st, &m, KEVLAR, TEST_MESH_TRI, F_pre, dA0, 30))
        return;
    wff_error err;
    const double bad[3] = {NAN, INFINITY, -INFINITY};
    for (int i = 0; i < 3; i++) {
        err.message[0] = 0;
        CHECK(st, wff_model_set_orientation(&m, bad[i], &err) != 0 &&
                      contains(err.message, "orientation") && contains(err.message, "finite"),
              "non-finite theta %g: %s", bad[i], err.message);
        CHECK(st, wff_model_set_option(&m, "orientation", bad[i], &err) != 0 &&
                      contains(err.message, "finite"), "option: %s", err.message);
    }
    /* angles beyond +-1e6 degrees (a double holds 1e30 only to 1e14 degrees: the old
     * test took it for a multiple of 90 and ran at a random angle); reduced modulo 360
     * exactly (450 is 90, -450 is -90, 720 is 0: k pi/2 exactly) */
    const double huge[3] = {1e30, -1e30, 1.000001e6};
    for (int i = 0; i < 3; i++) {
        err.message[0] = 0;
        CHECK(st, wff_model_set_option(&m, "orientation", huge[i], &err) != 0 &&
                      contains(err.message, "beyond +-1e6 degrees") &&
                      contains(err.message, "modulo 360"),
              "angle %g deg: %s", huge[i], err.message);
        CHECK(st, wff_model_set_orientation(&m, huge[i] * kDeg, &err) != 0 &&
                      contains(err.message, "beyond +-1e6 degrees"), "theta: %s", err.message);
    }
    const double given[5] = {450, -450, 720, 1e6, 405.5}, want[5] = {90, -90, 0, 280, 45.5};
    for (int i = 0; i < 5; i++) {
        double reduced = -1, theta = -1;
        CHECK(st, wff_angle_degrees(given[i], "angle", &reduced, &theta, &err) == 0 &&
                      reduced == want[i] && (want[i] != 0 || !signbit(reduced)) &&
                      (fmod(want[i], 90) != 0 || theta == want[i] / 90 * M_PI_2),
              "%g deg reduced to %.17g (theta %.17g), want %g", given[i], reduced, theta,
              want[i]);
    }
    CHECK(st, m.em.orientation == 30 * kDeg, "a refused angle leaves the model as it was");
    double e;
    if (run_to(st, &m, 0.01e-3, &e)) {
        wff_model_free(&m);
        return;
    }
    err.message[0] = 0;
    CHECK(st, wff_model_set_option(&m, "orientation", 45, &err) != 0 &&
                  contains(err.message, "run has started") && contains(err.message, "45"),
          "after the start: %s", err.message);
    CHECK(st, wff_model_set_option(&m, "orientation", 30, &err) == 0,
          "the same angle again is allowed (a restart sets it): %s", err.message);
    printf("  after the start: %s\n", err.message);
    /* a checkpoint at 30 degrees into a model at 0 and one at 31 */
    char path[1024];
    test_tmp_path(tmpdir, "turned.state", path, sizeof path);
    int rc = wff_model_save(&m, path, &err);
    CHECK(st, rc == 0, "save: %s", err.message);
    for (int k = 0; k < 2 && rc == 0; k++) {
        wff_model other;
        if (struck(st, &other, KEVLAR, TEST_MESH_TRI, F_pre, dA0, k ? 31 : NAN))
            break;
        err.message[0] = 0;
        CHECK(st, wff_model_load_state(&other, path, &err) != 0 &&
                      contains(err.message, "orientation 30") &&
                      contains(err.message, k ? "has 31" : "has 0"),
              "checkpoint of another orientation: %s", err.message);
        if (k == 0)
            printf("  restart refused: %s\n", err.message);
        wff_model_free(&other);
    }
    wff_model same;
    if (rc == 0 && struck(st, &same, KEVLAR, TEST_MESH_TRI, F_pre, dA0, 30) == 0) {
        CHECK(st, wff_model_load_state(&same, path, &err) == 0, "the same orientation loads: %s",
              err.message);
        wff_model_free(&same);
    }
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    if (test_tmp_dir("orientation", tmpdir, sizeof tmpdir))
        return 1;
    consistency_case(&st, TEST_MESH_TRI, "triangles");
    consistency_case(&st, TEST_MESH_QUAD, "quads");
    check_patch(&st);
    check_quarter_turn(&st);
    check_zero_and_energy(&st);
    check_bad_input(&st);
    test_tmp_remove(tmpdir);
    return check_summary(&st, "test_orientation");
}

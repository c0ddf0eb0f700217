/* Transverse cutting (plugin/cells/yarn_failure.h, docs/model.md §25): both yarn
 * strains times κ(p) = max(0, 1 − p/p_c) at the contact pressure p.
 *
 *   1. Keys: cutting_pressure absent or 0 is no cutting (the King cell's states
 *      as before); < 0, or given without the yarn strains, refused naming the
 *      key; basket_2x2 and linear_yarns refuse it naming the cell; with it the
 *      King cell's points carry nine states, contact_pressure last (Pa).
 *   2. The law alone: on a grid of strains and pressures the damage is
 *      clamp((ε − ε_f κ)/((ε_r − ε_f) κ), 0, 1) (written out here, not the
 *      header's function), zero just below the reduced failure strain ε_f κ and
 *      positive just above it; nondecreasing in p; at p ≥ p_c a stretched yarn
 *      is cut (d = 1, its tension gone), a slack one is not; off
 *      (cutting_pressure 0) and at p = 0 every result has the bits of the law
 *      without cutting.
 *   3. The King cell: a warp stretched to 2 % (below ε_f = 3.8 %) is undamaged
 *      at p = 0 and damaged as the law says at p = 0.5 p_c; its contact_pressure
 *      state is held (dt > 0 and dt = 0); with cutting_pressure = 0 in the file
 *      a point has the bits of the file without the key. */
#include "check.h"
#include "test_material.h"
#include "cells/yarn_failure.h"
#include "wovenff/material.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"

static int load_text(const char *text, wff_material *m, wff_error *e)
{
    return wff_material_parse_text(text, "test_cutting", m, e);
}

/* A material from path with assignments; 0 or -1 (reported when refusal is 0). */
static int load(check_state *st, const char *path, const char *set, wff_material *m,
                wff_error *e, int refusal)
{
    char *text = test_material_text(st, path, set);
    if (!text)
        return -1;
    int rc = load_text(text, m, e);
    free(text);
    if (rc && !refusal)
        CHECK(st, 0, "%s with %s: %s", path, set, e->message);
    return rc;
}

static void check_keys(check_state *st)
{
    wff_material m;
    wff_error e;
    if (load(st, KEVLAR, "failure=1", &m, &e, 0) == 0)
        CHECK(st, m.n_state == 3 && wff_material_state_index(&m, "contact_pressure") < 0,
              "cutting_pressure = 0: 3 states, no contact_pressure (n_state %d)", m.n_state);
    if (load(st, KEVLAR, "failure=1,cutting_pressure=1e8", &m, &e, 0) == 0)
        CHECK(st, m.n_state == 9 && wff_material_state_index(&m, "contact_pressure") == 8,
              "cutting on: 9 states, contact_pressure last (n_state %d, at %d)", m.n_state,
              wff_material_state_index(&m, "contact_pressure"));
    int rc = load(st, KEVLAR, "cutting_pressure=-1", &m, &e, 1);
    CHECK(st, rc != 0 && strstr(e.message, "cutting_pressure"), "cutting_pressure < 0: %s",
          rc ? e.message : "accepted");
    static const char *const other[] = {"tests/data/basket_symmetric.txt",
                                        "freefem_scripts/materials/kevlar_basket.txt",
                                        "freefem_scripts/materials/kevlar_linear.txt"};
    for (int i = 0; i < 3; i++) {
        char *text = test_material_text(st, other[i], "");
        if (!text)
            continue;
        char *more = malloc(strlen(text) + 200);
        sprintf(more, "%s\nfail_strain_1 = 0.03\nfail_strain_2 = 0.03\nrupture_strain_1 = 0.04\n"
                      "rupture_strain_2 = 0.04\ncutting_pressure = 1e8\n", text);
        if (strstr(text, "fail_strain_1")) /* (the file has the strains: the key alone) */
            sprintf(more, "%s\ncutting_pressure = 1e8\n", text);
        rc = load_text(more, &m, &e);
        CHECK(st, rc != 0 && strstr(e.message, "cutting_pressure") && strstr(e.message, "king_plain"),
              "%s: cutting refused naming the key and the cell: %s", other[i],
              rc ? e.message : "accepted");
        free(more);
        free(text);
    }
    /* the key without the strains (a material with no failure keys at all) */
    wff_kv kv;
    memset(&kv, 0, sizeof kv);
    kv.source = "case.txt";
    snprintf(kv.entry[0].key, sizeof kv.entry[0].key, "cutting_pressure");
    snprintf(kv.entry[0].value, sizeof kv.entry[0].value, "1e8");
    kv.entry[0].line = 1;
    kv.n = 1;
    wff_yarn_failure f;
    rc = wff_yarn_failure_parse(&kv, &f, &e);
    CHECK(st, rc != 0 && strstr(e.message, "cutting_pressure"),
          "cutting_pressure without the strains: %s", rc ? e.message : "accepted");
}

static int same_bits(wff_yarn_damage a, wff_yarn_damage b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

static void check_law(check_state *st)
{
    const double ef = 0.038, er = 0.0452, pc = 2e8, dt = 1e-7;
    wff_yarn_failure off = {1, {ef, ef}, {er, er}, 0, 0, 0, 0};
    wff_yarn_failure on = off;
    on.cutting_pressure = pc;
    int checked = 0, worst_off = 0;
    double worst = 0;
    for (int i = 0; i <= 40; i++) {
        const double p = pc * i / 32.0; /* 0 .. 1.25 p_c */
        const double kappa = fmax(0, 1 - p / pc);
        double d_last = -1;
        for (int j = -4; j <= 60; j++) {
            const double e = 0.001 * j, energy = 0.5 * e * e; /* (any W ≥ 0) */
            wff_yarn_damage y = wff_yarn_damage_step_pressed(&on, 0, e, energy, 0, 0, 0, p, dt);
            double want = kappa > 0 ? (e - ef * kappa) / ((er - ef) * kappa) : (e > 0 ? 1 : 0);
            want = want < 0 ? 0 : want > 1 ? 1 : want;
            worst = fmax(worst, fabs(y.damage - want));
            CHECK(st, y.damage >= d_last, "p = %g Pa: damage falls with the strain", p);
            d_last = y.damage;
            /* nondecreasing in p */
            wff_yarn_damage less = wff_yarn_damage_step_pressed(&on, 0, e, energy, 0, 0, 0,
                                                                0.9 * p, dt);
            CHECK(st, y.damage >= less.damage, "p = %g, e = %g: damage %g below %g at 0.9 p", p,
                  e, y.damage, less.damage);
            /* off: the pressure is unused; at p = 0 the law without cutting */
            wff_yarn_damage plain = wff_yarn_damage_step(&off, 0, e, energy, 0, 0, 0, dt);
            worst_off += !same_bits(wff_yarn_damage_step_pressed(&off, 0, e, energy, 0, 0, 0,
                                                                 p, dt), plain);
            worst_off += !same_bits(wff_yarn_damage_step_pressed(&on, 0, e, energy, 0, 0, 0,
                                                                 0, dt), plain);
            checked++;
        }
        if (kappa > 0) { /* the onset moves to ε_f κ */
            const double below = ef * kappa * (1 - 1e-9), above = ef * kappa * (1 + 1e-6);
            CHECK(st, wff_yarn_damage_step_pressed(&on, 0, below, 1, 0, 0, 0, p, dt).damage == 0,
                  "p = %g: damaged below the reduced failure strain %g", p, ef * kappa);
            CHECK(st, wff_yarn_damage_step_pressed(&on, 0, above, 1, 0, 0, 0, p, dt).damage > 0,
                  "p = %g: not damaged above the reduced failure strain %g", p, ef * kappa);
        } else { /* cut through: stretched d = 1 and no tension left; slack untouched */
            wff_yarn_damage y = wff_yarn_damage_step_pressed(&on, 0, 1e-4, 1, 0, 0, 0, p, dt);
            CHECK(st, y.damage == 1 && y.factor == 0 && y.released == 1,
                  "p = %g >= p_c: a stretched yarn not cut (d %g, factor %g)", p, y.damage,
                  y.factor);
            y = wff_yarn_damage_step_pressed(&on, 0, -1e-3, 1, 0, 0, 0, p, dt);
            CHECK(st, y.damage == 0 && y.factor == 1, "p = %g: a slack yarn cut", p);
        }
    }
    CHECK(st, worst < 1e-12, "damage off the written-out law by %g", worst);
    CHECK(st, worst_off == 0, "%d results without cutting (off, or p = 0) differ in their bits "
          "from the law without cutting", worst_off);
    printf("  law: %d (p, strain) pairs, largest error %.2g; off and p = 0 bit for bit\n",
           checked, worst);
}

static void check_king(check_state *st)
{
    wff_material cut, zero, plain;
    wff_error e;
    const double pc = 2e8;
    if (load(st, KEVLAR, "failure=1,cutting_pressure=2e8", &cut, &e, 0) ||
        load(st, KEVLAR, "failure=1", &zero, &e, 0))
        return;
    /* the file without the key at all */
    char *text = test_material_text(st, KEVLAR, "failure=1");
    if (!text)
        return;
    char *line = strstr(text, "\ncutting_pressure");
    CHECK(st, line != NULL, "no cutting_pressure line in %s", KEVLAR);
    if (line)
        line[1] = '#'; /* commented out */
    int rc = load_text(text, &plain, &e);
    free(text);
    CHECK(st, rc == 0, "%s without cutting_pressure: %s", KEVLAR, e.message);
    if (rc)
        return;
    const double P0 = 0.3735e-3, A0 = 0.0602e-3, L0 = sqrt(P0 * P0 + A0 * A0);
    const double strain = 0.02, lam = sqrt(pow(L0 * (1 + strain), 2) - A0 * A0) / P0;
    const double F[6] = {lam, 0, 0, 1, 0, 0}, dA[2] = {0, 0}, dt = 1e-7;
    double state[WFF_STATE_MAX] = {0};
    wff_point_result r, r0, rp;
    wff_material_evaluate(&cut, F, dA, state, dt, &r0);
    CHECK(st, r0.state[1] == 0 && r0.state[2] == 0, "p = 0: damaged at 2 %% (%g)", r0.state[1]);
    state[8] = 0.5 * pc;
    wff_material_evaluate(&cut, F, dA, state, dt, &r);
    const double kappa = 0.5, want = (strain - 0.038 * kappa) / ((0.0452 - 0.038) * kappa);
    CHECK_CLOSE(st, r.state[1], want, 1e-9, 1e-12, "p = p_c/2: warp damage at 2 %%");
    CHECK(st, r.state[2] == 0, "p = p_c/2: the weft (unstretched) damaged: %g", r.state[2]);
    CHECK(st, r.state[8] == 0.5 * pc, "contact_pressure not held at dt > 0: %g", r.state[8]);
    CHECK(st, r.diag[0] < r0.diag[0], "the cut warp's tension %g not below the intact %g",
          r.diag[0], r0.diag[0]);
    wff_material_evaluate(&cut, F, dA, state, 0, &rp);
    CHECK(st, rp.state[8] == 0.5 * pc && rp.state[1] == 0, "dt = 0: state changed");
    printf("  king: warp at 2 %% strain, p = p_c/2: damage %.4f (law %.4f), tension %.2f N "
           "(intact %.2f N)\n", r.state[1], want, r.diag[0], r0.diag[0]);
    /* cutting_pressure = 0 in the file: the bits of the file without the key */
    double s1[WFF_STATE_MAX] = {0}, s2[WFF_STATE_MAX] = {0};
    int differ = 0;
    for (int i = 0; i <= 30; i++) {
        const double l = 1 + 0.002 * i, Fi[6] = {l, 0.01, 0, 1 + 0.001 * i, 0.002, 0};
        wff_point_result a, b;
        wff_material_evaluate(&zero, Fi, dA, s1, dt, &a);
        wff_material_evaluate(&plain, Fi, dA, s2, dt, &b);
        differ += memcmp(a.stress, b.stress, sizeof a.stress) != 0 ||
                  memcmp(a.state, b.state, sizeof(double) * 3) != 0 || a.energy != b.energy ||
                  a.failure_dissipated != b.failure_dissipated;
        memcpy(s1, a.state, sizeof s1), memcpy(s2, b.state, sizeof s2);
    }
    CHECK(st, differ == 0, "cutting_pressure = 0: %d of 31 updates differ from the file "
          "without the key", differ);
    CHECK(st, s1[1] > 0, "the path did not reach damage (d_1 %g): the comparison is weak", s1[1]);
}

int main(void)
{
    check_state st = {0, 0};
    check_keys(&st);
    check_law(&st);
    check_king(&st);
    return check_summary(&st, "test_cutting");
}

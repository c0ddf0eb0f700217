/* The yarn failure law alone (plugin/cells/yarn_failure.h, docs/model.md §20):
 * damage linear between the failure and the rupture strain, never decreasing,
 * on tension only, the released energy, the Cowper–Symonds rate scaling, and
 * every bad key of the parser with a message naming it. The law inside the
 * cells is checked by the cell suite (tests/c/lib/cell_suite.c). */
#include "check.h"
#include "cells/yarn_failure.h"
#include "wovenff/material.h"

#include <math.h>
#include <string.h>

/* A parsed material text from "key = value" lines (no comments), as the
 * material reader would give it to a cell's parse. */
static void kv_from_text(wff_kv *kv, const char *text)
{
    memset(kv, 0, sizeof *kv);
    kv->source = "case.txt";
    int line = 0;
    const char *p = text;
    while (*p) {
        line++;
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        char buf[160];
        snprintf(buf, sizeof buf, "%.*s", (int)len, p);
        char *eq = strchr(buf, '=');
        if (eq) {
            *eq = '\0';
            char key[WFF_KV_KEY_MAX], value[WFF_KV_VALUE_MAX];
            if (sscanf(buf, "%47s", key) == 1 && sscanf(eq + 1, "%95s", value) == 1) {
                wff_kv_entry *e = &kv->entry[kv->n++];
                snprintf(e->key, sizeof e->key, "%s", key);
                snprintf(e->value, sizeof e->value, "%s", value);
                e->line = line;
            }
        }
        p += len + (eol ? 1 : 0);
    }
}

static int parse_text(const char *text, wff_yarn_failure *f, wff_error *err)
{
    wff_kv kv;
    kv_from_text(&kv, text);
    return wff_yarn_failure_parse(&kv, f, err);
}

#define FOUR "fail_strain_1 = 0.03\nfail_strain_2 = 0.035\n" \
             "rupture_strain_1 = 0.045\nrupture_strain_2 = 0.05\n"

/* Expect the text rejected with a message containing every needle. */
static void expect_error(check_state *st, const char *text, const char *what,
                         const char *needle1, const char *needle2)
{
    wff_yarn_failure f;
    wff_error err = {{0}};
    int rc = parse_text(text, &f, &err);
    CHECK(st, rc == -1, "%s: accepted", what);
    CHECK(st, strstr(err.message, "case.txt") != NULL, "%s: file not named: %s", what,
          err.message);
    CHECK(st, !needle1 || strstr(err.message, needle1), "%s: '%s' not in: %s", what, needle1,
          err.message);
    CHECK(st, !needle2 || strstr(err.message, needle2), "%s: '%s' not in: %s", what, needle2,
          err.message);
}

static void test_parse(check_state *st)
{
    wff_yarn_failure f;
    wff_error err = {{0}};
    /* no keys: off, no states */
    CHECK(st, parse_text("", &f, &err) == 0, "empty: %s", err.message);
    CHECK(st, f.enabled == 0 && wff_yarn_failure_states(&f) == 0, "empty: failure on");
    /* keys with failure = 0: kept, off */
    CHECK(st, parse_text("failure = 0\n" FOUR, &f, &err) == 0, "off with keys: %s", err.message);
    CHECK(st, f.enabled == 0 && f.fail_strain[1] == 0.035 && f.rupture_strain[0] == 0.045,
          "off with keys: values not kept");
    CHECK(st, wff_yarn_failure_states(&f) == 0, "off: states");
    /* keys, no failure key: off (the default) */
    CHECK(st, parse_text(FOUR, &f, &err) == 0 && f.enabled == 0, "default not off");
    /* on */
    CHECK(st, parse_text("failure = 1\n" FOUR, &f, &err) == 0, "on: %s", err.message);
    CHECK(st, f.enabled == 1 && f.fail_strain[0] == 0.03 && f.rupture_strain[1] == 0.05 &&
              f.rate_C == 0, "on: values");
    CHECK(st, wff_yarn_failure_states(&f) == 2, "on: %d states", wff_yarn_failure_states(&f));
    /* on with rate */
    CHECK(st, parse_text("failure = 1\n" FOUR "failure_rate_C = 1e8\nfailure_rate_p = 5\n", &f,
                         &err) == 0, "rate: %s", err.message);
    CHECK(st, f.rate_C == 1e8 && f.rate_p == 5 && wff_yarn_failure_states(&f) == 4, "rate");
    /* every key is taken (none left for the "unknown key" check) */
    wff_kv kv;
    kv_from_text(&kv, "failure = 0\n" FOUR "failure_rate_C = 1e8\nfailure_rate_p = 5\n");
    CHECK(st, wff_yarn_failure_parse(&kv, &f, &err) == 0, "used: %s", err.message);
    for (int i = 0; i < kv.n; i++)
        CHECK(st, kv.entry[i].used, "key '%s' not taken", kv.entry[i].key);

    expect_error(st, "failure = 2\n" FOUR, "failure = 2", "'failure'", "case.txt:1");
    expect_error(st, "failure = 0.5\n" FOUR, "failure = 0.5", "'failure'", NULL);
    expect_error(st, "failure = 1\n", "on without strains", "'failure'", "fail_strain_1");
    expect_error(st, "failure = 1\nfail_strain_1 = 0.03\nrupture_strain_1 = 0.045\n",
                 "one family", "'fail_strain_1'", "fail_strain_2, rupture_strain_2");
    expect_error(st, "fail_strain_2 = 0.03\nrupture_strain_2 = 0.045\n",
                 "one family, off", "'fail_strain_2'", "fail_strain_1, rupture_strain_1");
    expect_error(st, "failure = 1\nfail_strain_1 = 0.03\nfail_strain_2 = 0.03\n",
                 "no rupture strains", "'fail_strain_1'", "rupture_strain_1, rupture_strain_2");
    expect_error(st, "failure = 1\nfail_strain_1 = -0.03\nfail_strain_2 = 0.035\n"
                 "rupture_strain_1 = 0.045\nrupture_strain_2 = 0.05\n",
                 "negative", "'fail_strain_1'", "case.txt:2");
    expect_error(st, "failure = 1\nfail_strain_1 = 0.03\nfail_strain_2 = 0\n"
                 "rupture_strain_1 = 0.045\nrupture_strain_2 = 0.05\n",
                 "zero", "'fail_strain_2'", "> 0");
    expect_error(st, "failure = 1\nfail_strain_1 = 0.03\nfail_strain_2 = 0.035\n"
                 "rupture_strain_1 = 0.045\nrupture_strain_2 = -0.05\n",
                 "negative rupture", "'rupture_strain_2'", "> 0");
    expect_error(st, "failure = 1\nfail_strain_1 = 0.03\nfail_strain_2 = 0.035\n"
                 "rupture_strain_1 = 0.03\nrupture_strain_2 = 0.05\n",
                 "rupture = failure", "'rupture_strain_1'", "fail_strain_1");
    expect_error(st, "failure = 0\nfail_strain_1 = 0.03\nfail_strain_2 = 0.035\n"
                 "rupture_strain_1 = 0.045\nrupture_strain_2 = 0.02\n",
                 "rupture < failure (off)", "'rupture_strain_2'", "case.txt:5");
    expect_error(st, "failure = 1\n" FOUR "failure_rate_C = 1e8\n", "C alone",
                 "'failure_rate_C'", "failure_rate_p");
    expect_error(st, "failure = 1\n" FOUR "failure_rate_p = 5\n", "p alone",
                 "'failure_rate_p'", "failure_rate_C");
    expect_error(st, "failure = 1\n" FOUR "failure_rate_C = 0\nfailure_rate_p = 5\n", "C = 0",
                 "'failure_rate_C'", "> 0");
    expect_error(st, "failure = 1\n" FOUR "failure_rate_C = 1e8\nfailure_rate_p = -5\n",
                 "p < 0", "'failure_rate_p'", "> 0");
    expect_error(st, "failure_rate_C = 1e8\nfailure_rate_p = 5\n", "rate without strains",
                 "'failure_rate_C'", "without the strains");
    expect_error(st, "failure = yes\n" FOUR, "not a number", "'failure'", "not a number");
}

static wff_yarn_failure law(double rate_C, double rate_p)
{
    wff_yarn_failure f = {.enabled = 1,
                          .fail_strain = {0.03, 0.035},
                          .rupture_strain = {0.045, 0.05},
                          .rate_C = rate_C,
                          .rate_p = rate_p};
    return f;
}

/* A yarn's energy at strain e, W = ½ EA e² with EA = 1 (any positive number). */
static double yarn_energy(double e) { return 0.5 * e * e; }

static void test_linear_and_irreversible(check_state *st)
{
    const wff_yarn_failure f = law(0, 0);
    const double dt = 1e-6;
    for (int k = 0; k < 2; k++) {
        double ef = f.fail_strain[k], er = f.rupture_strain[k];
        /* a fresh yarn pulled to e: d = (e − ε_f)/(ε_r − ε_f), clamped */
        for (int i = 0; i <= 20; i++) {
            double e = 0.02 + 0.04 * i / 20.0;
            wff_yarn_damage y = wff_yarn_damage_step(&f, k, e, yarn_energy(e), 0, e, 0, dt);
            double want = e <= ef ? 0 : e >= er ? 1 : (e - ef) / (er - ef);
            CHECK_CLOSE(st, y.damage, want, 1e-14, 1e-14, "linear damage");
            CHECK_CLOSE(st, y.factor, 1 - want, 1e-14, 1e-14, "tension factor");
            CHECK_CLOSE(st, y.released, want * yarn_energy(e), 1e-14, 1e-18, "released");
        }
        /* load to the middle, unload, reload below the max: d unchanged */
        double e_max = 0.5 * (ef + er), d = 0, prev = 0, released = 0;
        const double path[] = {0.01, ef, e_max, 0.5 * ef, 0.0, -0.01, 0.9 * e_max, e_max};
        double d_at_max = (e_max - ef) / (er - ef);
        for (size_t i = 0; i < sizeof path / sizeof path[0]; i++) {
            wff_yarn_damage y = wff_yarn_damage_step(&f, k, path[i], yarn_energy(path[i]), d,
                                                     prev, 0, dt);
            CHECK(st, y.damage >= d, "damage decreased at step %zu: %g < %g", i, y.damage, d);
            CHECK(st, y.released >= 0, "negative release %g", y.released);
            released += y.released;
            d = y.damage;
            prev = y.strain_prev;
            if (i >= 2)
                CHECK_CLOSE(st, d, d_at_max, 1e-14, 1e-14, "held after the max");
        }
        CHECK_CLOSE(st, released, d_at_max * yarn_energy(e_max), 1e-14, 1e-18,
                    "released over the cycle");
        /* beyond rupture: 1, and stays 1 */
        wff_yarn_damage y = wff_yarn_damage_step(&f, k, 2 * er, yarn_energy(2 * er), d, prev, 0, dt);
        CHECK(st, y.damage == 1 && y.factor == 0, "not ruptured at 2 eps_r: %g", y.damage);
        y = wff_yarn_damage_step(&f, k, 0.001, yarn_energy(0.001), 1, 2 * er, 0, dt);
        CHECK(st, y.damage == 1 && y.factor == 0 && y.released == 0, "rupture undone");
    }
}

static void test_tension_only_and_held(check_state *st)
{
    const wff_yarn_failure f = law(0, 0);
    /* a compressed yarn keeps its force and energy whatever its damage */
    for (double d = 0; d <= 1; d += 0.25) {
        wff_yarn_damage y = wff_yarn_damage_step(&f, 0, -0.02, yarn_energy(-0.02), d, 0, 0, 1e-6);
        CHECK(st, y.factor == 1 && y.released == 0 && y.damage == d,
              "compression changed by damage %g: factor %g", d, y.factor);
        y = wff_yarn_damage_step(&f, 0, 0.02, yarn_energy(0.02), d, 0, 0, 1e-6);
        CHECK_CLOSE(st, y.factor, 1 - d, 1e-15, 1e-15, "tension at damage");
    }
    /* dt = 0 holds d and the strain history, even far beyond rupture */
    wff_yarn_damage y = wff_yarn_damage_step(&f, 1, 0.2, yarn_energy(0.2), 0.3, 0.01, 0, 0);
    CHECK(st, y.damage == 0.3 && y.strain_prev == 0.01 && y.released == 0,
          "dt = 0 moved the state: d %g prev %g", y.damage, y.strain_prev);
    CHECK_CLOSE(st, y.factor, 0.7, 1e-15, 1e-15, "dt = 0 factor");
    /* failure off: nothing */
    wff_yarn_failure off = f;
    off.enabled = 0;
    y = wff_yarn_damage_step(&off, 0, 0.2, yarn_energy(0.2), 0, 0, 0, 1e-6);
    CHECK(st, y.damage == 0 && y.factor == 1 && y.released == 0, "off: damaged");
    /* the damaged tension is the derivative of the damaged energy at fixed d:
     * W^d = (1 − d) ½ e² for e > 0, T^d = (1 − d) e */
    const double d = 0.4, h = 1e-6;
    for (double e = -0.03; e <= 0.03; e += 0.01) {
        if (fabs(e) < 2 * h)
            continue;
        double wp = wff_yarn_damage_step(&f, 0, e + h, 0, d, 0, 0, 0).factor * yarn_energy(e + h);
        double wm = wff_yarn_damage_step(&f, 0, e - h, 0, d, 0, 0, 0).factor * yarn_energy(e - h);
        double t = wff_yarn_damage_step(&f, 0, e, 0, d, 0, 0, 0).factor * e;
        CHECK_CLOSE(st, (wp - wm) / (2 * h), t, 1e-8, 1e-12, "T = dW/de at fixed d");
    }
}

static void test_rate(check_state *st)
{
    const double C = 1e4, p = 4;
    const wff_yarn_failure f = law(C, p), plain = law(0, 0);
    const double dt = 1e-6, e = 0.04; /* between ε_f and ε_r of family 1 */
    double last = 2;
    for (int i = 0; i < 6; i++) {
        double rate = i == 0 ? 0 : pow(10.0, i); /* 1/s */
        double prev = e - rate * dt;
        wff_yarn_damage y = wff_yarn_damage_step(&f, 0, e, yarn_energy(e), 0, prev, 0, dt);
        /* the stated law: both strains times φ = 1 + (ε̇/C)^(1/p) */
        double phi = 1 + pow(rate / C, 1 / p);
        double ef = 0.03 * phi, er = 0.045 * phi;
        double want = e <= ef ? 0 : e >= er ? 1 : (e - ef) / (er - ef);
        CHECK_CLOSE(st, y.damage, want, 1e-12, 1e-14, "rate law");
        CHECK(st, y.damage <= last, "damage grew with the rate: %g at %g 1/s", y.damage, rate);
        CHECK(st, y.strain_prev == e, "history not the strain now");
        last = y.damage;
        if (i == 0) {
            wff_yarn_damage z = wff_yarn_damage_step(&plain, 0, e, yarn_energy(e), 0, prev, 0, dt);
            CHECK_CLOSE(st, y.damage, z.damage, 1e-15, 1e-15, "zero rate = rate-free law");
        }
    }
    CHECK(st, last < 0.5 * wff_yarn_damage_step(&plain, 0, e, 0, 0, e, 0, dt).damage,
          "rate scaling too weak to test: %g", last);
    /* unloading fast scales by |ε̇| too, and damage never decreases */
    wff_yarn_damage y = wff_yarn_damage_step(&f, 0, e, yarn_energy(e), 0.5, e + 1e5 * dt, 0, dt);
    CHECK(st, y.damage == 0.5, "fast unloading changed damage: %g", y.damage);
    CHECK_CLOSE(st, wff_yarn_failure_rate_factor(&f, -1e6), 1 + pow(100.0, 1 / p), 1e-15, 1,
                "|rate|");
}

int main(void)
{
    check_state st = {0, 0};
    test_parse(&st);
    test_linear_and_irreversible(&st);
    test_tension_only_and_held(&st);
    test_rate(&st);
    return check_summary(&st, "test_yarn_failure");
}

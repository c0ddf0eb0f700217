/* The yarn failure law alone (plugin/cells/yarn_failure.h, docs/model.md §20):
 * damage linear between the failure and the rupture strain, never decreasing,
 * on tension only, the released energy, the Cowper–Symonds rate scaling, the
 * crack band (span per element length, onset unchanged, h_ref's law exactly at
 * h = h_ref, the energy of a bar's tear per unit cross-section independent of
 * the element length up to the snap-back length, the floor beyond), and every
 * bad key of the parser with a message naming it. The law inside the
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

    /* the crack band: optional, 0 = none, kept with failure off */
    CHECK(st, parse_text("failure = 1\n" FOUR "failure_band_length = 1.5e-3\n", &f, &err) == 0,
          "band: %s", err.message);
    CHECK(st, f.band_length == 1.5e-3 && wff_yarn_failure_states(&f) == 5, "band: %g, %d states",
          f.band_length, wff_yarn_failure_states(&f));
    CHECK(st, parse_text("failure = 1\n" FOUR "failure_band_length = 1.5e-3\nfailure_rate_C = 1e8\n"
                         "failure_rate_p = 5\n", &f, &err) == 0 &&
                  wff_yarn_failure_states(&f) == 5, "band and rate: %d states",
          wff_yarn_failure_states(&f));
    CHECK(st, parse_text("failure = 1\n" FOUR "failure_band_length = 0\n", &f, &err) == 0 &&
                  f.band_length == 0 && wff_yarn_failure_states(&f) == 2, "band 0: none");
    CHECK(st, parse_text("failure = 1\n" FOUR, &f, &err) == 0 && f.band_length == 0,
          "no band key: %g", f.band_length);
    CHECK(st, parse_text("failure = 0\n" FOUR "failure_band_length = 2e-3\n", &f, &err) == 0 &&
                  f.band_length == 2e-3 && wff_yarn_failure_states(&f) == 0,
          "band with failure off: %s", err.message);
    CHECK(st, parse_text("failure_band_length = 2e-3\n", &f, &err) == 0 &&
                  wff_yarn_failure_states(&f) == 0, "band alone: %s", err.message);
    kv_from_text(&kv, "failure = 1\n" FOUR "failure_band_length = 2e-3\n");
    CHECK(st, wff_yarn_failure_parse(&kv, &f, &err) == 0, "band used: %s", err.message);
    for (int i = 0; i < kv.n; i++)
        CHECK(st, kv.entry[i].used, "key '%s' not taken", kv.entry[i].key);
    expect_error(st, "failure = 1\n" FOUR "failure_band_length = -1e-3\n", "band < 0",
                 "'failure_band_length'", ">= 0");
    expect_error(st, "failure = 0\n" FOUR "failure_band_length = -1e-3\n", "band < 0 (off)",
                 "'failure_band_length'", "case.txt:6");
    expect_error(st, "failure = 1\n" FOUR "failure_band_length = wide\n", "band not a number",
                 "'failure_band_length'", "not a number");
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

/* ---- the crack band ------------------------------------------------------ */

static wff_yarn_failure band_law(double band_length)
{
    wff_yarn_failure f = law(0, 0);
    f.fail_strain[0] = f.fail_strain[1] = 0.038; /* KM2's (kevlar_s706.txt) */
    f.rupture_strain[0] = f.rupture_strain[1] = 0.0452;
    f.band_length = band_length;
    return f;
}

/* g = ∫ W dd per ½ EA over a rising strain from ε_f to ε_f + s: (3 ε_f² + 3 ε_f s + s²)/3. */
static double release_per_area(double onset, double span)
{
    return (3 * onset * onset + 3 * onset * span + span * span) / 3;
}

static void test_band_span(check_state *st)
{
    const double h_ref = 1.5e-3;
    const wff_yarn_failure f = band_law(h_ref), plain = band_law(0);
    const double ef = 0.038, s0 = 0.0452 - 0.038;
    const double snap = h_ref * release_per_area(ef, s0) / release_per_area(ef, 0);
    const double cap = h_ref * release_per_area(ef, s0) / release_per_area(ef, ef);
    /* no scaling: no band, h = 0 (a point outside any mesh), h = h_ref exactly */
    CHECK(st, wff_yarn_failure_span(&plain, 0, 1e-3) == s0, "no band: span scaled");
    CHECK(st, wff_yarn_failure_span(&f, 0, 0) == s0, "h = 0: span %g", wff_yarn_failure_span(&f, 0, 0));
    CHECK(st, wff_yarn_failure_span(&f, 1, h_ref) == s0, "h = h_ref: span %.17g, want %.17g",
          wff_yarn_failure_span(&f, 1, h_ref), s0);
    CHECK_CLOSE(st, wff_yarn_failure_span(&f, 0, h_ref * (1 + 1e-9)), s0, 1e-7, 0,
                "h just above h_ref (continuous)");
    CHECK_CLOSE(st, snap / h_ref, 1.2014, 1e-4, 0, "snap-back length / h_ref for 3.8 and 4.52 %");
    CHECK_CLOSE(st, cap / h_ref, 0.5149, 1e-3, 0, "the span's cap / h_ref for 3.8 and 4.52 %");
    /* the energy per unit crack length, g(s(h)) h, is h_ref's up to the snap-back length */
    double worst = 0, last = INFINITY;
    int monotone = 1;
    for (double r = 0.05; r < 3; r *= 1.07) {
        double h = r * h_ref, s = wff_yarn_failure_span(&f, 0, h);
        monotone &= s <= last;
        last = s;
        if (h < 0.999 * snap && h > 1.001 * cap)
            worst = fmax(worst, fabs(release_per_area(ef, s) * h /
                                     (release_per_area(ef, s0) * h_ref) - 1));
        if (h > snap)
            CHECK(st, s == WFF_YARN_BAND_SPAN_FLOOR * s0, "h = %g h_ref beyond the snap-back "
                  "length: span %g, not the floor %g", r, s, WFF_YARN_BAND_SPAN_FLOOR * s0);
        if (h < cap)
            CHECK(st, s == ef, "h = %g h_ref below the cap: span %g, not ε_f", r, s);
    }
    CHECK(st, monotone, "the span grows with the element length");
    CHECK(st, worst < 1e-13, "g(s(h)) h differs from h_ref's by %g", worst);
    /* onset unchanged, damage linear in the scaled span, never decreasing */
    for (double r = 0.25; r < 2.5; r *= 2) {
        double h = r * h_ref, s = wff_yarn_failure_span(&f, 0, h), d = 0;
        wff_yarn_damage y = wff_yarn_damage_step(&f, 0, ef, yarn_energy(ef), 0, 0, h, 1e-6);
        CHECK(st, y.damage == 0, "h = %g h_ref: damage %g at the onset", r, y.damage);
        y = wff_yarn_damage_step(&f, 0, ef + 0.5 * s, yarn_energy(ef + 0.5 * s), 0, 0, h, 1e-6);
        CHECK_CLOSE(st, y.damage, 0.5, 1e-12, 0, "half the scaled span");
        const double path[] = {0.039, 0.041, 0.039, 0.040, 0.05, 0.2, 0.0};
        for (int i = 0; i < 7; i++) {
            double e = path[i];
            y = wff_yarn_damage_step(&f, 0, e, yarn_energy(e), d, 0, h, 1e-6);
            CHECK(st, y.damage >= d, "band: damage decreased %g -> %g", d, y.damage);
            d = y.damage;
        }
        CHECK(st, d == 1, "band: not ruptured at 20 %% (%g)", d);
    }
    /* held (dt = 0) whatever h */
    wff_yarn_damage y = wff_yarn_damage_step(&f, 0, 0.2, yarn_energy(0.2), 0.3, 0, 0.5e-3, 0);
    CHECK(st, y.damage == 0.3 && y.released == 0, "band: dt = 0 changed damage");
}

/* A bar of n elements of length h = L/n, EA = 1, pulled quasi-statically
 * through rupture. The tear localises in one element (element 0, taken as
 * the weakest by an imperfection too small to matter): its strain ε_b rises
 * in small steps from 0 to past its rupture strain, the others carry the same
 * force, ε = (1 − d_b) ε_b ≤ ε_f, unloading. Returns the energy released by
 * damage in the whole bar per unit cross-section (J per EA): Σ released × h. */
static double bar_tear_energy(const wff_yarn_failure *f, double length, int n, int *damaged)
{
    const double h = length / n, top = 1.2 * (f->fail_strain[0] + 10 * (f->rupture_strain[0] -
                                                                        f->fail_strain[0]));
    const int steps = 40000;
    double d[64] = {0}, released = 0;
    for (int i = 1; i <= steps; i++) {
        double eb = top * i / steps;
        wff_yarn_damage yb = wff_yarn_damage_step(f, 0, eb, yarn_energy(eb), d[0], 0, h, 1e-6);
        d[0] = yb.damage;
        released += yb.released * h;
        double e = (1 - d[0]) * eb;
        for (int k = 1; k < n; k++) {
            wff_yarn_damage y = wff_yarn_damage_step(f, 0, e, yarn_energy(e), d[k], 0, h, 1e-6);
            d[k] = y.damage;
            released += y.released * h;
        }
    }
    *damaged = 0;
    for (int k = 0; k < n; k++)
        *damaged += d[k] > 0;
    return d[0] == 1 ? released : NAN;
}

static void test_band_bar(check_state *st)
{
    const double length = 8 * 1.5e-3, h_ref = 1.5e-3;
    const wff_yarn_failure f = band_law(h_ref), plain = band_law(0);
    const double want = yarn_energy(1) * release_per_area(0.038, 0.0452 - 0.038) * h_ref;
    const int ns[] = {4, 7, 8, 10, 12, 15, 16, 32};
    printf("  bar of 8 h_ref pulled through rupture, tear energy per EA / h_ref's "
           "(unscaled law's):\n   ");
    for (int i = 0; i < 8; i++) {
        int damaged, damaged0;
        double g = bar_tear_energy(&f, length, ns[i], &damaged);
        double g0 = bar_tear_energy(&plain, length, ns[i], &damaged0);
        double r = 8.0 / ns[i];
        printf(" h = %.3g h_ref: %.4f (%.4f)%s", r, g / want, g0 / want, i == 3 ? "\n   " : ";");
        CHECK(st, isfinite(g) && isfinite(g0), "bar of %d: not torn", ns[i]);
        CHECK(st, damaged == 1 && damaged0 == 1, "bar of %d: %d (unscaled %d) elements damaged, "
              "not the one that tears", ns[i], damaged, damaged0);
        CHECK_CLOSE(st, g0, want * r, 1e-3, 0, "unscaled: tear energy ∝ h");
        if (r > 0.52 && r < 1.2)
            CHECK_CLOSE(st, g, want, 1e-3, 0, "band: tear energy independent of h");
        else if (r >= 1.2)
            CHECK(st, g > want && g < g0, "h = %g h_ref beyond the snap-back length: %g, not "
                  "between h_ref's %g and the unscaled %g", r, g, want, g0);
        else
            CHECK(st, g < want && g > g0, "h = %g h_ref below the cap: %g, not between the "
                  "unscaled %g and h_ref's %g", r, g, g0, want);
    }
    printf("\n");
}

int main(void)
{
    check_state st = {0, 0};
    test_parse(&st);
    test_linear_and_irreversible(&st);
    test_tension_only_and_held(&st);
    test_rate(&st);
    test_band_span(&st);
    test_band_bar(&st);
    return check_summary(&st, "test_yarn_failure");
}

/* Which run-level features a model as configured takes (plugin/combine.c,
 * wff_model_refuses), and that where the table names a refusal of the core,
 * the core refuses the same:
 *   1. a plain King model takes every feature alone, and refuses the pairs
 *      remesh with checkpoint / restart / zones and static_amplitudes with
 *      zones; an unknown feature is an error (-1) naming the known ones;
 *   2. a pack of 2 plies takes checkpoint and restart (wff_model_save writes
 *      it; a pack of another gap or ply_mu refuses to load it, naming the
 *      pack's settings), refuses remesh and static_amplitudes (and the setting
 *      static_amplitudes is refused by the core);
 *   3. a material with yarn failure (erosion on) refuses remesh, zones and
 *      static_amplitudes, and takes checkpoint;
 *   4. a model with zones refuses remesh and static_amplitudes (the core's
 *      setting too);
 *   5. a cell without amplitudes refuses static_amplitudes (the core too);
 *   6. the reason is cut to the buffer, NUL-terminated;
 *   7. yarn slip without failure (kevlar_s706 with yarn_friction = 0.25, n_c 10,
 *      whose points carry the damage slots held at 0) is not a model with failure:
 *      erosion is off and refused naming failure = 0, static amplitudes and remesh
 *      are taken, and a struck square with static amplitudes slips (dissipation
 *      > 0) with its energy balance closed and no invariant violated. */
#include "check.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "wovenff/cell_ops.h"
#include "wovenff/combine.h"
#include "wovenff/pack.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define LINEAR "freefem_scripts/materials/kevlar_linear.txt"

/* wff_model_refuses(m, features) is want (0, 1, -1) with a reason holding text. */
static void expect(check_state *st, const wff_model *m, const char *features, int want,
                   const char *text)
{
    char why[512];
    int rc = wff_model_refuses(m, features, why, sizeof why);
    CHECK(st, rc == want, "'%s': %d, want %d (%s)", features, rc, want, why);
    CHECK(st, strstr(why, text) != NULL, "'%s': reason '%s' lacks '%s'", features, why, text);
    if (want == 0)
        CHECK(st, why[0] == '\0', "'%s' combines but has a reason '%s'", features, why);
}

static int model(check_state *st, wff_model *m, const char *material)
{
    test_rect r = {-0.02, 0.02, -0.02, 0.02, 6, 6, TEST_MESH_TRI, 1, 0, 0};
    wff_error err;
    int rc = test_model_rect(m, &r, material, &err);
    CHECK(st, rc == 0, "model of %s: %s", material, err.message);
    return rc;
}

int main(void)
{
    check_state st = {0, 0};
    wff_model m;
    wff_error err;
    char dir[512], path[600];
    if (test_tmp_dir("combine", dir, sizeof dir))
        return 1;

    /* 1. plain */
    if (model(&st, &m, KEVLAR))
        return check_summary(&st, "test_combine");
    expect(&st, &m, "", 0, "");
    expect(&st, &m, "remesh", 0, "");
    expect(&st, &m, "checkpoint restart static_amplitudes", 0, "");
    expect(&st, &m, "zones checkpoint", 0, "");
    expect(&st, &m, "remesh checkpoint", 1, "remesh with checkpoint: a checkpoint holds one mesh");
    expect(&st, &m, "restart remesh", 1, "remesh with restart: ");
    expect(&st, &m, "remesh zones", 1, "remesh with zones: a mesh transfer does not carry the zones");
    expect(&st, &m, "zones  static_amplitudes", 1, "static_amplitudes with zones: zones keep");
    expect(&st, &m, "remesh adapt", -1, "unknown feature 'adapt' (known: remesh checkpoint");
    expect(&st, &m, "checkpointx", -1, "unknown feature 'checkpointx'");
    /* 6. cut to the buffer */
    char small[12];
    CHECK(&st, wff_model_refuses(&m, "remesh checkpoint", small, sizeof small) == 1 &&
               strlen(small) == sizeof small - 1, "cut reason '%s'", small);

    /* 2. a pack */
    CHECK(&st, wff_model_set_plies(&m, 2, 1e-3, &err) == 0, "plies: %s", err.message);
    expect(&st, &m, "checkpoint restart", 0, "");
    expect(&st, &m, "remesh", 1, "remesh: the model is a pack of 2 plies: a mesh transfer");
    expect(&st, &m, "static_amplitudes", 1, "static_amplitudes: the model is a pack");
    expect(&st, &m, "zones", 1, "zones: the model is a pack of 2 plies");
    CHECK(&st, wff_model_save(&m, test_tmp_path(dir, "pack.bin", path, sizeof path), &err) == 0,
          "the pack's checkpoint: %s", err.message);
    CHECK(&st, wff_model_load_state(&m, path, &err) == 0, "the pack's checkpoint loaded: %s",
          err.message);
    {   /* the same pack with another ply friction: the settings' fingerprint */
        wff_model other;
        if (model(&st, &other, KEVLAR) == 0) {
            CHECK(&st, wff_model_set_plies(&other, 2, 1e-3, &err) == 0, "plies: %s", err.message);
            CHECK(&st, wff_model_set_option(&other, "ply_mu", 0.1, &err) == 0, "ply_mu: %s",
                  err.message);
            CHECK(&st, wff_model_load_state(&other, path, &err) != 0 &&
                       strstr(err.message, "ply_mu") != NULL,
                  "a pack of another ply_mu loads the checkpoint: '%s'", err.message);
            wff_model_free(&other);
        }
    }
    CHECK(&st, wff_model_set_option(&m, "static_amplitudes", 1, &err) != 0,
          "the core takes static amplitudes on the pack the table refuses");
    wff_model_free(&m);

    /* 3. yarn failure: erosion on */
    test_tmp_path(dir, "kevlar_failure.txt", path, sizeof path);
    CHECK(&st, test_tmp_copy_replacing(KEVLAR, path, "failure = 0", "failure = 1\n") == 1,
          "failure = 1 copy of %s", KEVLAR);
    if (model(&st, &m, path) == 0) {
        CHECK(&st, wff_material_damage_state(&m.mat, 0) >= 0 && wff_material_damage_state(&m.mat, 1) >= 0,
              "failure = 1: no damage state");
        expect(&st, &m, "remesh", 1, "remesh: the model has yarn failure with erosion on");
        expect(&st, &m, "zones", 1, "zones: the model has yarn failure with erosion on");
        expect(&st, &m, "static_amplitudes", 1, "static_amplitudes: the model has yarn failure");
        expect(&st, &m, "checkpoint restart", 0, "");
        wff_model_free(&m);
    }

    /* 4. zones */
    if (model(&st, &m, KEVLAR) == 0) {
        int n = wff_model_zone_disc(&m, 0, 0, 0.01, 1, LINEAR, 0, &err);
        CHECK(&st, n > 0, "zone: %s", err.message);
        expect(&st, &m, "remesh", 1, "remesh: the model has zonal materials (2 zones)");
        expect(&st, &m, "static_amplitudes", 1, "static_amplitudes: the model has zonal materials");
        expect(&st, &m, "checkpoint", 0, "");
        CHECK(&st, wff_model_set_option(&m, "static_amplitudes", 1, &err) != 0,
              "the core takes static amplitudes on the zones the table refuses");
        wff_model_free(&m);
    }

    /* 5. a cell without amplitudes */
    if (model(&st, &m, LINEAR) == 0) {
        expect(&st, &m, "static_amplitudes", 1, "the model's cell 'linear_yarns' has no crimp amplitudes");
        expect(&st, &m, "remesh checkpoint", 1, "remesh with checkpoint");
        CHECK(&st, wff_model_set_option(&m, "static_amplitudes", 1, &err) != 0,
              "the core takes static amplitudes on a cell without any");
        wff_model_free(&m);
    }
    /* 7. yarn slip, failure off */
    char half[600];
    test_tmp_path(dir, "kevlar_slip_half.txt", half, sizeof half);
    test_tmp_path(dir, "kevlar_slip.txt", path, sizeof path);
    CHECK(&st, test_tmp_copy_replacing(KEVLAR, half, "yarn_friction ", "yarn_friction = 0.25\n") == 1 &&
               test_tmp_copy_replacing(half, path, "slip_crossovers ", "slip_crossovers = 10\n") == 1,
          "slip copy of %s", KEVLAR);
    if (test_model_struck(&m, 12, path, 0, 0, &err) == 0) {
        expect(&st, &m, "static_amplitudes", 0, "");
        expect(&st, &m, "remesh", 0, "");
        CHECK(&st, m.mat.n_state == 8 && wff_material_damage_state(&m.mat, 0) == -1 &&
                   wff_material_damage_state(&m.mat, 1) == -1,
              "a slip-only material (%d states) has no damage state: %d %d", m.mat.n_state,
              wff_material_damage_state(&m.mat, 0), wff_material_damage_state(&m.mat, 1));
        CHECK(&st, wff_model_set_option(&m, "erosion", 1, &err) != 0 &&
                   strstr(err.message, "failure = 0") != NULL,
              "erosion on a slip-only material: '%s'", err.message);
        wff_model_free(&m);
    } else {
        CHECK(&st, 0, "struck slip model: %s", err.message);
    }
    /* the struck square to 0.3 ms with static amplitudes, with slip and without: the
     * energy balance as close with slip as without (the static balance's own error,
     * a few 1e-4 of the impact energy here: without slip this square's amplitudes
     * stop balancing at 0.36 ms) */
    const char *const square[2] = {KEVLAR, path};
    double error[2] = {0, 0}, slipped[2] = {0, 0};
    for (int i = 0; i < 2; i++) {
        if (test_model_struck(&m, 12, square[i], 0, 0, &err) ||
            wff_model_set_option(&m, "static_amplitudes", 1, &err) ||
            wff_model_advance(&m, 3e-4, 1000000, &err)) {
            CHECK(&st, 0, "static amplitudes, %s: %s", square[i], err.message);
            error[i] = NAN;
            continue;
        }
        wff_energies en;
        wff_model_energies(&m, &en);
        char violations[1024];
        int n = wff_model_invariants(&m, violations, sizeof violations);
        CHECK(&st, n == 0, "invariants, %s: %s", square[i], violations);
        error[i] = en.error;
        slipped[i] = en.dissipated_slip;
        printf("  static amplitudes %s slip to 0.3 ms: %ld steps, dissipated by slip %.4g J, "
               "energy error %.2e of %.3g J\n", i ? "with" : "without", m.step,
               en.dissipated_slip, en.error, en.reference);
        wff_model_free(&m);
    }
    CHECK(&st, slipped[0] == 0 && slipped[1] > 0, "slip dissipated: %g J without, %g J with",
          slipped[0], slipped[1]);
    CHECK(&st, fabs(error[1]) <= 2 * fabs(error[0]), "static amplitudes: energy error %.3g with "
          "slip against %.3g without", error[1], error[0]);
    test_tmp_remove(dir);
    return check_summary(&st, "test_combine");
}

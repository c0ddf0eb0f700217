/* Checkpoints (solver.h: wff_model_save / wff_model_load_state):
 *   1. a run stopped halfway, saved, loaded into a fresh model built the same
 *      way and continued ends bit for bit where the uninterrupted run ends
 *      (projectile with friction, friction clamp, shear flow; and a strip
 *      pulled at a changing prescribed velocity, which does external work);
 *   2. a checkpoint does not load into a model that differs (mesh sizes, mesh
 *      coordinates, material, preload, boundary conditions, settings,
 *      projectile), each with a message saying what differs;
 *   3. a truncated, altered, foreign or missing file is refused with its
 *      reason; writing into a missing folder fails; no .tmp is left behind. */
#include "check.h"
#include "test_tmp.h"
#include "test_meshes.h"
#include "wovenff/solver.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define ELASTIC "tests/data/king_elastic.txt"
#define D WFF_DOFS_PER_NODE

static char tmpdir[512];

static const char *tmp_path(const char *name)
{
    static char path[4][700];
    static int next;
    return test_tmp_path(tmpdir, name, path[next++ % 4], sizeof path[0]);
}

/* The impact case: clamped-by-friction square, projectile with friction. */
typedef struct impact_setup {
    const char *material;
    int nx, type;
    double jitter;
    double preload;      /* stretch of the preload (1: none) */
    const char *clamped; /* edge group held by the friction clamp */
    double dtfactor;
    int projectile;
} impact_setup;

static const impact_setup base = {KEVLAR, 12, TEST_MESH_TRI, 0.2, 1.002, "right", 0.8, 1};

static int build(check_state *st, wff_model *m, const impact_setup *s)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, s->nx, s->nx, s->type, 1, s->jitter, 7};
    wff_error err;
    if (test_model_rect(m, &r, s->material, &err)) {
        CHECK(st, 0, "%s", err.message);
        return -1;
    }
    double F[4] = {s->preload, 0, 0, s->preload}, dA[2] = {-2e-6, -3e-6};
    static const char *const fixed[] = {"left", "top", "bottom"};
    int rc = wff_model_set_preload(m, F, dA, &err);
    for (int g = 0; g < 3 && rc == 0; g++)
        for (int c = 0; c < 3 && rc == 0; c++)
            rc = wff_model_fix_group(m, fixed[g], c, &err) < 0;
    if (rc == 0)
        rc = wff_model_clamp_friction(m, s->clamped, 200, 0.3, &err) < 0;
    if (rc == 0)
        rc = wff_model_set_option(m, "dtfactor", s->dtfactor, &err);
    if (rc == 0 && s->projectile)
        rc = wff_model_set_projectile(m, 6.35e-3, 0.002, 40, 0.3, &err);
    CHECK(st, rc == 0, "setup: %s", err.message);
    if (rc)
        wff_model_free(m);
    return rc ? -1 : 0;
}

static int advance_blocks(check_state *st, wff_model *m, int from, int to, double block)
{
    wff_error err;
    for (int b = from + 1; b <= to; b++)
        if (wff_model_advance(m, b * block, 10000000, &err)) {
            CHECK(st, 0, "advance: %s", err.message);
            return -1;
        }
    return 0;
}

static int same_doubles(const double *a, const double *b, size_t n)
{
    return memcmp(a, b, n * sizeof(double)) == 0;
}

/* Everything a later step or an output reads, compared bitwise. */
static void compare_models(check_state *st, const wff_model *a, const wff_model *b,
                           const char *what)
{
    size_t nq = 3 * (size_t)a->el.n_tris + 4 * (size_t)a->el.n_quads;
    CHECK(st, a->step == b->step && a->time == b->time && a->dt == b->dt,
          "%s: step %ld/%ld, time %.17g/%.17g, dt %.17g/%.17g", what, a->step, b->step, a->time,
          b->time, a->dt, b->dt);
    CHECK(st, same_doubles(a->u, b->u, (size_t)a->n_dofs), "%s: u differs", what);
    CHECK(st, same_doubles(a->v, b->v, (size_t)a->n_dofs), "%s: v differs", what);
    CHECK(st, same_doubles(a->f, b->f, (size_t)a->n_dofs), "%s: f differs", what);
    CHECK(st, a->n_state == b->n_state &&
                  same_doubles(a->state, b->state, nq * (size_t)a->n_state),
          "%s: the points' states differ", what);
    CHECK(st, a->dissipated_failure == b->dissipated_failure &&
                  a->eroded_energy == b->eroded_energy && a->n_eroded == b->n_eroded,
          "%s: failure or eroded energy differs", what);
    CHECK(st, a->projectile.tip == b->projectile.tip &&
                  a->projectile.velocity == b->projectile.velocity &&
                  a->projectile.max_penetration == b->projectile.max_penetration,
          "%s: projectile differs: tip %.17g/%.17g, v %.17g/%.17g", what, a->projectile.tip,
          b->projectile.tip, a->projectile.velocity, b->projectile.velocity);
    wff_energies ea, eb;
    wff_model_energies(a, &ea);
    wff_model_energies(b, &eb);
    CHECK(st, memcmp(&ea, &eb, sizeof ea) == 0,
          "%s: energies differ: error %.17g/%.17g, friction %.17g/%.17g", what, ea.error,
          eb.error, ea.dissipated_friction, eb.dissipated_friction);
}

/* 1a. Impact: stop at block 6 of 12, save, load into a fresh model, go on. */
static void restart_impact(check_state *st)
{
    const double block = 10e-6;
    wff_model whole, first, second;
    if (build(st, &whole, &base))
        return;
    if (advance_blocks(st, &whole, 0, 12, block) == 0 && build(st, &first, &base) == 0) {
        wff_error err;
        const char *file = tmp_path("impact.ckpt");
        if (advance_blocks(st, &first, 0, 6, block) == 0) {
            int rc = wff_model_save(&first, file, &err);
            CHECK(st, rc == 0, "save: %s", err.message);
            CHECK(st, access(tmp_path("impact.ckpt.tmp"), F_OK) != 0, "no .tmp left behind");
        }
        wff_model_free(&first);
        if (build(st, &second, &base) == 0) {
            int rc = wff_model_load_state(&second, file, &err);
            CHECK(st, rc == 0, "load: %s", err.message);
            if (rc == 0 && advance_blocks(st, &second, 6, 12, block) == 0)
                compare_models(st, &whole, &second, "impact restarted at 60 us");
            wff_energies e;
            wff_model_energies(&second, &e);
            printf("  impact restart: %ld steps, projectile %.4f m/s, friction %.4e J, shear "
                   "dissipation %.4e J, energy error %.2e: bitwise equal to the whole run\n",
                   second.step, second.projectile.velocity, e.dissipated_friction,
                   e.dissipated_shear, e.error);
            CHECK(st, e.dissipated_shear > 0 && e.dissipated_friction > 0,
                  "the case exercises shear flow and friction");
            wff_model_free(&second);
        }
    }
    wff_model_free(&whole);
}

/* 1b. Strip pulled at a velocity changed every block: external work and
 * reactions carry over. */
static int build_strip(check_state *st, wff_model *m)
{
    test_rect r = {0, 0.05, 0, 0.01, 10, 2, TEST_MESH_QUAD, 0, 0, 0};
    wff_error err;
    if (test_model_rect(m, &r, KEVLAR, &err)) {
        CHECK(st, 0, "%s", err.message);
        return -1;
    }
    int rc = wff_model_fix_group(m, "left", WFF_UX, &err) < 0 ||
             wff_model_fix_group(m, "left", WFF_UZ, &err) < 0 ||
             wff_model_fix_group(m, "bottom", WFF_UY, &err) < 0 ||
             wff_model_prescribe_group(m, "right", WFF_UX, 0, &err) < 0;
    CHECK(st, rc == 0, "strip setup: %s", err.message);
    if (rc)
        wff_model_free(m);
    return rc ? -1 : 0;
}

static int pull(check_state *st, wff_model *m, int from, int to)
{
    wff_error err;
    for (int b = from + 1; b <= to; b++) {
        double v = 0.2 * b;
        if (wff_model_prescribe_group(m, "right", WFF_UX, v, &err) < 0 ||
            wff_model_advance(m, b * 5e-6, 10000000, &err)) {
            CHECK(st, 0, "strip: %s", err.message);
            return -1;
        }
    }
    return 0;
}

static void restart_strip(check_state *st)
{
    wff_model whole, first, second;
    if (build_strip(st, &whole))
        return;
    wff_error err;
    const char *file = tmp_path("strip.ckpt");
    if (pull(st, &whole, 0, 10) == 0 && build_strip(st, &first) == 0) {
        if (pull(st, &first, 0, 4) == 0)
            CHECK(st, wff_model_save(&first, file, &err) == 0, "save: %s", err.message);
        wff_model_free(&first);
        if (build_strip(st, &second) == 0) {
            /* the script sets the block's velocity before it loads: the load
             * restores the velocity in force at the checkpoint */
            int rc = wff_model_load_state(&second, file, &err);
            CHECK(st, rc == 0, "load: %s", err.message);
            if (rc == 0 && pull(st, &second, 4, 10) == 0) {
                compare_models(st, &whole, &second, "strip restarted at 20 us");
                CHECK(st, same_doubles(whole.reaction, second.reaction, (size_t)whole.n_dofs),
                      "reactions");
                CHECK(st, whole.external_work == second.external_work && whole.external_work > 0,
                      "external work %.17g / %.17g", whole.external_work, second.external_work);
                printf("  strip restart: %ld steps, external work %.6e J: bitwise equal\n",
                       second.step, second.external_work);
            }
            wff_model_free(&second);
        }
    }
    wff_model_free(&whole);
}

/* 2. Loading into a model that differs. */
static void expect_refused(check_state *st, const impact_setup *s, const char *file,
                           const char *want, const char *what)
{
    wff_model m;
    if (build(st, &m, s))
        return;
    wff_error err;
    err.message[0] = 0;
    int rc = wff_model_load_state(&m, file, &err);
    CHECK(st, rc != 0, "%s: a mismatched checkpoint loaded", what);
    CHECK(st, strstr(err.message, want) != NULL, "%s: message '%s' lacks '%s'", what,
          err.message, want);
    CHECK(st, strstr(err.message, file) != NULL, "%s: message names the file: %s", what,
          err.message);
    printf("  refused (%s): %s\n", what, err.message);
    CHECK(st, m.step == 0 && m.time == 0, "%s: the model is untouched", what);
    wff_model_free(&m);
}

static void mismatches(check_state *st)
{
    wff_model m;
    if (build(st, &m, &base))
        return;
    wff_error err;
    const char *file = tmp_path("base.ckpt");
    int rc = advance_blocks(st, &m, 0, 1, 5e-6) || wff_model_save(&m, file, &err);
    wff_model_free(&m);
    CHECK(st, rc == 0, "save: %s", err.message);
    if (rc)
        return;
    impact_setup s;
    s = base, s.nx = 10;
    expect_refused(st, &s, file, "was written for a model of 169 nodes", "mesh size");
    s = base, s.jitter = 0.1;
    expect_refused(st, &s, file, "the mesh differs", "mesh coordinates");
    s = base, s.material = ELASTIC;
    expect_refused(st, &s, file, "the material differs", "material");
    s = base, s.preload = 1.003;
    expect_refused(st, &s, file, "the lumped masses differ", "preload");
    s = base, s.clamped = "left"; /* left now clamped by friction, right fixed */
    expect_refused(st, &s, file, "the boundary conditions differ", "boundary conditions");
    s = base, s.dtfactor = 0.7;
    expect_refused(st, &s, file, "solver settings dtfactor 0.8", "dtfactor");
    s = base, s.projectile = 0;
    expect_refused(st, &s, file, "written with a projectile, this model has none", "projectile");

    /* 3. damaged files */
    FILE *in = fopen(file, "rb");
    fseek(in, 0, SEEK_END);
    long size = ftell(in);
    rewind(in);
    unsigned char *buf = malloc((size_t)size);
    CHECK(st, fread(buf, 1, (size_t)size, in) == (size_t)size, "read back");
    fclose(in);
    const char *bad = tmp_path("bad.ckpt");
    FILE *out = fopen(bad, "wb");
    fwrite(buf, 1, (size_t)size - 100, out);
    fclose(out);
    expect_refused(st, &base, bad, "is truncated", "truncated");
    buf[size / 2] ^= 0x10;
    out = fopen(bad, "wb");
    fwrite(buf, 1, (size_t)size, out);
    fclose(out);
    expect_refused(st, &base, bad, "corrupt (checksum mismatch)", "one bit flipped");
    out = fopen(bad, "wb");
    fputs("time,apex\n0,0\n", out);
    fclose(out);
    expect_refused(st, &base, bad, "is not a wovenff checkpoint", "foreign file");
    expect_refused(st, &base, tmp_path("missing.ckpt"), "cannot open checkpoint", "missing");
    free(buf);

    if (build(st, &m, &base) == 0) {
        const char *nowhere = tmp_path("no_such_folder/x.ckpt");
        rc = wff_model_save(&m, nowhere, &err);
        CHECK(st, rc != 0 && strstr(err.message, "cannot write checkpoint"),
              "save into a missing folder: %s", err.message);
        printf("  refused (save into a missing folder): %s\n", err.message);
        wff_model_free(&m);
    }
}

int main(void)
{
    check_state st = {0, 0};
    if (test_tmp_dir("test_checkpoint", tmpdir, sizeof tmpdir))
        return 1;
    restart_impact(&st);
    restart_strip(&st);
    mismatches(&st);
    test_tmp_remove(tmpdir);
    return check_summary(&st, "test_checkpoint");
}

/* Material files: every malformed case is rejected with a message that names
 * the file, the line and the key; an unknown key is named with the known key
 * nearest to it (before a missing key it stands for); what is not a regular
 * file (a named pipe, a folder, a device) is refused without waiting on it;
 * the scales check (wff_material_scales) passes every material of the tree and
 * a factor of a few off, and names each unit slip with its key, line and
 * likely unit. */
#include "check.h"
#include "test_tmp.h"
#include "wovenff/material.h"
#include "wovenff/text_io.h"

#include <glob.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    char *buf = calloc(1, 65536);
    size_t n = fread(buf, 1, 65535, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* The Kevlar file with the line starting with `key` replaced by `line` (NULL:
 * removed); `line` is appended when no line starts with key. */
static void edit(const char *base, const char *key, const char *line, char *out, size_t size)
{
    out[0] = '\0';
    const char *p = base;
    int replaced = 0;
    size_t klen = strlen(key);
    while (*p) {
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p + 1) : strlen(p);
        int match = klen && strncmp(p, key, klen) == 0 && (p[klen] == ' ' || p[klen] == '=');
        if (match && !replaced) {
            replaced = 1;
            if (line) {
                strncat(out, line, size - strlen(out) - 1);
                strncat(out, "\n", size - strlen(out) - 1);
            }
        } else {
            strncat(out, p, len < size - strlen(out) - 1 ? len : size - strlen(out) - 1);
        }
        p += len;
    }
    if (!replaced && line) {
        strncat(out, line, size - strlen(out) - 1);
        strncat(out, "\n", size - strlen(out) - 1);
    }
}

/* Expect failure whose message contains every needle (NULL-terminated list). */
static void expect_error(check_state *st, const char *text, const char *what, const char *n1,
                         const char *n2, const char *n3)
{
    wff_material m;
    wff_error e = {{0}};
    int rc = wff_material_parse_text(text, "case.txt", &m, &e);
    CHECK(st, rc == -1, "%s: accepted", what);
    const char *needles[] = {"case.txt", n1, n2, n3};
    for (int i = 0; i < 4; i++)
        if (needles[i])
            CHECK(st, strstr(e.message, needles[i]) != NULL, "%s: message '%s' lacks '%s'", what,
                  e.message, needles[i]);
}

static int line_of(const char *text, const char *key)
{
    int line = 1;
    size_t klen = strlen(key);
    for (const char *p = text; *p; p++) {
        if ((p == text || p[-1] == '\n') && strncmp(p, key, klen) == 0 &&
            (p[klen] == ' ' || p[klen] == '='))
            return line;
        if (*p == '\n')
            line++;
    }
    return line;
}


/* Expect the scales check of text to pass (0). */
static void expect_scales_ok(check_state *st, const char *text, const char *what)
{
    wff_error e = {{0}};
    int rc = wff_material_scales_text(text, "case.txt", &e);
    CHECK(st, rc == 0, "%s: scales check %d: %s", what, rc, e.message);
}

/* Expect a unit slip (1) whose message holds every needle (NULL ends). */
static void expect_slip(check_state *st, const char *text, const char *what,
                        const char *const *needles)
{
    wff_error e = {{0}};
    int rc = wff_material_scales_text(text, "case.txt", &e);
    CHECK(st, rc == 1, "%s: scales check %d, want 1 (a slip): %s", what, rc,
          rc ? e.message : "");
    for (int i = 0; rc == 1 && needles[i]; i++)
        CHECK(st, strstr(e.message, needles[i]) != NULL, "%s: message '%s' lacks '%s'", what,
              e.message, needles[i]);
}

/* An unknown key named with its line and the known key nearest to it. */
static void test_unknown_keys(check_state *st, const char *base)
{
    static char text[70000];
    char needle[3][160];
    /* a slipped required key: named in place of "missing key" */
    const char *slips[][3] = {
        {"k_2", "k2", "k_2"},       {"kb_1", "kb1", "kb_1"},   {"K_I", "k_i", "K_I"},
        {"cell", "Cell", "cell"},   {"rho_A", "rhoA", "rho_A"},
        {"gammadot_0", "gamma_dot_0", "gammadot_0"}, {"p0_2", "p02", "p0_2"},
    };
    for (size_t i = 0; i < sizeof slips / sizeof slips[0]; i++) {
        char from[64], to[64];
        snprintf(from, sizeof from, "%s ", slips[i][0]);
        /* the line of the key, renamed in place (the value kept) */
        const char *at = strstr(base, from);
        while (at && at != base && at[-1] != '\n')
            at = strstr(at + 1, from);
        CHECK(st, at != NULL, "no line '%s' in the Kevlar file", slips[i][0]);
        if (!at)
            continue;
        const char *eol = strchr(at, '\n');
        snprintf(to, sizeof to, "%s", slips[i][1]);
        char line[200];
        snprintf(line, sizeof line, "%s%.*s", to, (int)(eol - at - strlen(slips[i][0])),
                 at + strlen(slips[i][0]));
        edit(base, slips[i][0], line, text, sizeof text);
        int l = line_of(text, slips[i][1]);
        snprintf(needle[0], sizeof needle[0], "case.txt:%d: unknown key '%s' (line %d)", l,
                 slips[i][1], l);
        snprintf(needle[1], sizeof needle[1], "did you mean '%s'?", slips[i][2]);
        expect_error(st, text, slips[i][1], needle[0], needle[1], NULL);
        wff_material m;
        wff_error e = {{0}};
        wff_material_parse_text(text, "case.txt", &m, &e);
        CHECK(st, strstr(e.message, "missing key") == NULL, "%s: still 'missing key': %s",
              slips[i][1], e.message);
    }
    /* an optional key slipped (the parse completes): the unknown key, the nearest known */
    edit(base, "lever", "levr = 0", text, sizeof text);
    snprintf(needle[0], sizeof needle[0], "unknown key 'levr' (line %d) for cell 'king_plain'",
             line_of(text, "levr"));
    expect_error(st, text, "levr", needle[0], "did you mean 'lever'?", NULL);
    edit(base, "tension_only", "tension_onyl = 0", text, sizeof text);
    expect_error(st, text, "tension_onyl", "unknown key 'tension_onyl'",
                 "did you mean 'tension_only'?", NULL);
    /* a key near nothing the cell knows: named, no guess */
    edit(base, "warp_spacing", "warp_spacing = 1", text, sizeof text);
    {
        wff_material m;
        wff_error e = {{0}};
        wff_material_parse_text(text, "case.txt", &m, &e);
        CHECK(st, strstr(e.message, "unknown key 'warp_spacing'") &&
                      !strstr(e.message, "did you mean"), "warp_spacing guessed: %s", e.message);
    }
    /* a missing key whose near neighbours are real keys (kb_2, k_1 for k_2):
     * still "missing key", no false guess */
    edit(base, "k_2", NULL, text, sizeof text);
    expect_error(st, text, "k_2 removed", "missing key 'k_2'", NULL, NULL);
    {
        wff_material m;
        wff_error e = {{0}};
        wff_material_parse_text(text, "case.txt", &m, &e);
        CHECK(st, !strstr(e.message, "did you mean"), "k_2 removed: a false guess: %s",
              e.message);
    }
    /* one-letter keys are not guessed from another letter (b for a) */
    edit(base, "a", "b = 1.0e5", text, sizeof text);
    expect_error(st, text, "a as b", "missing key 'a'", NULL, NULL);
}

/* What is not a regular file is refused at once, naming the path and its kind. */
static void test_not_regular(check_state *st)
{
    char dir[512], fifo[700];
    CHECK(st, test_tmp_dir("test_material_fifo", dir, sizeof dir) == 0, "temporary folder");
    test_tmp_path(dir, "material.fifo", fifo, sizeof fifo);
    CHECK(st, mkfifo(fifo, 0600) == 0, "mkfifo %s", fifo);
    alarm(20); /* a read that waits on the pipe fails the test (SIGALRM), not the suite */
    wff_material m;
    wff_error e = {{0}};
    CHECK(st, wff_material_load(fifo, &m, &e) == -1 && strstr(e.message, fifo) &&
                  strstr(e.message, "is a pipe") && strstr(e.message, "not a regular file"),
          "named pipe: %s", e.message);
    CHECK(st, wff_material_scales(fifo, &e) == -1 && strstr(e.message, "is a pipe"),
          "named pipe, scales check: %s", e.message);
    char *data = NULL;
    size_t size;
    CHECK(st, wff_read_file(fifo, "checkpoint", 1000, &data, &size, &e) == -1 &&
                  strstr(e.message, "checkpoint") && strstr(e.message, "is a pipe"),
          "named pipe as a checkpoint: %s", e.message);
    CHECK(st, wff_regular_file_check(fifo, "mesh file", &e) == -1 &&
                  strstr(e.message, "mesh file") && strstr(e.message, "is a pipe"),
          "named pipe as a mesh: %s", e.message);
    CHECK(st, wff_material_load(dir, &m, &e) == -1 && strstr(e.message, "is a folder"),
          "folder: %s", e.message);
    CHECK(st, wff_material_load("/dev/null", &m, &e) == -1 && strstr(e.message, "is a device"),
          "device: %s", e.message);
    alarm(0);
    CHECK(st, wff_regular_file_check(KEVLAR, "material file", &e) == 0, "a file: %s",
          e.message);
    test_tmp_remove(dir);
}

/* The scales check: every material of the tree passes, a factor of a few
 * passes, orders of magnitude are named. */
static void test_scales(check_state *st, const char *base)
{
    static char text[70000];
    const char *patterns[] = {"freefem_scripts/materials/*.txt", "tests/data/*.txt"};
    int checked = 0;
    for (int g = 0; g < 2; g++) {
        glob_t files;
        if (glob(patterns[g], 0, NULL, &files) != 0)
            continue;
        for (size_t i = 0; i < files.gl_pathc; i++) {
            wff_material m;
            wff_error e = {{0}};
            if (wff_material_load(files.gl_pathv[i], &m, &e) != 0)
                continue; /* (the tests' own cells, not materials: test_erosion checks those) */
            int rc = wff_material_scales(files.gl_pathv[i], &e);
            CHECK(st, rc == 0, "%s: scales check %d: %s", files.gl_pathv[i], rc, e.message);
            checked++;
        }
        globfree(&files);
    }
    CHECK(st, checked >= 10, "only %d material files of the tree checked", checked);
    printf("scales: %d material files of the tree pass\n", checked);

    /* a factor of a few off: accepted */
    const char *few[][2] = {{"rho_A", "rho_A = 0.6"},  {"rho_A", "rho_A = 0.05"},
                            {"rho_A", "rho_A = 14"},   {"k_1", "k_1 = 3e6"},
                            {"k_1", "k_1 = 1e8"},      {"p0_2", "p0_2 = 1.2e-3"},
                            {"p0_1", "p0_1 = 0.12e-3"}};
    for (size_t i = 0; i < sizeof few / sizeof few[0]; i++) {
        edit(base, few[i][0], few[i][1], text, sizeof text);
        expect_scales_ok(st, text, few[i][1]);
    }
    /* orders of magnitude: each named with its key, line, file, how far off and the unit */
    char where[64];
    edit(base, "rho_A", "rho_A = 181", text, sizeof text);
    snprintf(where, sizeof where, "(line %d of case.txt)", line_of(text, "rho_A"));
    expect_slip(st, text, "rho_A in g/m^2",
                (const char *[]){"rho_A = 181 kg/m^2", where, "~1000x", "0.03-1.5 kg/m^2",
                                 "given in g/m^2?", NULL});
    edit(base, "rho_A", "rho_A = 16", text, sizeof text);
    expect_slip(st, text, "rho_A = 16", (const char *[]){"rho_A = 16 kg/m^2", NULL});
    edit(base, "rho_A", "rho_A = 1.81e-4", text, sizeof text);
    expect_slip(st, text, "rho_A 1000x low",
                (const char *[]){"~1/1000 of", "check its unit (kg/m^2)", NULL});
    edit(base, "k_1", "k_1 = 1.03e4", text, sizeof text);
    snprintf(where, sizeof where, "(line %d of case.txt)", line_of(text, "k_1"));
    expect_slip(st, text, "k_1 in N/mm",
                (const char *[]){"k_1 = 10300 N/m", where, "the warp (family 1)",
                                 "~1000x softer", "wave speed of 167 m/s", "given in N/mm?",
                                 NULL});
    edit(base, "k_2", "k_2 = 1.03e10", text, sizeof text);
    expect_slip(st, text, "k_2 x 1000",
                (const char *[]){"k_2 = 1.03e+10 N/m", "the weft (family 2)", "~1000x stiffer",
                                 NULL});
    edit(base, "p0_1", "p0_1 = 0.3735", text, sizeof text);
    snprintf(where, sizeof where, "(line %d of case.txt)", line_of(text, "p0_1"));
    expect_slip(st, text, "p0_1 in mm",
                (const char *[]){"p0_1 = 0.3735 m", where, "yarn spacing 0.747 m", "~1000x",
                                 "given in mm?", NULL});
    /* the other cells' keys */
    char *linear = read_all("freefem_scripts/materials/kevlar_linear.txt");
    char *basket = read_all("freefem_scripts/materials/kevlar_basket.txt");
    CHECK(st, linear && basket, "read the linear and basket materials");
    if (linear && basket) {
        edit(linear, "yarn_spacing_2", "yarn_spacing_2 = 0.747", text, sizeof text);
        expect_slip(st, text, "yarn_spacing_2 in mm",
                    (const char *[]){"yarn_spacing_2 = 0.747 m", "given in mm?", NULL});
        edit(linear, "yarn_spacing_1", "yarn_spacing_1 = 747", text, sizeof text);
        expect_slip(st, text, "yarn_spacing_1 in um",
                    (const char *[]){"yarn_spacing_1 = 747 m", "given in um?", NULL});
        edit(linear, "S_1", "S_1 = 5150", text, sizeof text);
        expect_slip(st, text, "S_1 in N/mm",
                    (const char *[]){"S_1 = 5150 N/m", "given in N/mm?", NULL});
        edit(basket, "EA_1", "EA_1 = 3.9", text, sizeof text);
        expect_slip(st, text, "EA_1 in kN", (const char *[]){"EA_1 = 3.9 N", "given in kN?", NULL});
    }
    free(linear);
    free(basket);
    /* not a material: -1, the reader's message */
    wff_error e = {{0}};
    CHECK(st, wff_material_scales_text("cell = king_plain\n", "case.txt", &e) == -1 &&
                  strstr(e.message, "missing key"), "not a material: %s", e.message);
}

int main(void)
{
    check_state st = {0, 0};
    char *base = read_all(KEVLAR);
    CHECK(&st, base != NULL, "read %s", KEVLAR);
    if (!base)
        return check_summary(&st, "test_material");
    static char text[70000];
    char where[64];
    wff_material m;
    wff_error e;

    CHECK(&st, wff_material_parse_text(base, "case.txt", &m, &e) == 0, "kevlar parses: %s",
          e.message);
    CHECK(&st, wff_material_load(KEVLAR, &m, &e) == 0, "kevlar loads: %s", e.message);
    CHECK(&st, strcmp(m.cell->name, "king_plain") == 0, "cell name");
    CHECK(&st, m.areal_density == 0.181, "rho_A read");

    /* missing: each required key */
    const char *required[] = {"cell", "rho_A", "p0_1", "p0_2", "A0_1", "A0_2", "k_1", "k_2",
                              "kb_1", "kb_2", "K_I", "a", "K_d", "c", "K_s", "M_0",
                              "gammadot_0"};
    for (size_t i = 0; i < sizeof required / sizeof required[0]; i++) {
        edit(base, required[i], NULL, text, sizeof text);
        char key[64];
        snprintf(key, sizeof key, "'%s'", required[i]);
        expect_error(&st, text, "missing key", "missing", key, NULL);
    }
    /* optional keys really are optional */
    edit(base, "lever", NULL, text, sizeof text);
    CHECK(&st, wff_material_parse_text(text, "case.txt", &m, &e) == 0, "lever optional: %s",
          e.message);

    /* unknown key, with its line */
    edit(base, "warp_spacing", "warp_spacing = 1", text, sizeof text);
    snprintf(where, sizeof where, "case.txt:%d", line_of(text, "warp_spacing"));
    expect_error(&st, text, "unknown key", "unknown key", "'warp_spacing'", where);

    /* duplicate key: both lines named */
    edit(base, "k_9", "k_1 = 2e7", text, sizeof text);
    expect_error(&st, text, "duplicate", "duplicate", "'k_1'", "first given on line");

    /* non-numeric values */
    const char *bad_numbers[][2] = {{"k_1", "k_1 = abc"}, {"K_I", "K_I = 8.3e-3N"},
                                    {"a", "a = 1e5 2"}, {"K_s", "K_s = 1e999"},
                                    {"M_0", "M_0 = nan"}, {"rho_A", "rho_A = inf"}};
    for (size_t i = 0; i < sizeof bad_numbers / sizeof bad_numbers[0]; i++) {
        edit(base, bad_numbers[i][0], bad_numbers[i][1], text, sizeof text);
        char key[64];
        snprintf(key, sizeof key, "'%s'", bad_numbers[i][0]);
        snprintf(where, sizeof where, "case.txt:%d", line_of(text, bad_numbers[i][0]));
        expect_error(&st, text, bad_numbers[i][1], key, where, "number");
    }

    /* the one number grammar (decimal only, as the scenes' options): hex, a
     * comma, blanks inside, a lone point or sign are not numbers; overflow and
     * underflow are not finite numbers */
    const char *not_decimal[][2] = {{"k_1", "k_1 = 0x10"}, {"k_1", "k_1 = 1,5"},
                                    {"k_1", "k_1 = 1e"}, {"k_1", "k_1 = ."},
                                    {"k_1", "k_1 = -"}, {"k_1", "k_1 = 1.2.3"},
                                    {"k_1", "k_1 = 0x1p3"}, {"k_1", "k_1 = infinity"}};
    for (size_t i = 0; i < sizeof not_decimal / sizeof not_decimal[0]; i++) {
        edit(base, not_decimal[i][0], not_decimal[i][1], text, sizeof text);
        expect_error(&st, text, not_decimal[i][1], "'k_1'", "is not a number", "decimal");
    }
    const char *out_of_range[] = {"k_1 = 1e400", "k_1 = -1e400", "k_1 = 1e-400"};
    for (size_t i = 0; i < sizeof out_of_range / sizeof out_of_range[0]; i++) {
        edit(base, "k_1", out_of_range[i], text, sizeof text);
        expect_error(&st, text, out_of_range[i], "'k_1'", "not a finite number", NULL);
    }
    const char *decimal[] = {"k_1 = 2e7", "k_1 = +2E+7", "k_1 = 20000000.", "k_1 = .2e8"};
    for (size_t i = 0; i < sizeof decimal / sizeof decimal[0]; i++) {
        edit(base, "k_1", decimal[i], text, sizeof text);
        CHECK(&st, wff_material_parse_text(text, "case.txt", &m, &e) == 0,
              "'%s' is a number: %s", decimal[i], e.message);
    }
    CHECK(&st, wff_material_parse_text(base, "case.txt", &m, &e) == 0, "kevlar again");

    /* syntax */
    edit(base, "K_d", "K_d 1e8", text, sizeof text);
    expect_error(&st, text, "no '='", "expected 'key = value'", NULL, NULL);
    edit(base, "K_d", "K_d =", text, sizeof text);
    expect_error(&st, text, "empty value", "'K_d'", "no value", NULL);
    edit(base, "K_d", "K-d = 1e8", text, sizeof text);
    expect_error(&st, text, "bad key characters", "'K-d'", NULL, NULL);
    edit(base, "K_d", "= 1e8", text, sizeof text);
    expect_error(&st, text, "missing key name", "missing key before", NULL, NULL);

    /* cell */
    edit(base, "cell", "cell = satin_8", text, sizeof text);
    expect_error(&st, text, "unknown cell", "unknown unit cell 'satin_8'", "king_plain", NULL);

    /* physically impossible values */
    const char *impossible[][3] = {
        {"p0_1", "p0_1 = 0", "> 0"},          {"p0_2", "p0_2 = -3e-4", "> 0"},
        {"A0_1", "A0_1 = 0", "> 0"},          {"A0_2", "A0_2 = 0.5e-3", "smaller than"},
        {"k_1", "k_1 = -1e7", "> 0"},         {"k_2", "k_2 = 0", "> 0"},
        {"kb_1", "kb_1 = -1e-4", ">= 0"},     {"kb_2", "kb_2 = -1", ">= 0"},
        {"K_I", "K_I = -8e-3", "> 0"},        {"a", "a = 0", "> 0"},
        {"K_d", "K_d = -1", ">= 0"},          {"c", "c = 0.5", ">= 1"},
        {"K_s", "K_s = -1e-4", ">= 0"},       {"M_0", "M_0 = 0", "> 0"},
        {"gammadot_0", "gammadot_0 = -5", ">= 0"}, {"n", "n = 0.5", ">= 1"},
        {"lever", "lever = 2", "0"},          {"tension_only", "tension_only = 0.5", "0 or 1"},
        {"rho_A", "rho_A = 0", "> 0"},
    };
    for (size_t i = 0; i < sizeof impossible / sizeof impossible[0]; i++) {
        edit(base, impossible[i][0], impossible[i][1], text, sizeof text);
        char key[64];
        snprintf(key, sizeof key, "'%s'", impossible[i][0]);
        snprintf(where, sizeof where, "case.txt:%d", line_of(text, impossible[i][0]));
        expect_error(&st, text, impossible[i][1], key, where, impossible[i][2]);
    }

    /* files */
    CHECK(&st, wff_material_load("tests/data/no_such_material.txt", &m, &e) == -1 &&
                   strstr(e.message, "no_such_material.txt") && strstr(e.message, "cannot open"),
          "missing file: %s", e.message);
    memset(text, 'x', 300);
    strcpy(text + 300, " = 1\n");
    expect_error(&st, text, "long line", "line too long", "case.txt:1", NULL);

    /* overrides: a copy with values replaced, validated, written whole */
    {
        char dir[512], out[700];
        CHECK(&st, test_tmp_dir("test_material", dir, sizeof dir) == 0, "temporary folder");
        test_tmp_path(dir, "override_material.txt", out, sizeof out);
        int rc = wff_material_override(KEVLAR, "K_d=0,kb_1=0, kb_2=0", out, &e);
        CHECK(&st, rc == 0, "override: %s", rc ? e.message : "");
        wff_material mo;
        CHECK(&st, wff_material_load(out, &mo, &e) == 0, "overridden file loads: %s", e.message);
        double g = 0.5, F[6] = {1, sin(g), 0, cos(g), 0, 0}, dA[2] = {-20e-6, -20e-6};
        wff_point_result a, b;
        wff_material_evaluate(&m, F, dA, wff_rest_state, 0, &a);
        wff_material_evaluate(&mo, F, dA, wff_rest_state, 0, &b);
        CHECK(&st, a.diag[5] > 0 && b.diag[5] == 0 && b.diag[6] == 0,
              "K_d = 0 removes the spar forces (%g -> %g)", a.diag[5], b.diag[5]);
        double mech_a[WFF_MECH_MAX], mech_b[WFF_MECH_MAX];
        m.cell->energy_split(m.params, F, dA, wff_rest_state, mech_a);
        mo.cell->energy_split(mo.params, F, dA, wff_rest_state, mech_b);
        CHECK(&st, mech_a[1] > 0 && mech_b[1] == 0, "kb = 0 removes bending energy");
        CHECK(&st, mech_b[0] == mech_a[0] && mech_b[2] == mech_a[2] && mech_b[4] == mech_a[4],
              "other mechanisms unchanged");
        CHECK(&st, wff_material_override(KEVLAR, "K_x=1", out, &e) == -1 &&
                       strstr(e.message, "no key 'K_x'"), "unknown override key: %s", e.message);
        CHECK(&st, wff_material_override(KEVLAR, "k_1=-5", out, &e) == -1 &&
                       strstr(e.message, "'k_1'") && strstr(e.message, "> 0"),
              "impossible override value: %s", e.message);
        CHECK(&st, wff_material_override(KEVLAR, "K_d", out, &e) == -1 &&
                       strstr(e.message, "key=value"), "malformed override: %s", e.message);
        test_tmp_remove(dir);
    }
    test_unknown_keys(&st, base);
    test_not_regular(&st);
    test_scales(&st, base);
    free(base);
    return check_summary(&st, "test_material");
}

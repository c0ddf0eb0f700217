/* Material files: every malformed case is rejected with a message that names
 * the file, the line and the key. */
#include "check.h"
#include "test_tmp.h"
#include "wovenff/material.h"

#include <stdlib.h>
#include <string.h>

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
    free(base);
    return check_summary(&st, "test_material");
}

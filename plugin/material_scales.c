/* material_scales.c: a material's scales against woven fabrics, to catch
 * slips of units before a run (rho_A = 181 written in g/m^2, a pitch in mm,
 * a yarn stiffness in N/mm): the areal density, each family's yarn spacing
 * (mat->yarn_spacing, which every cell's parse sets) and each family's
 * stiffness (the cell's stress per width at 1 % stretch, over rho_A: the
 * square of a wave speed), each against a wide band of Kevlar-like fabrics
 * and their kin (docs/limits.md "Input checks"). Values a factor of a few
 * outside a band pass; orders of magnitude outside are a slip, named with the
 * key, its line and file, how far off it is and the likely unit. The key a
 * derived quantity came from is found by the shipped cells' key names; a cell
 * with other names gets the quantity named without its key. Knows the
 * material reader and the cells' ops; nothing of meshes or the solver. */
#include "wovenff/cell_ops.h"
#include "wovenff/material.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A band: what woven fabrics of this kind have (typical_lo .. typical_hi, the
 * message quotes it) and how far outside it a value may lie before it is a
 * slip (a factor `slack` beyond either end). */
typedef struct scale_band {
    double typical_lo, typical_hi, slack;
} scale_band;

/* Areal density of one ply, kg/m^2: a light aramid weave (Kevlar 49 style 120,
 * 0.061) to a heavy glass woven roving (~1.2); Kevlar S706 0.181, UHMWPE and
 * aramid ballistic weaves 0.1-0.5. Slip: outside 0.003..15. */
static const scale_band kArealDensity = {0.03, 1.5, 10};
/* Distance between neighbouring yarns, m: fine weaves (~60 ends/cm, 0.17 mm)
 * to rovings (~2 ends/cm, 5 mm); Kevlar S706 0.747 mm. Slip: outside 10 um..6 cm. */
static const scale_band kYarnSpacing = {0.1e-3, 6e-3, 10};
/* Stress per width at 1 % stretch / (1 % x rho_A), m^2/s^2, the square of an
 * in-plane wave speed: 1.5 km/s (nylon weaves) to 12 km/s (UHMWPE, the fibre's
 * own is ~12); Kevlar S706 5.3 km/s, glass ~4. Slip: a factor 14 in stiffness
 * below (400 m/s) or 11 above (40 km/s): a thousandfold slip (N/mm for N/m,
 * kN for N) of any fabric in the band lands outside. */
static const scale_band kSpecificStiffness = {1.5e3 * 1.5e3, 12e3 * 12e3, 1.6e9 / 1.44e8};

static const double kStretch = 0.01; /* the stretch the stiffness is measured at */

/* The power of ten nearest to value over the band's geometric middle. */
static int slip_power(const scale_band *b, double value)
{
    return (int)lround(log10(value / sqrt(b->typical_lo * b->typical_hi)));
}

static int off_band(const scale_band *b, double value)
{
    return !(value >= b->typical_lo / b->slack && value <= b->typical_hi * b->slack);
}

/* "~1000x" or "~1/1000 of" (power p of ten). */
static void ratio_text(int p, char *buf, size_t cap)
{
    if (p >= 0)
        snprintf(buf, cap, "~%.0fx", pow(10, p));
    else
        snprintf(buf, cap, "~1/%.0f of", pow(10, -p));
}

/* A key of the text with its value and line, or 0 if absent. */
static int text_key(const char *text, const char *key, double *value, int *line)
{
    const char *b, *e;
    if (!wff_material_text_find(text, key, &b, &e, line))
        return 0;
    char buf[WFF_KV_VALUE_MAX];
    snprintf(buf, sizeof buf, "%.*s", (int)(e - b), b);
    *value = strtod(buf, NULL);
    return 1;
}

/* The likely unit of a slip of 10^p in the quantity of `unit`, or "". */
static const char *likely_unit(const char *unit, int p)
{
    static const struct { const char *unit; int power; const char *hint; } hints[] = {
        {"kg/m^2", 3, "given in g/m^2?"},  {"kg/m^2", 6, "given in mg/m^2?"},
        {"m", 3, "given in mm?"},          {"m", 2, "given in cm?"},
        {"m", 6, "given in um?"},          {"N/m", -3, "given in N/mm?"},
        {"N/m", -6, "given in kN/mm?"},    {"N", -3, "given in kN?"},
        {"N", -6, "given in MN?"},
    };
    for (size_t i = 0; i < sizeof hints / sizeof hints[0]; i++)
        if (strcmp(hints[i].unit, unit) == 0 && hints[i].power == p)
            return hints[i].hint;
    return "";
}

static int report(wff_error *err, const char *hint, const char *unit, const char *format, ...)
    __attribute__((__format__(printf, 4, 5)));

static int report(wff_error *err, const char *hint, const char *unit, const char *format, ...)
{
    char what[WFF_ERROR_MAX];
    va_list args;
    va_start(args, format);
    vsnprintf(what, sizeof what, format, args);
    va_end(args);
    if (hint[0])
        wff_fail(err, "%s: %s", what, hint);
    else
        wff_fail(err, "%s: check its unit (%s)", what, unit);
    return 1;
}

static const char *const kFamily[2] = {"the warp (family 1)", "the weft (family 2)"};
static const char *const kFamilyOf[2] = {"the warp's (family 1)", "the weft's (family 2)"};

static int check_density(const wff_material *mat, const char *text, const char *source,
                         wff_error *err)
{
    double rho = mat->areal_density, given;
    int line = 0;
    if (!off_band(&kArealDensity, rho))
        return 0;
    text_key(text, "rho_A", &given, &line);
    int p = slip_power(&kArealDensity, rho);
    char ratio[32];
    ratio_text(p, ratio, sizeof ratio);
    return report(err, likely_unit("kg/m^2", p), "kg/m^2",
                  "rho_A = %g kg/m^2 (line %d of %s) is %s the areal density of Kevlar-like "
                  "fabrics (%g-%g kg/m^2; Kevlar S706 0.181)", rho, line, source, ratio,
                  kArealDensity.typical_lo, kArealDensity.typical_hi);
}

static int check_spacing(const wff_material *mat, int f, const char *text, const char *source,
                         wff_error *err)
{
    double spacing = mat->yarn_spacing[f];
    if (!off_band(&kYarnSpacing, spacing))
        return 0;
    int p = slip_power(&kYarnSpacing, spacing);
    char ratio[32], band[96];
    ratio_text(p, ratio, sizeof ratio);
    snprintf(band, sizeof band, "that of Kevlar-like fabrics (%g-%g mm; Kevlar S706 0.747 mm)",
             kYarnSpacing.typical_lo * 1e3, kYarnSpacing.typical_hi * 1e3);
    /* where it came from: the spacing itself, or twice a quarter wavelength */
    char key[2][16];
    double factor[2] = {1, 2};
    snprintf(key[0], sizeof key[0], "yarn_spacing_%d", f + 1);
    snprintf(key[1], sizeof key[1], "p0_%d", 2 - f);
    for (int k = 0; k < 2; k++) {
        double value;
        int line;
        if (text_key(text, key[k], &value, &line) &&
            fabs(value * factor[k] - spacing) <= 1e-12 * spacing) {
            if (k == 0)
                return report(err, likely_unit("m", p), "m",
                              "%s = %g m (line %d of %s): a yarn spacing %s %s", key[k],
                              value, line, source, ratio, band);
            return report(err, likely_unit("m", p), "m",
                          "%s = %g m (line %d of %s) makes %s yarn spacing %g m (twice "
                          "%s), %s %s", key[k], value, line, source, kFamilyOf[f], spacing,
                          key[k], ratio, band);
        }
    }
    return report(err, likely_unit("m", p), "m",
                  "%s: %s yarn spacing, %g m, is %s %s", source, kFamilyOf[f], spacing, ratio,
                  band);
}

double wff_material_specific_stiffness(const wff_material *mat, int family)
{
    double F[6] = {1, 0, 0, 1, 0, 0}, dA[2] = {0, 0}, state[WFF_STATE_MAX] = {0};
    F[family == 0 ? 0 : 3] = 1 + kStretch;
    wff_point_result r;
    if (wff_material_evaluate(mat, F, dA, state, 0, &r) != WFF_POINT_OK)
        return NAN;
    double stress = r.stress[family == 0 ? 0 : 3]; /* N/m */
    return stress / kStretch / mat->areal_density; /* m^2/s^2 */
}

static int check_stiffness(const wff_material *mat, int f, const char *text, const char *source,
                           wff_error *err)
{
    double specific = wff_material_specific_stiffness(mat, f);
    if (!(specific > 0) || !off_band(&kSpecificStiffness, specific))
        return 0; /* (NaN: the cell's own business; none in tension: the cell decides) */
    int p = slip_power(&kSpecificStiffness, specific);
    char what[320];
    snprintf(what, sizeof what, "%s is ~%.0fx %s than Kevlar-like fabrics: its stress per width "
             "at 1 %% stretch over (1 %% x rho_A) is %.3g m^2/s^2, a wave speed of %.3g m/s "
             "(such fabrics %g-%g km/s; Kevlar S706 5.3 km/s)", kFamily[f], pow(10, abs(p)),
             p < 0 ? "softer" : "stiffer", specific,
             sqrt(specific), sqrt(kSpecificStiffness.typical_lo) / 1e3,
             sqrt(kSpecificStiffness.typical_hi) / 1e3);
    static const struct { const char *prefix, *unit; } keys[] = {
        {"k_", "N/m"}, {"EA_", "N"}, {"S_", "N/m"}};
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++) {
        char key[16];
        double value;
        int line;
        snprintf(key, sizeof key, "%s%d", keys[k].prefix, f + 1);
        if (text_key(text, key, &value, &line))
            return report(err, likely_unit(keys[k].unit, p), keys[k].unit,
                          "%s = %g %s (line %d of %s): %s", key, value, keys[k].unit, line,
                          source, what);
    }
    return report(err, "", "N/m", "%s: %s", source, what);
}

int wff_material_scales_text(const char *text, const char *source, wff_error *err)
{
    wff_material *mat = malloc(sizeof *mat);
    if (!mat)
        return wff_fail(err, "%s: out of memory", source);
    int rc = wff_material_parse_text(text, source, mat, err);
    if (rc == 0)
        rc = check_density(mat, text, source, err);
    for (int f = 0; f < 2 && rc == 0; f++)
        rc = check_spacing(mat, f, text, source, err);
    for (int f = 0; f < 2 && rc == 0; f++)
        rc = check_stiffness(mat, f, text, source, err);
    free(mat);
    return rc;
}

int wff_material_scales(const char *path, wff_error *err)
{
    char *text;
    if (wff_read_text_file(path, "material file", WFF_MATERIAL_FILE_MAX, &text, err))
        return -1;
    int rc = wff_material_scales_text(text, path, err);
    free(text);
    return rc;
}

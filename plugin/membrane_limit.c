/* membrane_limit.c: the Phoenix–Porwal membrane estimate of a pack's ballistic
 * limit (include/wovenff/membrane_limit.h; docs/penetration.md "The
 * Phoenix–Porwal estimate"), the formulas of tools/phoenix_porwal.sh, for N
 * plies of any cell. Pure arithmetic, and a material file read for its wave
 * speed (the cell's own stiffness at 1 % stretch), failure strain and areal
 * density; nothing of meshes, the solver or FreeFEM. */
#include "wovenff/membrane_limit.h"

#include "wovenff/material.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

double wff_pp_edge_factor(double gamma, double x)
{
    /* K(x) = x exp(−4Γ(x² − 1)/3): the edge strain x ε_c with ε_c Smith's strain
     * for the speed V = V0/(1+Γ) exp(−Γ(x² − 1)), over Smith's strain for V0/(1+Γ) */
    return x * exp(-4.0 * gamma * (x * x - 1.0) / 3.0);
}

/* V50 = √2 (1 + Γ) c (ε_max / K)^(3/4), m/s */
static double pp_speed(const wff_pp_input *in, double k)
{
    return sqrt(2.0) * (1.0 + in->gamma) * in->wave_speed * pow(in->failure_strain / k, 0.75);
}

static int positive(double value, const char *name, const char *unit, wff_error *err)
{
    if (isfinite(value) && value > 0)
        return 0;
    return wff_fail(err, "Phoenix-Porwal estimate: %s = %g %s: must be finite and > 0", name,
                    value, unit);
}

int wff_phoenix_porwal(const wff_pp_input *in, wff_pp_result *out, wff_error *err)
{
    if (positive(in->wave_speed, "wave_speed (c)", "m/s", err) ||
        positive(in->failure_strain, "failure_strain (eps_max)", "", err) ||
        positive(in->gamma, "gamma (Gamma = m_m / M_p)", "", err))
        return -1;
    if (!(isfinite(in->opening_ratio) && in->opening_ratio >= 0))
        return wff_fail(err, "Phoenix-Porwal estimate: opening_ratio (R_o / r_p) = %g: must be "
                        "finite and >= 0 (0: no clamp)", in->opening_ratio);
    double x_peak = sqrt(3.0 / (8.0 * in->gamma)); /* x*² = 3/(8Γ): dK/dx = 0 */
    if (x_peak < 1.0)
        x_peak = 1.0; /* the cone starts at the projectile's edge */
    out->x_peak = x_peak;
    out->k_max = wff_pp_edge_factor(in->gamma, x_peak);
    out->v50 = pp_speed(in, out->k_max);
    out->k_clamp = out->v50_clamp = 0;
    if (in->opening_ratio > 0 && in->opening_ratio < x_peak) {
        out->k_clamp = wff_pp_edge_factor(in->gamma, in->opening_ratio);
        out->v50_clamp = pp_speed(in, out->k_clamp);
    }
    return 0;
}

/* The value of `key` in the material text, or fallback when absent; −1 (err
 * naming file, line and key) when present but not a finite number. */
static int text_number_or(const char *text, const char *path, const char *key, double fallback,
                          double *value, wff_error *err)
{
    const char *b, *e;
    int line;
    if (!wff_material_text_find(text, key, &b, &e, &line)) {
        *value = fallback;
        return 0;
    }
    if (wff_parse_number_span(b, e, value) || !isfinite(*value))
        return wff_fail(err, "%s:%d: %s = '%.*s': not a number", path, line, key, (int)(e - b), b);
    return 0;
}

static int estimate_from_text(const char *text, const char *path, int plies, double mass,
                              double radius, double opening_radius, wff_pp_result *out,
                              wff_pp_input *used, wff_error *err)
{
    wff_material *mat = malloc(sizeof *mat); /* (large: the cell's parameters) */
    if (!mat)
        return wff_fail(err, "%s: out of memory", path);
    int rc = wff_material_parse_text(text, path, mat, err);
    double specific = 0, strain = 0;
    if (rc == 0) {
        specific = wff_material_specific_stiffness(mat, 0);
        if (!(specific > 0 && isfinite(specific)))
            rc = wff_fail(err, "%s: cell %s: the warp's (family 1) stress per width at %g %% "
                          "stretch over rho_A is %g m^2/s^2: no tensile wave speed for the "
                          "Phoenix-Porwal estimate", path, mat->cell->name, WFF_PP_STRETCH * 100,
                          specific);
    }
    if (rc == 0)
        rc = text_number_or(text, path, "fail_strain_1", WFF_PP_DEFAULT_FAIL_STRAIN, &strain, err);
    if (rc == 0 && !(strain > 0))
        rc = wff_fail(err, "%s: fail_strain_1 = %g: the Phoenix-Porwal estimate needs a failure "
                      "strain > 0", path, strain);
    if (rc == 0) {
        wff_pp_input in = {
            .wave_speed = sqrt(specific),
            .failure_strain = strain,
            /* Γ = N ρ_A π r_p² / M_p: every ply's mass under the face */
            .gamma = plies * mat->areal_density * M_PI * radius * radius / mass,
            .opening_ratio = opening_radius / radius,
        };
        rc = wff_phoenix_porwal(&in, out, err);
        if (used)
            *used = in;
    }
    free(mat);
    return rc;
}

int wff_membrane_limit_estimate(const char *material_path, int plies, double mass,
                                double radius, double opening_radius, wff_pp_result *out,
                                wff_pp_input *used, wff_error *err)
{
    if (plies < 1)
        return wff_fail(err, "Phoenix-Porwal estimate: plies = %d: must be >= 1", plies);
    if (positive(mass, "the projectile's mass", "kg", err) ||
        positive(radius, "the projectile's radius", "m", err))
        return -1;
    if (!(isfinite(opening_radius) && (opening_radius == 0 || opening_radius > radius)))
        return wff_fail(err, "Phoenix-Porwal estimate: the clamp's opening radius = %g m: must "
                        "be 0 (no clamp) or larger than the projectile's radius %g m",
                        opening_radius, radius);
    char *text;
    if (wff_read_text_file(material_path, "material file", WFF_MATERIAL_FILE_MAX, &text, err))
        return -1;
    int rc = estimate_from_text(text, material_path, plies, mass, radius, opening_radius, out,
                                used, err);
    free(text);
    return rc;
}

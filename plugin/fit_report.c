/* fit_report.c: what a fit leaves behind: fit.json, the material with the
 * fitted values, the curves and points for plots, and the files-in,
 * files-out entry points the FreeFEM binding calls (wff_fit_files,
 * wff_fit_synthesize_file). Knows the fit's result and the material text,
 * nothing of GSL, meshes or the solver. */
#include "wovenff/fit.h"

#include "wovenff/text_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- reports ---------------------------------------------------------------------------- */

int wff_fit_write_json(const wff_fit_result *res, const char *material_path,
                       const char *data_path, const char *path, wff_error *err)
{
    wff_text b = {0};
    int p = res->n_params;
    const char *weighting = wff_fit_weighting_name(res->weighting);
    wff_text_printf(&b, "{\n  \"status\": \"ok\",\n  \"material\": ");
    wff_text_json_string(&b, material_path);
    wff_text_printf(&b, ",\n  \"data\": ");
    wff_text_json_string(&b, data_path);
    wff_text_printf(&b, ",\n  \"points\": %d,\n  \"weighting\": \"%s\",\n  \"parameters\": {\n",
                    res->n_points, weighting ? weighting : "?");
    for (int j = 0; j < p; j++) {
        double relative = res->value[j] != 0 ? res->std_error[j] / fabs(res->value[j]) : NAN;
        wff_text_printf(&b, "    ");
        wff_text_json_string(&b, res->name[j]);
        wff_text_json_member(&b, ": {\"value\": ", res->value[j]);
        wff_text_json_member(&b, ", \"std_error\": ", res->std_error[j]);
        wff_text_json_member(&b, ", \"relative_std_error\": ", relative);
        wff_text_json_member(&b, ", \"start\": ", res->start[j]);
        wff_text_json_member(&b, ", \"lower\": ", res->lo[j]);
        wff_text_json_member(&b, ", \"upper\": ", res->hi[j]);
        wff_text_printf(&b, ", \"at_bound\": %s}%s\n", res->at_bound[j] ? "true" : "false",
                        j + 1 < p ? "," : "");
    }
    wff_text_printf(&b, "  },\n  \"correlation\": [");
    for (int a = 0; a < p; a++) {
        wff_text_printf(&b, "%s[", a ? ", " : "");
        for (int c = 0; c < p; c++)
            wff_text_json_member(&b, c ? ", " : "", res->correlation[a][c]);
        wff_text_printf(&b, "]");
    }
    wff_text_json_member(&b, "],\n  \"residual_norm\": ", res->residual_norm);
    wff_text_json_member(&b, ",\n  \"start_residual_norm\": ", res->start_residual_norm);
    wff_text_json_member(&b, ",\n  \"ssr\": ", res->ssr);
    wff_text_json_member(&b, ",\n  \"residual_variance\": ", res->s2);
    wff_text_json_member(&b, ",\n  \"reciprocal_condition\": ", res->condition);
    wff_text_printf(&b, ",\n  \"iterations\": %d,\n  \"function_evaluations\": %d,\n"
                    "  \"converged\": %d", res->iterations, res->f_evals, res->converged);
    wff_text_json_member(&b, ",\n  \"wall_seconds\": ", res->wall_seconds);
    wff_text_printf(&b, ",\n  \"tests\": {");
    int first = 1;
    for (int t = 0; t < WFF_FIT_TESTS; t++) {
        if (!res->test_points[t])
            continue;
        wff_text_printf(&b, "%s\n    \"%s\": {\"points\": %d", first ? "" : ",",
                        wff_fit_test_name(t), res->test_points[t]);
        wff_text_json_member(&b, ", \"scale_N_per_m\": ", res->test_scale[t]);
        wff_text_json_member(&b, ", \"rms_residual_N_per_m\": ", res->test_rms[t]);
        wff_text_printf(&b, "}");
        first = 0;
    }
    wff_text_printf(&b, "\n  }\n}\n");
    int rc = wff_text_write(&b, path, "fit report", err);
    free(b.s);
    return rc;
}

static int fitted_text(const char *text, const char *source, const wff_fit_result *res,
                       const double *values, char **out, wff_error *err)
{
    const char *names[WFF_FIT_PARAMS_MAX];
    for (int j = 0; j < res->n_params; j++)
        names[j] = res->name[j];
    size_t cap = strlen(text) + (size_t)res->n_params * 32 + 64;
    *out = malloc(cap);
    if (!*out)
        return wff_fail(err, "fit: out of memory");
    if (wff_fit_material_edit(text, source, res->n_params, names, values, *out, cap, err)) {
        free(*out);
        *out = NULL;
        return -1;
    }
    return 0;
}

int wff_fit_write_material(const char *material_text, const char *source_name,
                           const wff_fit_result *res, const char *data_path, const char *path,
                           wff_error *err)
{
    char *text = NULL;
    if (fitted_text(material_text, source_name, res, res->value, &text, err))
        return -1;
    wff_text b = {0};
    wff_text_printf(&b, "# Fitted by wovenff (wff_fit_run) from %s to %s:\n", source_name,
                    data_path ? data_path : "(data)");
    for (int j = 0; j < res->n_params; j++)
        wff_text_printf(&b, "#   %s = %.10g +- %.3g (1 standard error; start %.6g)%s\n",
                        res->name[j], res->value[j], res->std_error[j], res->start[j],
                        res->at_bound[j] ? " AT A BOUND" : "");
    wff_text_printf(&b, "#   residual norm %.6g (start %.6g), %d points, %d iterations\n",
                    res->residual_norm, res->start_residual_norm, res->n_points, res->iterations);
    wff_text_printf(&b, "%s", text);
    free(text);
    int rc = wff_text_write(&b, path, "fit report", err);
    free(b.s);
    return rc;
}

int wff_fit_write_curves(const char *material_text, const char *source_name,
                         const wff_fit_result *res, const wff_fit_data *data, int n_curve,
                         const char *path, const char *points_path, wff_error *err)
{
    if (n_curve < 2)
        n_curve = 2;
    wff_material m0, m1;
    char *t0 = NULL, *t1 = NULL;
    int rc = fitted_text(material_text, source_name, res, res->start, &t0, err);
    if (rc == 0)
        rc = fitted_text(material_text, source_name, res, res->value, &t1, err);
    if (rc == 0)
        rc = wff_material_parse_text(t0, source_name, &m0, err);
    if (rc == 0)
        rc = wff_material_parse_text(t1, source_name, &m1, err);
    free(t0);
    free(t1);
    if (rc)
        return -1;
    size_t size = (size_t)(data->n > n_curve ? data->n : n_curve);
    double *x = malloc(3 * size * sizeof *x);
    if (!x)
        return wff_fail(err, "fit: out of memory");
    double *y0 = x + size, *y1 = y0 + size;
    wff_text cb = {0}, pb = {0};
    int block = 0;
    for (int t = 0; t < WFF_FIT_TESTS && rc == 0; t++) {
        double lo = 0, hi = 0;
        int m = 0;
        for (int i = 0; i < data->n; i++)
            if (data->point[i].test == t) {
                lo = fmin(lo, data->point[i].x);
                hi = fmax(hi, data->point[i].x);
                m++;
            }
        if (m == 0)
            continue;
        for (int k = 0; k < n_curve; k++)
            x[k] = lo + (hi - lo) * k / (n_curve - 1);
        rc = wff_fit_predict(&m0, t, n_curve, x, y0, err);
        if (rc == 0)
            rc = wff_fit_predict(&m1, t, n_curve, x, y1, err);
        if (rc)
            break;
        wff_text_printf(&cb, "%s# test %s: x,y_start,y_fit\n", block ? "\n\n" : "",
                        wff_fit_test_name(t));
        for (int k = 0; k < n_curve; k++)
            wff_text_printf(&cb, "%.10g,%.10g,%.10g\n", x[k], y0[k], y1[k]);
        m = 0;
        for (int i = 0; i < data->n; i++)
            if (data->point[i].test == t)
                x[m++] = data->point[i].x;
        rc = wff_fit_predict(&m1, t, m, x, y1, err);
        if (rc)
            break;
        wff_text_printf(&pb, "%s# test %s: x,y,y_fit\n", block ? "\n\n" : "", wff_fit_test_name(t));
        m = 0;
        for (int i = 0; i < data->n; i++)
            if (data->point[i].test == t) {
                wff_text_printf(&pb, "%.10g,%.10g,%.10g\n", x[m], data->point[i].y, y1[m]);
                m++;
            }
        block++;
    }
    free(x);
    if (rc == 0 && (cb.failed || pb.failed))
        rc = wff_fail(err, "%s: out of memory", path);
    if (rc == 0)
        rc = wff_text_write(&cb, path, "fit curves", err);
    if (rc == 0 && points_path)
        rc = wff_text_write(&pb, points_path, "fit points", err);
    free(cb.s);
    free(pb.s);
    return rc;
}

/* ---- files in, files out ------------------------------------------------------------------ */

int wff_fit_files(const char *material_path, const char *data_path, const char *names,
                  const char *bounds, const char *starts, const wff_fit_options *opt,
                  const char *out_dir, wff_fit_result *res, wff_error *err)
{
    wff_fit_param params[WFF_FIT_PARAMS_MAX];
    int n;
    if (wff_fit_params_parse(names, bounds, starts, params, WFF_FIT_PARAMS_MAX, &n, err))
        return -1;
    char *text = NULL;
    if (wff_read_text_file(material_path, "material file", WFF_MATERIAL_FILE_MAX, &text, err))
        return -1;
    wff_material check;
    if (wff_material_parse_text(text, material_path, &check, err)) {
        free(text);
        return -1;
    }
    wff_fit_data data;
    if (wff_fit_data_read(data_path, &data, err)) {
        free(text);
        return -1;
    }
    int rc = wff_fit_run(text, material_path, &data, params, n, opt, res, err);
    if (rc == 0 && out_dir) {
        char path[4][1024];
        static const char *const leaf[4] = {"fit.json", "fitted_material.txt", "fit_curves.csv",
                                            "fit_points.csv"};
        for (int k = 0; k < 4 && rc == 0; k++)
            if (snprintf(path[k], sizeof path[k], "%s/%s", out_dir, leaf[k]) >=
                (int)sizeof path[k])
                rc = wff_fail(err, "fit: output folder name too long: %s", out_dir);
        if (rc == 0)
            rc = wff_fit_write_json(res, material_path, data_path, path[0], err);
        if (rc == 0)
            rc = wff_fit_write_material(text, material_path, res, data_path, path[1], err);
        if (rc == 0)
            rc = wff_fit_write_curves(text, material_path, res, &data, 80, path[2], path[3], err);
    }
    wff_fit_data_free(&data);
    free(text);
    return rc;
}

int wff_fit_synthesize_file(const char *material_path, const wff_fit_synth *spec,
                            const char *csv_path, int *n_points, wff_error *err)
{
    wff_material mat;
    if (wff_material_load(material_path, &mat, err))
        return -1;
    wff_fit_data data;
    if (wff_fit_synthesize(&mat, spec, &data, err))
        return -1;
    int rc = wff_fit_data_write(&data, csv_path, err);
    if (n_points)
        *n_points = data.n;
    wff_fit_data_free(&data);
    return rc;
}

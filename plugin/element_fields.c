/* element_fields.c: per-element output of a model's state by name
 * (include/wovenff/state.h): stress P, yarn stretches, shear angle, W, the
 * points' internal states by name (γᶠ, ...), yarn tensions and the cell's
 * diagnostics, evaluated at each element's
 * centre; the same on FreeFEM's triangle twin (a quadrilateral's value to
 * both its triangles). Reads the state; changes nothing. Knows cells only
 * through their names tables and evaluate (via the elements); nothing of the
 * integrator, contact or FreeFEM. */
#include "solver_internal.h"
#include "erosion.h"
#include "zones.h"
#include "pack.h"
#include "wovenff/state.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

int wff_model_element_center_eval(const wff_model *m, const double *u, int e,
                                  wff_point_result *out)
{
    wff_element_material scratch;
    const wff_element_material *em = wff_zones_element_material(m, e, &scratch);
    const int nt = m->el.n_tris, n = e < nt ? WFF_TRI_POINTS : WFF_QUAD_POINTS;
    const int ns = m->n_state, nz = em->mat->n_state;
    const double *g = m->state + (size_t)ns * wff_element_first_point(nt, e);
    double mean[WFF_STATE_MAX] = {0}; /* as wff_element_center_eval: Σ_q s_q / n */
    for (int q = 0; q < n; q++)
        for (int j = 0; j < nz; j++)
            mean[j] += g[ns * q + j] / n;
    return wff_element_center_eval_state(&m->el, em, m->mesh.xy, u, mean, e, out);
}

int wff_model_element_diag(const wff_model *m, int e, int diag)
{
    if (!m->zones || diag < 0)
        return diag;
    wff_element_material scratch;
    const wff_cell_type *cell = wff_zones_element_material(m, e, &scratch)->mat->cell;
    const wff_cell_type *base = m->mat.cell;
    if (cell == base)
        return diag;
    for (int d = 0; d < wff_cell_n_diag(cell); d++)
        if (strcmp(wff_cell_diag_name(cell, d), wff_cell_diag_name(base, diag)) == 0)
            return d;
    return -1;
}

enum { EF_P = 0, EF_LAMBDA = 6, EF_SHEAR = 8, EF_W, EF_TENSION, EF_DAMAGE = 12, EF_ERODED = 14,
       EF_STATE = 16, EF_DIAG = EF_STATE + WFF_STATE_MAX };

static const char *const fixed_names[] = {"P11", "P12", "P21", "P22", "P31", "P32",
                                          "lambda1", "lambda2", "shear_angle", "W"};
#define N_FIXED ((int)(sizeof fixed_names / sizeof fixed_names[0]))

/* Code of a field name (EF_*, EF_STATE + j, EF_TENSION + k, EF_DIAG + d) or -1. */
static int field_code(const wff_model *m, const char *name)
{
    const wff_cell_type *cell = m->mat.cell;
    for (int i = 0; i < N_FIXED; i++)
        if (strcmp(name, fixed_names[i]) == 0)
            return i;
    /* yarn damage by family (the cell's damage_state; 0 where a material has none)
     * and the erosion flag: every model has them */
    for (int k = 0; k < 2; k++)
        if (strcmp(name, k ? "damage2" : "damage1") == 0)
            return EF_DAMAGE + k;
    if (strcmp(name, "eroded") == 0)
        return EF_ERODED;
    for (int j = 0; j < m->n_state; j++)
        if (strcmp(name, wff_model_state_name(m, j)) == 0)
            return EF_STATE + j;
    for (int k = 0; k < 2; k++)
        if (strcmp(name, k ? "T2" : "T1") == 0 && wff_cell_yarn_tension_diag(cell, k) >= 0)
            return EF_TENSION + k;
    for (int d = 0; d < wff_cell_n_diag(cell); d++)
        if (strcmp(name, wff_cell_diag_name(cell, d)) == 0)
            return EF_DIAG + d;
    return -1;
}

static int unknown(const wff_model *m, const char *name, wff_error *err)
{
    const wff_cell_type *cell = m->mat.cell;
    char known[600] = "";
    for (int i = 0; i < N_FIXED; i++) {
        size_t used = strlen(known);
        snprintf(known + used, sizeof known - used, "%s%s", i ? " " : "", fixed_names[i]);
    }
    snprintf(known + strlen(known), sizeof known - strlen(known), " damage1 damage2 eroded");
    for (int j = 0; j < m->n_state; j++) {
        if (field_code(m, wff_model_state_name(m, j)) != EF_STATE + j)
            continue; /* (named like one above: damage1, damage2) */
        size_t used = strlen(known);
        snprintf(known + used, sizeof known - used, " %s", wff_model_state_name(m, j));
    }
    for (int k = 0; k < 2; k++)
        if (wff_cell_yarn_tension_diag(cell, k) >= 0 && field_code(m, k ? "T2" : "T1") < EF_DIAG) {
            size_t used = strlen(known);
            snprintf(known + used, sizeof known - used, " T%d", k + 1);
        }
    for (int d = 0; d < wff_cell_n_diag(cell); d++)
        if (field_code(m, wff_cell_diag_name(cell, d)) == EF_DIAG + d) {
            size_t used = strlen(known);
            snprintf(known + used, sizeof known - used, " %s", wff_cell_diag_name(cell, d));
        }
    return wff_fail(err, "unknown element field '%s' (known: %s)", name, known);
}

int wff_model_element_values(const wff_model *m, const char *name, double *out,
                             wff_error *err)
{
    if (wff_model_element_values_model(m, name, out, err))
        return -1;
    return wff_model_elements_to_user_in_place(m, out, err); /* (the user's numbering) */
}

int wff_model_element_values_model(const wff_model *m, const char *name, double *out,
                                   wff_error *err)
{
    int n_el = m->el.n_tris + m->el.n_quads;
    if (strcmp(name, "ply") == 0) { /* a pack's ply of each element, 0-based (pack.h) */
        for (int e = 0; e < n_el; e++)
            out[e] = wff_pack_element_ply(m, e);
        return 0;
    }
    int code = field_code(m, name);
    if (code < 0)
        return unknown(m, name, err);
    const double *Fp = m->em.F_pre;
    for (int e = 0; e < n_el; e++) {
        double value;
        if (code == EF_DAMAGE || code == EF_DAMAGE + 1) {
            value = wff_element_damage(m, e, code - EF_DAMAGE);
        } else if (code == EF_ERODED) {
            value = wff_element_eroded(&m->el, e);
        } else if (wff_element_eroded(&m->el, e) && wff_element_field_evaluated(m, name)) {
            value = 0; /* an eroded element carries nothing (and may be inverted) */
        } else if (code >= EF_STATE && code < EF_DIAG) { /* the mean of the element's points */
            int n = e < m->el.n_tris ? 3 : 4, ns = m->n_state;
            const double *g = m->state + (size_t)ns * (e < m->el.n_tris
                                                           ? 3 * (size_t)e
                                                           : 3 * (size_t)m->el.n_tris +
                                                                 4 * (size_t)(e - m->el.n_tris));
            value = 0;
            for (int q = 0; q < n; q++)
                value += g[ns * q + code - EF_STATE] / n;
        } else if (code == EF_LAMBDA || code == EF_LAMBDA + 1 || code == EF_SHEAR) {
            double F[6], dA[2], g[2][3];
            wff_element_center_state(&m->el, m->mesh.xy, m->u, e, F, dA);
            for (int i = 0; i < 3; i++) { /* g_k = F_eff E_k, F_eff = F F_pre */
                g[0][i] = F[2 * i] * Fp[0] + F[2 * i + 1] * Fp[2];
                g[1][i] = F[2 * i] * Fp[1] + F[2 * i + 1] * Fp[3];
            }
            if (code != EF_SHEAR) {
                const double *gk = g[code - EF_LAMBDA];
                value = sqrt(gk[0] * gk[0] + gk[1] * gk[1] + gk[2] * gk[2]);
            } else {
                double dot = g[0][0] * g[1][0] + g[0][1] * g[1][1] + g[0][2] * g[1][2];
                double cx = g[0][1] * g[1][2] - g[0][2] * g[1][1],
                       cy = g[0][2] * g[1][0] - g[0][0] * g[1][2],
                       cz = g[0][0] * g[1][1] - g[0][1] * g[1][0];
                value = M_PI_2 - atan2(sqrt(cx * cx + cy * cy + cz * cz), dot);
            }
        } else {
            wff_point_result r;
            wff_element_material zone;
            const wff_element_material *em = wff_zones_element_material(m, e, &zone);
            if (wff_model_element_center_eval(m, m->u, e, &r) != WFF_POINT_OK) {
                char what[96];
                wff_model_element_name(m, e, what, sizeof what);
                return wff_fail(err, "element field '%s': %s is degenerate (yarns collapsed "
                                "or parallel)", name, what);
            }
            if (code < EF_LAMBDA)
                value = r.stress[code];
            else if (code == EF_W)
                value = r.energy;
            else if (code < EF_DIAG) /* (a zone's cell: its own tension, 0 if none) */
                value = wff_cell_yarn_tension_diag(em->mat->cell, code - EF_TENSION) >= 0
                            ? r.diag[wff_cell_yarn_tension_diag(em->mat->cell, code - EF_TENSION)] : 0;
            else
                value = wff_model_element_diag(m, e, code - EF_DIAG) >= 0
                            ? r.diag[wff_model_element_diag(m, e, code - EF_DIAG)] : 0;
        }
        out[e] = value;
    }
    return 0;
}

int wff_element_field_evaluated(const wff_model *m, const char *name)
{
    int code = field_code(m, name);
    return code >= 0 && (code < EF_LAMBDA || code == EF_W || (code >= EF_TENSION &&
                                                              code < EF_DAMAGE) ||
                         code >= EF_DIAG);
}

int wff_model_element_field(const wff_model *m, const char *name, double *out,
                            wff_error *err)
{
    int nt = m->el.n_tris, nq = m->el.n_quads;
    /* the quads' values go to the tail first, then spread backwards in place */
    if (wff_model_element_values(m, name, out, err))
        return -1;
    for (int q = nq - 1; q >= 0; q--) {
        double value = out[nt + q];
        out[nt + 2 * q] = out[nt + 2 * q + 1] = value;
    }
    return 0;
}

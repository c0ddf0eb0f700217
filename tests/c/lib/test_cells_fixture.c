/* The C tests' own cells' shared pieces (test_cells_fixture.h). */
#include "test_cells_fixture.h"

#include <math.h>
#include <string.h>

const char *const tcell_diag_names[2] = {"T1", "T2"};
const char *const tcell_diag_units[2] = {"N", "N"};
const char *const tcell_mech_names[2] = {"yarn_stretch", "shear"};

double tcell_damage_reached(const tcell_params *c, double strain)
{
    double reached = (strain - c->fail_strain) / (c->rupture_strain - c->fail_strain);
    return reached < 0 ? 0 : reached > 1 ? 1 : reached;
}

int tcell_parse(wff_kv *kv, wff_material *mat, size_t size, wff_error *err)
{
    tcell_params *c = (tcell_params *)mat->params;
    memset(mat->params, 0, size);
    return wff_kv_number(kv, "S_1", &c->stiffness[0], err) ||
                   wff_kv_number(kv, "S_2", &c->stiffness[1], err) ||
                   wff_kv_number(kv, "G", &c->shear_stiffness, err) ||
                   wff_kv_number(kv, "fail_strain", &c->fail_strain, err) ||
                   wff_kv_number(kv, "rupture_strain", &c->rupture_strain, err)
               ? -1
               : 0;
}

/* The frame, the strains and the shear energy at F. */
static int yarns_at(const tcell_params *c, const double F[6], tcell_yarns *y)
{
    static const double unit[2] = {1, 1};
    if (wff_yarn_kinematics(unit, F, &y->fr) != WFF_POINT_OK)
        return WFF_POINT_DEGENERATE;
    for (int f = 0; f < 2; f++)
        y->strain[f] = y->fr.p[f] - 1;
    y->energy_shear = 0.5 * c->shear_stiffness * y->fr.gamma * y->fr.gamma;
    return WFF_POINT_OK;
}

int tcell_evaluate(tcell_law *law, const void *params, const double F[6], const double *state,
                   double dt, wff_point_result *out)
{
    const tcell_params *c = params;
    tcell_yarns y;
    if (yarns_at(c, F, &y) != WFF_POINT_OK) {
        wff_point_result_nan(out, 2);
        return WFF_POINT_DEGENERATE;
    }
    law(params, state, dt, &y, out);
    static const double no_spars[2] = {0, 0}, unit_scale[2] = {1, 1};
    double q[2][2];
    for (int f = 0; f < 2; f++)
        wff_q_coefficients(&y.fr, f, y.force[f], c->shear_stiffness * y.fr.gamma, no_spars,
                           &q[f][f], &q[f][1 - f]);
    wff_stress_from_q(&y.fr, q, unit_scale, out->stress);
    out->residual[0] = out->residual[1] = 0;
    out->energy = y.energy_yarn + y.energy_shear;
    out->diag[0] = y.force[0] * 1e-3; /* a yarn every mm */
    out->diag[1] = y.force[1] * 1e-3;
    return WFF_POINT_OK;
}

void tcell_energy_split(tcell_law *law, const void *params, const double F[6],
                        const double *state, double *mech)
{
    tcell_yarns y;
    if (yarns_at(params, F, &y) != WFF_POINT_OK) {
        mech[0] = mech[1] = NAN;
        return;
    }
    law(params, state, 0, &y, NULL);
    mech[0] = y.energy_yarn;
    mech[1] = y.energy_shear;
}

void tcell_wave_speeds(const void *params, double areal_density, const double F[6],
                       const double dA[2], double *membrane_speed, double *amplitude_omega)
{
    (void)dA;
    const tcell_params *c = params;
    tcell_yarns y;
    *amplitude_omega = 0;
    if (yarns_at(c, F, &y) != WFF_POINT_OK) {
        *membrane_speed = INFINITY;
        return;
    }
    double sn = fmax(y.fr.sin_t, 0.05), stretch_min = fmin(y.fr.p[0], y.fr.p[1]);
    double shear = 2 * c->shear_stiffness * (1 + fabs(y.fr.gamma) * (1 + 1 / sn)) /
                   (stretch_min * stretch_min);
    double membrane = 0;
    for (int f = 0; f < 2; f++)
        membrane = fmax(membrane, c->stiffness[f] + c->stiffness[f] * fabs(y.strain[f]) /
                                                        y.fr.p[f] + shear);
    *membrane_speed = sqrt(membrane / areal_density);
}

int tcell_struck(check_state *st, wff_model *m, const test_rect *r, const char *material,
                 double mass, double velocity)
{
    wff_error err;
    int rc = test_model_rect(m, r, material, &err);
    CHECK(st, rc == 0, "%s: %s", material, err.message);
    if (rc)
        return -1;
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int g = 0; g < 4 && rc >= 0; g++)
        for (int c = WFF_UX; c <= WFF_UZ && rc >= 0; c++)
            rc = wff_model_fix_group(m, edges[g], c, &err);
    if (rc >= 0)
        rc = wff_model_set_projectile(m, 6.35e-3, mass, velocity, 0.2, &err);
    CHECK(st, rc >= 0, "%s", err.message);
    if (rc < 0)
        wff_model_free(m);
    return rc < 0 ? -1 : 0;
}

/* The wrappers of include/wovenff/cell_ops.h: the one file that reads a
 * unit cell's table (`cell->`), so that a caller never tests for an op nor
 * repeats a fallback. Each is the op's call, or what cell.h says a cell
 * without it gets. */
#include "wovenff/cell_ops.h"

#include <math.h>
#include <stddef.h>

const char *wff_cell_name(const wff_cell_type *cell) { return cell->name; }
const char *wff_cell_summary(const wff_cell_type *cell) { return cell->summary; }
int wff_cell_amplitudes(const wff_cell_type *cell) { return cell->n_amplitudes; }
int wff_cell_n_diag(const wff_cell_type *cell) { return cell->n_diag; }
const char *wff_cell_diag_name(const wff_cell_type *cell, int d) { return cell->diag_names[d]; }
const char *wff_cell_diag_unit(const wff_cell_type *cell, int d) { return cell->diag_units[d]; }
int wff_cell_yarn_tension_diag(const wff_cell_type *cell, int k)
{
    return cell->yarn_tension_diag[k];
}
int wff_cell_n_mech(const wff_cell_type *cell) { return cell->n_mech; }
const char *wff_cell_mech_name(const wff_cell_type *cell, int i) { return cell->mech_names[i]; }
int wff_cell_n_state_max(const wff_cell_type *cell) { return cell->n_state_max; }
const char *wff_cell_state_name(const wff_cell_type *cell, int i)
{
    return cell->state_names[i];
}
const char *wff_cell_state_unit(const wff_cell_type *cell, int i)
{
    return cell->state_units[i];
}
int wff_cell_damage_state(const wff_cell_type *cell, int k) { return cell->damage_state[k]; }
int wff_material_damage_state(const wff_material *mat, int k)
{
    const wff_cell_type *cell = mat->cell;
    const int i = cell->damage_state[k];
    if (i < 0 || i >= mat->n_state || (cell->yarns_fail && !cell->yarns_fail(mat->params)))
        return -1;
    return i;
}
int wff_cell_has_energy_split(const wff_cell_type *cell) { return cell->energy_split != NULL; }
int wff_cell_has_reference_geometry(const wff_cell_type *cell)
{
    return cell->reference_geometry != NULL;
}

int wff_cell_parse(wff_kv *kv, wff_material *mat, wff_error *err)
{
    return mat->cell->parse(kv, mat, err);
}

int wff_material_evaluate(const wff_material *mat, const double F[6], const double dA[2],
                          const double *state, double dt, wff_point_result *out)
{
    out->slip_dissipated = 0; /* (a cell without yarn slip leaves it: none) */
    return mat->cell->evaluate(mat->params, F, dA, state, dt, out);
}

void wff_cell_wave_speeds(const wff_material *mat, const double F[6], const double dA[2],
                          double *membrane_speed, double *amplitude_omega)
{
    mat->cell->wave_speeds(mat->params, mat->areal_density, F, dA, membrane_speed,
                           amplitude_omega);
}

int wff_cell_energy_split(const wff_material *mat, const double F[6], const double dA[2],
                          const double *state, double *mech_energy)
{
    if (!mat->cell->energy_split)
        return -1;
    mat->cell->energy_split(mat->params, F, dA, state, mech_energy);
    return 0;
}

int wff_cell_reference_geometry(const wff_material *mat, double pitch0[2], double amplitude0[2])
{
    if (!mat->cell->reference_geometry)
        return -1;
    mat->cell->reference_geometry(mat->params, pitch0, amplitude0);
    return 0;
}

int wff_cell_has_shared(const wff_material *mat) { return mat->cell->evaluate_shared != NULL; }

/* Without the op: evaluate() at each point, Σ_q weight[q] × (its P, W,
 * dissipations), R unweighted, the states in place (cell.h). */
int wff_cell_evaluate_shared(const wff_material *mat, const double F[6], int n_points,
                             const double *dA, const double *weight, double *state, double dt,
                             double stress_sum[6], double *residual, double *energy,
                             double *dissipated, double *failure_dissipated,
                             double *slip_dissipated, int *bad_point)
{
    const wff_cell_type *cell = mat->cell;
    if (cell->evaluate_shared)
        return cell->evaluate_shared(mat->params, F, n_points, dA, weight, state, dt,
                                     stress_sum, residual, energy, dissipated,
                                     failure_dissipated, slip_dissipated, bad_point);
    *bad_point = 0;
    const int ns = mat->n_state;
    for (int q = 0; q < n_points; q++) {
        wff_point_result r;
        r.slip_dissipated = 0; /* (a cell without yarn slip leaves it: none) */
        double *ps = state + ns * q;
        int status = cell->evaluate(mat->params, F, dA + 2 * q, ps, dt, &r);
        if (status != WFF_POINT_OK) {
            *bad_point = q;
            return status;
        }
        for (int i = 0; i < 6; i++)
            stress_sum[i] += weight[q] * r.stress[i];
        residual[2 * q] = r.residual[0];
        residual[2 * q + 1] = r.residual[1];
        *energy += weight[q] * r.energy;
        *dissipated += weight[q] * r.dissipated;
        *failure_dissipated += weight[q] * r.failure_dissipated;
        *slip_dissipated += weight[q] * r.slip_dissipated;
        for (int i = 0; i < ns; i++)
            ps[i] = r.state[i];
    }
    return WFF_POINT_OK;
}

int wff_amplitude_tangent(const wff_material *mat, const double F[6], const double dA[2],
                          const double *state, double residual[2], double tangent[4])
{
    const wff_cell_type *cell = mat->cell;
    if (cell->amplitude_tangent)
        return cell->amplitude_tangent(mat->params, F, dA, state, residual, tangent);
    const double h = 1e-9; /* m */
    wff_point_result r0, r1, r2;
    int status = cell->evaluate(mat->params, F, dA, state, 0, &r0);
    residual[0] = r0.residual[0];
    residual[1] = r0.residual[1];
    if (status != WFF_POINT_OK) {
        for (int i = 0; i < 4; i++)
            tangent[i] = NAN;
        return status;
    }
    const double d1[2] = {dA[0] + h, dA[1]}, d2[2] = {dA[0], dA[1] + h};
    cell->evaluate(mat->params, F, d1, state, 0, &r1);
    cell->evaluate(mat->params, F, d2, state, 0, &r2);
    tangent[0] = (r1.residual[0] - r0.residual[0]) / h;
    tangent[1] = (r2.residual[0] - r0.residual[0]) / h;
    tangent[2] = (r1.residual[1] - r0.residual[1]) / h;
    tangent[3] = (r2.residual[1] - r0.residual[1]) / h;
    return WFF_POINT_OK;
}

int wff_cell_has_tri_block(const wff_material *mat)
{
    return mat->cell->evaluate_tri_block != NULL;
}

int wff_cell_tri_block(const wff_material *mat, double dt, wff_tri_block *blk)
{
    if (!mat->cell->evaluate_tri_block)
        return -1;
    for (int j = 0; j < WFF_BLOCK; j++) /* (a cell without yarn slip leaves it: none) */
        blk->slip_dissipated[j] = 0;
    return mat->cell->evaluate_tri_block(mat->params, dt, blk) == 0 ? 0 : -1;
}

int wff_cell_has_point_block(const wff_material *mat)
{
    return mat->cell->evaluate_point_block != NULL;
}

int wff_cell_point_block(const wff_material *mat, double dt, wff_point_block *blk)
{
    if (!mat->cell->evaluate_point_block)
        return -1;
    for (int j = 0; j < WFF_BLOCK; j++) /* (a cell without yarn slip leaves it: none) */
        blk->slip_dissipated[j] = 0;
    return mat->cell->evaluate_point_block(mat->params, dt, blk) == 0 ? 0 : -1;
}

int wff_cell_has_tangent_block(const wff_material *mat)
{
    return mat->cell->amplitude_tangent_block != NULL;
}

int wff_cell_tangent_block(const wff_material *mat, wff_tangent_block *blk)
{
    if (!mat->cell->amplitude_tangent_block)
        return -1;
    return mat->cell->amplitude_tangent_block(mat->params, blk) == 0 ? 0 : -1;
}

double wff_cell_amplitude_length(const wff_material *mat)
{
    if (mat->cell->n_amplitudes == 0 || !mat->cell->amplitude_length)
        return INFINITY;
    double length = mat->cell->amplitude_length(mat->params);
    return length > 0 ? length : INFINITY;
}

int wff_cell_has_wave_block(const wff_material *mat)
{
    return mat->cell->wave_speeds_block != NULL;
}

int wff_cell_wave_block(const wff_material *mat, wff_wave_block *blk)
{
    if (!mat->cell->wave_speeds_block)
        return -1;
    return mat->cell->wave_speeds_block(mat->params, mat->areal_density, blk) == 0 ? 0 : -1;
}

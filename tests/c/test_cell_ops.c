/* The cell wrappers (include/wovenff/cell_ops.h, plugin/cell_ops.c): each
 * calls its op when the cell has it and otherwise gives cell.h's fallback —
 * evaluate_shared by evaluate() at each point with the same weighted sums
 * (bit for bit), amplitude_tangent by forward differences of evaluate(), the
 * blocked ops −1 for a cell without them or one that declines (any nonzero
 * answer), energy_split and reference_geometry −1 with nothing written. The
 * tables without ops are copies of registered cells with members cleared,
 * never registered. */
#include "check.h"
#include "wovenff/cell_ops.h"
#include "wovenff/material.h"

#include <math.h>
#include <string.h>

#define BASKET "freefem_scripts/materials/kevlar_basket.txt"
#define KING "freefem_scripts/materials/kevlar_s706.txt"
#define LINEAR "freefem_scripts/materials/kevlar_linear.txt"

/* A blocked op that answers neither 0 nor −1 (a cell's bug the wrapper still
 * reports as declined). */
static int odd_tri_block(const void *params, double dt, wff_tri_block *blk)
{
    (void)params, (void)dt, (void)blk;
    return 7;
}

static int load(check_state *st, const char *path, wff_material *mat)
{
    wff_error err;
    int rc = wff_material_load(path, mat, &err);
    CHECK(st, rc == 0, "%s: %s", path, rc ? err.message : "");
    return rc;
}

/* A stretched, sheared F and three points' amplitudes and states. */
static const double F_test[6] = {1.02, 0.05, -0.01, 0.99, 0.03, 0.02};
static const double dA_test[6] = {-1e-6, 2e-6, 0.5e-6, -0.5e-6, 1.5e-6, 1e-6};

/* evaluate_shared without the op equals evaluate() at each point, weighted. */
static void shared_fallback(check_state *st, const wff_material *mat)
{
    CHECK(st, !wff_cell_has_shared(mat), "%s has no evaluate_shared", wff_cell_name(mat->cell));
    const int ns = mat->n_state;
    const double weight[3] = {0.2, 0.3, 0.5}, dt = 1e-7;
    double state[3 * WFF_STATE_MAX] = {0}, state_ref[3 * WFF_STATE_MAX] = {0};
    for (int q = 0; q < 3 && ns > 0; q++)
        state[ns * q] = state_ref[ns * q] = 0.01 * (q + 1); /* γᶠ */
    double stress[6] = {0}, residual[6], energy = 0, dissipated = 0, failure = 0, slip = 0;
    int bad = -1;
    int status = wff_cell_evaluate_shared(mat, F_test, 3, dA_test, weight, state, dt, stress,
                                          residual, &energy, &dissipated, &failure, &slip,
                                          &bad);
    CHECK(st, status == WFF_POINT_OK && bad == 0, "fallback status %d, bad point %d", status, bad);
    double stress_ref[6] = {0}, energy_ref = 0, dissipated_ref = 0, failure_ref = 0;
    double slip_ref = 0;
    int same_residual = 1, same_state = 1;
    for (int q = 0; q < 3; q++) {
        wff_point_result r;
        wff_material_evaluate(mat, F_test, dA_test + 2 * q, state_ref + ns * q, dt, &r);
        for (int i = 0; i < 6; i++)
            stress_ref[i] += weight[q] * r.stress[i];
        energy_ref += weight[q] * r.energy;
        dissipated_ref += weight[q] * r.dissipated;
        failure_ref += weight[q] * r.failure_dissipated;
        slip_ref += weight[q] * r.slip_dissipated;
        same_residual &= residual[2 * q] == r.residual[0] && residual[2 * q + 1] == r.residual[1];
        for (int i = 0; i < ns; i++)
            same_state &= state[ns * q + i] == r.state[i];
    }
    int same_stress = 1;
    for (int i = 0; i < 6; i++)
        same_stress &= stress[i] == stress_ref[i];
    CHECK(st, same_stress && energy == energy_ref && dissipated == dissipated_ref &&
                  failure == failure_ref && slip == slip_ref,
          "%s: evaluate_shared's fallback is evaluate() weighted, bit for bit",
          wff_cell_name(mat->cell));
    CHECK(st, same_residual && same_state, "%s: residuals and states as evaluate() gives them",
          wff_cell_name(mat->cell));
    CHECK(st, dissipated > 0, "%s: the step dissipates (%g J/m^2)", wff_cell_name(mat->cell),
          dissipated);
}

/* wff_amplitude_tangent: the op, and without it forward differences. */
static void tangent_fallback(check_state *st, const wff_material *mat)
{
    double residual[2], tangent[4];
    int status = wff_amplitude_tangent(mat, F_test, dA_test, wff_rest_state, residual, tangent);
    CHECK(st, status == WFF_POINT_OK, "exact tangent: status %d", status);
    wff_cell_type no_tangent = *mat->cell;
    no_tangent.amplitude_tangent = NULL;
    wff_material fd = *mat;
    fd.cell = &no_tangent;
    double residual_fd[2], tangent_fd[4];
    status = wff_amplitude_tangent(&fd, F_test, dA_test, wff_rest_state, residual_fd, tangent_fd);
    CHECK(st, status == WFF_POINT_OK, "forward differences: status %d", status);
    wff_point_result r;
    wff_material_evaluate(mat, F_test, dA_test, wff_rest_state, 0, &r);
    CHECK(st, residual_fd[0] == r.residual[0] && residual_fd[1] == r.residual[1],
          "forward differences: the residual is evaluate()'s");
    double scale = fmax(fabs(tangent[0]), fabs(tangent[3]));
    for (int i = 0; i < 4; i++)
        CHECK_CLOSE(st, tangent_fd[i], tangent[i], 1e-3, scale, "forward-difference tangent");
}

int main(void)
{
    check_state st = {0, 0};
    wff_material king, basket, linear;
    if (load(&st, KING, &king) || load(&st, BASKET, &basket) || load(&st, LINEAR, &linear))
        return check_summary(&st, "test_cell_ops");

    /* the table through its wrappers */
    CHECK(&st, strcmp(wff_cell_name(king.cell), "king_plain") == 0, "name");
    CHECK(&st, wff_cell_amplitudes(king.cell) == 2 && wff_cell_amplitudes(linear.cell) == 0,
          "amplitudes");
    CHECK(&st, wff_cell_n_diag(king.cell) > 0 &&
                   strcmp(wff_cell_diag_name(king.cell, wff_cell_yarn_tension_diag(king.cell, 0)),
                          "T1") == 0,
          "diagnostics and the yarn tension's");
    CHECK(&st, wff_cell_has_energy_split(king.cell) && wff_cell_n_mech(king.cell) > 0, "split");
    CHECK(&st, strcmp(wff_cell_state_name(king.cell, 0), "gamma_f") == 0, "state names");

    shared_fallback(&st, &basket);
    tangent_fallback(&st, &basket);
    tangent_fallback(&st, &king);

    /* the blocked ops: 0 when taken, −1 when absent or declined */
    wff_tri_block blk;
    memset(&blk, 0, sizeof blk);
    for (int b = 0; b < WFF_BLOCK; b++)
        blk.F[0][b] = blk.F[3][b] = 1;
    blk.n = WFF_BLOCK;
    CHECK(&st, wff_cell_has_tri_block(&basket) && wff_cell_tri_block(&basket, 0, &blk) == 0,
          "basket_2x2's generated triangle block is taken");
    wff_cell_type bare = *linear.cell;
    bare.evaluate_tri_block = NULL;
    bare.evaluate_point_block = NULL;
    bare.wave_speeds_block = NULL;
    bare.energy_split = NULL;
    wff_material bare_mat = linear;
    bare_mat.cell = &bare;
    wff_point_block pb;
    wff_wave_block wb;
    memset(&pb, 0, sizeof pb);
    memset(&wb, 0, sizeof wb);
    CHECK(&st, !wff_cell_has_tri_block(&bare_mat) && wff_cell_tri_block(&bare_mat, 0, &blk) == -1,
          "no evaluate_tri_block: -1");
    CHECK(&st, wff_cell_point_block(&bare_mat, 0, &pb) == -1 && !wff_cell_has_point_block(&bare_mat),
          "no evaluate_point_block: -1");
    CHECK(&st, wff_cell_wave_block(&bare_mat, &wb) == -1 && !wff_cell_has_wave_block(&bare_mat),
          "no wave_speeds_block: -1");
    wff_tangent_block tb;
    memset(&tb, 0, sizeof tb);
    CHECK(&st, wff_cell_tangent_block(&linear, &tb) == -1 && !wff_cell_has_tangent_block(&linear),
          "linear_yarns has no amplitudes, no tangent block: -1");
    bare.evaluate_tri_block = odd_tri_block;
    CHECK(&st, wff_cell_tri_block(&bare_mat, 0, &blk) == -1, "an answer of 7 is declined: -1");
    double mech[WFF_MECH_MAX] = {42}, pitch0[2] = {42, 42}, amplitude0[2];
    CHECK(&st, wff_cell_energy_split(&bare_mat, F_test, dA_test, wff_rest_state, mech) == -1 &&
                   mech[0] == 42,
          "no energy_split: -1, nothing written");
    CHECK(&st, wff_cell_reference_geometry(&linear, pitch0, amplitude0) == -1 && pitch0[0] == 42,
          "linear_yarns has no reference geometry: -1, nothing written");
    CHECK(&st, wff_cell_reference_geometry(&king, pitch0, amplitude0) == 0 && pitch0[0] > 0 &&
                   pitch0[0] < 1e-2,
          "king_plain's reference geometry: p1_0 = %g m", pitch0[0]);
    return check_summary(&st, "test_cell_ops");
}

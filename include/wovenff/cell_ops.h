/* wovenff — every use of a unit cell's table goes through these wrappers
 * (defined in plugin/cell_ops.c, the one file that reads a wff_cell_type's
 * members): its tables (names, sizes), its required ops, and its optional
 * ops with the fallback inside, so that a caller never tests for a NULL op
 * nor repeats a default.
 *
 * Optional ops and what their wrapper does without them (cell.h's contract):
 *   energy_split             −1, nothing written (wff_cell_has_energy_split)
 *   evaluate_shared          evaluate() at each point, weighted as the op would
 *   reference_geometry       −1, nothing written (wff_cell_has_reference_geometry)
 *   amplitude_tangent        forward differences of evaluate() (wff_amplitude_tangent)
 *   yarns_fail               failure on where the material carries a damage state
 *                            (wff_material_damage_state)
 *   the blocked ops          −1 ("declined"): absent, or declined by these
 *                            parameters (params only, never the state); the
 *                            caller then takes its pointwise path, which it
 *                            owns (its gather and sums define its bits)
 * The blocked wrappers' wff_cell_has_* tell whether asking is worth it.
 * Nothing here allocates or keeps state. */
#ifndef WOVENFF_CELL_OPS_H
#define WOVENFF_CELL_OPS_H

#include "wovenff/cell.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The table: names and sizes (static storage, cell.h). */
const char *wff_cell_name(const wff_cell_type *cell);
const char *wff_cell_summary(const wff_cell_type *cell);
int wff_cell_amplitudes(const wff_cell_type *cell);   /* n_amplitudes: 0 or 2 */
int wff_cell_n_diag(const wff_cell_type *cell);
const char *wff_cell_diag_name(const wff_cell_type *cell, int d); /* 0 <= d < n_diag */
const char *wff_cell_diag_unit(const wff_cell_type *cell, int d);
int wff_cell_yarn_tension_diag(const wff_cell_type *cell, int k); /* diag index or −1 */
int wff_cell_n_mech(const wff_cell_type *cell);
const char *wff_cell_mech_name(const wff_cell_type *cell, int i); /* 0 <= i < n_mech */
int wff_cell_n_state_max(const wff_cell_type *cell);
const char *wff_cell_state_name(const wff_cell_type *cell, int i); /* i < n_state_max */
const char *wff_cell_state_unit(const wff_cell_type *cell, int i);
int wff_cell_damage_state(const wff_cell_type *cell, int k); /* state index or −1 */
/* The state index of family k's damage when this material's yarns fail (the
 * cell's damage_state[k], within mat->n_state, and the cell's yarns_fail says 1
 * or it has none), else −1: a material that carries the slots held at 0 (King
 * with yarn slip, failure off) has no failure. */
int wff_material_damage_state(const wff_material *mat, int k);
int wff_cell_has_energy_split(const wff_cell_type *cell);
int wff_cell_has_reference_geometry(const wff_cell_type *cell);

/* Required ops. parse fills mat->params (and mat->n_state) for mat->cell;
 * evaluate is cell.h's wff_material_evaluate. */
int wff_cell_parse(wff_kv *kv, wff_material *mat, wff_error *err);
/* wave_speeds at mat's areal density. */
void wff_cell_wave_speeds(const wff_material *mat, const double F[6], const double dA[2],
                          double *membrane_speed, double *amplitude_omega);

/* Optional pointwise ops (returns: 0 done, −1 the cell has none). */
int wff_cell_energy_split(const wff_material *mat, const double F[6], const double dA[2],
                          const double *state, double *mech_energy);
int wff_cell_reference_geometry(const wff_material *mat, double pitch0[2],
                                double amplitude0[2]);
/* n points sharing one F, as cell.h's evaluate_shared (the op, or evaluate()
 * at each point with the same weighted sums; states updated in place). */
int wff_cell_has_shared(const wff_material *mat);
int wff_cell_evaluate_shared(const wff_material *mat, const double F[6], int n_points,
                             const double *dA, const double *weight, double *state, double dt,
                             double stress_sum[6], double *residual, double *energy,
                             double *dissipated, double *failure_dissipated,
                             double *slip_dissipated, int *bad_point);
/* R_k and ∂R_k/∂ΔA_m (tangent[2k + m]) at one point, state held: the cell's
 * amplitude_tangent, or for a cell without it forward differences of
 * evaluate() with a 1 nm step (the static path's Jacobian before the op).
 * Returns the cell's status (WFF_POINT_DEGENERATE: outputs NaN). */
int wff_amplitude_tangent(const wff_material *mat, const double F[6], const double dA[2],
                          const double *state, double residual[2], double tangent[4]);

/* The blocked ops (cell.h): 0 when the block was handled, −1 when the cell
 * has no such op or declines these parameters (nothing done). */
int wff_cell_has_tri_block(const wff_material *mat);
int wff_cell_tri_block(const wff_material *mat, double dt, wff_tri_block *blk);
int wff_cell_has_point_block(const wff_material *mat);
int wff_cell_point_block(const wff_material *mat, double dt, wff_point_block *blk);
int wff_cell_has_tangent_block(const wff_material *mat);
int wff_cell_tangent_block(const wff_material *mat, wff_tangent_block *blk);
int wff_cell_has_wave_block(const wff_material *mat);
/* The cell's amplitude_length (m), INFINITY for a cell without amplitudes or
 * without the op (no travel limit on the step). */
double wff_cell_amplitude_length(const wff_material *mat);
int wff_cell_wave_block(const wff_material *mat, wff_wave_block *blk); /* mat's density */

#ifdef __cplusplus
}
#endif
#endif

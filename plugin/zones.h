/* zones.h: what the solver's files share about per-region materials
 * (plugin/zones.c; the public calls are in include/wovenff/solver.h). Every
 * function takes the plain path, the very call the model made before zones
 * existed, when the model has none (m->zones == NULL). */
#ifndef WFF_ZONES_H
#define WFF_ZONES_H

#include <stdint.h>

#include "solver_internal.h"

/* Every point whose material (its element's zone's) carries the state
 * WFF_ELEMENT_LENGTH_STATE gets its element's wff_element_band_length (cell.h's
 * contract): at model creation, after a zone assignment, after a mesh
 * transfer. Other points are left alone. */
void wff_model_set_element_lengths(wff_model *m);

/* The elements selected (the model's order) given a zone of the material at
 * material_path (preload WFF_ZONE_PRELOAD_*), one per ply a pack's selection
 * touches; the model's masses are not set again here (zones_model.c's callers
 * do). Returns the elements in it, or -1 (err set). */
int wff_zones_select(wff_model *m, const unsigned char *selected, const char *material_path,
                     int preload, wff_error *err);
/* Free the zones (wff_model_free). */
void wff_zones_free(wff_model *m);
/* The element force pass: wff_elements_forces over each zone with its own
 * material and preload, adding into f (not zeroed here), the points' states
 * (the model's layout: 3 points per tri then 4 per quad, m->n_state each; a
 * zone's material carries a prefix) advanced by dt; totals summed, a bad
 * element numbered in the model. */
void wff_zones_forces(wff_model *m, const double *u, double *state, double dt, double *f,
                      wff_force_totals *totals);
/* The model's erosion was switched on or off (m->el.eroded): the zones' own
 * flags allocated or freed (they follow the model's at every pass); -1 (err
 * set) if out of memory. */
int wff_zones_erosion_changed(wff_model *m, wff_error *err);
/* 1 if zone k's element pass works on the model's states in place (its
 * elements consecutive, its material's layout the model's), 0 if on a copy. */
int wff_zones_in_place(const wff_model *m, int k);
/* Lumped masses of every zone into m->mass (zeroed first). */
void wff_zones_masses(wff_model *m);
/* The smallest stable step over the zones; *worst the model's element. */
double wff_zones_stable_step(const wff_model *m, const double *u, int *worst);
/* The shortest amplitude length (cell.h's amplitude_length, m) of the
 * materials in use: the model's and its zones'; INFINITY if none has one. */
double wff_zones_amplitude_length(const wff_model *m);
/* Energy per mechanism in the order of the model's cell's mech_names; a zone
 * of another cell adds each of its mechanisms to the one of the same name
 * (one without a namesake is left out). */
void wff_zones_energy_split(const wff_model *m, const double *u, const double *state,
                            double *mech);
/* The material and preload element e (model numbering) sees: &m->em, or
 * *scratch filled for its zone. */
const wff_element_material *wff_zones_element_material(const wff_model *m, int e,
                                                       wff_element_material *scratch);
/* The model's preload changed: matched zone preloads solved again (the caller
 * sets the masses again: wff_model_masses_changed); -1 (err set) if a match fails. */
int wff_zones_preload_changed(wff_model *m, wff_error *err);
/* The zones' materials, preloads and element assignment folded into hash g
 * (g unchanged without zones: checkpoints of one-material models as before). */
uint64_t wff_zones_fingerprint(const wff_model *m, uint64_t g);
/* pack_build.c: a pack of several plies gets one zone per ply (zone 0, the model's material,
 * left empty), each of the model's material; -1 (err set) if the model has zones. The
 * caller sets the masses and element lengths again. */
int wff_zones_pack(wff_model *m, wff_error *err);
/* The last force pass's stored energy, shear, failure and slip dissipation of each
 * ply (model part, J; the model's wff_pack_plies entries); zeros without zones. */
void wff_zones_ply_totals(const wff_model *m, double *stored, double *shear, double *failure,
                          double *slip);
/* The masses changed (a zone's material or preload, the model's preload): the
 * zones' masses, the fabric mass, the clamp's shares (clamp.c) and the stored
 * energy before the run again; -1 (err set) if the clamp's shares fail. */
int wff_model_masses_changed(wff_model *m, wff_error *err);
/* m->fabric_mass from the nodal masses. */
void wff_model_sum_fabric_mass(wff_model *m);
/* Before the first step (nothing after it): the stored energy of the state
 * as set up (e.g. the preload) into m->internal_energy, so that energies read
 * before any step are complete (a force pass with the state held; a bad
 * element gives 0 here and is reported when the run starts). */
void wff_model_stored_energy_now(wff_model *m);

#endif

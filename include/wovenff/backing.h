/* wovenff — the backing block behind a pack (plugin/backing.c; docs/backing.md).
 *
 * Set by name (wff_model_set_option) before the first step: backing (0 none,
 * 1 Roma Plastilina No. 1 clay, 2 10 % ordnance gelatin), backing_depth (m),
 * backing_element (the finest element, m), backing_growth, backing_mu,
 * backing_hourglass, backing_gap (m). Its values by name (wff_model_value):
 * backface_signature, crater_diameter, crater_volume, backing_peak_depth,
 * backing_kinetic, backing_kinetic_peak, backing_stored, backing_dissipated,
 * backing_contact_loss, backing_elements, backing_contacts, backing_seconds,
 * backing_step, backing_overlap. */
#ifndef WOVENFF_BACKING_H
#define WOVENFF_BACKING_H

#include "wovenff/solver.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The block's top face along x through the impact point (the grid's row
 * nearest it): up to max points, their reference x (m) and indentation (m,
 * > 0 into the block) now; returns how many (0: no backing block yet). */
int wff_model_backing_profile(const wff_model *m, int max, double *x, double *depth);

/* The block as a VTK unstructured grid (.vtu, ASCII) at path: its hexahedra at
 * their current positions, point data displacement and velocity (m, m/s), cell
 * data eq_plastic_strain (clay's ᾱ; 0 for gelatin). Written whole. -1 (err
 * set) without a block or on a write error. */
int wff_model_backing_vtk(const wff_model *m, const char *path, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

/* erosion.h: element erosion (plugin/erosion.c; docs/model.md "Erosion"),
 * what the solver's files share about it. An element is eroded once its
 * yarns have ruptured at every quadrature point (both families, the default
 * rule, or either family: the setting erosion): from the next pass on it gives
 * no force, sets no stable step, holds no stored energy and has no share in
 * the energy split; the stored energy it had at that moment goes to
 * m->eroded_energy. Nodes keep their mass; a node left with no live element
 * is a free mass, still in contact with the projectile (contact works on
 * nodes). The flags live in m->el.eroded (NULL while erosion is off: every
 * pass as before erosion existed). */
#ifndef WFF_EROSION_H
#define WFF_EROSION_H

#include "part.h"

/* The setting erosion (wff_model_set_option): 0 off, 1 both families
 * ruptured, 2 either. Refused for a cell without yarn failure (damage_state
 * −1, naming the cell), for a model whose materials carry no damage states
 * (failure = 0), for a rule other than 0, 1, 2, and (0) once elements have
 * eroded. */
int wff_erosion_set(wff_model *m, double rule, wff_error *err);
/* At model creation: rule 1 when the material's points carry both damage
 * states (failure = 1), off otherwise. -1 (err set) if out of memory. */
int wff_erosion_default(wff_model *m, wff_error *err);
/* The part (part.h): after an accumulating force pass that advanced the
 * states (dt > 0) at displacement u, states `state` (m->n_state per point):
 * the elements the rule selects erode; their stored energy then (their points
 * evaluated at dt = 0, J, model part) is added to m->eroded_energy and taken
 * out of the pass's; m->n_eroded counts them, and the pass's list of them
 * (m->eroded_now, in element order, with their energies) is there for the
 * parts after it. The setting erosion. Nothing without erosion (m->el.eroded
 * NULL). */
extern const wff_part_ops wff_erosion_part;
/* Erosion switched on with `rule` (WFF_EROSION_BOTH or _EITHER): the flags and
 * the pass's list allocated (kept if they are); -1 (err set) if out of
 * memory. */
int wff_erosion_on(wff_model *m, int rule, wff_error *err);
/* Mean over element e's points of yarn family k's damage (0 .. 1), 0 when its
 * material carries none. */
double wff_element_damage(const wff_model *m, int e, int k);
/* 1 if element e has eroded or a yarn family has ruptured (damage >= 1) at a
 * point of it: the element no longer carries load along both yarn families
 * there (a pack's ply_apex follows only elements that do, pack.c). */
int wff_element_torn(const wff_model *m, int e);
/* 1 if an element has eroded or any point has damage > 0 (a mesh transfer
 * refuses such a model when erosion is on). */
int wff_model_damaged(const wff_model *m);

#endif

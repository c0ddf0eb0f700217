/* wovenff — a model's state in and out as arrays, and per-element fields.
 *
 * Vectors have the layout of FreeFEM's fespace Vh5(Th, [P1,P1,P1,P1,P1]):
 * node-major, interleaved, 5 per node (ux uy uz dA1 dA2; m, or m/s for v).
 *
 * "u" is the displacement and amplitude-change vector. "v" is the velocity
 * the integrator holds: before the first step the initial velocity v⁰; after
 * steps the half-step velocity v^{n+½} the next step uses (the kinetic
 * energies are those of v^n = v^{n+½} − ½Δt M⁻¹f^n, as always). So
 * set(get()) changes nothing, and a state read and set back continues the run
 * bit for bit.
 *
 * Setting a vector recomputes what describes the state: setting u runs a
 * force pass at the new u with γᶠ held and no time advanced (stored energy,
 * forces, the reactions of fixed and prescribed DOFs, fields and element
 * fields follow it); setting v changes the kinetic energies. Refused, with the
 * state unchanged: a non-finite entry, a fixed DOF's velocity other than 0, a
 * prescribed DOF's velocity other than its prescribed one, a non-zero
 * amplitude of a cell without amplitudes, a u that makes an element
 * degenerate (named). Each error names the DOF (1-based node and component).
 * Not checked: a u that puts nodes inside the projectile (the next step's
 * kinematic contact puts them back on its surface, the normal impulse's work
 * counted as contact dissipation, as for any contact).
 *
 * The energy balance: a state set before the first step is the initial state
 * the balance starts from. A state set after steps moves the balance's
 * reference by the energy the set changed (stored + kinetic): the set is
 * neither error nor external work, the error accumulated before it is kept,
 * and the balance then accounts for the run from the new state.
 *
 * Element fields (wff_model_element_field): one value per element (triangles,
 * then quadrilaterals), evaluated at the element's centre with the preload
 * applied and every internal state held at the mean of its points (as the
 * nodal fields are):
 *   P11 P12 P21 P22 P31 P32   first Piola-Kirchhoff membrane stress of the
 *                             cell at F_eff = F F_pre, N/m (wovenffPoint's P):
 *                             P_iJ, i the mesh's x y z (current configuration),
 *                             J the material axes (1 warp, 2 weft); with an
 *                             orientation θ F_pre holds R(θ) (membrane.h), so
 *                             these stay the cell's, material-frame columns
 *                             (on mesh axes: P F_preᵀ / det F_pre)
 *   lambda1 lambda2           yarn stretches |F_eff E_k| (preload and orientation
 *                             applied: the warp's and the weft's)
 *   shear_angle               π/2 − angle between F_eff E_1 and F_eff E_2, rad
 *   W                         stored energy per unit cell reference area, J/m²
 *                             (per mesh area: W / det F_pre)
 *   every internal state by its name (the cell's state_names; wff_model_state_name):
 *                             the mean of the element's points (King, basket:
 *                             gamma_f, the dissipative shear angle γᶠ, rad; a cell
 *                             with yarn failure adds its damages; a zone whose
 *                             material carries fewer states reads 0 for the rest)
 *   T1 T2                     yarn tensions, N (the cell's yarn-tension
 *                             diagnostics)
 *   damage1 damage2           yarn damage of family 1, 2 (0 intact .. 1 ruptured):
 *                             the mean of the element's points (the cell's
 *                             damage_state), 0 for a material without damage
 *   eroded                    1 on an eroded element, else 0 (plugin/erosion.h);
 *                             an eroded element's stresses, W, tensions and
 *                             diagnostics read 0
 *   every cell diagnostic by its name (a diagnostic named like one of the
 *   above is that one: linear_yarns' lambda1 lambda2 are the same stretches).
 * Nodal values (wff_model_nodal_field) of these names are the area-weighted
 * averages of the element values over the elements around each node. */
#ifndef WOVENFF_STATE_H
#define WOVENFF_STATE_H

#include "wovenff/solver.h"

#ifdef __cplusplus
extern "C" {
#endif

/* which: "u" or "v"; out has 5 × n_nodes entries. */
int wff_model_get_vector(const wff_model *m, const char *which, double *out, wff_error *err);
int wff_model_set_vector(wff_model *m, const char *which, const double *in, wff_error *err);

/* Values of element field `name` (above), one per element, triangles then
 * quadrilaterals, into out (n_tris + n_quads). -1 for an unknown name (the
 * known ones listed) or a degenerate element (named). */
int wff_model_element_values(const wff_model *m, const char *name, double *out,
                             wff_error *err);

/* The same on the triangle twin (wff_mesh_triangulate, FreeFEM's mesh of the
 * model): n_tris + 2 n_quads values, a quadrilateral's value given to both of
 * its triangles. */
int wff_model_element_field(const wff_model *m, const char *name, double *out,
                            wff_error *err);

/* Absolute crimp amplitude A_k = A_k⁰ + ΔA_k (k = 0, 1; m) at every node into
 * out (n_nodes); -1 naming the cell if it has no reference geometry. */
/* A 64-bit hash (FNV-1a) of the bits of the model's state: time, step, step
 * size, u, v, f, every point's internal state (with static amplitudes, its own amplitudes), the erosion flags, the
 * projectile's tip, velocity and force, the energy accounts. Equal hashes: the
 * same state bit for bit (a run over MPI ranks against one rank, tests). */
unsigned long long wff_model_state_hash(const wff_model *m);

int wff_model_amplitude(const wff_model *m, int k, double *out, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

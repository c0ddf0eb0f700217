/* wovenff — multi-ply packs (plugin/pack.c, plugin/ply_contact.c; docs/model.md "Packs").
 *
 * One model holds the whole pack: the specimen mesh copied N times (ply p =
 * 0 .. N−1, ply 0 the strike face, met first by a projectile moving along
 * +z). Ply p's mid-plane starts at z = p·gap, given as an initial transverse
 * displacement u_z = p·gap, so that every ply's reference configuration stays
 * the flat specimen. In the model's (and the caller's) numbering ply p's nodes
 * are p·n .. p·n + n − 1 of a specimen of n nodes, its triangles p·t ..
 * p·t + t − 1, its quads N·t + p·q .. (triangles of every ply first, then
 * quads, as everywhere). The mesh's groups keep their names and hold every
 * ply's nodes (a clamp holds every ply).
 *
 * Each ply has a material (a zone of its elements: the model's material by
 * default) and a warp direction (the model-wide orientation sets every ply's).
 * A pack of more than one ply keeps one zone per ply and material (zones.c):
 * a zone given by region or disc is split into one per ply it touches.
 *
 * Neighbouring plies touch by kinematic contact (ply_contact.c): each ply a
 * two-sided surface of thickness t (the contact surfaces at ±t/2 of the
 * mid-plane), so the mid-planes of plies p and p + 1 keep at least
 * h = min(t, gap) apart (a pack stacked closer than t is taken as touching at
 * its gap). Node i of ply p against node i of ply p + 1 (the plies are copies
 * of one mesh) along their mean normal, an inelastic normal impulse and
 * Coulomb friction μ, momentum conserved; the kinetic energy the impulses
 * remove is the ply contact dissipation, a term of the energy balance. The
 * interpenetration left after a step's correction is reported (ply_penetration;
 * on the tests' clamped 8-ply impact at most 10 % of t). Only neighbouring
 * plies are paired: enough while plies cannot pass each other (which the
 * contact itself keeps); their relative in-plane slip must stay small against
 * the element size. No effect on the stable step. */
#ifndef WOVENFF_PACK_H
#define WOVENFF_PACK_H

#include "wovenff/solver.h"

#ifdef __cplusplus
extern "C" {
#endif

#define WFF_PLIES_MAX 40
/* Fabric-on-fabric Coulomb friction by default: the low end of measured
 * aramid yarn-on-yarn friction, about 0.2 to 0.3 (Briscoe & Motamedi 1992). */
#define WFF_PLY_MU_DEFAULT 0.2
/* Default ply thickness t = rho_A / (rho_fibre · V_f): aramid fibre density
 * 1440 kg/m³ at a fibre volume fraction 0.6 (a woven aramid ply of 0.2 kg/m²
 * is then 0.23 mm thick). */
#define WFF_PLY_FIBRE_DENSITY 1440.0
#define WFF_PLY_FIBRE_FRACTION 0.6

/* Make the model a pack of n_plies (1 .. WFF_PLIES_MAX) plies at spacing gap
 * (m, >= 0). Right after the model is created: before a preload, boundary
 * conditions, the projectile, zones, a checkpoint load or the first step
 * (refused after any of them, naming it). The settings made so far (dtfactor,
 * dtinterval, symmetry, threads, reference_path, amplitude_mass_factor,
 * contact_search, erosion, orientation) are kept. n_plies = 1 leaves the model
 * exactly as it is (bit for bit). Once only. */
int wff_model_set_plies(wff_model *m, int n_plies, double gap, wff_error *err);
/* Plies of the model (1 without wff_model_set_plies). */
int wff_model_ply_count(const wff_model *m);
/* Ply p's material (the elements of ply p a zone of that material, the shared
 * preload; a later zone wins where both select an element). Before the first step. */
int wff_model_ply_material(wff_model *m, int ply, const char *material_path, wff_error *err);
/* Ply p's warp direction at theta (rad) to the mesh's x axis; before the first
 * step. wff_model_set_orientation sets every ply's. */
int wff_model_ply_orientation(wff_model *m, int ply, double theta, wff_error *err);
/* The ply of the caller's node / element (0-based); -1 out of range. */
int wff_model_node_ply(const wff_model *m, int user_node);
int wff_model_element_ply(const wff_model *m, int user_element);

/* One value of ply p by key: apex (largest u_z − p·gap over its nodes, m; once
 * elements have eroded, over the part still attached to a node whose u_z is held,
 * through elements not eroded: every element not eroded if none is held, 0 if
 * none is left),
 * kinetic, stored, dissipated (shear + failure + eroded energy of its
 * elements; the ply contact's friction is the pack's), absorbed (the sum of
 * the three), J, whole specimen (× symmetry); failed (elements with yarn
 * damage > 0 in either family), eroded (elements eroded); first_damage_time (s,
 * the time of the first force pass that damaged a yarn of the ply, recorded at
 * that step; -1 while the ply is intact, and for a model never made a pack
 * with wff_model_plies). -1 (err set,
 * naming p or the key) otherwise. */
int wff_model_ply_value(const wff_model *m, int ply, const char *key, double *value,
                        wff_error *err);
/* The pack's values by key: plies, back_face (the last ply's largest u_z −
 * p·gap now, m), ply_contact_dissipated (J, whole specimen), ply_penetration
 * (largest ply-ply interpenetration left after the last step's correction,
 * m), ply_contacts (node pairs corrected in the last step), ply_mu,
 * ply_thickness (m), ply_gap (m), ply_slip (the largest in-plane displacement of
 * a node relative to its partner in the next ply, m: the contact pairs node i
 * with node i, so this must stay small against the element size),
 * ply_contact_seconds (wall time spent in the ply contact so far, s: its share
 * of the step), ply_left_out (pairs left out in the last step: a fragment, slid
 * apart, crossed). -1 (err set) for another key. */
int wff_model_pack_value(const wff_model *m, const char *key, double *value, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

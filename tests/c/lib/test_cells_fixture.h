/* What the C tests' own cells share (test_erosion.c's "test_erosion" and
 * "test_erosion_nodamage", test_state.c's "test_two_states"): straight yarns
 * along E1, E2 (linear_yarns' laws, p_k⁰ = 1) with an in-plane shear
 * stiffness, W = W_yarn + ½ G γ², a yarn every mm, and a damage that follows
 * the largest yarn strain, clamp((ε − ε_f)/(ε_r − ε_f), 0, 1). Each cell
 * keeps its own law of the yarn forces (its damage, flow, states and
 * dissipations) in a tcell_law and its own parse keys; this file registers
 * no cell (each stays registered in its own test binary only).
 *
 * A cell's parameter struct begins with a tcell_params; the cell defines
 * PREFIX_law (a tcell_law), writes TCELL_OPS(PREFIX) for its evaluate and
 * energy_split, and fills its table with TCELL_TABLE. */
#ifndef WFF_TEST_CELLS_FIXTURE_H
#define WFF_TEST_CELLS_FIXTURE_H

#include "check.h"
#include "test_meshes.h"
#include "wovenff/cell.h"
#include "wovenff/material.h"
#include "wovenff/solver.h"
#include "cells/cell_laws.h"

/* The parameters every test cell has, first in its parameter struct. */
typedef struct tcell_params {
    double stiffness[2];    /* S_k, N/m */
    double shear_stiffness; /* G, N/m */
    double fail_strain;     /* ε_f: the damage starts */
    double rupture_strain;  /* ε_r: the damage reaches 1 */
} tcell_params;

/* A point's kinematics (from F) and the cell's yarn forces and energy (its law's). */
typedef struct tcell_yarns {
    wff_yarn_frame fr;   /* the yarn frame at F (p_k⁰ = 1) */
    double strain[2];    /* ε_k = λ_k − 1 */
    double force[2];     /* N_k, N/m (the law's) */
    double energy_yarn;  /* J/m² (the law's) */
    double energy_shear; /* ½ G γ², J/m² */
} tcell_yarns;

/* A cell's law at one point with y's frame and strains set: the yarn forces
 * y->force and energy y->energy_yarn with the states advanced by dt (held at
 * dt = 0); when out is not NULL also the new states out->state and the
 * dissipations out->dissipated, out->failure_dissipated. */
typedef void tcell_law(const void *params, const double *state, double dt, tcell_yarns *y,
                       wff_point_result *out);

/* clamp((strain − ε_f)/(ε_r − ε_f), 0, 1): the damage a yarn strain reaches. */
double tcell_damage_reached(const tcell_params *c, double strain);

/* Clear mat->params (size bytes, a struct beginning with a tcell_params) and
 * read S_1 S_2 G fail_strain rupture_strain into it. 0, or -1 with err set. */
int tcell_parse(wff_kv *kv, wff_material *mat, size_t size, wff_error *err);

/* The cell's evaluate with its law: stress from N_k and G γ, no residual,
 * W = W_yarn + ½ G γ², diagnostics T_k = N_k × 1 mm (N). */
int tcell_evaluate(tcell_law *law, const void *params, const double F[6], const double *state,
                   double dt, wff_point_result *out);

/* The cell's energy_split with its law: yarn_stretch, shear. */
void tcell_energy_split(tcell_law *law, const void *params, const double F[6],
                        const double *state, double *mech);

/* wave_speeds (the op itself): linear_yarns' bound at the undamaged
 * stiffnesses S_k (upper bounds of the damaged ones; |N| with a flow strain
 * at its extremes, 0 and the strain); no amplitudes. */
void tcell_wave_speeds(const void *params, double areal_density, const double F[6],
                       const double dA[2], double *membrane_speed, double *amplitude_omega);

/* The tests' scene: a model of `material` on r with its four edges fixed (u_x, u_y,
 * u_z) struck by a projectile of radius 6.35 mm, mass (kg) and velocity (m/s),
 * friction 0.2. 0, or -1 after a failed CHECK (nothing left to free). */
int tcell_struck(check_state *st, wff_model *m, const test_rect *r, const char *material,
                 double mass, double velocity);

extern const char *const tcell_diag_names[2]; /* T1 T2 */
extern const char *const tcell_diag_units[2];
extern const char *const tcell_mech_names[2]; /* yarn_stretch shear */

/* PREFIX_evaluate and PREFIX_energy_split, the cell's ops with PREFIX_law. */
#define TCELL_OPS(PREFIX)                                                                   \
    static int PREFIX##_evaluate(const void *params, const double F[6], const double dA[2],  \
                                 const double *state, double dt, wff_point_result *out)       \
    {                                                                                         \
        (void)dA;                                                                             \
        return tcell_evaluate(PREFIX##_law, params, F, state, dt, out);                       \
    }                                                                                         \
    static void PREFIX##_energy_split(const void *params, const double F[6],                 \
                                      const double dA[2], const double *state, double *mech)  \
    {                                                                                         \
        (void)dA;                                                                             \
        tcell_energy_split(PREFIX##_law, params, F, state, mech);                             \
    }

/* The table of a test cell NAME with PREFIX's ops and state names
 * (PREFIX_state_names, PREFIX_state_units) and parse PARSE; the designators
 * that follow give the rest (summary, n_state_max, damage_state). */
#define TCELL_TABLE(NAME, PREFIX, PARSE, ...)                                                 \
    {                                                                                         \
        .name = NAME, .n_amplitudes = 0, .n_diag = 2, .diag_names = tcell_diag_names,         \
        .diag_units = tcell_diag_units, .yarn_tension_diag = {0, 1}, .n_mech = 2,             \
        .mech_names = tcell_mech_names, .state_names = PREFIX##_state_names,                  \
        .state_units = PREFIX##_state_units, .parse = PARSE, .evaluate = PREFIX##_evaluate,   \
        .wave_speeds = tcell_wave_speeds, .energy_split = PREFIX##_energy_split, __VA_ARGS__  \
    }

#endif

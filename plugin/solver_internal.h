/* solver_internal.h: what the solver's files (model.c, contact.c,
 * integrator.c, fields.c, checkpoint.c, operators.c, the parts) share and nobody else
 * sees: the DOF stride, the force pass operators.c reuses, the per-step passes
 * over DOFs and nodes, the model's set-up and its order. The public
 * API is include/wovenff/solver.h. */
#ifndef WFF_SOLVER_INTERNAL_H
#define WFF_SOLVER_INTERNAL_H

#include "wovenff/solver.h"

#include <math.h>

#define D WFF_DOFS_PER_NODE

/* integrator.c: the element force pass at u into f (zeroed first), the
 * points' state (m->n_state each) advanced by dt_flow in state (0: held); accumulate 1: the model's stored
 * energy, shear dissipation and element-step count updated as a step does.
 * The pass's stored energy into *energy (J, model part; NULL: not wanted).
 * -1 (err set, naming the element) on a bad point. */
int wff_force_pass(wff_model *m, const double *u, double *f, double *state, double dt_flow,
                   int accumulate, double *energy, wff_error *err);
/* step_threads.c: the per-step passes, threaded (the model's thread count)
 * with sums in an order set by the item count alone: the same bits for any
 * thread count. u += dt v and m->f = 0, returning the first half of the
 * prescribed DOFs' external work; f[0..n) = 0; the velocity update with the boundary
 * conditions (returns the prescribed DOFs' second-half work); Σ m v² (in-plane, transverse, amplitude) of the
 * free DOFs at v − half f/m and Σ f²/m over them (sums[3]); the nodes within `reach` of the projectile's
 * axis in plane into candidates (returns how many, in node order). */
double wff_step_positions(wff_model *m, double dt);
void wff_step_zero(const wff_model *m, double *f, int n);
double wff_step_velocities(wff_model *m, double dt_mid, double dt_done);
void wff_step_kinetic(const wff_model *m, double half, double sums[5]);
void wff_step_replan(wff_model *m, double dt_new);
/* The travel limit (docs/model.md §12): a step moves no free amplitude more
 * than a fraction (× dtfactor) of its cell's amplitude length: WFF_TRAVEL (the
 * default of the setting travel_fraction) while the amplitudes' swings carry
 * all the energy in play, loosening as 1/sqrt of their share of it (the swing's
 * energy error goes as the fraction squared times the swing's energy) up to
 * WFF_TRAVEL_LOOSE. Measured on a square released from a bump with its
 * amplitudes far from balance (swings of ±20-60 µm at up to ~600 m/s into the
 * compaction exponential, 1/a = 10 µm; their kinetic energy ~all the energy
 * moving), 10,000 steps at dtfactor 0.8: 1.25 went unstable within 500 steps;
 * 0.625 held, with an energy error of 7.3e-3-2.6e-2, falling as the fraction
 * squared: 0.1 9.3e-4 at most, 0.08 6.0e-4 (0.9: 7.6e-4). Held at 0.08 in a
 * ballistic run, where the swings carry ~1e-4 of the impact energy, the limit
 * cost steps for nothing (300 m/s: 11,202 to 0.2 ms against 5,630 at 0.625;
 * 600 m/s 6.5 x). */
#define WFF_TRAVEL 0.08
#define WFF_TRAVEL_LOOSE 0.625

/* The work of impulse j (N·s) on free DOF k, booked once every part has
 * corrected the step (part.h's book op) at the DOF's final half-step velocity
 * and acceleration (every force of the step in f): at a step, j·(v^{n+½} −
 * ½Δt_before aⁿ), the trapezoidal rule's ½(gⁿ + gⁿ⁺¹)·Δu; at a start
 * (Δt_before = 0: the velocities given are the integer step's, v⁰ = v^{½} −
 * Δt_mid a⁰), the kinetic energy the impulses change there, j·(v⁰ + ½J/m), J
 * every part's impulse on the DOF (docs/model.md §14). */
static inline double wff_impulse_work(const wff_model *m, int k, double j, double dt_before,
                                      double dt_mid)
{
    const double a = m->f[k] / m->mass[k];
    if (dt_before > 0)
        return j * (m->v[k] - 0.5 * dt_before * a);
    const double all = m->contact_force ? m->contact_force[k] * dt_mid : j;
    return j * (m->v[k] - dt_mid * a + 0.5 * all / m->mass[k]);
}

/* The same for the projectile's share j = M Δv of one part (its acceleration
 * −force/M is all contact: at a start v⁰ + ½ΔV = v^{½} − ½Δt_mid a). */
static inline double wff_projectile_impulse_work(const wff_model *m, double j, double dt_before,
                                                 double dt_mid)
{
    const wff_projectile *p = &m->projectile;
    const double a = -p->force / p->mass;
    return j * (p->velocity - 0.5 * (dt_before > 0 ? dt_before : dt_mid) * a);
}

/* The longest step, s, in which a DOF moving at `speed` (m/s) under `accel`
 * (m/s²) travels no more than `reach` (m): the root of dt (speed + dt accel)
 * = reach (the built-in's wff_step_travel and a caller's wff_model_travel_step). */
static inline double wff_travel_dt(double speed, double accel, double reach)
{
    return 2 * reach / (speed + sqrt(speed * speed + 4 * accel * reach));
}

/* The adaptive step's good states (checkpoint.c): every evolving field of the
 * checkpoint copied into the older of two buffers (allocated on first use; -1
 * with err if out of memory); restore copies the newer back, or the older when
 * a restore was made since the newer was kept (-1 if there is none). */
int wff_model_snapshot(wff_model *m, wff_error *err);
int wff_model_restore(wff_model *m);

/* The longest step, s, in which no free amplitude DOF with a force on it, moving at v and
 * accelerated by f/m, travels more than reach (m): the smallest root of
 * dt (|v| + dt |f/m|) = reach over them (INFINITY if there is none). */
double wff_step_travel(const wff_model *m, double reach);
int wff_step_candidates(const wff_model *m, double reach, int *candidates);
/* model.c: a model's arrays, masses and defaults from its mesh, material and
 * elements (m->mesh, m->mat, m->el and the order arrays set; every other field
 * 0): the second half of wff_model_create_ordered. On failure m is freed. */
int wff_model_setup(wff_model *m, wff_error *err);
/* model.c: the per-DOF and per-point arrays of a model whose n_dofs, n_state
 * and elements are set, zeroed (u, v, f, mass, dof_kind, v_prescribed,
 * reaction, state), for a model's creation and a mesh transfer alike; -1 if
 * out of memory (what was allocated is left for wff_model_free). */
int wff_model_alloc_arrays(wff_model *m);

/* renumber.c: renumber the model's mesh (before its elements are set up)
 * and keep the permutations; free them. */
int wff_model_renumber(wff_model *m, wff_error *err);
void wff_model_order_free(wff_model *m);
/* element_fields.c: element values in the model's order (the public call
 * gives them in the user's). */
int wff_model_element_values_model(const wff_model *m, const char *name, double *out,
                                   wff_error *err);
/* element_fields.c: 1 if element field `name` is evaluated by the cell at the
 * element's centre (stress, W, tensions, diagnostics: 0 on an eroded element,
 * which nodal averages leave out), 0 for the kinematic and state fields. */
int wff_element_field_evaluated(const wff_model *m, const char *name);
/* element_fields.c: index in element e's cell's diagnostics of the model
 * cell's diagnostic `diag` (the same name; a zone's cell may differ), or -1 when
 * that cell has none of the name. */
int wff_model_element_diag(const wff_model *m, int e, int diag);
/* element_fields.c: element e (model numbering) evaluated at its centre with
 * its zone's material and preload, each of its material's states held at the
 * mean of the element's points (m->state), displacement u; the point status. */
int wff_model_element_center_eval(const wff_model *m, const double *u, int e,
                                  wff_point_result *out);

#endif

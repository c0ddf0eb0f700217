/* integrator.c: the explicit central-difference integrator
 * (docs/model.md §12, §14): the force pass, the velocity update with the
 * boundary conditions, the stable step, the advance loop, the energies and the
 * instability detector. The step's other participants are parts (part.h)
 * run from the list in parts.c: after the force pass, after the velocity
 * update, at each stable-step refresh, and their terms of the balance; the
 * integrator names none of them. Knows nothing of cells by name, of output
 * fields, of checkpoints or of FreeFEM. */
#include "part.h"
#include "zones.h"
#include "distribute.h"
#include "wall_clock.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Energy created, relative to the reference energy, beyond which the run is
 * taken as unstable. */
#define ENERGY_BLOWUP 0.5
/* ... on this many steps in a row (an instability keeps growing; a spike of a
 * step or two, e.g. a prescribed velocity jumped by the script, does not) ... */
#define BLOWUP_STEPS 3
/* ... or at once beyond this (50 times the reference energy created). */
#define ENERGY_BLOWUP_NOW 50.0

/* The amplitudes' share of the energy in play that the travel limit follows is
 * held at its largest, decaying by this factor a step (a swing's kinetic energy
 * falls to 0 at each turn). */
#define TRAVEL_SHARE_HOLD 0.99

/* The travel limit grows by at most this factor a step (it falls at once): a
 * step following every turn of a swing changes by ~30 % a step, and the
 * central difference does not keep its energy across such jumps (the bumped
 * square: ~4 x the energy error of the slowly growing limit). */
#define TRAVEL_GROWTH 1.01

/* Growth (the adaptive step's earlier trigger): the energy created past this
 * fraction of the reference and rising by half again on this many steps in a
 * row (an instability grows geometrically; a release's transient does not). */
#define GROWTH_FROM 0.05
#define GROWTH_STEPS 3
/* Most halvings of dtfactor a run takes (0.8 → 0.8/2^8 = 0.003). */
#define MAX_CUTS 8

/* "triangle 3 (nodes 4 5 9)" or "quadrilateral 2 (nodes ...)" for element e
 * (triangles first, then quads), numbered from 1 within its type. */
static void element_name(const wff_model *m, int e, char *out, size_t size)
{
    wff_model_element_name(m, e, out, size); /* (renumber.c: in the user's numbering) */
}

/* The run is unstable: say what showed it (`what`), when, the element that
 * sets the stable step, and a step and a dtfactor to try. */
/* The free DOF with the largest acceleration |f/m| (the growing mode's): its
 * node (the caller's numbering, from 1), kind and state, for the message. */
static void fastest_dof(const wff_model *m, char *out, size_t size)
{
    static const char *const kinds[D] = {"in-plane u_x", "in-plane u_y", "transverse u_z",
                                          "amplitude dA1", "amplitude dA2"};
    int best = -1;
    double fastest = -1;
    for (int i = 0; i < m->n_dofs; i++) {
        double a = m->dof_kind[i] == WFF_DOF_FREE ? fabs(m->f[i] / m->mass[i]) : -1;
        if (a != a) /* a NaN first: it is the one to name */
            a = INFINITY;
        if (a > fastest) {
            fastest = a;
            best = i;
        }
    }
    if (best < 0) {
        snprintf(out, size, "no free DOF");
        return;
    }
    const int node = best / D, c = best % D;
    snprintf(out, size, "the fastest DOF: node %d, %s = %.3g m moving at %.3g m/s, "
             "accelerated at %.3g m/s^2", wff_model_user_node(m, node) + 1, kinds[c], m->u[best],
             m->v[best], m->f[best] / m->mass[best]);
}

static int fail_unstable(const wff_model *m, const char *what, wff_error *err)
{
    char name[96], dof[200];
    element_name(m, m->dt_worst_element, name, sizeof name);
    fastest_dof(m, dof, sizeof dof);
    /* above the default: back to 0.8; at or below it the estimate was not
     * safe here: halve the factor */
    double suggested = m->dt_factor > 0.8 ? 0.8 : 0.5 * m->dt_factor;
    return wff_fail(err, "t = %.6g s (step %ld): %s: unstable (time step %.3g s = %.3g x the "
                    "stable estimate %.3g s at %s; %s); suggested step %.3g s: suggested "
                    "-dtfactor %.2g", m->time, m->step, what, m->dt, m->dt_factor,
                    m->dt_stable, name, dof, suggested * m->dt_stable, suggested);
}

/* The element force pass (internal forces only) at displacement u into f
 * (zeroed first), the points' state advanced by dt_flow in state; with
 * `accumulate` the model's stored energy, shear, failure and slip dissipation and
 * element-step count follow it;
 * the pass's stored energy (J, model part) into *energy unless NULL.
 * Returns 0 or -1 (err set, naming the element and quadrature point). Shared
 * with operators.c (solver_internal.h). */
static int force_pass_added(wff_model *m, const double *u, double *f, double *state,
                            double dt_flow, int accumulate, double *energy, wff_error *err);

int wff_force_pass(wff_model *m, const double *u, double *f, double *state, double dt_flow,
                   int accumulate, double *energy, wff_error *err)
{
    wff_step_zero(m, f, m->n_dofs);
    return force_pass_added(m, u, f, state, dt_flow, accumulate, energy, err);
}

/* wff_force_pass into an f already zeroed. */
static int force_pass_added(wff_model *m, const double *u, double *f, double *state,
                            double dt_flow, int accumulate, double *energy, wff_error *err)
{
    wff_force_totals t;
    wff_zones_forces(m, u, state, dt_flow, f, &t);
    if (accumulate) {
        m->element_steps += m->el.n_tris + m->el.n_quads;
        m->amplitude_iterations += t.amplitude_iterations;
    }
    if (t.bad_element >= 0) {
        char name[96], unbalanced[64];
        element_name(m, t.bad_element, name, sizeof name);
        snprintf(unbalanced, sizeof unbalanced, "amplitudes unbalanced, |R| %.3g N/m^2 after %d "
                 "Newton steps", t.bad_residual, t.bad_iterations);
        const char *quantity = t.bad_status == WFF_POINT_DEGENERATE
                                   ? "degenerate deformation (yarns collapsed or parallel: "
                                     "inverted element)"
                               : t.bad_status == WFF_POINT_UNBALANCED
                                   ? unbalanced
                                   : "NaN or infinite displacement, amplitude, stress or energy";
        if (m->blowup_steps > 0) { /* the detector was already counting */
            char what[WFF_ERROR_MAX - 200];
            snprintf(what, sizeof what, "%s, quadrature point %d: %s, with the energy balance "
                     "off by %.3g%% of the reference energy the step before", name,
                     t.bad_point + 1, quantity, 100 * m->last_error);
            return fail_unstable(m, what, err);
        }
        char hint[160] = "";
        if (m->dt_factor > 1)
            snprintf(hint, sizeof hint, " (the step is %.3g x the stable estimate: likely "
                     "unstable; suggested -dtfactor 0.8)", m->dt_factor);
        return wff_fail(err, "t = %.6g s (step %ld): %s, quadrature point %d: %s%s", m->time,
                        m->step, name, t.bad_point + 1, quantity, hint);
    }
    /* the parts after the pass (part.h): erosion takes the elements whose yarns
     * have ruptured, their stored energy out of the pass's; a pack's per-ply
     * accounts follow */
    if (accumulate)
        t.internal_energy -= wff_parts_after_forces(m, u, state, dt_flow);
    if (energy)
        *energy = t.internal_energy;
    if (accumulate) {
        m->internal_energy = t.internal_energy;
        m->dissipated_shear += t.dissipated;
        m->dissipated_failure += t.failure_dissipated;
        m->dissipated_slip += t.slip_dissipated;
    }
    return 0;
}

/* Internal forces at the current u (contact forces are added after the
 * velocity update); returns 0 or -1 (err set). */
static int compute_forces(wff_model *m, double dt_flow, wff_error *err)
{
    return wff_force_pass(m, m->u, m->f, m->state, dt_flow, 1, NULL, err);
}

/* The same, f zeroed already (by the position update: one pass less a step);
 * its wall time into m->force_seconds. */
static int compute_forces_zeroed(wff_model *m, double dt_flow, wff_error *err)
{
    const double start = wff_wall_seconds();
    int rc = force_pass_added(m, m->u, m->f, m->state, dt_flow, 1, NULL, err);
    m->force_seconds += wff_wall_seconds() - start;
    return rc;
}

/* v^{n+½} from f^n; dt_done is the step just taken (0 on the first half step):
 * the second half of its trapezoidal external work, ½ Rⁿ⁺¹·Δu, is added here
 * on the prescribed DOFs (the first half was added with the position update). */
static void update_velocities(wff_model *m, double dt_mid, double dt_done)
{
    m->external_work += wff_step_velocities(m, dt_mid, dt_done); /* (step_threads.c) */
}

static int update_time_step(wff_model *m, wff_error *err)
{
    int worst;
    double dt = wff_zones_stable_step(m, m->u, &worst);
    /* a part's own solid (a backing block): its step if shorter (the message
     * below names the fabric's element that sets the fabric's) */
    const double parts_dt = wff_parts_stable_step(m);
    if (parts_dt < dt && worst >= 0)
        dt = parts_dt;
    if (dt == INFINITY && worst < 0 && m->n_eroded > 0 && m->dt_stable > 0) {
        /* every element eroded: free masses, no element sets a step; keep the last */
        m->dt = m->dt_factor * m->dt_stable;
        return 0;
    }
    if (!(dt > 0) || !isfinite(dt)) {
        char name[96];
        element_name(m, worst, name, sizeof name);
        return wff_fail(err, "t = %.6g s (step %ld): %s: stable time step %g s is not "
                        "positive: degenerate deformation (yarns collapsed or parallel) or "
                        "NaN", m->time, m->step, name, dt);
    }
    m->dt_stable = dt;
    m->dt_worst_element = worst;
    m->dt = m->dt_factor * dt;
    return 0;
}

/* The next step: dtfactor × the stable step, shortened where a free amplitude,
 * at its velocity and this step's acceleration, would travel more than WFF_TRAVEL ×
 * dtfactor of the amplitude length (wff_step_travel). */
static void travel_limit(wff_model *m)
{
    m->dt = m->dt_factor * m->dt_stable;
    const double length = m->travel_off ? INFINITY : wff_zones_amplitude_length(m);
    if (!(length < INFINITY))
        return;
    /* the fraction: travel_fraction where the amplitudes' swings carry all the
     * energy in play, loosening as 1/sqrt of their share (solver_internal.h) */
    const double loose = fmax(WFF_TRAVEL_LOOSE, m->travel_fraction);
    const double fraction = m->travel_share > 0
                                ? fmin(loose, m->travel_fraction / sqrt(m->travel_share))
                                : loose;
    double limit = wff_step_travel(m, m->dt_factor * fraction * length);
    /* down at once, up slowly: the step follows the fastest swing, not each turn */
    if (m->dt_travel > 0 && limit > TRAVEL_GROWTH * m->dt_travel)
        limit = TRAVEL_GROWTH * m->dt_travel;
    m->dt_travel = limit;
    if (limit < m->dt) {
        m->dt = limit;
        m->travel_steps++;
    }
}

/* Kinetic energies (model part) at the integer step, v^{n+½} − ½Δt a^n from
 * the last half step: in-plane, transverse, amplitude, projectile; and the
 * stagger (Δt²/8) Σ f²/m (k[4]): the integer-step kinetic energy less it is
 * ½ Σ m v^{n−½}·v^{n+½}, which with the stored energy at step n the central
 * difference conserves exactly on a linear system at any stable step (the
 * integer-step one swings by (ωΔt)²/4 of a mode's energy); and the contact
 * forces' share of that stagger, ½Δt Σ v^{n+½}·g (k[5]: the balance takes them
 * back out of it, their work booked by the parts' book op). No allocation: the
 * advance loop calls it every step. */
static void kinetic_now(const wff_model *m, double k[6])
{
    const double half = m->v_half_valid ? 0.5 * m->dt : 0;
    double sums[5]; /* Σ m v² in-plane, transverse, amplitude, Σ f²/m, Σ v^{n+½}·g
                       (threaded: step_threads.c; over ranks every rank's pass is whole,
                       plugin/distribute.c) */
    wff_step_kinetic(m, half, sums);
    const double inplane = sums[0], transverse = sums[1], amplitude = sums[2];
    k[0] = 0.5 * inplane;
    k[1] = 0.5 * transverse;
    k[2] = 0.5 * amplitude;
    k[3] = 0;
    double force_sq = sums[3];
    if (m->projectile.active) {
        double vp = m->projectile.velocity + half * m->projectile.force / m->projectile.mass;
        k[3] = 0.5 * m->projectile.mass * vp * vp;
        force_sq += m->projectile.force * m->projectile.force / m->projectile.mass;
    }
    k[4] = 0.5 * half * half * force_sq; /* (Δt²/8 Σ f²/m, half = Δt/2) */
    /* the contact forces' share of it, ½Δt Σ v^{n+½}·g (the projectile's force
     * on it is −force, all contact) */
    k[5] = half * (sums[4] - (m->projectile.active ? m->projectile.velocity * m->projectile.force : 0));
}

void wff_model_energies(const wff_model *m, wff_energies *out)
{
    double k[6];
    kinetic_now(m, k);
    double s = m->symmetry_factor;
    out->kinetic_inplane = s * k[0];
    out->kinetic_transverse = s * k[1];
    out->kinetic_amplitude = s * k[2];
    out->kinetic_projectile = s * k[3];
    out->kinetic_stagger = s * k[4];
    out->internal = s * (m->internal_energy);
    out->dissipated_shear = s * m->dissipated_shear;
    out->dissipated_friction = s * m->dissipated_friction;
    out->external_work = s * m->external_work;
    out->transfer = s * m->transfer_energy;
    out->dissipated_failure = s * m->dissipated_failure;
    out->dissipated_slip = s * m->dissipated_slip;
    out->eroded = s * m->eroded_energy;
    const double parts = wff_parts_dissipated(m); /* (part.h: the ply contact's) */
    out->dissipated_ply_contact = s * parts;
    /* initial + external work = kinetic + internal + shear + friction + failure + slip +
     * eroded, the kinetic energy the staggered one ½ m v^{n−½}·v^{n+½} */
    const double kinetic = k[0] + k[1] + k[2] + k[3];
    out->impulse_stagger = s * k[5];
    /* the balance's kinetic measure, ½ Σ m v^{n+½}·(v^{n+½} − Δt_{n+½} a_elastic^n): the
     * staggered one with the contact forces' part of the stagger taken back out
     * (their work is booked at the trapezoidal rule's measure, part.h's book) */
    double total = kinetic - k[4] + k[5] + m->stagger_shift + m->internal_energy +
                   m->dissipated_shear + m->dissipated_friction + m->dissipated_failure +
                   m->dissipated_slip + m->eroded_energy - m->external_work -
                   m->transfer_energy + parts;
    /* normaliser: the initial kinetic energy, or (for a scene driven by its
     * boundaries) the work done on it or the energy it now holds */
    double stored = m->internal_energy - (m->initial_total - m->initial_kinetic);
    double ref = fmax(m->initial_kinetic, fabs(m->external_work));
    ref = fmax(ref, fmax(kinetic, fabs(stored)));
    /* below the kinetic energy of the fabric moving at ~3e-5 m/s, energies are
     * round-off: floor the normaliser there */
    ref = fmax(ref, 1e-9 * m->fabric_mass * 1.0 /* (m/s)^2 */);
    out->reference = s * ref;
    out->error = m->v_half_valid ? (total - m->initial_total) / ref : 0; /* not started: exact */
    out->error_integer_step = m->v_half_valid ? (total + k[4] - k[5] -
                                                 m->stagger_shift - m->initial_total -
                                                 m->stagger_reference) / ref : 0;
}

/* After the parts' corrections: their impulses' work booked at the final
 * velocities (part.h's book), the kick's Δt_mid kept (a re-planned step
 * re-expresses the contact forces with it). With the contact forces g out of
 * the balance's stagger (wff_model_energies) and the impulses' work at
 * j·(v^{n+½} − ½Δt_{n−½} aⁿ), the trapezoidal rule's ½(gⁿ + gⁿ⁺¹)·Δu summed,
 * the balance is exact on a linear system with any impulses at any sequence of
 * steps (with the stagger's shift); booked at the integer-step velocity with
 * the contact forces in the stagger it was off by ½ j·v^{n+½} at every step
 * and by ¼(Δt_{n+½} − Δt_{n−½})Δt_mid g·M⁻¹f summed over the steps that
 * change (docs/model.md §14). */
static void book_impulses(wff_model *m, double dt_before, double dt_mid)
{
    wff_parts_book(m, dt_before, dt_mid);
    m->dt_mid = dt_mid;
}

double wff_model_step_estimate(const wff_model *m)
{
    int worst;
    return m->dt_factor * fmin(wff_zones_stable_step(m, m->u, &worst), wff_parts_stable_step(m));
}

/* The step after this one toward the model's t_stop (stop, s): the full step
 * while two or more are left, then half of what is left and the rest, so that
 * the model ends at t_stop exactly with no step under half the full one (the
 * contact's correction divides by the step). Only the last two steps of a run
 * change: shortening every frame's last steps instead pumps energy into the
 * finest modes (a periodic step pattern; measured: the teaching scene's
 * rebound case, 5 m/s, its energy error 1e-10 -> 4 % in 0.4 ms, then NaN).
 * Returns 1 if the step planned (m->dt) ends at stop; at stop (within 1e-9 of
 * a step) the time is stop and the full step is planned. */
static int plan_stop_step(wff_model *m, double stop)
{
    const double full = m->dt, left = stop - m->time; /* (the step travel_limit chose) */
    if (left >= 2 * full)
        return 0; /* (m->dt is the full step: the planned one left alone) */
    m->dt = full;
    if (left <= 1e-9 * full) {
        m->time = stop;
        return 0;
    }
    if (left <= full * (1 + 1e-9)) {
        m->dt = left;
        return 1;
    }
    m->dt = 0.5 * left;
    return 0;
}

/* The adaptive step (setting adaptive_step): the run keeps its state every
 * dtinterval steps (the last two); at an instability it goes back to the newer
 * with dtfactor halved, to the older if it fails again before the next is kept
 * (the newer already held the growing mode), at most MAX_CUTS times a run. Refused for a model whose parts do not
 * checkpoint (a pack): what the snapshot holds is the checkpoint's state. */
static int start_adaptive(wff_model *m, wff_error *err)
{
    char why[WFF_ERROR_MAX - 100];
    if (wff_parts_refuse_checkpoint(m, why, sizeof why))
        return wff_fail(err, "adaptive_step: the last good state cannot be kept: %s: refused",
                        why);
    return wff_model_snapshot(m, err);
}

/* Back to the last good state with dtfactor halved; 0 if there is none to go
 * back to (not adaptive, or MAX_CUTS reached): the caller reports the failure. */
static int cut_step(wff_model *m)
{
    if (!m->adaptive || m->step_cuts >= MAX_CUTS || wff_model_restore(m))
        return 0;
    m->step_cuts++;
    m->dt_factor *= 0.5;
    /* v^{n+½} was kicked with ½(Δt_done + Δt): the new half of the kick, the
     * stagger's move booked (step_threads.c) */
    wff_step_replan(m, 0.5 * m->dt);
    m->dt_travel = m->dt_travel > 0 ? 0.5 * m->dt_travel : 0;
    m->blowup_steps = m->growth_steps = 0;
    return 1;
}

static int advance(wff_model *m, double t_end, long max_steps, wff_error *err);

/* Over ranks, every rank's points' states whole again when the advance
 * returns (each advanced its own elements': fields, values and checkpoints
 * read them all; plugin/distribute.c). */
int wff_model_advance(wff_model *m, double t_end, long max_steps, wff_error *err)
{
    int rc = advance(m, t_end, max_steps, err);
    wff_dist_states_whole(m);
    return rc;
}

static int advance(wff_model *m, double t_end, long max_steps, wff_error *err)
{
    const double stop = m->t_stop > 0 ? m->t_stop : INFINITY;
    int lands = 0; /* the step planned ends at stop */
    if (!isfinite(t_end))
        return wff_fail(err, "advance to t_end = %g s: must be a finite time", t_end);
    if (t_end < m->time)
        return wff_fail(err, "advance to t_end = %.9g s: before the model's time %.9g s "
                        "(step %ld): a model cannot go back", t_end, m->time, m->step);
    if (m->step == 0 && !m->v_half_valid) {
        /* start: forces at u⁰, energy reference */
        if (update_time_step(m, err) || wff_parts_setup(m, err))
            return -1;
        wff_parts_refresh(m);
        if (compute_forces(m, 0, err))
            return -1;
        double k[6];
        kinetic_now(m, k); /* v_half_valid is 0: the velocities as given */
        const double given = k[0] + k[1] + k[2] + k[3];
        m->v_half_valid = 1;
        /* first half step */
        travel_limit(m);
        if (stop < INFINITY)
            lands = plan_stop_step(m, stop);
        /* the balance's energy at the start: the given kinetic energy less the
         * stagger of the first half step's elastic forces, and the stored energy;
         * the start's impulses act at t = 0, their work the kinetic energy they
         * change there (book_impulses) */
        kinetic_now(m, k); /* (its k[4] only: f the elastic forces here) */
        m->initial_kinetic = given - k[4];
        m->stagger_reference = k[4];
        m->initial_total = m->initial_kinetic + m->internal_energy;
        update_velocities(m, 0.5 * m->dt, 0);
        if (wff_parts_correct(m, m->dt, 0.5 * m->dt, err))
            return -1;
        book_impulses(m, 0, 0.5 * m->dt);
    }
    wff_parts_refresh(m);
    if (m->adaptive && m->snapshot_step[m->snapshot_newest] < 0 && start_adaptive(m, err))
        return -1;
    long done = 0;
    while (m->time < t_end && m->time < stop && done < max_steps) {
        /* u^{n+1} = u^n + Δt v^{n+½} */
        double dt = m->dt;
        /* external work by the trapezoidal rule: ½(R^n + R^{n+1})·Δu */
        m->external_work += wff_step_positions(m, dt); /* and f = 0 (step_threads.c) */
        if (m->projectile.active)
            m->projectile.tip += dt * m->projectile.velocity;
        m->time = lands ? stop : m->time + dt;
        m->step++;
        done++;
        if (m->step % m->dt_interval == 0) {
            if (update_time_step(m, err)) {
                if (cut_step(m)) {   /* (back to a state kept earlier: its step is planned anew) */
                    lands = 0;
                    continue;
                }
                return -1;
            }
            wff_parts_refresh(m);
        }
        if (compute_forces_zeroed(m, dt, err)) {
            if (cut_step(m)) {   /* (back to a state kept earlier: its step is planned anew) */
                lands = 0;
                continue;
            }
            return -1;
        }
        travel_limit(m);
        if (stop < INFINITY)
            lands = plan_stop_step(m, stop);
        update_velocities(m, 0.5 * (dt + m->dt), dt);
        if (wff_parts_correct(m, m->dt, 0.5 * (dt + m->dt), err))
            return -1;
        book_impulses(m, dt, 0.5 * (dt + m->dt));
        {   /* every step (a pass over the DOFs, ~4 % of a step): an unstable
             * step grows the energy by a large factor per step */
            wff_energies e;
            wff_model_energies(m, &e);
            /* the stagger (Δt²/8) Σ f²/m is of the step planned: a step that
             * changes shifts the staggered kinetic energy at the same state,
             * which the central difference with the new step then conserves
             * (exactly on a linear system); the shift is the balance's
             * (docs/model.md §12) */
            if (m->dt != dt)
                m->stagger_shift += e.kinetic_stagger / m->symmetry_factor * (1 - dt * dt / (m->dt * m->dt));
            /* (with the integer-step kinetic energy: the staggered balance of
             * e.error is conserved by a growing linear mode too) */
            const double created = e.error_integer_step;
            /* an unstable step creates energy (a deficit is not instability) and
             * keeps creating it: a one- or two-step spike, as when a script jumps
             * a prescribed velocity while the work done is still tiny, is not */
            m->blowup_steps = created > ENERGY_BLOWUP ? m->blowup_steps + 1 : 0;
            /* growth: the energy created rising by half again on each of
             * GROWTH_STEPS steps past GROWTH_FROM (the adaptive step acts on it) */
            m->growth_steps = created > GROWTH_FROM && created > 1.5 * m->last_error
                                  ? m->growth_steps + 1 : 0;
            if (!isfinite(created) || m->blowup_steps >= BLOWUP_STEPS ||
                created > ENERGY_BLOWUP_NOW || (m->adaptive && m->growth_steps >= GROWTH_STEPS)) {
                if (cut_step(m)) {   /* (back to a state kept earlier: its step is planned anew) */
                    lands = 0;
                    continue;
                }
                char what[160];
                snprintf(what, sizeof what, "energy balance off by %.3g%% of the reference "
                         "energy", 100 * created);
                return fail_unstable(m, what, err);
            }
            m->last_error = created;
            /* the amplitudes' share of the energy in play, held (travel_limit) */
            const double share = e.reference > 0 ? e.kinetic_amplitude / e.reference : 0;
            m->travel_share = fmax(share, TRAVEL_SHARE_HOLD * m->travel_share);
        }
        if (m->adaptive && m->step % m->dt_interval == 0 && wff_model_snapshot(m, err))
            return -1;
    }
    return 0;
}

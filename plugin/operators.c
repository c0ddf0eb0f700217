/* operators.c: the element operators a caller's own explicit loop needs
 * (docs/freefem_api.md "Your own loop"): internal and amplitude residual
 * forces at a given state (with or without advancing γᶠ), the lumped masses,
 * the stable step at a state, one built-in step, the DOF kinds, the
 * projectile's contact and the friction clamp's correction applied to a
 * caller's arrays, and the shot's verdict at a caller's state. Each reuses the built-in step's own code (integrator.c's
 * force pass and clamp correction, contact.c's search and correction), so a
 * scripted loop that calls them in the built-in order gives the built-in's
 * numbers. Knows the model; nothing of cells by name, of output fields, of
 * checkpoints or of FreeFEM. */
#include "distribute.h"
#include "clamp.h"
#include "contact.h"
#include "zones.h"
#include "wovenff/perforation.h"
#include "wovenff/renumber.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Quadrature points of the mesh (γᶠ entries). */
static size_t n_points(const wff_model *m)
{
    return wff_elements_point_count(&m->el);
}

/* The scratch copy of the points' state (n_points × n_state) followed by room for the static
 * amplitudes (2 per point), allocated once. */
static double *scratch(wff_model *m, wff_error *err)
{
    if (!m->operator_scratch) {
        size_t nq = n_points(m);
        m->operator_scratch = malloc((size_t)(m->n_state + 2) * sizeof(double) * (nq ? nq : 1));
        if (!m->operator_scratch)
            wff_fail(err, "out of memory for the force operator's workspace");
    }
    return m->operator_scratch;
}

/* The caller's DOF vectors (the user's numbering) in the model's order:
 * n copies of n_dofs into one block (NULL, err set, if out of memory; free it). */
static double *model_copies(const wff_model *m, const double *const *user, int n,
                            wff_error *err)
{
    size_t nd = (size_t)m->n_dofs;
    double *block = malloc(sizeof(double) * nd * (size_t)n + 1);
    if (!block) {
        wff_fail(err, "out of memory for the operator's %d vectors of %zu DOFs", n, nd);
        return NULL;
    }
    for (int k = 0; k < n; k++)
        if (user[k])
            wff_model_nodes_from_user(m, user[k], block + nd * (size_t)k, D);
    return block;
}

static int forces_model(wff_model *m, const double *U, double *R, double dt, double *energy,
                        wff_error *err);

int wff_model_forces(wff_model *m, const double *U, double *R, double dt, double *energy,
                     wff_error *err)
{
    if (!m->node_user)
        return forces_model(m, U, R, dt, energy, err);
    const double *in[2] = {U, NULL};
    double *b = model_copies(m, in, 2, err);
    if (!b)
        return -1;
    int rc = forces_model(m, b, b + m->n_dofs, dt, energy, err);
    if (!rc)
        wff_model_nodes_to_user(m, b + m->n_dofs, R, D);
    free(b);
    return rc;
}

static int forces_model(wff_model *m, const double *U, double *R, double dt, double *energy,
                        wff_error *err)
{
    if (!(dt >= 0) || !isfinite(dt))
        return wff_fail(err, "time step dt = %g s: must be >= 0 and finite (0: γᶠ held)", dt);
    double e = 0;
    if (dt > 0) { /* as the built-in step's force pass */
        if (wff_force_pass(m, U, R, m->state, dt, 1, &e, err))
            return -1;
        wff_dist_states_whole(m); /* (over ranks: each rank advanced its own points) */
    } else {      /* γᶠ (and static amplitudes) on a copy: the model stays as it was */
        double *held = scratch(m, err);
        if (!held)
            return -1;
        size_t nq = n_points(m), ns = nq * (size_t)m->n_state;
        memcpy(held, m->state, sizeof(double) * ns);
        double *dA = m->el.point_dA;
        if (dA)
            memcpy(held + ns, dA, 2 * sizeof(double) * nq);
        int rc = wff_force_pass(m, U, R, held, 0, 0, &e, err);
        if (dA)
            memcpy(dA, held + ns, 2 * sizeof(double) * nq);
        if (rc)
            return -1;
    }
    if (energy)
        *energy = m->symmetry_factor * e;
    return 0;
}

void wff_model_masses(const wff_model *m, double *M)
{
    wff_model_nodes_to_user(m, m->mass, M, D);
}

int wff_model_stable_step(const wff_model *m, const double *U, double *dt, int *worst,
                          wff_error *err)
{
    int w = -1;
    double *b = NULL;
    if (U && m->node_user) {
        const double *in[1] = {U};
        if (!(b = model_copies(m, in, 1, err)))
            return -1;
    }
    *dt = wff_zones_stable_step(m, b ? b : U ? U : m->u, &w);
    free(b);
    w = wff_model_user_element(m, w);
    if (worst)
        *worst = w;
    if (!(*dt > 0) || !isfinite(*dt))
        return wff_fail(err, "stable time step %g s at element %d is not positive: degenerate "
                        "deformation (yarns collapsed or parallel) or NaN", *dt, w + 1);
    return 0;
}

int wff_model_travel_step(const wff_model *m, const double *V, const double *R, double *dt,
                          wff_error *err)
{
    *dt = INFINITY;
    const double length = wff_zones_amplitude_length(m), reach = m->travel_fraction * length;
    if (!(length < INFINITY))
        return 0;
    for (int user = 0; user < m->n_nodes; user++) {
        const int n = m->node_model ? m->node_model[user] : user;
        for (int j = D - 2; j < D; j++) {
            const int i = D * n + j, iu = D * user + j;
            if (m->dof_kind[i] != WFF_DOF_FREE || R[iu] == 0) /* (as wff_step_travel) */
                continue;
            const double speed = fabs(V[iu]), accel = fabs(R[iu] / m->mass[i]);
            if (!isfinite(speed) || !isfinite(accel))
                return wff_fail(err, "travel limit: node %d, amplitude %d: velocity %g m/s, "
                                "force %g N: not finite", user + 1, j - D + 3, V[iu], R[iu]);
            const double step = wff_travel_dt(speed, accel, reach);
            if (step < *dt)
                *dt = step;
        }
    }
    return 0;
}

int wff_model_step(wff_model *m, double *dt_taken, wff_error *err)
{
    /* not started: the start (forces at u⁰, the first half step) sets the step */
    if (m->step == 0 && !m->v_half_valid && wff_model_advance(m, DBL_MAX, 0, err))
        return -1;
    double dt = m->dt;
    if (wff_model_advance(m, DBL_MAX, 1, err))
        return -1;
    *dt_taken = dt;
    return 0;
}

void wff_model_dof_kinds(const wff_model *m, double *kind, double *v_prescribed)
{
    for (int i = 0; i < m->n_dofs; i++) { /* (into the user's numbering) */
        int ui = D * wff_model_user_node(m, i / D) + i % D;
        kind[ui] = m->dof_kind[i];
        if (v_prescribed)
            v_prescribed[ui] = m->dof_kind[i] == WFF_DOF_PRESCRIBED ? m->v_prescribed[i] : 0;
    }
}

int wff_model_contact_search(wff_model *m, const double *U)
{
    if (!m->projectile.active)
        return 0;
    double *u = m->u, *b = NULL;
    if (m->node_user) {
        const double *in[1] = {U};
        wff_error err;
        if (!(b = model_copies(m, in, 1, &err)))
            return 0;
    }
    m->u = b ? b : (double *)U; /* contact.c reads the state from the model: lend it the caller's */
    wff_contact_refresh_candidates(m);
    m->u = u;
    free(b);
    return m->projectile.n_candidates;
}

int wff_model_contact(wff_model *m, const double *U, double *V, double *R, double tip[2],
                      double dt, double dt_mid, double *dissipated, wff_error *err)
{
    wff_projectile *p = &m->projectile;
    if (!p->active)
        return wff_fail(err, "no projectile: set one first");
    if (!(dt > 0) || !(dt_mid > 0) || !isfinite(dt) || !isfinite(dt_mid))
        return wff_fail(err, "dt = %g s and dt_mid = %g s must be > 0 and finite", dt, dt_mid);
    if (!isfinite(tip[0]) || !isfinite(tip[1])) /* (a rebounding projectile moves along -z) */
        return wff_fail(err, "projectile tip %g m and velocity %g m/s must be finite", tip[0],
                        tip[1]);
    double *b = NULL, *Um = (double *)U, *Vm = V, *Rm = R;
    if (m->node_user) { /* the caller's vectors into the model's order and back */
        const double *in[3] = {U, V, R};
        if (!(b = model_copies(m, in, 3, err)))
            return -1;
        Um = b, Vm = b + m->n_dofs, Rm = b + 2 * (size_t)m->n_dofs;
    }
    p->tip = tip[0];
    p->velocity = tip[1];
    double *u = m->u, *v = m->v, *f = m->f, before = m->dissipated_friction;
    m->u = Um; /* contact.c works on the model's arrays: lend it the caller's */
    m->v = Vm;
    m->f = Rm;
    double *g = m->contact_force;
    m->contact_force = NULL; /* (the caller keeps its own balance: R holds the forces) */
    int rc = wff_contact_correct(m, dt, dt_mid, err);
    if (rc == 0) /* its impulses' work: the step before this one is 2 dt_mid − dt */
        wff_contact_book(m, 2 * dt_mid - dt, dt_mid);
    m->contact_force = g;
    m->u = u;
    m->v = v;
    m->f = f;
    if (b) {
        wff_model_nodes_to_user(m, Vm, V, D);
        wff_model_nodes_to_user(m, Rm, R, D);
        free(b);
    }
    tip[1] = p->velocity;
    *dissipated = m->symmetry_factor * (m->dissipated_friction - before);
    return rc;
}

int wff_model_perforation_at(wff_model *m, const double *U, wff_perforation *out,
                             wff_error *err)
{
    double *u = m->u, *b = NULL;
    if (m->node_user) {
        const double *in[1] = {U};
        if (!(b = model_copies(m, in, 1, err)))
            return -1;
    }
    m->u = b ? b : (double *)U; /* perforation.c reads the state from the model: lend it the caller's */
    int rc = wff_model_perforation(m, out, err);
    m->u = u;
    free(b);
    return rc;
}

int wff_model_clamp_correct_booked(wff_model *m, double *V, double *R, double dt,
                                   double dt_mid, double *dissipated, wff_error *err)
{
    *dissipated = 0;
    if (!(dt > 0) || !(dt_mid > 0) || !isfinite(dt) || !isfinite(dt_mid))
        return wff_fail(err, "dt = %g s and dt_mid = %g s must be > 0 and finite", dt, dt_mid);
    if (!m->clamp.n)
        return 0;
    double *b = NULL, *Vm = V, *Rm = R;
    if (m->node_user) { /* the caller's vectors into the model's order and back */
        const double *in[2] = {V, R};
        if (!(b = model_copies(m, in, 2, err)))
            return -1;
        Vm = b, Rm = b + m->n_dofs;
    }
    double *v = m->v, *f = m->f, *g = m->contact_force, before = m->dissipated_friction;
    m->v = Vm; /* clamp.c works on the model's arrays: lend it the caller's */
    m->f = Rm;
    m->contact_force = NULL; /* (the caller keeps its own balance) */
    wff_clamp_correct_all(m, Vm, dt_mid, 1);
    for (int c = 0; c < m->clamp.n; c++)
        for (int k = 0; k < 2; k++)
            Rm[D * m->clamp.node[c] + k] += m->clamp.impulse[2 * c + k] / dt_mid;
    wff_clamp_book(m, 2 * dt_mid - dt, dt_mid);
    m->v = v;
    m->f = f;
    m->contact_force = g;
    if (b) {
        wff_model_nodes_to_user(m, Vm, V, D);
        wff_model_nodes_to_user(m, Rm, R, D);
        free(b);
    }
    *dissipated = m->symmetry_factor * (m->dissipated_friction - before);
    return 0;
}

double wff_model_clamp_correct(wff_model *m, double *V, double dt_mid)
{
    double *b = NULL;
    if (m->node_user) {
        const double *in[1] = {V};
        wff_error err;
        if (!(b = model_copies(m, in, 1, &err)))
            return 0;
    }
    double dissipated = wff_clamp_correct_all(m, b ? b : V, dt_mid, 0);
    if (b) {
        wff_model_nodes_to_user(m, b, V, D);
        free(b);
    }
    m->dissipated_friction += dissipated;
    return m->symmetry_factor * dissipated;
}

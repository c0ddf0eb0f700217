/* state.c: a model's state in and out as arrays (include/wovenff/state.h):
 * get and set u or v with checks, the recomputation that makes energies,
 * forces and fields describe a set state, the energy balance's reference
 * moved by a set after steps; absolute crimp amplitudes. Knows the model, the
 * elements' force pass and a cell's reference geometry; nothing of how a
 * step is taken, of contact, of FreeFEM. */
#include "solver_internal.h"
#include "state_fields.h"
#include "zones.h"
#include "wovenff/state.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static const char *const component_names[D] = {"ux", "uy", "uz", "dA1", "dA2"};

static int which_vector(const char *which, wff_error *err)
{
    if (which && strcmp(which, "u") == 0)
        return 0;
    if (which && strcmp(which, "v") == 0)
        return 1;
    return wff_fail(err, "unknown state vector '%s' (known: u, the displacements and amplitude "
                    "changes; v, the velocities)", which ? which : "");
}

int wff_model_get_vector(const wff_model *m, const char *which, double *out, wff_error *err)
{
    int w = which_vector(which, err);
    if (w < 0)
        return -1;
    wff_model_nodes_to_user(m, w ? m->v : m->u, out, D); /* (the user's numbering) */
    return 0;
}

/* Kinetic (the balance's: less the stagger) + stored energy now and the
 * stagger, model part (what a set may change). */
static void state_energy(const wff_model *m, double *kinetic, double *stored, double *stagger)
{
    wff_energies e;
    wff_model_energies(m, &e);
    double s = m->symmetry_factor;
    *kinetic = (e.kinetic_inplane + e.kinetic_transverse + e.kinetic_amplitude +
                e.kinetic_projectile - e.kinetic_stagger) / s;
    *stored = m->internal_energy;
    *stagger = e.kinetic_stagger / s;
}

/* Check a vector to be set; -1 naming the first DOF at fault. */
static int check_vector(const wff_model *m, int w, const double *in, wff_error *err)
{
    const char *vec = w ? "v" : "u";
    int no_amplitudes = wff_cell_amplitudes(m->mat.cell) == 0;
    for (int i = 0; i < m->n_dofs; i++) { /* (in: the model's order; named in the user's) */
        int node = wff_model_user_node(m, i / D) + 1, c = i % D, ui = D * (node - 1) + c;
        if (!isfinite(in[i]))
            return wff_fail(err, "%s[%d] (node %d, %s) = %g is not a finite number", vec, ui,
                            node, component_names[c], in[i]);
        if (no_amplitudes && c >= WFF_DA1 && in[i] != 0)
            return wff_fail(err, "%s[%d] (node %d, %s) = %g: cell '%s' has no amplitudes (must "
                            "be 0)", vec, ui, node, component_names[c], in[i], wff_cell_name(m->mat.cell));
        if (!w)
            continue;
        if (m->dof_kind[i] == WFF_DOF_FIXED && in[i] != 0)
            return wff_fail(err, "v[%d] (node %d, %s) = %g: the DOF is fixed (its velocity "
                            "must be 0)", ui, node, component_names[c], in[i]);
        if (m->dof_kind[i] == WFF_DOF_PRESCRIBED && in[i] != m->v_prescribed[i])
            return wff_fail(err, "v[%d] (node %d, %s) = %g: the DOF moves at its prescribed "
                            "velocity %g m/s", ui, node, component_names[c], in[i],
                            m->v_prescribed[i]);
    }
    return 0;
}

/* Forces, stored energy and reactions at the current u, γᶠ held, no time;
 * -1 naming the element if one is degenerate or not finite. */
static int forces_now(wff_model *m, wff_error *err)
{
    wff_force_totals t;
    memset(m->f, 0, sizeof(double) * (size_t)m->n_dofs);
    wff_zones_forces(m, m->u, m->state, 0, m->f, &t);
    if (t.bad_element >= 0) {
        char name[96];
        wff_model_element_name(m, t.bad_element, name, sizeof name);
        return wff_fail(err, "the state set makes %s %s", name,
                        t.bad_status == WFF_POINT_DEGENERATE
                            ? "degenerate (yarns collapsed or parallel: inverted element)"
                        : t.bad_status == WFF_POINT_UNBALANCED
                            ? "leave its static amplitudes unbalanced (Newton did not converge)"
                            : "give a non-finite stress or energy");
    }
    m->internal_energy = t.internal_energy;
    for (int i = 0; i < m->n_dofs; i++)
        if (m->dof_kind[i] != WFF_DOF_FREE)
            m->reaction[i] = -m->f[i];
    return 0;
}

static int set_vector_model(wff_model *m, int w, const double *in, wff_error *err);

int wff_model_set_vector(wff_model *m, const char *which, const double *user_in,
                         wff_error *err)
{
    int w = which_vector(which, err);
    if (w < 0)
        return -1;
    double *in = malloc(sizeof(double) * (size_t)m->n_dofs + 1); /* the model's order */
    if (!in)
        return wff_fail(err, "out of memory");
    wff_model_nodes_from_user(m, user_in, in, D);
    int rc = set_vector_model(m, w, in, err);
    free(in);
    return rc;
}

static int set_vector_model(wff_model *m, int w, const double *in, wff_error *err)
{
    if (check_vector(m, w, in, err))
        return -1;
    size_t bytes = sizeof(double) * (size_t)m->n_dofs;
    double k0, e0, k1, e1, s0, s1;
    state_energy(m, &k0, &e0, &s0);
    if (w) {
        memcpy(m->v, in, bytes);
    } else {
        /* static amplitudes: the points' own dA are state the force pass updates */
        size_t n_point_dA = m->el.point_dA ? 2 * (size_t)(WFF_TRI_POINTS * m->el.n_tris +
                                                          WFF_QUAD_POINTS * m->el.n_quads) : 0;
        double *saved = malloc(3 * bytes + n_point_dA * sizeof(double) + 1);
        if (!saved)
            return wff_fail(err, "out of memory");
        double *saved_dA = saved + 3 * (size_t)m->n_dofs;
        memcpy(saved, m->u, bytes);
        memcpy(saved + m->n_dofs, m->f, bytes);
        memcpy(saved + 2 * (size_t)m->n_dofs, m->reaction, bytes);
        if (n_point_dA)
            memcpy(saved_dA, m->el.point_dA, n_point_dA * sizeof(double));
        double saved_energy = m->internal_energy;
        memcpy(m->u, in, bytes);
        if (forces_now(m, err)) { /* back to the state as it was */
            memcpy(m->u, saved, bytes);
            memcpy(m->f, saved + m->n_dofs, bytes);
            memcpy(m->reaction, saved + 2 * (size_t)m->n_dofs, bytes);
            if (n_point_dA)
                memcpy(m->el.point_dA, saved_dA, n_point_dA * sizeof(double));
            m->internal_energy = saved_energy;
            free(saved);
            return -1;
        }
        free(saved);
    }
    state_energy(m, &k1, &e1, &s1);
    if (m->v_half_valid) { /* after steps: the set moves the balance's reference */
        m->initial_kinetic += k1 - k0;
        m->initial_total += (k1 - k0) + (e1 - e0);
        m->stagger_reference += s1 - s0;
    }
    return 0;
}

int wff_model_amplitude(const wff_model *m, int k, double *out, wff_error *err)
{
    const wff_cell_type *cell = m->mat.cell;
    if (k < 0 || k > 1)
        return wff_fail(err, "amplitude %d: must be 1 or 2", k + 1);
    if (!wff_cell_has_reference_geometry(cell) || wff_cell_amplitudes(cell) == 0)
        return wff_fail(err, "A%d: cell '%s' has no reference crimp amplitude A%d0 (no "
                        "reference_geometry)", k + 1, wff_cell_name(cell), k + 1);
    double pitch0[2], amplitude0[2];
    wff_cell_reference_geometry(&m->mat, pitch0, amplitude0);
    for (int n = 0; n < m->n_nodes; n++)
        out[wff_model_user_node(m, n)] = amplitude0[k] + m->u[D * n + WFF_DA1 + k];
    return 0;
}

static unsigned long long hash_bytes(unsigned long long h, const void *data, size_t size)
{
    const unsigned char *b = data;
    for (size_t i = 0; i < size; i++) {
        h ^= b[i];
        h *= 1099511628211ULL; /* (FNV-1a, 64 bits) */
    }
    return h;
}

unsigned long long wff_model_state_hash(const wff_model *m)
{
    unsigned long long h = 14695981039346656037ULL;
    const double scalars[] = {m->time, (double)m->step, m->dt, m->projectile.tip,
                              m->projectile.velocity, m->projectile.force,
                              m->projectile.impulse_total, m->internal_energy,
                              m->dissipated_shear, m->dissipated_friction,
                              m->dissipated_failure, m->dissipated_slip, m->eroded_energy,
                              m->external_work,
                              (double)m->n_eroded};
    h = hash_bytes(h, scalars, sizeof scalars);
    const size_t dofs = sizeof(double) * (size_t)m->n_dofs;
    h = hash_bytes(h, m->u, dofs);
    h = hash_bytes(h, m->v, dofs);
    h = hash_bytes(h, m->f, dofs);
    const int n_el = m->el.n_tris + m->el.n_quads;
    h = hash_bytes(h, m->state, sizeof(double) * (size_t)m->n_state *
                                    wff_element_first_point(m->el.n_tris, n_el));
    if (m->em.static_amplitudes && m->el.point_dA) /* (the points' own amplitudes: state) */
        h = hash_bytes(h, m->el.point_dA, sizeof(double) * 2 *
                                              wff_element_first_point(m->el.n_tris, n_el));
    if (m->el.eroded)
        h = hash_bytes(h, m->el.eroded, (size_t)n_el);
    /* the parts' own fields, as a checkpoint saves them (a pack's accounts, a backing
     * block's nodes, points and account; a block not yet built is built, as a
     * checkpoint would) */
    wff_state_field parts[WFF_STATE_FIELDS_MAX];
    const int n_parts = wff_parts_state_fields((wff_model *)m, parts);
    for (int i = 0; i < n_parts; i++)
        h = hash_bytes(h, parts[i].data, parts[i].size * parts[i].count);
    return h;
}

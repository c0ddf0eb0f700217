/* state_fields.c: the model's evolving state as a list of fields (the
 * checkpoint's file order, plugin/checkpoint.c) and the adaptive step's two
 * snapshots of it in memory (plugin/integrator.c). Knows the model's arrays;
 * nothing of how they evolve. */
#include "state_fields.h"
#include "part.h"

#include <stdlib.h>
#include <string.h>

static size_t n_points(const wff_model *m)
{
    return wff_elements_point_count(&m->el);
}

int wff_state_fields(wff_model *m, int n_candidates, wff_state_field *f)
{
    wff_projectile *p = &m->projectile;
    int k = 0;
#define FIELD(ptr, n) f[k++] = (wff_state_field){(void *)(ptr), sizeof *(ptr), (size_t)(n)}
    FIELD(&m->time, 1);
    FIELD(&m->dt, 1);
    FIELD(&m->dt_stable, 1);
    FIELD(&m->dt_travel, 1);
    FIELD(&m->travel_share, 1);
    FIELD(&m->travel_steps, 1);
    FIELD(&m->step, 1);
    FIELD(&m->dt_worst_element, 1);
    FIELD(&m->internal_energy, 1);
    FIELD(&m->dissipated_shear, 1);
    FIELD(&m->dissipated_friction, 1);
    FIELD(&m->dissipated_failure, 1);
    FIELD(&m->dissipated_slip, 1);
    FIELD(&m->eroded_energy, 1);
    FIELD(&m->n_eroded, 1);
    FIELD(&m->external_work, 1);
    FIELD(&m->initial_total, 1);
    FIELD(&m->initial_kinetic, 1);
    FIELD(&m->stagger_reference, 1);
    FIELD(&m->stagger_shift, 1);
    FIELD(&m->dt_mid, 1);
    FIELD(&m->v_half_valid, 1);
    FIELD(&m->element_steps, 1);
    FIELD(&m->blowup_steps, 1);
    FIELD(&m->last_error, 1);
    FIELD(&p->tip, 1);
    FIELD(&p->velocity, 1);
    FIELD(p->axis, 2);
    FIELD(&p->max_penetration, 1);
    FIELD(&p->force, 1);
    FIELD(&p->impulse_total, 1);
    FIELD(&p->n_candidates, 1);
    FIELD(p->candidates, n_candidates);
    FIELD(m->u, m->n_dofs);
    FIELD(m->v, m->n_dofs);
    FIELD(m->f, m->n_dofs);
    FIELD(m->contact_force, m->n_dofs);
    FIELD(m->reaction, m->n_dofs);
    FIELD(m->v_prescribed, m->n_dofs);
    FIELD(m->state, n_points(m) * (size_t)m->n_state); /* every point's every state */
    if (m->em.static_amplitudes) /* the points' own amplitudes */
        FIELD(m->el.point_dA, 2 * n_points(m));
    if (m->el.eroded) /* erosion on: every element's flag */
        FIELD(m->el.eroded, m->el.n_tris + m->el.n_quads);
#undef FIELD
    return k + wff_parts_state_fields(m, f + k); /* the parts' own (a pack's accounts) */
}
/* The adaptive step's snapshots: the state fields, the contact candidates at
 * their capacity. */
static int snapshot_fields(wff_model *m, wff_state_field *f)
{
    return wff_state_fields(m, m->projectile.candidates ? m->n_nodes : 0, f);
}

int wff_model_snapshot(wff_model *m, wff_error *err)
{
    wff_state_field fields[WFF_STATE_FIELDS_MAX];
    int nf = snapshot_fields(m, fields);
    size_t bytes = 0;
    for (int i = 0; i < nf; i++)
        bytes += fields[i].size * fields[i].count;
    const int k = m->snapshot_step[m->snapshot_newest] < 0 ? m->snapshot_newest
                                                            : 1 - m->snapshot_newest;
    if (bytes != m->snapshot_size[k]) {
        free(m->snapshot[k]);
        m->snapshot_size[k] = 0;
        m->snapshot_step[k] = -1;
        if (!(m->snapshot[k] = malloc(bytes)))
            return wff_fail(err, "adaptive step: out of memory for the last good state "
                            "(%zu bytes)", bytes);
        m->snapshot_size[k] = bytes;
    }
    char *at = m->snapshot[k];
    for (int i = 0; i < nf; i++) {
        size_t n = fields[i].size * fields[i].count;
        if (n)
            memcpy(at, fields[i].data, n);
        at += n;
    }
    m->snapshot_step[k] = m->step;
    m->snapshot_newest = k;
    m->cut_since_snapshot = 0;
    return 0;
}

int wff_model_restore(wff_model *m)
{
    /* a second cut before a new state was kept: the newer one was not good */
    int k = m->snapshot_newest;
    if (m->cut_since_snapshot && m->snapshot_step[1 - k] >= 0) {
        m->snapshot_step[k] = -1;
        k = m->snapshot_newest = 1 - k;
    }
    if (m->snapshot_step[k] < 0)
        return -1;
    wff_state_field fields[WFF_STATE_FIELDS_MAX];
    int nf = snapshot_fields(m, fields);
    const char *at = m->snapshot[k];
    for (int i = 0; i < nf; i++) {
        size_t n = fields[i].size * fields[i].count;
        if (n)
            memcpy(fields[i].data, at, n);
        at += n;
    }
    m->cut_since_snapshot = 1;
    return 0;
}

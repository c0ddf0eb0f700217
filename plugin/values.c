/* values.c: a model's state quantities by name (wff_model_value and
 * wff_model_values, solver.h): what wovenffGet, wovenffState and every
 * summary.json read. The model's own quantities first, then each part's
 * (part.h: its value_names and value op, in the list's order), so the names
 * and their order are given once, here and in the parts. Every mass, force and
 * energy is the whole specimen's. */
#include "part.h"
#include "wovenff/renumber.h"

#include <string.h>

/* The model's own quantities; `energy`: computed by wff_model_energies (a
 * pass over the nodes). */
typedef struct own_value {
    const char *name;
    int energy;
} own_value;

static const own_value own_values[] = {
    {"time", 0},              {"step", 0},
    {"dt", 0},                {"dt_stable", 0},
    {"projectile_tip", 0},    {"projectile_velocity", 0},
    {"projectile_force", 0},  {"max_penetration", 0},
    {"kinetic_inplane", 1},   {"kinetic_transverse", 1},
    {"kinetic_amplitude", 1}, {"kinetic_projectile", 1},
    {"internal_energy", 1},   {"dissipated_shear", 1},
    {"dissipated_friction", 1}, {"external_work", 1},
    {"energy_error", 1},      {"element_steps", 0},
    {"elements", 0},          {"nodes", 0},
    {"dt_worst_element", 0},  {"transfer_energy", 1},
    {"projectile_impulse", 0}, {"dissipated_failure", 1},
    {"eroded_energy", 1},     {"eroded_elements", 0},
    {"failure_energy", 1},    {"travel_steps", 0},
    {"step_cuts", 0},         {"dtfactor", 0},
    {"kinetic_stagger", 1},   {"stagger_shift", 1},
    {"impulse_stagger", 1}, {"dissipated_slip", 1},
    {"yarn_slip", 0},
};
#define N_OWN ((int)(sizeof own_values / sizeof own_values[0]))

/* 1 when the model's points carry yarn slip states (slip_1: docs/model.md §24), else 0. */
static double has_slip(const wff_model *m)
{
    for (int j = 0; j < m->n_state; j++)
        if (strcmp(wff_model_state_name(m, j), "slip_1") == 0)
            return 1;
    return 0;
}

/* The model's own quantities in own_values' order (the energies only when
 * with_energies, else 0). */
static void own(const wff_model *m, int with_energies, double *out)
{
    wff_energies e;
    memset(&e, 0, sizeof e);
    if (with_energies)
        wff_model_energies(m, &e);
    const double s = m->symmetry_factor;
    const double v[N_OWN] = {
        m->time, (double)m->step, m->dt, m->dt_stable, m->projectile.tip,
        m->projectile.velocity, s * m->projectile.force, m->projectile.max_penetration,
        e.kinetic_inplane, e.kinetic_transverse, e.kinetic_amplitude, e.kinetic_projectile,
        e.internal, e.dissipated_shear, e.dissipated_friction, e.external_work, e.error,
        (double)m->element_steps, (double)(m->el.n_tris + m->el.n_quads), (double)m->n_nodes,
        (double)(wff_model_user_element(m, m->dt_worst_element) + 1), e.transfer,
        s * m->projectile.impulse_total, e.dissipated_failure, e.eroded, (double)m->n_eroded,
        e.dissipated_failure, (double)m->travel_steps, (double)m->step_cuts, m->dt_factor,
        e.kinetic_stagger, s * m->stagger_shift, e.impulse_stagger, e.dissipated_slip,
        has_slip(m)};
    memcpy(out, v, sizeof v);
}

/* Calls visit(name, part, index) for every quantity in order: the model's
 * own (part NULL), then each part's. */
#define EACH_PART_VALUE(ops, k)                                                   \
    for (const wff_part_ops *const *ops = wff_parts; *ops; ops++)                \
        for (int k = 0; (*ops)->value_names && (*ops)->value_names[k]; k++)

int wff_model_value_count(void)
{
    int n = N_OWN;
    EACH_PART_VALUE(p, k)
        n++;
    return n;
}

const char *wff_model_value_name(int index)
{
    if (index < 0)
        return NULL;
    if (index < N_OWN)
        return own_values[index].name;
    int i = N_OWN;
    EACH_PART_VALUE(p, k)
        if (i++ == index)
            return (*p)->value_names[k];
    return NULL;
}

void wff_model_values(const wff_model *m, int with_energies, int with_parts, double *out)
{
    own(m, with_energies, out);
    int i = N_OWN;
    EACH_PART_VALUE(p, k) {
        double v = 0;
        if (with_parts)
            (*p)->value(m, (*p)->value_names[k], &v);
        out[i++] = v;
    }
}

int wff_model_value(const wff_model *m, const char *key, double *value, wff_error *err)
{
    for (int i = 0; i < N_OWN; i++)
        if (strcmp(key, own_values[i].name) == 0) {
            double v[N_OWN];
            own(m, own_values[i].energy, v);
            *value = v[i];
            return 0;
        }
    EACH_PART_VALUE(p, k)
        if (strcmp(key, (*p)->value_names[k]) == 0) { /* (that one alone) */
            (*p)->value(m, key, value);
            return 0;
        }
    return wff_fail(err, "unknown state quantity '%s'", key); /* (wff_model_value_name
                                                                    lists the known) */
}

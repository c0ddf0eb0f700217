/* zones_model.c: the model's masses, stored energy and element lengths from
 * its element sets (zones.c): what the model, a pack's build and a mesh
 * transfer ask once the elements' materials are known (zones.h). */
#include "zones.h"
#include "clamp.h"

#include <string.h>

void wff_model_sum_fabric_mass(wff_model *m)
{
    m->fabric_mass = 0;
    for (int n = 0; n < m->n_nodes; n++)
        m->fabric_mass += m->mass[D * n];
}

/* Every point whose material carries WFF_ELEMENT_LENGTH_STATE gets its
 * element's band length (the material looked up again only where it changes). */
void wff_model_set_element_lengths(wff_model *m)
{
    const int nt = m->el.n_tris, n_el = nt + m->el.n_quads, ns = m->n_state;
    const wff_material *last = NULL;
    int slot = -1;
    for (int e = 0; e < n_el; e++) {
        wff_element_material scratch;
        const wff_material *mat = wff_zones_element_material(m, e, &scratch)->mat;
        if (mat != last)
            slot = wff_material_state_index(mat, WFF_ELEMENT_LENGTH_STATE), last = mat;
        if (slot < 0)
            continue;
        const int np = e < nt ? WFF_TRI_POINTS : WFF_QUAD_POINTS;
        const double h = wff_element_band_length(&m->el, e);
        double *state = m->state + (size_t)ns * wff_element_first_point(nt, e);
        for (int q = 0; q < np; q++)
            state[ns * q + slot] = h;
    }
}

/* Before the first step: the stored energy of the state as set up (e.g. the
 * preload), so that energies read before any step are complete. A force pass
 * with the state held; its forces are recomputed when the run starts, and a bad
 * element is reported then. */
void wff_model_stored_energy_now(wff_model *m)
{
    if (m->v_half_valid || m->step > 0)
        return;
    wff_force_totals t;
    memset(m->f, 0, sizeof(double) * (size_t)m->n_dofs);
    wff_zones_forces(m, m->u, m->state, 0, m->f, &t);
    m->internal_energy = t.bad_element >= 0 ? 0 : t.internal_energy;
}

/* The masses changed with a zone's material or preload (zones.h). */
int wff_model_masses_changed(wff_model *m, wff_error *err)
{
    wff_zones_masses(m);
    wff_model_sum_fabric_mass(m);
    if (m->clamp.n && wff_clamp_share(m, err))
        return -1;
    wff_model_stored_energy_now(m);
    return 0;
}


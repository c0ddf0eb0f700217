/* zones_model.c: the model's masses, stored energy and element lengths from
 * its element sets (zones.c): what the model, a pack's build and a mesh
 * transfer ask once the elements' materials are known (zones.h); and the
 * model's zone calls (wff_model_zone_region, _disc, _elements), which give
 * elements a zone (zones.c) and then set the model's masses and element
 * lengths again. */
#include "zones.h"
#include "clamp.h"
#include "wovenff/mesh.h"

#include <math.h>
#include <stdlib.h>
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


/* Elements selected (the model's order) into a zone (wff_zones_select), then
 * the model follows: its masses, and the element lengths the zone's material
 * may carry. Returns the zone's element count or -1 (err set). */
static int zone_then_model(wff_model *m, const unsigned char *selected,
                           const char *material_path, int preload, wff_error *err)
{
    const int n = wff_zones_select(m, selected, material_path, preload, err);
    if (n < 0 || wff_model_masses_changed(m, err))
        return -1;
    wff_model_set_element_lengths(m);
    return n;
}

int wff_model_zone_region(wff_model *m, const char *group, int group_tag,
                          const char *material_path, int preload, wff_error *err)
{
    int tag = group_tag;
    if (group && group[0]) {
        tag = wff_mesh_group_tag(&m->mesh, 2, group);
        if (tag < 0)
            return wff_fail(err, "zone material '%s': no physical surface named '%s' in the "
                            "mesh", material_path, group);
    }
    int nt = m->el.n_tris, n_el = nt + m->el.n_quads, count = 0;
    unsigned char *sel = calloc((size_t)(n_el ? n_el : 1), 1);
    if (!sel)
        return wff_fail(err, "out of memory");
    for (int e = 0; e < n_el; e++) {
        int region = e < nt ? m->mesh.tri_region[e] : m->mesh.quad_region[e - nt];
        sel[e] = region == tag;
        count += sel[e];
    }
    if (count == 0) {
        free(sel);
        return wff_fail(err, "zone material '%s': no element in region %d%s%s", material_path,
                        tag, group && group[0] ? " " : "", group && group[0] ? group : "");
    }
    int n = zone_then_model(m, sel, material_path, preload, err);
    free(sel);
    return n;
}

int wff_model_zone_disc(wff_model *m, double x, double y, double radius, int outside,
                        const char *material_path, int preload, wff_error *err)
{
    if (!(radius >= 0) || !isfinite(radius) || !isfinite(x) || !isfinite(y))
        return wff_fail(err, "zone material '%s': disc centre (%g, %g) m, radius %g m: must "
                        "be finite, radius >= 0", material_path, x, y, radius);
    int nt = m->el.n_tris, n_el = nt + m->el.n_quads;
    unsigned char *sel = calloc((size_t)(n_el ? n_el : 1), 1);
    if (!sel)
        return wff_fail(err, "out of memory");
    for (int e = 0; e < n_el; e++) {
        int nn = e < nt ? 3 : 4;
        const int *node = e < nt ? m->mesh.tri + 3 * e : m->mesh.quad + 4 * (e - nt);
        double cx = 0, cy = 0;
        for (int a = 0; a < nn; a++) {
            cx += m->mesh.xy[2 * node[a]] / nn;
            cy += m->mesh.xy[2 * node[a] + 1] / nn;
        }
        int beyond = hypot(cx - x, cy - y) > radius;
        sel[e] = outside ? beyond : !beyond;
    }
    int n = zone_then_model(m, sel, material_path, preload, err);
    free(sel);
    return n;
}

int wff_model_zone_elements(wff_model *m, const unsigned char *selected,
                            const char *material_path, int preload, wff_error *err)
{
    if (!m->element_user) /* the caller's order is the model's */
        return zone_then_model(m, selected, material_path, preload, err);
    int n_el = m->el.n_tris + m->el.n_quads;
    unsigned char *sel = malloc((size_t)(n_el ? n_el : 1));
    if (!sel)
        return wff_fail(err, "out of memory");
    for (int e = 0; e < n_el; e++) /* model element e is the caller's element_user[e] */
        sel[e] = selected[m->element_user[e]];
    int n = zone_then_model(m, sel, material_path, preload, err);
    free(sel);
    return n;
}

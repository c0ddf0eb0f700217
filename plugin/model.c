/* model.c: a model's set-up and settings: create and free, the preload,
 * the mesh's named groups, fixed and prescribed DOFs, the friction clamp's
 * nodes and forces (docs/model.md §15), reactions, solver settings by name
 * and the nearest node. Knows the mesh, the material and the elements;
 * nothing of how a step is taken (integrator.c), of contact (contact.c),
 * of output fields or checkpoints, of cells by name or of FreeFEM. */
#include "solver_internal.h"
#include "erosion.h"
#include "zones.h"
#include "pack.h"
#include "wovenff/material.h"
#include "wovenff/kernel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* zones.h: every point whose material carries WFF_ELEMENT_LENGTH_STATE gets its
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

void wff_model_free(wff_model *m)
{
    free(m->u);
    free(m->v);
    free(m->f);
    free(m->mass);
    free(m->dof_kind);
    free(m->v_prescribed);
    free(m->state);
    free(m->reaction);
    free(m->projectile.candidates);
    free(m->projectile.contact_node);
    free(m->projectile.impulse);
    free(m->clamp.node);
    free(m->clamp.normal_force);
    free(m->operator_scratch);
    free(m->bc);
    wff_pack_free(m);
    wff_zones_free(m);
    wff_model_order_free(m);
    wff_elements_free(&m->el);
    wff_mesh_free(&m->mesh);
    memset(m, 0, sizeof *m);
}

int wff_model_create(wff_model *m, const char *mesh_path, const wff_mesh_options *mesh_options,
                     const char *material_path, wff_error *err)
{
    wff_mesh mesh;
    if (wff_mesh_load(mesh_path, mesh_options, &mesh, err))
        return -1;
    if (wff_model_create_ordered(m, &mesh, material_path, 1, err)) {
        char why[WFF_ERROR_MAX];
        snprintf(why, sizeof why, "%s", err->message);
        return wff_fail(err, "%s: %s", mesh_path, why);
    }
    return 0;
}

static void sum_fabric_mass(wff_model *m)
{
    m->fabric_mass = 0;
    for (int n = 0; n < m->n_nodes; n++)
        m->fabric_mass += m->mass[D * n];
}

static void set_dof(wff_model *m, int node, void *data);
static int share_clamp_force(wff_model *m, wff_error *err);

/* Before the first step: the stored energy of the state as set up (e.g. the
 * preload), so that energies read before any step are complete. A force pass
 * with the state held; its forces are recomputed when the run starts, and a bad
 * element is reported then. */
static void stored_energy_now(wff_model *m)
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
    sum_fabric_mass(m);
    if (m->clamp.n && share_clamp_force(m, err))
        return -1;
    stored_energy_now(m);
    return 0;
}

int wff_model_create_from_mesh(wff_model *m, wff_mesh *mesh, const char *material_path,
                               wff_error *err)
{
    return wff_model_create_ordered(m, mesh, material_path, 0, err);
}

int wff_model_create_ordered(wff_model *m, wff_mesh *mesh, const char *material_path,
                             int renumber, wff_error *err)
{
    memset(m, 0, sizeof *m);
    m->mesh = *mesh;
    memset(mesh, 0, sizeof *mesh);
    if (wff_mesh_check(&m->mesh, 1, "mesh", err)) {
        wff_mesh_free(&m->mesh);
        return -1;
    }
    /* the kernel variant: WOVENFF_KERNEL, read once here (kernel.h) */
    if (wff_material_load(material_path, &m->mat, err) || wff_kernel_apply(&m->mat, NULL, err)) {
        wff_mesh_free(&m->mesh);
        return -1;
    }
    if (wff_elements_init(&m->el, m->mesh.xy, m->mesh.n_tris, m->mesh.tri, m->mesh.n_quads,
                          m->mesh.quad, err)) {
        wff_mesh_free(&m->mesh);
        return -1;
    }
    if (renumber) { /* (the elements checked above in the caller's numbering) */
        wff_elements_free(&m->el);
        if (wff_model_renumber(m, err) ||
            wff_elements_init(&m->el, m->mesh.xy, m->mesh.n_tris, m->mesh.tri,
                              m->mesh.n_quads, m->mesh.quad, err)) {
            wff_model_order_free(m);
            wff_mesh_free(&m->mesh);
            return -1;
        }
    }
    return wff_model_setup(m, err);
}

int wff_model_setup(wff_model *m, wff_error *err)
{
    m->n_nodes = m->mesh.n_nodes;
    m->n_dofs = D * m->n_nodes;
    size_t nd = (size_t)m->n_dofs;
    size_t nq = wff_elements_point_count(&m->el);
    m->u = calloc(nd, sizeof(double));
    m->v = calloc(nd, sizeof(double));
    m->f = calloc(nd, sizeof(double));
    m->mass = calloc(nd, sizeof(double));
    m->dof_kind = calloc(nd, 1);
    m->v_prescribed = calloc(nd, sizeof(double));
    m->reaction = calloc(nd, sizeof(double));
    m->n_state = m->mat.n_state;
    size_t ns = nq * (size_t)m->n_state;
    m->state = calloc(ns ? ns : 1, sizeof(double)); /* every state starts at 0 */
    if (!m->u || !m->v || !m->f || !m->mass || !m->dof_kind || !m->v_prescribed ||
        !m->reaction || !m->state) {
        wff_model_free(m);
        return wff_fail(err, "out of memory for a model of %d nodes", m->n_nodes);
    }
    m->em.mat = &m->mat;
    m->em.F_pre[0] = m->em.F_pre[3] = 1;
    m->em.J_pre = 1;
    m->preload[0] = m->preload[3] = 1;
    wff_elements_masses(&m->el, &m->em, m->n_nodes, m->mass);
    sum_fabric_mass(m);
    /* amplitude DOFs of a cell without amplitudes stay put */
    if (wff_cell_amplitudes(m->mat.cell) == 0)
        for (int n = 0; n < m->n_nodes; n++)
            m->dof_kind[D * n + 3] = m->dof_kind[D * n + 4] = WFF_DOF_FIXED;
    m->dt_factor = 0.8;
    m->dt_interval = 20;
    m->symmetry_factor = 1;
    if (wff_erosion_default(m, err)) { /* erosion on (both families) when the points carry damage */
        wff_model_free(m);
        return -1;
    }
    wff_model_set_element_lengths(m); /* a state the element code sets (cell.h) */
    stored_energy_now(m);
    return 0;
}

int wff_model_set_preload(wff_model *m, const double F_pre[4], const double dA0[2],
                          wff_error *err)
{
    if (m->step > 0 || m->v_half_valid)
        return wff_fail(err, "preload: the run has started (t = %g s, step %ld); a preload is "
                        "the initial state: set it before the first step", m->time, m->step);
    double det = F_pre[0] * F_pre[3] - F_pre[1] * F_pre[2];
    if (!(det > 0))
        return wff_fail(err, "preload F_pre = [%g %g; %g %g] has det %g: must be > 0", F_pre[0],
                        F_pre[1], F_pre[2], F_pre[3], det);
    memcpy(m->preload, F_pre, 4 * sizeof(double));
    wff_orientation_map(m->em.orientation, m->preload, m->em.F_pre); /* (θ = 0: a copy) */
    m->em.J_pre = det;
    wff_elements_masses(&m->el, &m->em, m->n_nodes, m->mass);
    sum_fabric_mass(m);
    if (m->clamp.n && share_clamp_force(m, err)) /* the new masses: order of calls free */
        return -1;
    if (wff_cell_amplitudes(m->mat.cell))
        for (int n = 0; n < m->n_nodes; n++) {
            m->u[D * n + 3] = dA0[0];
            m->u[D * n + 4] = dA0[1];
        }
    if (m->zones && wff_zones_preload_changed(m, err)) /* matched zone preloads follow */
        return -1;
    stored_energy_now(m);
    return 0;
}

int wff_model_set_orientation(wff_model *m, double theta, wff_error *err)
{
    if (!isfinite(theta))
        return wff_fail(err, "orientation = %g rad: must be a finite angle", theta);
    if ((m->step > 0 || m->v_half_valid) && theta != m->em.orientation)
        return wff_fail(err, "orientation = %g deg: the run has started (t = %g s, step %ld) "
                        "at %g deg; the warp direction is part of the initial state: set it "
                        "before the first step", theta * 180 / M_PI, m->time, m->step,
                        m->em.orientation * 180 / M_PI);
    m->em.orientation = theta;
    wff_pack_orientation_all(m, theta); /* every ply of a pack */
    /* the map the kernels apply (det unchanged: J_pre, the masses and a zone's
     * matched preload, a material-frame state, stay) */
    wff_orientation_map(theta, m->preload, m->em.F_pre);
    stored_energy_now(m);
    return 0;
}

/* Mark the nodes of a named group; calls visit(m, node, data) once per node. */
static int for_group_nodes(wff_model *m, const char *group, wff_error *err,
                           void (*visit)(wff_model *, int, void *), void *data)
{
    int tag1 = wff_mesh_group_tag(&m->mesh, 1, group);
    int tag2 = wff_mesh_group_tag(&m->mesh, 2, group);
    if (tag1 < 0 && tag2 < 0) {
        char names[256] = "";
        for (int g = 0; g < m->mesh.n_groups; g++) {
            size_t used = strlen(names);
            snprintf(names + used, sizeof names - used, "%s%s", g ? ", " : "",
                     m->mesh.groups[g].name);
        }
        return wff_fail(err, "no physical group named '%s' in the mesh (groups: %s)", group,
                        names[0] ? names : "none");
    }
    unsigned char *seen = calloc((size_t)m->n_nodes, 1);
    if (!seen)
        return wff_fail(err, "out of memory");
    if (tag1 >= 0)
        for (int e = 0; e < m->mesh.n_edges; e++)
            if (m->mesh.edge_label[e] == tag1)
                seen[m->mesh.edge[2 * e]] = seen[m->mesh.edge[2 * e + 1]] = 1;
    if (tag2 >= 0) {
        for (int e = 0; e < m->mesh.n_tris; e++)
            if (m->mesh.tri_region[e] == tag2)
                for (int a = 0; a < 3; a++)
                    seen[m->mesh.tri[3 * e + a]] = 1;
        for (int e = 0; e < m->mesh.n_quads; e++)
            if (m->mesh.quad_region[e] == tag2)
                for (int a = 0; a < 4; a++)
                    seen[m->mesh.quad[4 * e + a]] = 1;
    }
    int count = 0;
    for (int k = 0; k < m->n_nodes; k++) { /* in the user's order (clamp lists, errors) */
        int n = wff_model_node_of_user(m, k);
        if (seen[n]) {
            visit(m, n, data);
            count++;
        }
    }
    free(seen);
    if (count == 0)
        return wff_fail(err, "physical group '%s' has no nodes", group);
    return count;
}

typedef struct dof_setting { int component, kind; double velocity; int conflict; } dof_setting;

/* The first node (conflict, from 0; -1: none) whose DOF is already of the
 * other kind (fixed against prescribed). */
static void check_dof(wff_model *m, int node, void *data)
{
    dof_setting *s = data;
    int kind = m->dof_kind[D * node + s->component];
    if (s->conflict < 0 && kind != WFF_DOF_FREE && kind != s->kind)
        s->conflict = node;
}

static const char *const dof_names[] = {"ux", "uy", "uz", "dA1", "dA2"};

/* Apply s to the group's nodes unless one of them has that DOF of the other
 * kind already (an error naming it: nothing changed). */
static int set_group_dofs(wff_model *m, const char *group, dof_setting *s, const char *what,
                          wff_error *err)
{
    s->conflict = -1;
    if (for_group_nodes(m, group, err, check_dof, s) < 0)
        return -1;
    if (s->conflict >= 0) {
        int n = s->conflict;
        const char *was = s->kind == WFF_DOF_FIXED ? "prescribed" : "fixed";
        return wff_fail(err, "%s '%s' %s: node %d at (%g, %g) m has %s %s already (a DOF is "
                        "free, fixed or prescribed, once)%s", what, group,
                        dof_names[s->component], wff_model_user_node(m, n) + 1, m->mesh.xy[2 * n],
                        m->mesh.xy[2 * n + 1], dof_names[s->component], was,
                        s->component >= 3 && wff_cell_amplitudes(m->mat.cell) == 0
                            ? " (the cell has no amplitudes: they are fixed)"
                        : s->component == WFF_UZ && m->clamp.n
                            ? " (a friction clamp fixes u_z of its nodes)" : "");
    }
    return for_group_nodes(m, group, err, set_dof, s);
}

static void set_dof(wff_model *m, int node, void *data)
{
    const dof_setting *s = data;
    int i = D * node + s->component;
    m->dof_kind[i] = (unsigned char)s->kind;
    m->v_prescribed[i] = s->velocity;
    m->v[i] = s->kind == WFF_DOF_PRESCRIBED ? s->velocity : 0;
}

static int check_component(int component, wff_error *err)
{
    if (component < 0 || component >= D)
        return wff_fail(err, "DOF component %d: must be 0..4 (ux uy uz dA1 dA2)", component);
    return 0;
}

int wff_model_fix_group(wff_model *m, const char *group, int component, wff_error *err)
{
    if (check_component(component, err))
        return -1;
    dof_setting s = {component, WFF_DOF_FIXED, 0, -1};
    int count = set_group_dofs(m, group, &s, "fix", err);
    if (count > 0 && wff_model_log_bc(m, WFF_DOF_FIXED, group, component, 0, 0, err))
        return -1;
    return count;
}

int wff_model_prescribe_group(wff_model *m, const char *group, int component, double velocity,
                              wff_error *err)
{
    if (check_component(component, err))
        return -1;
    if (!isfinite(velocity))
        return wff_fail(err, "prescribed velocity of '%s' is not finite", group);
    dof_setting s = {component, WFF_DOF_PRESCRIBED, velocity, -1};
    int count = set_group_dofs(m, group, &s, "prescribe", err);
    if (count > 0 && wff_model_log_bc(m, WFF_DOF_PRESCRIBED, group, component, velocity, 0, err))
        return -1;
    return count;
}

static void add_clamp_node(wff_model *m, int node, void *data)
{
    (void)data;
    m->clamp.node[m->clamp.n++] = node;
    m->dof_kind[D * node + WFF_UZ] = WFF_DOF_FIXED; /* pressed flat */
    m->v[D * node + WFF_UZ] = 0;
}

/* The clamping force shared among the clamp's nodes: by the area of the
 * elements of the clamp's surface (a third of a triangle, a quarter of a
 * quadrilateral, at each corner) or, for a curve group, by lumped mass; only
 * nodes within clamp.radius of (0, 0) when it is set. */
static int share_clamp_force(wff_model *m, wff_error *err)
{
    wff_clamp *c = &m->clamp;
    double *share = c->normal_force;
    for (int i = 0; i < c->n; i++)
        share[i] = 0;
    if (c->region >= 0) { /* node area by element, gathered per clamp node below */
        double *area = calloc((size_t)m->n_nodes, sizeof(double));
        if (!area)
            return wff_fail(err, "out of memory");
        const double *xy = m->mesh.xy;
        for (int e = 0; e < m->mesh.n_tris; e++) {
            if (m->mesh.tri_region[e] != c->region)
                continue;
            const int *t = m->mesh.tri + 3 * e;
            const double *p0 = xy + 2 * t[0], *p1 = xy + 2 * t[1], *p2 = xy + 2 * t[2];
            double a = 0.5 * fabs((p1[0] - p0[0]) * (p2[1] - p0[1]) -
                                  (p2[0] - p0[0]) * (p1[1] - p0[1]));
            for (int k = 0; k < 3; k++)
                area[t[k]] += a / 3;
        }
        for (int e = 0; e < m->mesh.n_quads; e++) {
            if (m->mesh.quad_region[e] != c->region)
                continue;
            const int *q = m->mesh.quad + 4 * e;
            double a = 0; /* shoelace */
            for (int k = 0; k < 4; k++) {
                int p = q[k], r = q[(k + 1) % 4];
                a += xy[2 * p] * xy[2 * r + 1] - xy[2 * r] * xy[2 * p + 1];
            }
            for (int k = 0; k < 4; k++)
                area[q[k]] += 0.25 * fabs(0.5 * a);
        }
        for (int i = 0; i < c->n; i++)
            share[i] = area[c->node[i]];
        free(area);
    } else {
        for (int i = 0; i < c->n; i++)
            share[i] = m->mass[D * c->node[i]];
    }
    double total = 0;
    for (int i = 0; i < c->n; i++) {
        const double *p = m->mesh.xy + 2 * c->node[i];
        if (c->radius > 0 && hypot(p[0], p[1]) > c->radius)
            share[i] = 0;
        total += share[i];
    }
    if (!(total > 0))
        return wff_fail(err, "friction clamp: no clamped node within clamp_radius %g m of (0, 0)",
                        c->radius);
    for (int i = 0; i < c->n; i++)
        share[i] *= c->force_whole / m->symmetry_factor / total; /* modelled part */
    return 0;
}

int wff_model_clamp_friction(wff_model *m, const char *group, double normal_force, double mu,
                             wff_error *err)
{
    if (!(normal_force > 0) || !(mu >= 0) || !isfinite(normal_force) || !isfinite(mu))
        return wff_fail(err, "friction clamp '%s': normal force %g N must be > 0 and mu %g >= 0",
                        group, normal_force, mu);
    dof_setting uz = {WFF_UZ, WFF_DOF_FIXED, 0, -1};
    if (for_group_nodes(m, group, err, check_dof, &uz) < 0)
        return -1;
    if (uz.conflict >= 0)
        return wff_fail(err, "friction clamp '%s': node %d has u_z prescribed: the clamp presses "
                        "its nodes flat (u_z fixed)", group,
                        wff_model_user_node(m, uz.conflict) + 1);
    free(m->clamp.node);
    free(m->clamp.normal_force);
    m->clamp.n = 0;
    m->clamp.node = malloc(sizeof(int) * (size_t)m->n_nodes);
    m->clamp.normal_force = malloc(sizeof(double) * (size_t)m->n_nodes);
    if (!m->clamp.node || !m->clamp.normal_force)
        return wff_fail(err, "out of memory");
    int count = for_group_nodes(m, group, err, add_clamp_node, NULL);
    if (count < 0)
        return -1;
    m->clamp.mu = mu;
    m->clamp.force_whole = normal_force;
    m->clamp.region = wff_mesh_group_tag(&m->mesh, 2, group);
    m->clamp.radius = 0;
    m->clamp.edge_reaction = 0;
    if (share_clamp_force(m, err))
        return -1;
    if (wff_model_log_bc(m, WFF_BC_CLAMP, group, 0, normal_force, mu, err))
        return -1;
    return count;
}

typedef struct reaction_sum { const wff_model *m; int component; double sum; } reaction_sum;

static void add_reaction(wff_model *m, int node, void *data)
{
    reaction_sum *r = data;
    r->sum += m->reaction[D * node + r->component];
}

int wff_model_group_reaction(wff_model *m, const char *group, int component, double *sum,
                             wff_error *err)
{
    if (check_component(component, err))
        return -1;
    reaction_sum r = {m, component, 0};
    int n = for_group_nodes(m, group, err, add_reaction, &r);
    *sum = r.sum;
    return n;
}

int wff_model_set_option(wff_model *m, const char *key, double value, wff_error *err)
{
    int rc;
    if (wff_pack_set_option(m, key, value, &rc, err)) /* ply_mu, ply_thickness */
        return rc;
    if (strcmp(key, "dtfactor") == 0) {
        if (!(value > 0 && value <= 2))
            return wff_fail(err, "dtfactor = %g: must be in (0, 2] (1 is the stability limit)",
                            value);
        m->dt_factor = value;
        if (m->dt_stable > 0)
            m->dt = value * m->dt_stable;
    } else if (strcmp(key, "dtinterval") == 0) {
        if (!(value >= 1 && value <= 1e6) || value != floor(value))
            return wff_fail(err, "dtinterval = %g: must be a whole number of steps >= 1", value);
        m->dt_interval = (int)value;
    } else if (strcmp(key, "symmetry") == 0) {
        if (value != 1 && value != 2 && value != 4)
            return wff_fail(err, "symmetry = %g: must be 1 (full), 2 (half) or 4 (quarter)",
                            value);
        if ((m->step > 0 || m->v_half_valid) && value != m->symmetry_factor)
            return wff_fail(err, "symmetry = %g: the run has started (step %ld); set the "
                            "symmetry before the first step", value, m->step);
        double old = m->symmetry_factor;
        m->symmetry_factor = value;
        if (wff_contact_symmetry_changed(m, err)) {
            m->symmetry_factor = old;
            return -1;
        }
        if (m->clamp.n && share_clamp_force(m, err)) {
            wff_error ignored;
            m->symmetry_factor = old;
            wff_contact_symmetry_changed(m, &ignored);
            share_clamp_force(m, &ignored);
            return -1;
        }
    } else if (strcmp(key, "threads") == 0) {
        if (value == 0) /* the default: the cores this process may use */
            value = wff_default_threads() < m->el.max_threads ? wff_default_threads()
                                                              : m->el.max_threads;
        if (value != floor(value) || wff_elements_set_threads(&m->el, (int)value, err))
            return value != floor(value) ? wff_fail(err, "threads = %g: a whole number", value)
                                         : -1;
    } else if (strcmp(key, "amplitude_mass_factor") == 0) {
        if (!(value >= 1 && value <= 1e6))
            return wff_fail(err, "amplitude_mass_factor = %g: must be >= 1 (1 is the paper's "
                            "1/6 of the displacement mass)", value);
        m->em.amplitude_mass_factor = value;
        wff_zones_masses(m);
    } else if (strcmp(key, "static_amplitudes") == 0) {
        if (value != 0 && value != 1)
            return wff_fail(err, "static_amplitudes = %g: must be 0 (dynamic nodal amplitudes, "
                            "the paper) or 1 (balanced at every point, King 2005)", value);
        if (value == 1 && m->zones)
            return wff_fail(err, "static_amplitudes: the model has zonal materials; zones keep "
                            "the amplitudes dynamic");
        if (value == 1 && wff_cell_amplitudes(m->mat.cell) == 0)
            return wff_fail(err, "static_amplitudes: cell '%s' has no amplitudes",
                            wff_cell_name(m->mat.cell));
        if (value == 1) { /* first guess: the amplitudes of node 0 (the preload's) */
            const double guess[2] = {m->u[3], m->u[4]};
            if (wff_elements_static_amplitudes(&m->el, &m->em, guess, err))
                return -1;
        } else {
            m->em.static_amplitudes = 0;
        }
    } else if (strcmp(key, "contact_search") == 0) {
        if (value != 0 && value != 1)
            return wff_fail(err, "contact_search = %g: must be 1 (only nodes the projectile "
                            "can reach) or 0 (every node, every step)", value);
        m->projectile.search_all = value == 0;
    } else if (strcmp(key, "reference_path") == 0) {
        if (value != 0 && value != 1)
            return wff_fail(err, "reference_path = %g: must be 0 (cell fast path where there "
                            "is one) or 1 (plain evaluate)", value);
        m->em.reference_path = (int)value;
    } else if (strcmp(key, "clamp_radius") == 0) {
        if (m->clamp.n == 0)
            return wff_fail(err, "clamp_radius: no friction clamp yet (set the clamp first)");
        if (!(value >= 0) || !isfinite(value))
            return wff_fail(err, "clamp_radius = %g: must be >= 0 m (0: the whole clamp)", value);
        double before = m->clamp.radius;
        m->clamp.radius = value;
        if (share_clamp_force(m, err)) { /* no node within: keep the force as it was */
            wff_error ignored;
            m->clamp.radius = before;
            share_clamp_force(m, &ignored);
            return -1;
        }
    } else if (strcmp(key, "erosion") == 0) {
        return wff_erosion_set(m, value, err);
    } else if (strcmp(key, "orientation") == 0) { /* degrees */
        if (!isfinite(value))
            return wff_fail(err, "orientation = %g: must be a finite angle in degrees", value);
        double right_angles = value / 90; /* exact multiples of 90 degrees: k pi/2 */
        double theta = right_angles == nearbyint(right_angles) ? right_angles * M_PI_2
                                                               : value * (M_PI / 180);
        return wff_model_set_orientation(m, theta, err);
    } else if (strcmp(key, "clamp_edge_reaction") == 0) {
        if (m->clamp.n == 0)
            return wff_fail(err, "clamp_edge_reaction: no friction clamp yet (set the clamp "
                            "first)");
        if (value != 0 && value != 1)
            return wff_fail(err, "clamp_edge_reaction = %g: must be 0 (friction from the "
                            "clamping force only) or 1 (also mu |R_z|)", value);
        m->clamp.edge_reaction = (int)value;
    } else {
        return wff_fail(err, "unknown solver setting '%s' (known: dtfactor, dtinterval, "
                        "symmetry, reference_path, threads, amplitude_mass_factor, "
                        "static_amplitudes, contact_search, erosion, orientation, "
                        "clamp_radius, clamp_edge_reaction, ply_mu, ply_thickness)",
                        key);
    }
    return 0;
}

int wff_model_nearest_node(const wff_model *m, double x, double y)
{
    int best = 0;
    double best_d = INFINITY;
    for (int n = 0; n < m->n_nodes; n++) {
        double d = hypot(m->mesh.xy[2 * n] - x, m->mesh.xy[2 * n + 1] - y);
        if (d < best_d || (d == best_d && wff_model_user_node(m, n) < wff_model_user_node(m, best))) {
            best_d = d;
            best = n;
        }
    }
    return wff_model_user_node(m, best); /* (the first of equals in the user's numbering) */
}

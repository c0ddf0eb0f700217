/* Explicit central-difference time integration of a fabric membrane with
 * boundary conditions, a friction clamp and a rigid projectile. See
 * include/wovenff/solver.h. */
#include "wovenff/solver.h"
#include "wovenff/material.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define D WFF_DOFS_PER_NODE

/* Predicted penetration, as a fraction of the nose radius, taken as the
 * projectile having passed through the fabric (a step moves a node by far
 * less than this). */
#define RUNAWAY_PENETRATION 0.5
/* Energy created, relative to the reference energy, beyond which the run is
 * taken as unstable. */
#define ENERGY_BLOWUP 0.5
/* ... on this many steps in a row (an instability keeps growing; a spike of a
 * step or two, e.g. a prescribed velocity jumped by the script, does not) ... */
#define BLOWUP_STEPS 3
/* ... or at once beyond this (50 times the reference energy created). */
#define ENERGY_BLOWUP_NOW 50.0

static const char *const dof_names[D] = {"ux", "uy", "uz", "dA1", "dA2"};

void wff_model_free(wff_model *m)
{
    free(m->u);
    free(m->v);
    free(m->f);
    free(m->mass);
    free(m->dof_kind);
    free(m->v_prescribed);
    free(m->gamma_f);
    free(m->reaction);
    free(m->projectile.candidates);
    free(m->projectile.contact_node);
    free(m->projectile.impulse);
    free(m->clamp.node);
    free(m->clamp.normal_force);
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
    if (wff_model_create_from_mesh(m, &mesh, material_path, err)) {
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

/* Before the first step: the stored energy of the state as set up (e.g. the
 * preload), so that energies read before any step are complete. A force pass
 * with γᶠ held; its forces are recomputed when the run starts, and a bad
 * element is reported then. */
static void stored_energy_now(wff_model *m)
{
    if (m->v_half_valid || m->step > 0)
        return;
    wff_force_totals t;
    memset(m->f, 0, sizeof(double) * (size_t)m->n_dofs);
    wff_elements_forces(&m->el, &m->em, m->mesh.xy, m->u, m->gamma_f, 0, m->f, &t);
    m->internal_energy = t.bad_element >= 0 ? 0 : t.internal_energy;
}

int wff_model_create_from_mesh(wff_model *m, wff_mesh *mesh, const char *material_path,
                               wff_error *err)
{
    memset(m, 0, sizeof *m);
    m->mesh = *mesh;
    memset(mesh, 0, sizeof *mesh);
    if (wff_material_load(material_path, &m->mat, err)) {
        wff_mesh_free(&m->mesh);
        return -1;
    }
    if (wff_elements_init(&m->el, m->mesh.xy, m->mesh.n_tris, m->mesh.tri, m->mesh.n_quads,
                          m->mesh.quad, err)) {
        wff_mesh_free(&m->mesh);
        return -1;
    }
    m->n_nodes = m->mesh.n_nodes;
    m->n_dofs = D * m->n_nodes;
    size_t nd = (size_t)m->n_dofs;
    size_t nq = (size_t)(WFF_TRI_POINTS * m->el.n_tris + WFF_QUAD_POINTS * m->el.n_quads);
    m->u = calloc(nd, sizeof(double));
    m->v = calloc(nd, sizeof(double));
    m->f = calloc(nd, sizeof(double));
    m->mass = calloc(nd, sizeof(double));
    m->dof_kind = calloc(nd, 1);
    m->v_prescribed = calloc(nd, sizeof(double));
    m->reaction = calloc(nd, sizeof(double));
    m->gamma_f = calloc(nq ? nq : 1, sizeof(double));
    if (!m->u || !m->v || !m->f || !m->mass || !m->dof_kind || !m->v_prescribed ||
        !m->reaction || !m->gamma_f) {
        wff_model_free(m);
        return wff_fail(err, "out of memory for a model of %d nodes", m->n_nodes);
    }
    m->em.mat = &m->mat;
    m->em.F_pre[0] = m->em.F_pre[3] = 1;
    m->em.J_pre = 1;
    wff_elements_masses(&m->el, &m->em, m->n_nodes, m->mass);
    sum_fabric_mass(m);
    /* amplitude DOFs of a cell without amplitudes stay put */
    if (m->mat.cell->n_amplitudes == 0)
        for (int n = 0; n < m->n_nodes; n++)
            m->dof_kind[D * n + 3] = m->dof_kind[D * n + 4] = WFF_DOF_FIXED;
    m->dt_factor = 0.8;
    m->dt_interval = 20;
    m->symmetry_factor = 1;
    stored_energy_now(m);
    return 0;
}

int wff_model_set_preload(wff_model *m, const double F_pre[4], const double dA0[2],
                          wff_error *err)
{
    double det = F_pre[0] * F_pre[3] - F_pre[1] * F_pre[2];
    if (!(det > 0))
        return wff_fail(err, "preload F_pre = [%g %g; %g %g] has det %g: must be > 0", F_pre[0],
                        F_pre[1], F_pre[2], F_pre[3], det);
    memcpy(m->em.F_pre, F_pre, 4 * sizeof(double));
    m->em.J_pre = det;
    wff_elements_masses(&m->el, &m->em, m->n_nodes, m->mass);
    sum_fabric_mass(m);
    if (m->mat.cell->n_amplitudes)
        for (int n = 0; n < m->n_nodes; n++) {
            m->u[D * n + 3] = dA0[0];
            m->u[D * n + 4] = dA0[1];
        }
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
    for (int n = 0; n < m->n_nodes; n++)
        if (seen[n]) {
            visit(m, n, data);
            count++;
        }
    free(seen);
    if (count == 0)
        return wff_fail(err, "physical group '%s' has no nodes", group);
    return count;
}

typedef struct dof_setting { int component, kind; double velocity; } dof_setting;

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
    dof_setting s = {component, WFF_DOF_FIXED, 0};
    return for_group_nodes(m, group, err, set_dof, &s);
}

int wff_model_prescribe_group(wff_model *m, const char *group, int component, double velocity,
                              wff_error *err)
{
    if (check_component(component, err))
        return -1;
    if (!isfinite(velocity))
        return wff_fail(err, "prescribed velocity of '%s' is not finite", group);
    dof_setting s = {component, WFF_DOF_PRESCRIBED, velocity};
    return for_group_nodes(m, group, err, set_dof, &s);
}

static void add_clamp_node(wff_model *m, int node, void *data)
{
    (void)data;
    m->clamp.node[m->clamp.n++] = node;
    m->dof_kind[D * node + WFF_UZ] = WFF_DOF_FIXED; /* pressed flat */
    m->v[D * node + WFF_UZ] = 0;
}

int wff_model_clamp_friction(wff_model *m, const char *group, double normal_force, double mu,
                             wff_error *err)
{
    if (!(normal_force > 0) || !(mu >= 0))
        return wff_fail(err, "friction clamp '%s': normal force %g N must be > 0 and mu %g >= 0",
                        group, normal_force, mu);
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
    /* share the force by lumped (displacement) mass, i.e. by nodal area */
    double total = 0;
    for (int i = 0; i < m->clamp.n; i++)
        total += m->mass[D * m->clamp.node[i]];
    for (int i = 0; i < m->clamp.n; i++)
        m->clamp.normal_force[i] = normal_force * m->mass[D * m->clamp.node[i]] / total;
    m->clamp.mu = mu;
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
        m->symmetry_factor = value;
    } else if (strcmp(key, "threads") == 0) {
        if (value != floor(value) || wff_elements_set_threads(&m->el, (int)value, err))
            return value != floor(value) ? wff_fail(err, "threads = %g: a whole number", value)
                                         : -1;
    } else if (strcmp(key, "amplitude_mass_factor") == 0) {
        if (!(value >= 1 && value <= 1e6))
            return wff_fail(err, "amplitude_mass_factor = %g: must be >= 1 (1 is the paper's "
                            "1/6 of the displacement mass)", value);
        m->em.amplitude_mass_factor = value;
        wff_elements_masses(&m->el, &m->em, m->n_nodes, m->mass);
    } else if (strcmp(key, "static_amplitudes") == 0) {
        if (value != 0 && value != 1)
            return wff_fail(err, "static_amplitudes = %g: must be 0 (dynamic nodal amplitudes, "
                            "the paper) or 1 (balanced at every point, King 2005)", value);
        if (value == 1 && m->mat.cell->n_amplitudes == 0)
            return wff_fail(err, "static_amplitudes: cell '%s' has no amplitudes",
                            m->mat.cell->name);
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
    } else {
        return wff_fail(err, "unknown solver setting '%s' (known: dtfactor, dtinterval, "
                        "symmetry, reference_path, threads, amplitude_mass_factor, static_amplitudes, "
                        "contact_search)", key);
    }
    return 0;
}

int wff_model_set_projectile(wff_model *m, double radius, double mass, double velocity,
                             double mu, wff_error *err)
{
    if (!(radius > 0))
        return wff_fail(err, "projectile radius %g m must be > 0", radius);
    if (!(mass > 0))
        return wff_fail(err, "projectile mass %g kg must be > 0", mass);
    if (!(velocity >= 0) || !isfinite(velocity))
        return wff_fail(err, "projectile velocity %g m/s must be >= 0 (it moves along +z)",
                        velocity);
    if (!(mu >= 0))
        return wff_fail(err, "projectile friction coefficient %g must be >= 0", mu);
    wff_projectile *p = &m->projectile;
    free(p->candidates);
    free(p->contact_node);
    free(p->impulse);
    p->candidates = malloc(sizeof(int) * (size_t)m->n_nodes);
    p->contact_node = malloc(sizeof(int) * (size_t)m->n_nodes);
    p->impulse = malloc(3 * sizeof(double) * (size_t)m->n_nodes);
    if (!p->candidates || !p->contact_node || !p->impulse)
        return wff_fail(err, "out of memory");
    p->active = 1;
    p->radius = radius;
    p->mass = mass;
    p->velocity = velocity;
    p->mu = mu;
    p->axis[0] = p->axis[1] = 0;
    p->n_candidates = 0;
    p->max_penetration = 0;
    p->force = 0;
    /* nose tip touching the fabric plane z = 0 */
    return wff_model_place_projectile(m, 0, err);
}

static double penetration(const wff_projectile *p, const double x[3], double normal[3]);

int wff_model_place_projectile(wff_model *m, double tip, wff_error *err)
{
    wff_projectile *p = &m->projectile;
    if (!p->active)
        return wff_fail(err, "no projectile to place: set one first");
    if (!isfinite(tip))
        return wff_fail(err, "projectile tip z = %g m: must be finite", tip);
    double old = p->tip;
    p->tip = tip;
    /* the deepest node inside the nose or the shank behind it */
    int worst = -1;
    double deepest = 0, at[3] = {0, 0, 0};
    for (int n = 0; n < m->n_nodes; n++) {
        double x[3] = {m->mesh.xy[2 * n] + m->u[D * n], m->mesh.xy[2 * n + 1] + m->u[D * n + 1],
                       m->u[D * n + 2]};
        double nrm[3], delta = penetration(p, x, nrm);
        if (delta > deepest) {
            deepest = delta;
            worst = n;
            memcpy(at, x, sizeof at);
        }
    }
    if (worst >= 0) {
        p->tip = old;
        return wff_fail(err, "projectile starts inside the fabric: node %d at (%g, %g, %g) m "
                        "is %.3g m inside the projectile (nose tip at z = %g m, radius %g m; "
                        "the fabric lies at z = 0 and the projectile moves along +z: put the "
                        "tip at z <= 0)", worst + 1, at[0], at[1], at[2], deepest, tip,
                        p->radius);
    }
    return 0;
}

int wff_model_nearest_node(const wff_model *m, double x, double y)
{
    int best = 0;
    double best_d = INFINITY;
    for (int n = 0; n < m->n_nodes; n++) {
        double d = hypot(m->mesh.xy[2 * n] - x, m->mesh.xy[2 * n + 1] - y);
        if (d < best_d) {
            best_d = d;
            best = n;
        }
    }
    return best;
}

/* Nodes whose current in-plane position is near enough the projectile axis
 * to touch it before the next refresh. */
static void refresh_candidates(wff_model *m)
{
    wff_projectile *p = &m->projectile;
    double reach = p->search_all ? INFINITY : 1.2 * p->radius + 2e-3;
    p->n_candidates = 0;
    for (int n = 0; n < m->n_nodes; n++) {
        double dx = m->mesh.xy[2 * n] + m->u[D * n] - p->axis[0];
        double dy = m->mesh.xy[2 * n + 1] + m->u[D * n + 1] - p->axis[1];
        if (dx * dx + dy * dy < reach * reach)
            p->candidates[p->n_candidates++] = n;
    }
}

/* Penetration δ and outward normal of a point against the nose (sphere of the
 * nose radius centred a radius behind the tip) or the shank behind it. */
static double penetration(const wff_projectile *p, const double x[3], double normal[3])
{
    double c[3] = {p->axis[0], p->axis[1], p->tip - p->radius};
    double d[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    if (d[2] > 0) {
        double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (r >= p->radius || r == 0)
            return 0;
        for (int i = 0; i < 3; i++)
            normal[i] = d[i] / r;
        return p->radius - r;
    }
    double r = hypot(d[0], d[1]);
    if (r >= p->radius || r == 0)
        return 0;
    normal[0] = d[0] / r, normal[1] = d[1] / r, normal[2] = 0;
    return p->radius - r;
}

/* "triangle 3 (nodes 4 5 9)" or "quadrilateral 2 (nodes ...)" for element e
 * (triangles first, then quads), numbered from 1 within its type. */
static void element_name(const wff_model *m, int e, char *out, size_t size)
{
    if (e < 0) {
        snprintf(out, size, "no element");
        return;
    }
    int tri = e < m->el.n_tris;
    const int *node = tri ? m->el.tri + 3 * e : m->el.quad + 4 * (e - m->el.n_tris);
    if (tri)
        snprintf(out, size, "triangle %d (nodes %d %d %d)", e + 1, node[0] + 1, node[1] + 1,
                 node[2] + 1);
    else
        snprintf(out, size, "quadrilateral %d (nodes %d %d %d %d)", e - m->el.n_tris + 1,
                 node[0] + 1, node[1] + 1, node[2] + 1, node[3] + 1);
}

/* The run is unstable: say what showed it (`what`), when, the element that
 * sets the stable step, and a step and a dtfactor to try. */
static int fail_unstable(const wff_model *m, const char *what, wff_error *err)
{
    char name[96];
    element_name(m, m->dt_worst_element, name, sizeof name);
    /* above the default: back to 0.8; at or below it the estimate was not
     * safe here: halve the factor */
    double suggested = m->dt_factor > 0.8 ? 0.8 : 0.5 * m->dt_factor;
    return wff_fail(err, "t = %.6g s (step %ld): %s: unstable (time step %.3g s = %.3g x the "
                    "stable estimate %.3g s at %s); suggested step %.3g s: suggested "
                    "-dtfactor %.2g", m->time, m->step, what, m->dt, m->dt_factor,
                    m->dt_stable, name, suggested * m->dt_stable, suggested);
}

/* Internal and contact forces at the current u; returns 0 or -1 (err set). */
static int compute_forces(wff_model *m, double dt_flow, wff_error *err)
{
    memset(m->f, 0, sizeof(double) * (size_t)m->n_dofs);
    wff_force_totals t;
    wff_elements_forces(&m->el, &m->em, m->mesh.xy, m->u, m->gamma_f, dt_flow, m->f, &t);
    m->element_steps += m->el.n_tris + m->el.n_quads;
    if (t.bad_element >= 0) {
        char name[96];
        element_name(m, t.bad_element, name, sizeof name);
        const char *quantity = t.bad_status == WFF_POINT_DEGENERATE
                                   ? "degenerate deformation (yarns collapsed or parallel: "
                                     "inverted element)"
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
    m->internal_energy = t.internal_energy;
    m->dissipated_shear += t.dissipated;

    return 0;
}

/* Coulomb friction as a velocity correction: an impulse up to `limit`
 * against the relative tangential speed `speed` of a node of mass `mass`
 * (sticking if the limit allows). The friction force impulse/Δt works
 * against the slip that remains, speed − impulse/mass, over the step: that is
 * the energy it dissipates (zero while sticking). Returns the impulse. */
static double friction_impulse(double mass, double speed, double limit, double *dissipated)
{
    double stick = mass * speed;
    double impulse = stick < limit ? stick : limit;
    double slip = speed - impulse / mass;
    *dissipated += impulse * slip;
    return impulse;
}

/* Kinematic (hard) contact with the projectile, a predictor–corrector on
 * velocities: with the trial velocities of this step, find the nodes whose
 * predicted position at t + dt lies inside the projectile, and give each an
 * impulse along the surface normal, shared with the projectile by their
 * masses, that puts it back on the surface (perfectly inelastic, like a hard
 * contact in an explicit code); then Coulomb friction limits the tangential
 * impulse to μ times the normal one. The impulses enter f as forces
 * impulse/dt_mid, and their work J·vⁿ (vⁿ the integer-step velocity, the
 * central-difference measure of the displacement over the step) is what the
 * contact dissipates. Returns -1 (err set) if a node is found deep inside,
 * i.e. the projectile has gone through the fabric. */
static int contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    wff_projectile *p = &m->projectile;
    p->force = 0;
    if (!p->active)
        return 0;
    const double tip_now = p->tip, v_proj_before = p->velocity;
    int touched = 0;
    for (int c = 0; c < p->n_candidates; c++) {
        int n = p->candidates[c];
        double *un = m->u + D * n, *vn = m->v + D * n, *jc = p->impulse + 3 * touched;
        const double mass = m->mass[D * n];
        double x[3] = {m->mesh.xy[2 * n] + un[0] + dt * vn[0],
                       m->mesh.xy[2 * n + 1] + un[1] + dt * vn[1], un[2] + dt * vn[2]};
        p->tip = tip_now + dt * p->velocity; /* predicted */
        double nrm[3], delta = penetration(p, x, nrm);
        p->tip = tip_now;
        if (delta <= 0)
            continue;
        if (delta > RUNAWAY_PENETRATION * p->radius)
            return wff_fail(err, "t = %.6g s (step %ld): node %d would be %.3g m inside the "
                            "projectile (more than %.0f%% of its radius): the projectile has "
                            "passed through the fabric", m->time, m->step, n + 1, delta,
                            100 * RUNAWAY_PENETRATION);
        /* inverse mass along the normal: free node components and the projectile (z) */
        double w_node = 0;
        for (int i = 0; i < 3; i++)
            if (m->dof_kind[D * n + i] == WFF_DOF_FREE)
                w_node += nrm[i] * nrm[i];
        if (w_node == 0)
            continue;
        w_node /= mass;
        double jn = delta / dt / (w_node + nrm[2] * nrm[2] / p->mass); /* N·s */
        double j[3] = {jn * nrm[0], jn * nrm[1], jn * nrm[2]};
        /* friction against the tangential relative velocity left after jn */
        if (p->mu > 0) {
            double rel[3] = {vn[0] + j[0] / mass, vn[1] + j[1] / mass,
                             vn[2] + j[2] / mass - (p->velocity - j[2] / p->mass)};
            double along = rel[0] * nrm[0] + rel[1] * nrm[1] + rel[2] * nrm[2];
            double vt[3], speed = 0;
            for (int i = 0; i < 3; i++) {
                vt[i] = rel[i] - along * nrm[i];
                speed += vt[i] * vt[i];
            }
            speed = sqrt(speed);
            if (speed > 0) {
                double jt = fmin(p->mu * jn, mass * speed); /* stick if the cone allows */
                for (int i = 0; i < 3; i++)
                    j[i] -= jt * vt[i] / speed;
            }
        }
        for (int i = 0; i < 3; i++) {
            if (m->dof_kind[D * n + i] != WFF_DOF_FREE)
                j[i] = 0;
            vn[i] += j[i] / mass;
            jc[i] = j[i];
        }
        p->velocity -= j[2] / p->mass;
        p->contact_node[touched++] = n;
        /* what remains inside after the correction */
        double x2[3] = {m->mesh.xy[2 * n] + un[0] + dt * vn[0],
                        m->mesh.xy[2 * n + 1] + un[1] + dt * vn[1], un[2] + dt * vn[2]};
        p->tip = tip_now + dt * p->velocity;
        double rest = penetration(p, x2, nrm);
        p->tip = tip_now;
        if (rest > p->max_penetration)
            p->max_penetration = rest;
    }
    /* forces and their work over the step */
    double work = 0;
    for (int c = 0; c < touched; c++) {
        int n = p->contact_node[c];
        const double *jc = p->impulse + 3 * c;
        for (int i = 0; i < 3; i++) {
            int k = D * n + i;
            if (m->dof_kind[k] != WFF_DOF_FREE)
                continue;
            m->f[k] += jc[i] / dt_mid;
            double v_int = m->v[k] - 0.5 * dt_mid * m->f[k] / m->mass[k]; /* vⁿ */
            work += jc[i] * v_int;
        }
    }
    double dv = p->velocity - v_proj_before;
    p->force = -p->mass * dv / dt_mid;
    work += p->mass * dv * (p->velocity - 0.5 * dv);
    m->dissipated_friction -= work;
    return 0;
}

/* v^{n+½} from f^n; dt_done is the step just taken (0 on the first half step):
 * the second half of its trapezoidal external work, ½ Rⁿ⁺¹·Δu, is added here
 * on the prescribed DOFs (the first half was added with the position update). */
static void update_velocities(wff_model *m, double dt_mid, double dt_done)
{
    for (int i = 0; i < m->n_dofs; i++) {
        switch (m->dof_kind[i]) {
        case WFF_DOF_FREE:
            m->v[i] += dt_mid * m->f[i] / m->mass[i];
            m->reaction[i] = 0;
            break;
        case WFF_DOF_FIXED:
            m->v[i] = 0;
            m->reaction[i] = -m->f[i];
            break;
        default:
            m->external_work += 0.5 * (-m->f[i]) * dt_done * m->v[i];
            m->v[i] = m->v_prescribed[i];
            m->reaction[i] = -m->f[i];
            break;
        }
    }
    double dissipated = 0;
    /* friction clamp: in-plane, two faces */
    for (int c = 0; c < m->clamp.n; c++) {
        int n = m->clamp.node[c];
        double *vn = m->v + D * n;
        if (m->dof_kind[D * n] != WFF_DOF_FREE || m->dof_kind[D * n + 1] != WFF_DOF_FREE)
            continue;
        double speed = hypot(vn[0], vn[1]);
        if (speed == 0)
            continue;
        double impulse = friction_impulse(m->mass[D * n], speed,
                                          2 * m->clamp.mu * m->clamp.normal_force[c] * dt_mid,
                                          &dissipated);
        double scale = 1 - impulse / (m->mass[D * n] * speed);
        vn[0] *= scale;
        vn[1] *= scale;
    }
    m->dissipated_friction += dissipated;
}

static int update_time_step(wff_model *m, wff_error *err)
{
    int worst;
    double dt = wff_elements_stable_step(&m->el, &m->em, m->mesh.xy, m->u, &worst);
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

/* Kinetic energies (model part) at the integer step, v^{n+½} − ½Δt a^n from
 * the last half step: in-plane, transverse, amplitude, projectile. No
 * allocation: the advance loop calls it every step. */
static void kinetic_now(const wff_model *m, double k[4])
{
    const double half = m->v_half_valid ? 0.5 * m->dt : 0;
    const double *v = m->v, *f = m->f, *mass = m->mass;
    const unsigned char *kind = m->dof_kind;
    double inplane = 0, transverse = 0, amplitude = 0;
    for (int n = 0; n < m->n_nodes; n++) { /* branch-free over the 5 DOFs of a node */
        const int i = D * n;
        double e[D];
        for (int j = 0; j < D; j++) {
            double vn = v[i + j] - half * f[i + j] / mass[i + j];
            e[j] = kind[i + j] == WFF_DOF_FREE ? mass[i + j] * vn * vn : 0;
        }
        inplane += e[0] + e[1];
        transverse += e[2];
        amplitude += e[3] + e[4];
    }
    k[0] = 0.5 * inplane;
    k[1] = 0.5 * transverse;
    k[2] = 0.5 * amplitude;
    k[3] = 0;
    if (m->projectile.active) {
        double vp = m->projectile.velocity + half * m->projectile.force / m->projectile.mass;
        k[3] = 0.5 * m->projectile.mass * vp * vp;
    }
}

void wff_model_energies(const wff_model *m, wff_energies *out)
{
    double k[4];
    kinetic_now(m, k);
    double s = m->symmetry_factor;
    out->kinetic_inplane = s * k[0];
    out->kinetic_transverse = s * k[1];
    out->kinetic_amplitude = s * k[2];
    out->kinetic_projectile = s * k[3];
    out->internal = s * (m->internal_energy);
    out->dissipated_shear = s * m->dissipated_shear;
    out->dissipated_friction = s * m->dissipated_friction;
    out->external_work = s * m->external_work;
    double total = k[0] + k[1] + k[2] + k[3] + m->internal_energy +
                   m->dissipated_shear + m->dissipated_friction - m->external_work;
    /* normaliser: the initial kinetic energy, or (for a scene driven by its
     * boundaries) the work done on it or the energy it now holds */
    double stored = m->internal_energy - (m->initial_total - m->initial_kinetic);
    double ref = fmax(m->initial_kinetic, fabs(m->external_work));
    ref = fmax(ref, fmax(k[0] + k[1] + k[2] + k[3], fabs(stored)));
    /* below the kinetic energy of the fabric moving at ~3e-5 m/s, energies are
     * round-off: floor the normaliser there */
    ref = fmax(ref, 1e-9 * m->fabric_mass * 1.0 /* (m/s)^2 */);
    out->reference = s * ref;
    out->error = m->v_half_valid ? (total - m->initial_total) / ref : 0; /* not started: exact */
}

int wff_model_advance(wff_model *m, double t_end, long max_steps, wff_error *err)
{
    if (m->step == 0 && !m->v_half_valid) {
        /* start: forces at u⁰, energy reference */
        if (update_time_step(m, err))
            return -1;
        if (m->projectile.active)
            refresh_candidates(m);
        if (compute_forces(m, 0, err))
            return -1;
        double k[4];
        kinetic_now(m, k); /* v_half_valid is 0: the velocities as given */
        m->initial_kinetic = k[0] + k[1] + k[2] + k[3];
        m->initial_total = m->initial_kinetic + m->internal_energy;
        m->v_half_valid = 1;
        /* first half step */
        update_velocities(m, 0.5 * m->dt, 0);
        if (contact_correct(m, m->dt, 0.5 * m->dt, err))
            return -1;
    }
    if (m->projectile.active)
        refresh_candidates(m);
    long done = 0;
    while (m->time < t_end && done < max_steps) {
        /* u^{n+1} = u^n + Δt v^{n+½} */
        double dt = m->dt;
        /* external work by the trapezoidal rule: ½(R^n + R^{n+1})·Δu */
        for (int i = 0; i < m->n_dofs; i++) {
            double du = dt * m->v[i];
            if (m->dof_kind[i] == WFF_DOF_PRESCRIBED)
                m->external_work += 0.5 * m->reaction[i] * du;
            m->u[i] += du;
        }
        if (m->projectile.active)
            m->projectile.tip += dt * m->projectile.velocity;
        m->time += dt;
        m->step++;
        done++;
        if (m->step % m->dt_interval == 0) {
            if (update_time_step(m, err))
                return -1;
            if (m->projectile.active)
                refresh_candidates(m);
        }
        if (compute_forces(m, dt, err))
            return -1;
        update_velocities(m, 0.5 * (dt + m->dt), dt);
        if (contact_correct(m, m->dt, 0.5 * (dt + m->dt), err))
            return -1;
        {   /* every step (a pass over the DOFs, ~4 % of a step): an unstable
             * step grows the energy by a large factor per step */
            wff_energies e;
            wff_model_energies(m, &e);
            /* an unstable step creates energy (a deficit is not instability) and
             * keeps creating it: a one- or two-step spike, as when a script jumps
             * a prescribed velocity while the work done is still tiny, is not */
            m->blowup_steps = e.error > ENERGY_BLOWUP ? m->blowup_steps + 1 : 0;
            if (!isfinite(e.error) || m->blowup_steps >= BLOWUP_STEPS ||
                e.error > ENERGY_BLOWUP_NOW) {
                char what[160];
                snprintf(what, sizeof what, "energy balance off by %.3g%% of the reference "
                         "energy", 100 * e.error);
                return fail_unstable(m, what, err);
            }
            m->last_error = e.error;
        }
    }
    return 0;
}

int wff_model_nodal_field(const wff_model *m, const char *name, double *out, wff_error *err)
{
    for (int c = 0; c < D; c++)
        if (strcmp(name, dof_names[c]) == 0) {
            for (int n = 0; n < m->n_nodes; n++)
                out[n] = m->u[D * n + c];
            return 0;
        }
    if (strcmp(name, "vz") == 0) {
        for (int n = 0; n < m->n_nodes; n++)
            out[n] = m->v[D * n + 2];
        return 0;
    }
    const wff_cell_type *cell = m->mat.cell;
    int diag = -1;
    for (int d = 0; d < cell->n_diag; d++)
        if (strcmp(name, cell->diag_names[d]) == 0)
            diag = d;
    /* generic names for the yarn tensions, whatever the cell calls them */
    for (int k = 0; k < 2; k++)
        if (strcmp(name, k ? "yarn_tension2" : "yarn_tension1") == 0)
            diag = cell->yarn_tension_diag[k];
    int shear = strcmp(name, "gamma") == 0, energy = strcmp(name, "W") == 0;
    if (diag < 0 && !shear && !energy) {
        char known[512] = "ux uy uz dA1 dA2 vz gamma W yarn_tension1 yarn_tension2";
        for (int d = 0; d < cell->n_diag; d++) {
            size_t used = strlen(known);
            snprintf(known + used, sizeof known - used, " %s", cell->diag_names[d]);
        }
        return wff_fail(err, "unknown field '%s' (known: %s)", name, known);
    }
    double *weight = calloc((size_t)m->n_nodes, sizeof(double));
    if (!weight)
        return wff_fail(err, "out of memory");
    memset(out, 0, sizeof(double) * (size_t)m->n_nodes);
    int n_el = m->el.n_tris + m->el.n_quads;
    for (int e = 0; e < n_el; e++) {
        double value;
        if (shear) {
            double F[6], dA[2];
            wff_element_center_state(&m->el, m->mesh.xy, m->u, e, F, dA);
            const double *Fp = m->em.F_pre;
            double g1[3], g2[3];
            for (int i = 0; i < 3; i++) {
                g1[i] = F[2 * i] * Fp[0] + F[2 * i + 1] * Fp[2];
                g2[i] = F[2 * i] * Fp[1] + F[2 * i + 1] * Fp[3];
            }
            double dot = g1[0] * g2[0] + g1[1] * g2[1] + g1[2] * g2[2];
            double cx = g1[1] * g2[2] - g1[2] * g2[1], cy = g1[2] * g2[0] - g1[0] * g2[2],
                   cz = g1[0] * g2[1] - g1[1] * g2[0];
            value = M_PI_2 - atan2(sqrt(cx * cx + cy * cy + cz * cz), dot);
        } else {
            wff_point_result r;
            wff_element_center_eval(&m->el, &m->em, m->mesh.xy, m->u, m->gamma_f, e, &r);
            value = energy ? r.energy : r.diag[diag];
        }
        int nn = e < m->el.n_tris ? 3 : 4;
        const int *node = e < m->el.n_tris ? m->el.tri + 3 * e : m->el.quad + 4 * (e - m->el.n_tris);
        double area;
        if (e < m->el.n_tris)
            area = m->el.tri_area[e];
        else {
            area = 0;
            for (int q = 0; q < 4; q++)
                area += m->el.quad_weight[4 * (e - m->el.n_tris) + q];
        }
        for (int a = 0; a < nn; a++) {
            out[node[a]] += area * value;
            weight[node[a]] += area;
        }
    }
    for (int n = 0; n < m->n_nodes; n++)
        out[n] = weight[n] > 0 ? out[n] / weight[n] : 0;
    free(weight);
    return 0;
}

int wff_model_energy_split(const wff_model *m, double *out)
{
    const wff_cell_type *cell = m->mat.cell;
    int n = cell->n_mech < WFF_MECH_MAX ? cell->n_mech : WFF_MECH_MAX;
    double mech[WFF_MECH_MAX] = {0};
    if (n > 0)
        wff_elements_energy_split(&m->el, &m->em, m->mesh.xy, m->u, m->gamma_f, mech);
    for (int k = 0; k < n; k++)
        out[k] = m->symmetry_factor * mech[k];
    return n;
}

/* ---- checkpoints --------------------------------------------------------- */

static const char checkpoint_magic[8] = {'W', 'F', 'F', 'S', 'T', 'A', 'T', 'E'};
#define BYTE_ORDER_MARK 0x0102030405060708ULL

static uint64_t fnv1a(uint64_t h, const void *data, size_t size)
{
    const unsigned char *b = data;
    for (size_t i = 0; i < size; i++) {
        h ^= b[i];
        h *= 0x100000001b3ULL;
    }
    return h;
}
#define FNV_START 0xcbf29ce484222325ULL

static size_t n_gamma(const wff_model *m)
{
    return (size_t)(WFF_TRI_POINTS * m->el.n_tris + WFF_QUAD_POINTS * m->el.n_quads);
}

/* What a checkpoint must match: sizes, fingerprints, settings. */
typedef struct checkpoint_header {
    char magic[8];
    uint32_t version, header_size;
    uint64_t byte_order;
    int32_t n_nodes, n_tris, n_quads, n_gamma, n_candidates, projectile_active, clamp_nodes,
        dt_interval, reference_path, pad;
    uint64_t mesh_hash, material_hash, mass_hash, bc_hash, settings_hash;
    double dt_factor, symmetry_factor, projectile_radius, projectile_mass, projectile_mu;
    uint64_t payload_size;
} checkpoint_header;

static void fingerprint(const wff_model *m, checkpoint_header *h)
{
    memset(h, 0, sizeof *h);
    memcpy(h->magic, checkpoint_magic, sizeof h->magic);
    h->version = WFF_CHECKPOINT_VERSION;
    h->header_size = sizeof *h;
    h->byte_order = BYTE_ORDER_MARK;
    h->n_nodes = m->n_nodes;
    h->n_tris = m->el.n_tris;
    h->n_quads = m->el.n_quads;
    h->n_gamma = (int32_t)n_gamma(m);
    h->n_candidates = m->projectile.active ? m->projectile.n_candidates : 0;
    h->projectile_active = m->projectile.active;
    h->clamp_nodes = m->clamp.n;
    h->dt_interval = m->dt_interval;
    h->reference_path = m->em.reference_path;
    h->pad = 0;
    uint64_t g = FNV_START;
    g = fnv1a(g, m->mesh.xy, sizeof(double) * 2 * (size_t)m->n_nodes);
    g = fnv1a(g, m->el.tri, sizeof(int) * 3 * (size_t)m->el.n_tris);
    g = fnv1a(g, m->el.quad, sizeof(int) * 4 * (size_t)m->el.n_quads);
    h->mesh_hash = g;
    const char *cell = m->mat.cell ? m->mat.cell->name : "";
    g = fnv1a(FNV_START, cell, strlen(cell));
    g = fnv1a(g, &m->mat.areal_density, sizeof(double));
    g = fnv1a(g, m->mat.params, sizeof m->mat.params);
    h->material_hash = g;
    h->mass_hash = fnv1a(FNV_START, m->mass, sizeof(double) * (size_t)m->n_dofs);
    g = fnv1a(FNV_START, m->dof_kind, (size_t)m->n_dofs);
    g = fnv1a(g, m->clamp.node, sizeof(int) * (size_t)m->clamp.n);
    g = fnv1a(g, m->clamp.normal_force, sizeof(double) * (size_t)m->clamp.n);
    g = fnv1a(g, &m->clamp.mu, sizeof(double));
    h->bc_hash = g;
    /* settings that change the numbers: preload, amplitude treatment, contact search,
     * threads (the force sums' order) */
    g = fnv1a(FNV_START, m->em.F_pre, sizeof m->em.F_pre);
    g = fnv1a(g, &m->em.amplitude_mass_factor, sizeof(double));
    g = fnv1a(g, &m->em.static_amplitudes, sizeof(int));
    g = fnv1a(g, &m->projectile.search_all, sizeof(int));
    g = fnv1a(g, &m->el.n_threads, sizeof(int));
    h->settings_hash = g;
    h->dt_factor = m->dt_factor;
    h->symmetry_factor = m->symmetry_factor;
    if (m->projectile.active) {
        h->projectile_radius = m->projectile.radius;
        h->projectile_mass = m->projectile.mass;
        h->projectile_mu = m->projectile.mu;
    }
}

/* The evolving state, in file order: pointer, element size, count. */
typedef struct state_field { void *data; size_t size, count; } state_field;

static int state_fields(wff_model *m, int n_candidates, state_field *f)
{
    wff_projectile *p = &m->projectile;
    int k = 0;
#define FIELD(ptr, n) f[k++] = (state_field){(void *)(ptr), sizeof *(ptr), (size_t)(n)}
    FIELD(&m->time, 1);
    FIELD(&m->dt, 1);
    FIELD(&m->dt_stable, 1);
    FIELD(&m->step, 1);
    FIELD(&m->dt_worst_element, 1);
    FIELD(&m->internal_energy, 1);
    FIELD(&m->dissipated_shear, 1);
    FIELD(&m->dissipated_friction, 1);
    FIELD(&m->external_work, 1);
    FIELD(&m->initial_total, 1);
    FIELD(&m->initial_kinetic, 1);
    FIELD(&m->v_half_valid, 1);
    FIELD(&m->element_steps, 1);
    FIELD(&m->blowup_steps, 1);
    FIELD(&m->last_error, 1);
    FIELD(&p->tip, 1);
    FIELD(&p->velocity, 1);
    FIELD(p->axis, 2);
    FIELD(&p->max_penetration, 1);
    FIELD(&p->force, 1);
    FIELD(&p->n_candidates, 1);
    FIELD(p->candidates, n_candidates);
    FIELD(m->u, m->n_dofs);
    FIELD(m->v, m->n_dofs);
    FIELD(m->f, m->n_dofs);
    FIELD(m->reaction, m->n_dofs);
    FIELD(m->v_prescribed, m->n_dofs);
    FIELD(m->gamma_f, n_gamma(m));
    if (m->em.static_amplitudes) /* the points' own amplitudes */
        FIELD(m->el.point_dA, 2 * n_gamma(m));
#undef FIELD
    return k;
}
#define MAX_STATE_FIELDS 32

int wff_model_save(const wff_model *m, const char *path, wff_error *err)
{
    checkpoint_header h;
    fingerprint(m, &h);
    state_field fields[MAX_STATE_FIELDS];
    int nf = state_fields((wff_model *)m, h.n_candidates, fields);
    size_t payload = 0;
    for (int i = 0; i < nf; i++)
        payload += fields[i].size * fields[i].count;
    h.payload_size = payload;
    char tmp[4096];
    if (snprintf(tmp, sizeof tmp, "%s.tmp", path) >= (int)sizeof tmp)
        return wff_fail(err, "checkpoint path too long: %s", path);
    FILE *out = fopen(tmp, "wb");
    if (!out)
        return wff_fail(err, "cannot write checkpoint %s: %s", tmp, strerror(errno));
    uint64_t sum = fnv1a(FNV_START, &h, sizeof h);
    int bad = fwrite(&h, sizeof h, 1, out) != 1;
    for (int i = 0; i < nf && !bad; i++) {
        size_t bytes = fields[i].size * fields[i].count;
        if (bytes == 0)
            continue;
        sum = fnv1a(sum, fields[i].data, bytes);
        bad = fwrite(fields[i].data, 1, bytes, out) != bytes;
    }
    if (!bad)
        bad = fwrite(&sum, sizeof sum, 1, out) != 1;
    if (!bad)
        bad = fflush(out) != 0 || fsync(fileno(out)) != 0;
    int saved_errno = errno;
    if (fclose(out) != 0 && !bad) {
        bad = 1;
        saved_errno = errno;
    }
    if (bad) {
        remove(tmp);
        return wff_fail(err, "cannot write checkpoint %s: %s", tmp, strerror(saved_errno));
    }
    if (rename(tmp, path) != 0) {
        saved_errno = errno;
        remove(tmp);
        return wff_fail(err, "cannot rename checkpoint %s to %s: %s", tmp, path,
                        strerror(saved_errno));
    }
    return 0;
}

static const char *hash_mismatch(const checkpoint_header *a, const checkpoint_header *b)
{
    if (a->mesh_hash != b->mesh_hash)
        return "the mesh differs (same sizes, other node coordinates or connectivity)";
    if (a->material_hash != b->material_hash)
        return "the material differs (cell or parameters)";
    if (a->mass_hash != b->mass_hash)
        return "the lumped masses differ (another preload or areal density)";
    if (a->bc_hash != b->bc_hash)
        return "the boundary conditions differ (fixed or prescribed DOFs, friction clamp)";
    if (a->settings_hash != b->settings_hash)
        return "the solver settings differ (preload F_pre, amplitude mass factor, static "
               "amplitudes, contact search or threads)";
    return NULL;
}

int wff_model_load_state(wff_model *m, const char *path, wff_error *err)
{
    FILE *in = fopen(path, "rb");
    if (!in)
        return wff_fail(err, "cannot open checkpoint %s: %s", path, strerror(errno));
    unsigned char *buf = NULL;
    size_t size = 0, cap = 0;
    for (;;) {
        if (size == cap) {
            cap = cap ? 2 * cap : 1 << 16;
            unsigned char *grown = realloc(buf, cap);
            if (!grown) {
                free(buf);
                fclose(in);
                return wff_fail(err, "checkpoint %s: out of memory", path);
            }
            buf = grown;
        }
        size_t got = fread(buf + size, 1, cap - size, in);
        size += got;
        if (got == 0)
            break;
    }
    int read_error = ferror(in);
    fclose(in);
    int rc = -1;
    checkpoint_header h, want;
    if (read_error) {
        wff_fail(err, "cannot read checkpoint %s", path);
        goto done;
    }
    if (size < sizeof checkpoint_magic || memcmp(buf, checkpoint_magic, sizeof checkpoint_magic)) {
        wff_fail(err, "%s is not a wovenff checkpoint (no WFFSTATE magic)", path);
        goto done;
    }
    if (size < sizeof h + sizeof(uint64_t)) {
        wff_fail(err, "checkpoint %s is truncated (%zu bytes)", path, size);
        goto done;
    }
    memcpy(&h, buf, sizeof h);
    if (h.byte_order != BYTE_ORDER_MARK) {
        wff_fail(err, "checkpoint %s was written on a machine with another byte order", path);
        goto done;
    }
    if (h.version != WFF_CHECKPOINT_VERSION || h.header_size != sizeof h) {
        wff_fail(err, "checkpoint %s has format version %u (header %u bytes); this build reads "
                 "version %d (header %zu bytes)", path, h.version, h.header_size,
                 WFF_CHECKPOINT_VERSION, sizeof h);
        goto done;
    }
    if (h.payload_size != size - sizeof h - sizeof(uint64_t)) {
        wff_fail(err, "checkpoint %s is truncated or has trailing data (%zu bytes, header says "
                 "%llu)", path, size, (unsigned long long)(sizeof h + h.payload_size + 8));
        goto done;
    }
    uint64_t stored;
    memcpy(&stored, buf + size - sizeof stored, sizeof stored);
    if (fnv1a(FNV_START, buf, size - sizeof stored) != stored) {
        wff_fail(err, "checkpoint %s is corrupt (checksum mismatch)", path);
        goto done;
    }
    fingerprint(m, &want);
    if (h.n_nodes != want.n_nodes || h.n_tris != want.n_tris || h.n_quads != want.n_quads ||
        h.n_gamma != want.n_gamma) {
        wff_fail(err, "checkpoint %s was written for a model of %d nodes, %d triangles, %d "
                 "quadrilaterals; this model has %d nodes, %d triangles, %d quadrilaterals "
                 "(another mesh)", path, h.n_nodes, h.n_tris, h.n_quads, want.n_nodes,
                 want.n_tris, want.n_quads);
        goto done;
    }
    const char *why = hash_mismatch(&h, &want);
    if (why) {
        wff_fail(err, "checkpoint %s does not match this model: %s", path, why);
        goto done;
    }
    if (h.dt_factor != want.dt_factor || h.dt_interval != want.dt_interval ||
        h.symmetry_factor != want.symmetry_factor || h.reference_path != want.reference_path) {
        wff_fail(err, "checkpoint %s has solver settings dtfactor %g, dtinterval %d, symmetry "
                 "%g, reference_path %d; this model has %g, %d, %g, %d", path, h.dt_factor,
                 h.dt_interval, h.symmetry_factor, h.reference_path, want.dt_factor,
                 want.dt_interval, want.symmetry_factor, want.reference_path);
        goto done;
    }
    if (h.projectile_active != want.projectile_active ||
        h.projectile_radius != want.projectile_radius ||
        h.projectile_mass != want.projectile_mass || h.projectile_mu != want.projectile_mu) {
        if (h.projectile_active && want.projectile_active)
            wff_fail(err, "checkpoint %s has a projectile of radius %g m, mass %g kg, mu %g; "
                     "this model's has %g m, %g kg, %g", path, h.projectile_radius,
                     h.projectile_mass, h.projectile_mu, want.projectile_radius,
                     want.projectile_mass, want.projectile_mu);
        else
            wff_fail(err, "checkpoint %s was written %s a projectile, this model has %s", path,
                     h.projectile_active ? "with" : "without",
                     want.projectile_active ? "one" : "none");
        goto done;
    }
    if (h.n_candidates < 0 || h.n_candidates > h.n_nodes) {
        wff_fail(err, "checkpoint %s is corrupt (%d contact candidates)", path, h.n_candidates);
        goto done;
    }
    state_field fields[MAX_STATE_FIELDS];
    int nf = state_fields(m, h.n_candidates, fields);
    size_t payload = 0;
    for (int i = 0; i < nf; i++)
        payload += fields[i].size * fields[i].count;
    if (payload != h.payload_size) {
        wff_fail(err, "checkpoint %s: state of %llu bytes, this model's is %zu", path,
                 (unsigned long long)h.payload_size, payload);
        goto done;
    }
    const unsigned char *at = buf + sizeof h;
    for (int i = 0; i < nf; i++) {
        size_t bytes = fields[i].size * fields[i].count;
        if (bytes)
            memcpy(fields[i].data, at, bytes);
        at += bytes;
    }
    rc = 0;
done:
    free(buf);
    return rc;
}

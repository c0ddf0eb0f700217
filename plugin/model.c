/* model.c: a model's set-up and settings: create and free, the preload,
 * the mesh's named groups, fixed and prescribed DOFs, the friction clamp's
 * nodes and forces (docs/model.md §15), reactions, solver settings by name
 * and the nearest node. Knows the mesh, the material and the elements;
 * nothing of how a step is taken (integrator.c), of contact (contact.c),
 * of output fields or checkpoints, of cells by name or of FreeFEM. */
#include "part.h"
#include "clamp.h"
#include "contact.h"
#include "erosion.h"
#include "zones.h"
#include "distribute.h"
#include "wovenff/material.h"
#include "wovenff/kernel.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

wff_model *wff_model_new(void)
{
    return calloc(1, sizeof(wff_model));
}

void wff_model_delete(wff_model *m)
{
    if (m)
        wff_model_free(m);
    free(m);
}

int wff_model_dof_count(const wff_model *m) { return m->n_dofs; }
int wff_model_node_count(const wff_model *m) { return m->n_nodes; }
int wff_model_triangle_count(const wff_model *m) { return m->el.n_tris; }
int wff_model_quad_count(const wff_model *m) { return m->el.n_quads; }
long wff_model_step_count(const wff_model *m) { return m->step; }
int wff_model_thread_count(const wff_model *m) { return m->el.n_threads; }
int wff_model_has_projectile(const wff_model *m) { return m->projectile.active; }
const wff_mesh *wff_model_mesh(const wff_model *m) { return &m->mesh; }
const wff_material *wff_model_material(const wff_model *m) { return &m->mat; }

void wff_model_free(wff_model *m)
{
    wff_dist_free(m);
    wff_comm_free(&m->comm);
    free(m->u);
    free(m->v);
    free(m->f);
    free(m->mass);
    free(m->dof_kind);
    free(m->v_prescribed);
    free(m->state);
    free(m->reaction);
    free(m->contact_force);
    free(m->projectile.candidates);
    free(m->projectile.contact_node);
    free(m->projectile.impulse);
    free(m->clamp.node);
    free(m->clamp.normal_force);
    free(m->clamp.impulse);
    free(m->operator_scratch);
    free(m->snapshot[0]);
    free(m->snapshot[1]);
    free(m->bc);
    wff_parts_free(m); /* each part what it allocated (part.h) */
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

static void set_dof(wff_model *m, int node, void *data);

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

int wff_model_alloc_arrays(wff_model *m)
{
    size_t nd = (size_t)m->n_dofs;
    size_t nq = wff_elements_point_count(&m->el);
    m->u = calloc(nd, sizeof(double));
    m->v = calloc(nd, sizeof(double));
    m->f = calloc(nd, sizeof(double));
    m->mass = calloc(nd, sizeof(double));
    m->dof_kind = calloc(nd, 1);
    m->v_prescribed = calloc(nd, sizeof(double));
    m->reaction = calloc(nd, sizeof(double));
    m->contact_force = calloc(nd, sizeof(double));
    size_t ns = nq * (size_t)m->n_state;
    m->state = calloc(ns ? ns : 1, sizeof(double)); /* every state starts at 0 */
    return m->u && m->v && m->f && m->mass && m->dof_kind && m->v_prescribed && m->reaction &&
           m->contact_force &&
                   m->state
               ? 0
               : -1;
}

int wff_model_setup(wff_model *m, wff_error *err)
{
    m->n_nodes = m->mesh.n_nodes;
    m->n_dofs = D * m->n_nodes;
    m->n_state = m->mat.n_state;
    if (wff_model_alloc_arrays(m)) {
        wff_model_free(m);
        return wff_fail(err, "out of memory for a model of %d nodes", m->n_nodes);
    }
    m->em.mat = &m->mat;
    m->em.F_pre[0] = m->em.F_pre[3] = 1;
    m->em.J_pre = 1;
    m->preload[0] = m->preload[3] = 1;
    wff_elements_masses(&m->el, &m->em, m->n_nodes, m->mass);
    wff_model_sum_fabric_mass(m);
    /* amplitude DOFs of a cell without amplitudes stay put */
    if (wff_cell_amplitudes(m->mat.cell) == 0)
        for (int n = 0; n < m->n_nodes; n++)
            m->dof_kind[D * n + 3] = m->dof_kind[D * n + 4] = WFF_DOF_FIXED;
    m->dt_factor = 0.8;
    m->travel_fraction = WFF_TRAVEL;
    if (wff_comm_default(&m->comm, err)) { /* (every rank of mpirun's, or one) */
        wff_model_free(m);
        return -1;
    }
    m->travel_share = 1; /* (before a step: as tight as the limit goes) */
    m->dt_interval = 20;
    m->snapshot_step[0] = m->snapshot_step[1] = -1;
    m->symmetry_factor = 1;
    if (wff_erosion_default(m, err)) { /* erosion on (both families) when the points carry damage */
        wff_model_free(m);
        return -1;
    }
    wff_model_set_element_lengths(m); /* a state the element code sets (cell.h) */
    wff_model_stored_energy_now(m);
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
    wff_model_sum_fabric_mass(m);
    if (m->clamp.n && wff_clamp_share(m, err)) /* the new masses: order of calls free */
        return -1;
    if (wff_cell_amplitudes(m->mat.cell))
        for (int n = 0; n < m->n_nodes; n++) {
            m->u[D * n + 3] = dA0[0];
            m->u[D * n + 4] = dA0[1];
        }
    if (m->zones && (wff_zones_preload_changed(m, err) || /* matched zone preloads follow */
                     wff_model_masses_changed(m, err)))
        return -1;
    wff_model_stored_energy_now(m);
    return 0;
}

int wff_angle_degrees(double deg, const char *what, double *reduced, double *theta,
                      wff_error *err)
{
    if (!isfinite(deg))
        return wff_fail(err, "%s = %g: must be a finite angle in degrees", what, deg);
    if (fabs(deg) > WFF_ANGLE_MAX_DEG)
        return wff_fail(err, "%s = %g deg: beyond +-1e6 degrees (%.0f turns), no angle a user "
                        "means, and a double holds it only to within %.2g deg: give it "
                        "modulo 360", what, deg, WFF_ANGLE_MAX_DEG / 360,
                        nextafter(fabs(deg), INFINITY) - fabs(deg));
    double r = fmod(deg, 360.0); /* exact */
    if (r == 0)
        r = 0; /* (-0: 0) */
    double right_angles = r / 90;
    *reduced = r;
    *theta = right_angles == nearbyint(right_angles) ? right_angles * M_PI_2 : r * (M_PI / 180);
    return 0;
}

int wff_model_set_orientation(wff_model *m, double theta, wff_error *err)
{
    if (!isfinite(theta))
        return wff_fail(err, "orientation = %g rad: must be a finite angle", theta);
    if (fabs(theta) > WFF_ANGLE_MAX_DEG * (M_PI / 180))
        return wff_fail(err, "orientation = %g rad (%g deg): an angle beyond +-1e6 degrees is "
                        "refused (give it modulo 360)", theta, theta * 180 / M_PI);
    if ((m->step > 0 || m->v_half_valid) && theta != m->em.orientation)
        return wff_fail(err, "orientation = %g deg: the run has started (t = %g s, step %ld) "
                        "at %g deg; the warp direction is part of the initial state: set it "
                        "before the first step", theta * 180 / M_PI, m->time, m->step,
                        m->em.orientation * 180 / M_PI);
    m->em.orientation = theta;
    wff_parts_follow(m, "orientation", theta); /* (a pack: every ply) */
    /* the map the kernels apply (det unchanged: J_pre, the masses and a zone's
     * matched preload, a material-frame state, stay) */
    wff_orientation_map(theta, m->preload, m->em.F_pre);
    wff_model_stored_energy_now(m);
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

/* The boundary condition just set by group, kept so that a mesh transfer
 * (remesh.c) can set it again on the new mesh. */
static int log_bc(wff_model *m, int kind, const char *group, int component, double value,
                  double mu, wff_error *err)
{
    wff_bc_record *bc = realloc(m->bc, sizeof *bc * (size_t)(m->n_bc + 1));
    if (!bc)
        return wff_fail(err, "out of memory recording a boundary condition on '%s'", group);
    m->bc = bc;
    wff_bc_record *r = &bc[m->n_bc++];
    memset(r, 0, sizeof *r);
    snprintf(r->group, sizeof r->group, "%s", group);
    r->kind = kind;
    r->component = component;
    r->value = value;
    r->mu = mu;
    return 0;
}

int wff_model_fix_group(wff_model *m, const char *group, int component, wff_error *err)
{
    if (check_component(component, err))
        return -1;
    dof_setting s = {component, WFF_DOF_FIXED, 0, -1};
    int count = set_group_dofs(m, group, &s, "fix", err);
    if (count > 0 && log_bc(m, WFF_DOF_FIXED, group, component, 0, 0, err))
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
    if (count > 0 && log_bc(m, WFF_DOF_PRESCRIBED, group, component, velocity, 0, err))
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
    free(m->clamp.impulse);
    m->clamp.n = 0;
    m->clamp.node = malloc(sizeof(int) * (size_t)m->n_nodes);
    m->clamp.normal_force = malloc(sizeof(double) * (size_t)m->n_nodes);
    m->clamp.impulse = calloc(2 * (size_t)m->n_nodes, sizeof(double));
    if (!m->clamp.node || !m->clamp.normal_force || !m->clamp.impulse)
        return wff_fail(err, "out of memory");
    int count = for_group_nodes(m, group, err, add_clamp_node, NULL);
    if (count < 0)
        return -1;
    m->clamp.mu = mu;
    m->clamp.force_whole = normal_force;
    m->clamp.region = wff_mesh_group_tag(&m->mesh, 2, group);
    m->clamp.radius = 0;
    m->clamp.edge_reaction = 0;
    if (wff_clamp_share(m, err))
        return -1;
    if (log_bc(m, WFF_BC_CLAMP, group, 0, normal_force, mu, err))
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

/* ---- the model's own settings (wff_model_set_option), one {name, check, apply}
 * row each; the parts extend them with their own tables (part.h) ---- */

/* A value that must be 0 or 1 (what each means in `meaning`). */
static int check_flag(const char *name, double value, const char *meaning, wff_error *err)
{
    if (value != 0 && value != 1)
        return wff_fail(err, "%s = %g: must be %s", name, value, meaning);
    return 0;
}

static int check_dtfactor(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    if (!(value > 0 && value <= 2))
        return wff_fail(err, "dtfactor = %g: must be in (0, 2] (1 is the stability limit)",
                        value);
    return 0;
}

static int apply_dtfactor(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->dt_factor = value;
    if (m->dt_stable > 0)
        wff_step_replan(m, value * m->dt_stable); /* (after steps: v^{n+½} for it) */
    return 0;
}

static int check_t_stop(const wff_model *m, double value, wff_error *err)
{
    if (!(value >= 0) || !isfinite(value))
        return wff_fail(err, "t_stop = %g s: must be a finite time >= 0 (0: none)", value);
    if (value > 0 && value < m->time)
        return wff_fail(err, "t_stop = %.9g s: before the model's time %.9g s", value, m->time);
    return 0;
}

static int apply_t_stop(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->t_stop = value;
    return 0;
}

static int check_dtinterval(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    if (!(value >= 1 && value <= 1e6) || value != floor(value))
        return wff_fail(err, "dtinterval = %g: must be a whole number of steps >= 1", value);
    return 0;
}

static int apply_dtinterval(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->dt_interval = (int)value;
    return 0;
}

static int check_symmetry(const wff_model *m, double value, wff_error *err)
{
    if (value != 1 && value != 2 && value != 4)
        return wff_fail(err, "symmetry = %g: must be 1 (full), 2 (half) or 4 (quarter)", value);
    if ((m->step > 0 || m->v_half_valid) && value != m->symmetry_factor)
        return wff_fail(err, "symmetry = %g: the run has started (step %ld); set the "
                        "symmetry before the first step", value, m->step);
    return 0;
}

/* The projectile's modelled mass and the clamp's shares follow (both kept as
 * they were when either refuses). */
static int apply_symmetry(wff_model *m, double value, wff_error *err)
{
    double old = m->symmetry_factor;
    m->symmetry_factor = value;
    if (wff_contact_symmetry_changed(m, err)) {
        m->symmetry_factor = old;
        return -1;
    }
    if (m->clamp.n && wff_clamp_share(m, err)) {
        wff_error ignored;
        m->symmetry_factor = old;
        wff_contact_symmetry_changed(m, &ignored);
        wff_clamp_share(m, &ignored);
        return -1;
    }
    return 0;
}

static int check_threads(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    if (value != floor(value))
        return wff_fail(err, "threads = %g: a whole number", value);
    return 0;
}

static int apply_threads(wff_model *m, double value, wff_error *err)
{
    if (value == 0) /* the default: the cores this process may use */
        value = wff_default_threads() < m->el.max_threads ? wff_default_threads()
                                                          : m->el.max_threads;
    return wff_elements_set_threads(&m->el, (int)value, err);
}

static int check_amplitude_mass_factor(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    if (!(value >= 1 && value <= 1e6))
        return wff_fail(err, "amplitude_mass_factor = %g: must be >= 1 (1 is the paper's "
                        "1/6 of the displacement mass)", value);
    return 0;
}

static int apply_amplitude_mass_factor(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->em.amplitude_mass_factor = value;
    wff_zones_masses(m);
    return 0;
}

static int check_travel_limit(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    return check_flag("travel_limit", value, "1 (the amplitudes' travel per step limited, "
                      "docs/model.md §12) or 0 (dtfactor x the stable step only)", err);
}

static int apply_travel_limit(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->travel_off = value == 0;
    return 0;
}

static int check_travel_fraction(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    if (!(value > 0 && value <= 2))
        return wff_fail(err, "travel_fraction %g: must be in (0, 2] (the share of the cell's "
                        "amplitude length a free amplitude may travel in one step at dtfactor 1; "
                        "default %g; travel_limit 0 switches the limit off)", value, WFF_TRAVEL);
    return 0;
}

static int apply_travel_fraction(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->travel_fraction = value;
    return 0;
}

static int check_adaptive_step(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    return check_flag("adaptive_step", value, "1 (an instability halves dtfactor and the run "
                      "goes on from the last good state) or 0 (it stops the run)", err);
}

static int apply_adaptive_step(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->adaptive = value != 0;
    return 0;
}

static int check_static_amplitudes(const wff_model *m, double value, wff_error *err)
{
    if (check_flag("static_amplitudes", value, "0 (dynamic nodal amplitudes, the paper) or "
                   "1 (balanced at every point, King 2005)", err))
        return -1;
    if (value == 1 && m->zones)
        return wff_fail(err, "static_amplitudes: the model has zonal materials; zones keep "
                        "the amplitudes dynamic");
    if (value == 1 && wff_cell_amplitudes(m->mat.cell) == 0)
        return wff_fail(err, "static_amplitudes: cell '%s' has no amplitudes",
                        wff_cell_name(m->mat.cell));
    return 0;
}

static int apply_static_amplitudes(wff_model *m, double value, wff_error *err)
{
    if (value == 1) { /* first guess: the amplitudes of node 0 (the preload's) */
        const double guess[2] = {m->u[3], m->u[4]};
        return wff_elements_static_amplitudes(&m->el, &m->em, guess, err);
    }
    m->em.static_amplitudes = 0;
    return 0;
}

static int check_contact_search(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    return check_flag("contact_search", value, "1 (only nodes the projectile can reach) or 0 "
                      "(every node, every step)", err);
}

static int apply_contact_search(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->projectile.search_all = value == 0;
    return 0;
}

static int check_reference_path(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    return check_flag("reference_path", value, "0 (cell fast path where there is one) or 1 "
                      "(plain evaluate)", err);
}

static int apply_reference_path(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->em.reference_path = (int)value;
    return 0;
}

static int check_clamp_radius(const wff_model *m, double value, wff_error *err)
{
    if (m->clamp.n == 0)
        return wff_fail(err, "clamp_radius: no friction clamp yet (set the clamp first)");
    if (!(value >= 0) || !isfinite(value))
        return wff_fail(err, "clamp_radius = %g: must be >= 0 m (0: the whole clamp)", value);
    return 0;
}

static int apply_clamp_radius(wff_model *m, double value, wff_error *err)
{
    double before = m->clamp.radius;
    m->clamp.radius = value;
    if (wff_clamp_share(m, err)) { /* no node within: keep the force as it was */
        wff_error ignored;
        m->clamp.radius = before;
        wff_clamp_share(m, &ignored);
        return -1;
    }
    return 0;
}

static int check_orientation(const wff_model *m, double value, wff_error *err)
{
    (void)m;
    double reduced, theta;
    return wff_angle_degrees(value, "orientation", &reduced, &theta, err);
}

/* degrees, reduced modulo 360 first; exact multiples of 90 degrees: exactly k pi/2 */
static int apply_orientation(wff_model *m, double value, wff_error *err)
{
    double reduced, theta;
    if (wff_angle_degrees(value, "orientation", &reduced, &theta, err))
        return -1;
    return wff_model_set_orientation(m, theta, err);
}

static int check_clamp_edge_reaction(const wff_model *m, double value, wff_error *err)
{
    if (m->clamp.n == 0)
        return wff_fail(err, "clamp_edge_reaction: no friction clamp yet (set the clamp "
                        "first)");
    return check_flag("clamp_edge_reaction", value, "0 (friction from the clamping force "
                      "only) or 1 (also mu |R_z|)", err);
}

static int apply_clamp_edge_reaction(wff_model *m, double value, wff_error *err)
{
    (void)err;
    m->clamp.edge_reaction = (int)value;
    return 0;
}

static const wff_setting model_settings[] = {
    {"dtfactor", check_dtfactor, apply_dtfactor},
    {"dtinterval", check_dtinterval, apply_dtinterval},
    {"t_stop", check_t_stop, apply_t_stop},
    {"symmetry", check_symmetry, apply_symmetry},
    {"reference_path", check_reference_path, apply_reference_path},
    {"threads", check_threads, apply_threads},
    {"amplitude_mass_factor", check_amplitude_mass_factor, apply_amplitude_mass_factor},
    {"static_amplitudes", check_static_amplitudes, apply_static_amplitudes},
    {"travel_limit", check_travel_limit, apply_travel_limit},
    {"travel_fraction", check_travel_fraction, apply_travel_fraction},
    {"adaptive_step", check_adaptive_step, apply_adaptive_step},
    {"contact_search", check_contact_search, apply_contact_search},
    {"orientation", check_orientation, apply_orientation},
    {"clamp_radius", check_clamp_radius, apply_clamp_radius},
    {"clamp_edge_reaction", check_clamp_edge_reaction, apply_clamp_edge_reaction},
    {NULL, NULL, NULL},
};

/* The row named key: the model's own first, then the parts' in list order. */
static const wff_setting *find_setting(const char *key)
{
    for (const wff_setting *s = model_settings; s->name; s++)
        if (strcmp(s->name, key) == 0)
            return s;
    return wff_parts_setting(key);
}

int wff_model_set_option(wff_model *m, const char *key, double value, wff_error *err)
{
    const wff_setting *s = find_setting(key);
    if (!s) {
        char known[WFF_ERROR_MAX / 2] = "";
        size_t used = 0;
        for (const wff_setting *r = model_settings; r->name; r++)
            used += (size_t)snprintf(known + used, used < sizeof known ? sizeof known - used : 0,
                                     "%s%s", used ? ", " : "", r->name);
        if (used < sizeof known)
            wff_parts_setting_names(known + used, sizeof known - used, used > 0);
        return wff_fail(err, "unknown solver setting '%s' (known: %s)", key, known);
    }
    if (s->check && s->check(m, value, err))
        return -1;
    return s->apply(m, value, err);
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

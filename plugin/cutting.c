/* cutting.c: the nose's contact pressure on the fabric, a part of the step
 * (cutting.h; docs/model.md §25). After every contact's correction of the step
 * (the projectile's, and a pack's ply solve, which adds its own impulses to
 * the nodes it holds on the nose), node n's pressure is
 *
 *   p_n = ⟨−(f_n − j_n/Δt_mid)·ĵ_n⟩ / A_n,
 *
 * j_n the nose's impulse on the node in the step (normal and friction, ĵ_n its
 * direction), f_n the node's force (its yarns', the ply contact's), so
 * f_n − j_n/Δt_mid is what the rest of the model presses the node onto the
 * nose with, and A_n the node's tributary reference area (a third of each
 * triangle's area, a quarter of each quad's). Not |j_n|/(Δt_mid A_n): a node
 * the nose picks up takes at once an impulse ρ_A v A_n, and that spike,
 * ρ_A v/Δt (25 MPa at 10 m/s on the coarse mesh, for any nose), is the
 * step's, not a pressure the yarn feels; in steady contact the two agree. On
 * a flat nose's edge the force is borne by a strip narrower than the node
 * (edge_share). Every point of an element round such a node gets the largest
 * of its nodes' p_n in its contact_pressure state (press_element), and the
 * points the nose touched in the step before go back to 0 first: the force pass of the next step reads them
 * (yarn failure's transverse cutting, yarn_failure.h), one step behind the
 * contact, as the projectile's contact itself is behind the forces. Pointwise
 * physics stays in the cell: this file only measures the pressure. Knows the
 * model's arrays, the projectile and the zones; nothing of FreeFEM. */
#include "cutting.h"
#include "plies.h"
#include "zones.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The narrowest contact strip under an edge, m: a KM2 fibre's diameter, ~12 µm
 * (Cheng, Chen & Weerasooriya 2005), for a sharp edge (r_e = 0). */
#define WFF_CUTTING_FIBRE 12e-6

struct wff_cutting {
    int on;                 /* 1: some element's material carries contact_pressure */
    double *node_area;      /* per node: its tributary reference area, m² */
    double *node_pressure;  /* per node: this step's contact pressure, Pa (0 elsewhere) */
    int *slot;              /* per element: its material's contact_pressure state, -1 none */
    int *node_elements;     /* per node: its elements, from node_start[n] (CSR) */
    int *node_start;        /* n_nodes + 1 */
    int *pressed;           /* elements whose points hold a pressure now */
    int n_pressed;
    unsigned char *listed;  /* per element: 1 while in pressed */
    double max, peak;       /* Pa: the last step's largest nodal pressure, the run's */
};

static void cutting_free(wff_model *m)
{
    struct wff_cutting *c = m->cutting;
    if (!c)
        return;
    free(c->node_area), free(c->node_pressure), free(c->slot), free(c->node_elements);
    free(c->node_start), free(c->pressed), free(c->listed);
    free(c);
    m->cutting = NULL;
}

/* The set-up at the first correction: areas, each node's elements, each
 * element's state slot. -1 (err set) if out of memory. */
static int cutting_init(wff_model *m, wff_error *err)
{
    const int nt = m->el.n_tris, n_el = nt + m->el.n_quads, nn = m->n_nodes;
    struct wff_cutting *c = calloc(1, sizeof *c);
    if (!c)
        return wff_fail(err, "contact pressure: out of memory");
    m->cutting = c;
    c->node_area = calloc((size_t)nn, sizeof(double));
    c->node_pressure = calloc((size_t)nn, sizeof(double));
    c->slot = malloc(sizeof(int) * (size_t)n_el);
    c->node_start = calloc((size_t)nn + 1, sizeof(int));
    c->pressed = malloc(sizeof(int) * (size_t)n_el);
    c->listed = calloc((size_t)n_el, 1);
    if (!c->node_area || !c->node_pressure || !c->slot || !c->node_start || !c->pressed ||
        !c->listed)
        return wff_fail(err, "contact pressure: out of memory");
    const wff_material *last = NULL;
    int slot = -1;
    for (int e = 0; e < n_el; e++) {
        wff_element_material scratch;
        const wff_material *mat = wff_zones_element_material(m, e, &scratch)->mat;
        if (mat != last)
            slot = wff_material_state_index(mat, WFF_CONTACT_PRESSURE_STATE), last = mat;
        c->slot[e] = slot;
        c->on |= slot >= 0;
        const int *nodes, np = wff_element_nodes(&m->el, e, &nodes);
        const double area = wff_element_area(&m->el, e);
        for (int a = 0; a < np; a++) {
            c->node_area[nodes[a]] += area / np;
            c->node_start[nodes[a] + 1]++;
        }
    }
    for (int n = 0; n < nn; n++)
        c->node_start[n + 1] += c->node_start[n];
    c->node_elements = malloc(sizeof(int) * (size_t)(c->node_start[nn] > 0 ? c->node_start[nn] : 1));
    int *fill = malloc(sizeof(int) * (size_t)nn);
    if (!c->node_elements || !fill) {
        free(fill);
        return wff_fail(err, "contact pressure: out of memory");
    }
    memcpy(fill, c->node_start, sizeof(int) * (size_t)nn);
    for (int e = 0; e < n_el; e++) {
        const int *nodes, np = wff_element_nodes(&m->el, e, &nodes);
        for (int a = 0; a < np; a++)
            c->node_elements[fill[nodes[a]]++] = e; /* (ascending e per node) */
    }
    free(fill);
    /* points holding a pressure already (a state loaded from a checkpoint) */
    for (int e = 0; e < n_el && c->on; e++) {
        if (c->slot[e] < 0)
            continue;
        const int np = e < nt ? WFF_TRI_POINTS : WFF_QUAD_POINTS;
        const double *state = m->state + (size_t)m->n_state * wff_element_first_point(nt, e);
        int held = 0;
        for (int q = 0; q < np; q++)
            held |= state[m->n_state * q + c->slot[e]] != 0;
        if (held)
            c->listed[e] = 1, c->pressed[c->n_pressed++] = e;
    }
    return 0;
}

/* The share of node n's area that bears its contact force: 1, except at a flat
 * nose's rounded edge (the node's patch, √A_n wide, reaching R − r_e from the
 * axis: on a mesh coarser than the edge the node that takes the membrane's kink
 * over the edge lies on the face short of it), where the
 * contact strip across the edge is at most the edge's quarter arc r_e π/2 (at
 * least WFF_CUTTING_FIBRE wide), narrower than the node's width √A_n on a mesh
 * that does not resolve the edge: min(1, max(r_e π/2, fibre)/√A_n). Without it
 * the edge's pressure would be the mesh's (its force over a whole node's area),
 * a tenth or less of what the edge puts on a yarn (docs/model.md §25). */
static double edge_share(const wff_model *m, const struct wff_cutting *c, int n)
{
    const wff_projectile *p = &m->projectile;
    if (p->nose != WFF_NOSE_FLAT)
        return 1;
    const double x = m->mesh.xy[2 * n] + m->u[D * n] - p->axis[0];
    const double y = m->mesh.xy[2 * n + 1] + m->u[D * n + 1] - p->axis[1];
    const double strip = fmax(0.5 * M_PI * p->edge_radius, WFF_CUTTING_FIBRE);
    const double width = sqrt(c->node_area[n]);
    if (hypot(x, y) + width < p->radius - p->edge_radius)
        return 1; /* on the flat face, its patch short of the edge */
    return strip < width ? strip / width : 1;
}

/* Node n's yarns' force (the force pass's: f less every part's impulses of the
 * step) along the unit vector e. Without the parts' record (a caller's own loop,
 * operators.c), f less the nose's impulse j over dt_mid. */
static double yarn_force_along(const wff_model *m, int n, const double e[3], const double *j,
                               double dt_mid)
{
    double along = 0;
    for (int i = 0; i < 3; i++) {
        const int k = D * n + i;
        if (m->dof_kind[k] != WFF_DOF_FREE)
            continue;
        const double parts = m->contact_force ? m->contact_force[k] : j[i] / dt_mid;
        along += (m->f[k] - parts) * e[i];
    }
    return along;
}

/* The force pressing node n onto the nose (N, the nose's impulse j on it, |j|
 * = size): its own yarns' pull against the nose's push, and in a pack the pull
 * of the same node of each ply behind it as long as the column is held together
 * by the ply contact (a pair impulse on that node this step): the plies behind
 * press on the nose through this one. The yarns' forces, not the contacts'
 * impulses: a node the nose or a ply picks up takes an impulse m v at once, the
 * spike ρ_A v/Δt of the step, which is not a pressure the yarn feels. */
static double pressing_force(const wff_model *m, int n, const double j[3], double size,
                             double dt_mid)
{
    const double e[3] = {j[0] / size, j[1] / size, j[2] / size};
    double force = -yarn_force_along(m, n, e, j, dt_mid);
    const struct wff_pack *P = m->pack;
    if (!P || P->n < 2 || !P->impulse)
        return force;
    const double none[3] = {0, 0, 0};
    for (int q = n / P->nodes + 1; q < P->n; q++) {
        const int b = n + (q - n / P->nodes) * P->nodes; /* the node behind, in ply q */
        const double *pair = P->impulse + 3 * b;
        if (pair[0] == 0 && pair[1] == 0 && pair[2] == 0)
            break; /* the column is open here */
        force -= yarn_force_along(m, b, e, none, dt_mid);
    }
    return force;
}

/* Element e's points' contact_pressure: the largest of its nodes' pressures, at
 * every point. The edge's line crosses the patch of the node that carries it,
 * so the elements round that node; the element is the smallest piece the mesh
 * can cut (erosion takes an element whose points have all ruptured), and a cut
 * at the pressed node's point alone would leave the element standing. Returns
 * that pressure (0: no node of e pressed now). */
static double press_element(wff_model *m, const struct wff_cutting *c, int e)
{
    const int nt = m->el.n_tris, ns = m->n_state, slot = c->slot[e];
    double *state = m->state + (size_t)ns * wff_element_first_point(nt, e) + slot;
    const int *nodes, np = wff_element_nodes(&m->el, e, &nodes);
    double most = 0;
    for (int a = 0; a < np; a++)
        most = fmax(most, c->node_pressure[nodes[a]]);
    for (int q = 0; q < (e < nt ? WFF_TRI_POINTS : WFF_QUAD_POINTS); q++)
        state[ns * q] = most;
    return most;
}

static int cutting_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    (void)dt;
    const wff_projectile *p = &m->projectile;
    if (!p->active)
        return 0;
    if (!m->cutting && cutting_init(m, err))
        return -1;
    struct wff_cutting *c = m->cutting;
    const double *nose = m->pack && m->pack->nose_impulse ? m->pack->nose_impulse : NULL;
    c->max = 0;
    for (int k = 0; k < p->n_contact; k++) {
        const int n = p->contact_node[k];
        double j[3], j2 = 0, along = 0;
        for (int i = 0; i < 3; i++) {
            j[i] = p->impulse[3 * k + i] + (nose ? nose[3 * n + i] : 0);
            j2 += j[i] * j[i];
        }
        if (j2 > 0 && dt_mid > 0)
            along = pressing_force(m, n, j, sqrt(j2), dt_mid); /* N, > 0 onto the nose */
        const double pressure = c->node_area[n] > 0 && along > 0
                                    ? along / (c->node_area[n] * edge_share(m, c, n)) : 0;
        c->node_pressure[n] = pressure;
        c->max = fmax(c->max, pressure);
    }
    c->peak = fmax(c->peak, c->max);
    if (c->on) {
        /* last step's pressed elements back to 0 (or to this step's), then this step's */
        for (int k = 0; k < p->n_contact; k++) {
            const int n = p->contact_node[k];
            for (int s = c->node_start[n]; s < c->node_start[n + 1]; s++) {
                const int e = c->node_elements[s];
                if (c->slot[e] >= 0 && !c->listed[e])
                    c->listed[e] = 1, c->pressed[c->n_pressed++] = e;
            }
        }
        /* pressed now, or back to 0 and off the list */
        int kept = 0;
        for (int k = 0; k < c->n_pressed; k++) {
            const int e = c->pressed[k];
            if (press_element(m, c, e) > 0)
                c->pressed[kept++] = e;
            else
                c->listed[e] = 0;
        }
        c->n_pressed = kept;
    }
    for (int k = 0; k < p->n_contact; k++)
        c->node_pressure[p->contact_node[k]] = 0;
    return 0;
}

/* A mesh transfer does not carry the points' pressures (they would be held at
 * the old nodes' values where the nose has gone): refused with cutting on. */
static int cutting_refuses_remesh(const wff_model *m, char *why, size_t size)
{
    if (!m->cutting || !m->cutting->on)
        return 0;
    snprintf(why, size, "transverse cutting (the material key cutting_pressure) keeps the "
             "nose's contact pressure at every point, which a mesh transfer does not carry: "
             "run without -adapt or without cutting_pressure");
    return 1;
}

/* The new model sets its own up at its first correction. */
static int cutting_carry(const wff_model *from, wff_model *to, wff_error *err)
{
    (void)from, (void)err;
    to->cutting = NULL;
    return 0;
}

static const char *const cutting_value_names[] = {"contact_pressure_max",
                                                  "contact_pressure_peak", NULL};

static void cutting_value(const wff_model *m, const char *key, double *value)
{
    const struct wff_cutting *c = m->cutting;
    *value = !c ? 0 : strcmp(key, "contact_pressure_max") == 0 ? c->max : c->peak;
}

const wff_part_ops wff_cutting_part = {
    .name = "contact_pressure",
    .correct = cutting_correct,
    .value_names = cutting_value_names,
    .value = cutting_value,
    .refuses_remesh = cutting_refuses_remesh,
    .carry = cutting_carry,
    .free = cutting_free,
};

/* clamp.c: the friction clamp (docs/model.md §15): the clamping force shared
 * among the clamped nodes, and the Coulomb correction of a clamped node's
 * in-plane velocity after the velocity update: a part of the step (part.h),
 * the first to correct the velocities (threaded as step_parts.h splits a
 * pass). The clamp's nodes are set by group in model.c
 * (wff_model_clamp_friction); knows the model's arrays only. */
#include "clamp.h"
#include "part.h"
#include "step_parts.h"

#include <math.h>
#include <stdlib.h>

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

/* The clamping force shared among the clamp's nodes: by the area of the
 * elements of the clamp's surface (a third of a triangle, a quarter of a
 * quadrilateral, at each corner) or, for a curve group, by lumped mass; only
 * nodes within clamp.radius of (0, 0) when it is set. */
int wff_clamp_share(wff_model *m, wff_error *err)
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

/* friction clamp: in-plane, two faces, on the node's free in-plane
 * components (a node on a symmetry line slides along it and is held by
 * friction there too) */
double wff_clamp_node(const wff_model *m, double *v, int c, double dt_mid, double *impulse)
{
    double dissipated = 0;
    int n = m->clamp.node[c];
    double *vn = v + D * n;
    if (impulse)
        impulse[0] = impulse[1] = 0;
    int free_x = m->dof_kind[D * n + WFF_UX] == WFF_DOF_FREE;
    int free_y = m->dof_kind[D * n + WFF_UY] == WFF_DOF_FREE;
    double speed = hypot(free_x ? vn[0] : 0, free_y ? vn[1] : 0);
    if (speed == 0)
        return 0;
    /* both faces press with N_a; an out-of-plane load R_z adds to one */
    double pressed = 2 * m->clamp.normal_force[c];
    if (m->clamp.edge_reaction)
        pressed += fabs(m->reaction[D * n + WFF_UZ]);
    double friction = friction_impulse(m->mass[D * n], speed,
                                       m->clamp.mu * pressed * dt_mid, &dissipated);
    double scale = 1 - friction / (m->mass[D * n] * speed);
    if (impulse) /* (what the scaling below takes off the node's momentum) */
        for (int k = 0; k < 2; k++)
            impulse[k] = (k ? free_y : free_x) ? -(1 - scale) * m->mass[D * n] * vn[k] : 0;
    if (free_x)
        vn[0] *= scale;
    if (free_y)
        vn[1] *= scale;
    return dissipated;
}


/* Clamped nodes per part of the threaded pass (step_parts.h). */
#define CLAMP_GRAIN 64

double wff_clamp_correct_all(const wff_model *m, double *v, double dt_mid, int keep)
{
    const int n_clamp = m->clamp.n, parts = wff_part_count(n_clamp, CLAMP_GRAIN);
    double part_dissipated[MAX_PARTS];
#pragma omp parallel for schedule(static) num_threads(wff_pass_threads(m, parts)) if (wff_pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int end = wff_part_begin(n_clamp, parts, k + 1);
        double d = 0;
        for (int c = wff_part_begin(n_clamp, parts, k); c < end; c++)
            d += wff_clamp_node(m, v, c, dt_mid, keep ? m->clamp.impulse + 2 * c : NULL);
        part_dissipated[k] = d;
    }
    return wff_sum_parts(part_dissipated, parts);
}

/* After the velocity update: the Coulomb correction of every clamped node,
 * its impulses kept and added to f as forces over dt_mid (their work: the book
 * op). */
static int clamp_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    (void)dt, (void)err;
    if (!m->clamp.n)
        return 0;
    wff_clamp_correct_all(m, m->v, dt_mid, 1);
    for (int c = 0; c < m->clamp.n; c++) {
        const int n = m->clamp.node[c];
        for (int k = 0; k < 2; k++) {
            m->f[D * n + k] += m->clamp.impulse[2 * c + k] / dt_mid;
            m->contact_force[D * n + k] += m->clamp.impulse[2 * c + k] / dt_mid;
        }
    }
    return 0;
}

/* The book op (part.h): the friction impulses' work at the final velocities,
 * j·(v^{n+½} − ½Δt_before a^n), counted with the friction. */
void wff_clamp_book(wff_model *m, double dt_before, double dt_mid)
{
    double work = 0;
    for (int c = 0; c < m->clamp.n; c++) {
        const int n = m->clamp.node[c];
        for (int k = 0; k < 2; k++) {
            const double j = m->clamp.impulse[2 * c + k];
            if (j == 0)
                continue;
            const int i = D * n + k;
            work += wff_impulse_work(m, i, j, dt_before, dt_mid);
        }
    }
    m->dissipated_friction -= work;
}

const wff_part_ops wff_clamp_part = {
    .name = "friction_clamp",
    .correct = clamp_correct,
    .book = wff_clamp_book,
};

/* contact.c: the rigid projectile (a cylinder with a hemispherical nose
 * moving along +z; docs/model.md §16): its set-up and placement, the search
 * for nodes that may touch it, and the kinematic (hard, inelastic) contact
 * with Coulomb friction as velocity impulses each step. Knows the model's
 * arrays; nothing of cells, elements, the friction clamp or FreeFEM. */
#include "solver_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Predicted penetration, as a fraction of the nose radius, taken as the
 * projectile having passed through the fabric (a step moves a node by far
 * less than this). */
#define RUNAWAY_PENETRATION 0.5

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
    p->impulse_total = 0;
    /* nose tip touching the fabric plane z = 0 */
    return wff_model_place_projectile(m, 0, err);
}

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

/* Nodes whose current in-plane position is near enough the projectile axis
 * to touch it before the next refresh. */
void wff_contact_refresh_candidates(wff_model *m)
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
int wff_contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
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
        /* inverse mass along the normal: free node components and the projectile (z);
         * a node held in every direction along the normal (clamped, fixed) has none:
         * the projectile alone takes the correction, its support the force */
        double w_node = 0;
        for (int i = 0; i < 3; i++)
            if (m->dof_kind[D * n + i] == WFF_DOF_FREE)
                w_node += nrm[i] * nrm[i];
        w_node /= mass;
        double w_total = w_node + nrm[2] * nrm[2] / p->mass;
        if (w_total == 0)
            continue; /* neither side can move along the normal */
        double jn = delta / dt / w_total; /* N·s */
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
        const double j_projectile = j[2]; /* the projectile takes all of it */
        for (int i = 0; i < 3; i++) {
            if (m->dof_kind[D * n + i] != WFF_DOF_FREE) {
                /* a held component: its support takes the contact force */
                m->reaction[D * n + i] -= j[i] / dt_mid;
                j[i] = 0;
            }
            vn[i] += j[i] / mass;
            jc[i] = j[i];
        }
        p->velocity -= j_projectile / p->mass;
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
    p->impulse_total -= p->mass * dv;
    work += p->mass * dv * (p->velocity - 0.5 * dv);
    m->dissipated_friction -= work;
    return 0;
}

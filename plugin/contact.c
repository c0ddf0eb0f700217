/* contact.c: the rigid projectile (moving along +z with its axis at (x, y),
 * or along a path tilted by an obliquity: a cylinder with a hemispherical
 * nose, a flat-faced cylinder with an edge radius, a sphere, or an FSP's
 * chisel; docs/model.md §16): its shapes, set-up and placement,
 * the whole-specimen mass against the symmetry factor, the search
 * for nodes that may touch it, and the kinematic (hard, inelastic) contact
 * with Coulomb friction as velocity impulses each step. Knows the model's
 * arrays; nothing of cells, elements, the friction clamp or FreeFEM. */
#include "contact.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Predicted penetration, as a fraction of the nose radius, taken as the
 * projectile having passed through the fabric (a step moves a node by far
 * less than this). */
#define RUNAWAY_PENETRATION 0.5

/* Penetration δ and outward normal of a point against the hemispherical nose
 * (sphere of the shank radius centred a radius behind the tip) or the shank
 * behind it. The default shape: kept as it was, so runs stay bit for bit. */
static double penetration_hemisphere(const wff_projectile *p, const double x[3],
                                     double normal[3])
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

/* A sphere of radius r whose front point is the tip. */
static double penetration_sphere(const wff_projectile *p, const double x[3], double normal[3])
{
    double d[3] = {x[0] - p->axis[0], x[1] - p->axis[1], x[2] - (p->tip - p->radius)};
    double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (r >= p->radius || r == 0)
        return 0;
    for (int i = 0; i < 3; i++)
        normal[i] = d[i] / r;
    return p->radius - r;
}

/* The flat nose: the set of points within r_e of the core cylinder
 * {ρ <= a, z <= z_c} (a = r − r_e, z_c = tip − r_e), i.e. a flat face of
 * radius a at z = tip, a torus of tube radius r_e round its edge and the
 * shank of radius r behind. Inside the core the depth is r_e plus the depth
 * in the core (to its face or its side); outside, r_e minus the distance to
 * the nearest core point, along the line to it. */
static double penetration_flat(const wff_projectile *p, const double x[3], double normal[3])
{
    const double re = p->edge_radius, a = p->radius - re, zc = p->tip - re;
    double dx = x[0] - p->axis[0], dy = x[1] - p->axis[1], dz = x[2] - zc;
    double rho = hypot(dx, dy);
    if (rho <= a && dz <= 0) { /* inside the core */
        double to_side = a - rho, to_face = -dz;
        if (to_face <= to_side || rho == 0) {
            normal[0] = normal[1] = 0, normal[2] = 1;
            return re + to_face;
        }
        normal[0] = dx / rho, normal[1] = dy / rho, normal[2] = 0;
        return re + to_side;
    }
    double out_r = rho > a ? rho - a : 0, out_z = dz > 0 ? dz : 0;
    double dist = hypot(out_r, out_z);
    if (dist >= re || dist == 0)
        return 0;
    /* radial unit vector (rho > a >= 0 whenever out_r > 0) */
    double er[2] = {out_r > 0 ? dx / rho : 0, out_r > 0 ? dy / rho : 0};
    normal[0] = er[0] * out_r / dist, normal[1] = er[1] * out_r / dist;
    normal[2] = out_z / dist;
    return re - dist;
}

static double penetration_straight(const wff_projectile *p, const double x[3], double normal[3])
{
    switch (p->nose) {
    case WFF_NOSE_FLAT:
        return penetration_flat(p, x, normal);
    case WFF_NOSE_SPHERE:
        return penetration_sphere(p, x, normal);
    case WFF_NOSE_CHISEL:
        return wff_chisel_penetration(p, x, normal);
    default:
        return penetration_hemisphere(p, x, normal);
    }
}

double wff_projectile_penetration(const wff_projectile *p, const double x[3], double normal[3])
{
    if (!p->oblique)
        return penetration_straight(p, x, normal);
    wff_projectile local;
    double y[3];
    wff_projectile_to_frame(p, x, y, &local);
    const double delta = penetration_straight(&local, y, normal);
    if (delta > 0)
        wff_projectile_from_frame(p, normal);
    return delta;
}

/* The signed distance of a point from the projectile's surface (> 0 outside,
 * −δ inside: −wff_projectile_penetration's δ there) and the outward normal at
 * the nearest surface point (for the ply contact's solve, which holds a node
 * on the nose with the plies behind it, inside or just outside). */
static double gap_straight(const wff_projectile *p, const double x[3], double normal[3]);

double wff_projectile_gap(const wff_projectile *p, const double x[3], double normal[3])
{
    if (!p->oblique)
        return gap_straight(p, x, normal);
    wff_projectile local;
    double y[3];
    wff_projectile_to_frame(p, x, y, &local);
    const double gap = gap_straight(&local, y, normal);
    wff_projectile_from_frame(p, normal);
    return gap;
}

static double gap_straight(const wff_projectile *p, const double x[3], double normal[3])
{
    if (p->nose == WFF_NOSE_CHISEL)
        return -wff_chisel_depth(p, x, normal);
    if (p->nose == WFF_NOSE_FLAT) {
        const double re = p->edge_radius, a = p->radius - re, zc = p->tip - re;
        const double dx = x[0] - p->axis[0], dy = x[1] - p->axis[1], dz = x[2] - zc;
        const double rho = hypot(dx, dy);
        if (rho <= a && dz <= 0) { /* inside the core: as penetration_flat */
            const double to_side = a - rho, to_face = -dz;
            if (to_face <= to_side || rho == 0) {
                normal[0] = normal[1] = 0, normal[2] = 1;
                return -(re + to_face);
            }
            normal[0] = dx / rho, normal[1] = dy / rho, normal[2] = 0;
            return -(re + to_side);
        }
        const double out_r = rho > a ? rho - a : 0, out_z = dz > 0 ? dz : 0;
        const double dist = hypot(out_r, out_z); /* (> 0: outside the core) */
        const double er[2] = {out_r > 0 ? dx / rho : 0, out_r > 0 ? dy / rho : 0};
        normal[0] = er[0] * out_r / dist, normal[1] = er[1] * out_r / dist;
        normal[2] = out_z / dist;
        return dist - re;
    }
    /* the sphere, or the hemisphere's nose (ahead of its centre) and shank */
    const double c[3] = {p->axis[0], p->axis[1], p->tip - p->radius};
    const double d[3] = {x[0] - c[0], x[1] - c[1], x[2] - c[2]};
    const int shank = p->nose != WFF_NOSE_SPHERE && d[2] <= 0;
    const double r = shank ? hypot(d[0], d[1]) : sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (r == 0) {
        normal[0] = normal[1] = 0, normal[2] = 1;
        return -p->radius;
    }
    normal[0] = d[0] / r, normal[1] = d[1] / r, normal[2] = shank ? 0 : d[2] / r;
    return r - p->radius;
}

double wff_projectile_nose_length(const wff_projectile *p)
{
    switch (p->nose) {
    case WFF_NOSE_FLAT:
        return p->edge_radius;
    case WFF_NOSE_SPHERE:
        return 2 * p->radius;
    case WFF_NOSE_CHISEL:
        return (p->radius - 0.5 * p->chisel_flat) * tan(p->chisel_bevel);
    default:
        return p->radius;
    }
}

static double penetration(const wff_projectile *p, const double x[3], double normal[3])
{
    return wff_projectile_penetration(p, x, normal);
}

static const char *const nose_names[WFF_NOSE_COUNT] = {"hemisphere", "flat", "sphere", "chisel"};

const char *wff_nose_name(int nose)
{
    return nose >= 0 && nose < WFF_NOSE_COUNT ? nose_names[nose] : "unknown";
}

int wff_nose_from_name(const char *name, wff_error *err)
{
    for (int k = 0; k < WFF_NOSE_COUNT; k++)
        if (strcmp(name, nose_names[k]) == 0)
            return k;
    return wff_fail(err, "unknown nose shape '%s' (known: hemisphere, flat, sphere, chisel)", name);
}

static int started(const wff_model *m)
{
    return m->step > 0 || m->v_half_valid;
}

/* Is (x, y) on the symmetry planes a model with this factor has? */
static int axis_check(double symmetry, const double axis[2], wff_error *err)
{
    const double tol = 1e-12; /* m */
    int on_x = fabs(axis[0]) <= tol, on_y = fabs(axis[1]) <= tol;
    if (symmetry == 4 && !(on_x && on_y))
        return wff_fail(err, "projectile axis at (%g, %g) m is off the symmetry planes x = 0 "
                        "and y = 0 of a quarter model (symmetry 4): a symmetric model can be "
                        "struck only on its symmetry planes (model the full specimen, "
                        "symmetry 1, for an impact off them)", axis[0], axis[1]);
    if (symmetry == 2 && !on_x && !on_y)
        return wff_fail(err, "projectile axis at (%g, %g) m is off both x = 0 and y = 0: a half "
                        "model (symmetry 2) can be struck only on its symmetry plane (model "
                        "the full specimen, symmetry 1, for an impact off it)", axis[0],
                        axis[1]);
    return 0;
}

int wff_contact_symmetry_changed(wff_model *m, wff_error *err)
{
    wff_projectile *p = &m->projectile;
    if (axis_check(m->symmetry_factor, p->axis, err) ||
        wff_contact_oblique_check(m->symmetry_factor, p, err))
        return -1;
    if (p->active)
        p->mass = p->mass_whole / m->symmetry_factor;
    return 0;
}

int wff_model_set_projectile(wff_model *m, double radius, double mass, double velocity,
                             double mu, wff_error *err)
{
    if (m->projectile.active)
        return wff_fail(err, "a second projectile: this model has one already (radius %g m, "
                        "mass %g kg); one projectile per model", m->projectile.radius,
                        m->projectile.mass_whole);
    if (!(radius > 0) || !isfinite(radius))
        return wff_fail(err, "projectile radius %g m must be > 0", radius);
    if (!(mass > 0) || !isfinite(mass))
        return wff_fail(err, "projectile mass %g kg must be > 0", mass);
    if (!(velocity >= 0) || !isfinite(velocity))
        return wff_fail(err, "projectile velocity %g m/s must be >= 0 (it moves along +z)",
                        velocity);
    if (!(mu >= 0))
        return wff_fail(err, "projectile friction coefficient %g must be >= 0", mu);
    wff_projectile *p = &m->projectile;
    if (p->nose == WFF_NOSE_FLAT && !(p->edge_radius <= radius))
        return wff_fail(err, "projectile radius %g m is smaller than the flat nose's edge "
                        "radius %g m", radius, p->edge_radius);
    if (axis_check(m->symmetry_factor, p->axis, err))
        return -1;
    free(p->candidates);
    free(p->contact_node);
    free(p->impulse);
    p->candidates = malloc(sizeof(int) * (size_t)m->n_nodes);
    p->contact_node = malloc(sizeof(int) * (size_t)m->n_nodes);
    p->impulse = malloc(3 * sizeof(double) * (size_t)m->n_nodes);
    if (!p->candidates || !p->contact_node || !p->impulse)
        return wff_fail(err, "out of memory");
    p->radius = radius;
    p->mass_whole = mass;
    p->mass = mass / m->symmetry_factor;
    p->velocity = velocity;
    p->mu = mu;
    p->n_candidates = 0;
    p->max_penetration = 0;
    p->force = 0;
    p->impulse_total = 0;
    /* nose tip touching the fabric plane z = 0 (oblique: its foremost point) */
    p->active = 1;
    if (p->nose == WFF_NOSE_CHISEL && p->chisel_flat > 2 * radius) {
        p->active = 0;
        return wff_fail(err, "projectile radius %g m is smaller than half the chisel's flat "
                        "(%g m wide)", radius, p->chisel_flat);
    }
    if (wff_model_place_projectile(m, p->oblique ? -wff_projectile_lead(p) / p->path[2] : 0, err)) {
        p->active = 0;
        return -1;
    }
    return 0;
}

int wff_model_set_projectile_shape(wff_model *m, int nose, double edge_radius, wff_error *err)
{
    wff_projectile *p = &m->projectile;
    if (started(m))
        return wff_fail(err, "projectile shape: the run has started (step %ld); set the nose "
                        "before the first step", m->step);
    if (nose < 0 || nose >= WFF_NOSE_COUNT)
        return wff_fail(err, "nose shape %d: must be %d (hemisphere), %d (flat), %d (sphere) or "
                        "%d (chisel)", nose, WFF_NOSE_HEMISPHERE, WFF_NOSE_FLAT, WFF_NOSE_SPHERE,
                        WFF_NOSE_CHISEL);
    if (nose == WFF_NOSE_CHISEL && !(p->chisel_bevel > 0))
        return wff_fail(err, "the chisel nose needs its flat's width and bevel angle: set it with "
                        "wff_model_set_projectile_chisel");
    if (nose != WFF_NOSE_FLAT)
        edge_radius = 0;
    if (!(edge_radius >= 0) || !isfinite(edge_radius))
        return wff_fail(err, "flat nose edge radius %g m must be >= 0", edge_radius);
    if (p->active && edge_radius > p->radius)
        return wff_fail(err, "flat nose edge radius %g m is larger than the projectile radius "
                        "%g m (at most equal: that is the hemisphere)", edge_radius, p->radius);
    int old_nose = p->nose;
    double old_edge = p->edge_radius;
    p->nose = nose;
    p->edge_radius = edge_radius;
    if (p->active && wff_model_place_projectile(m, p->tip, err)) {
        p->nose = old_nose;
        p->edge_radius = old_edge;
        return -1;
    }
    return 0;
}

int wff_model_set_impact_point(wff_model *m, double x, double y, wff_error *err)
{
    wff_projectile *p = &m->projectile;
    if (started(m))
        return wff_fail(err, "impact point: the run has started (step %ld); set it before the "
                        "first step", m->step);
    if (!isfinite(x) || !isfinite(y))
        return wff_fail(err, "impact point (%g, %g) m must be finite", x, y);
    double axis[2] = {x, y};
    if (axis_check(m->symmetry_factor, axis, err))
        return -1;
    double old[2] = {p->axis[0], p->axis[1]};
    p->axis[0] = x, p->axis[1] = y;
    if (p->active && wff_model_place_projectile(m, p->tip, err)) {
        p->axis[0] = old[0], p->axis[1] = old[1];
        return -1;
    }
    return 0;
}

/* The FSP's chisel nose and the oblique path (their geometry: projectile_shape.c). */
int wff_model_set_projectile_chisel(wff_model *m, double flat_width, double bevel_degrees,
                                    wff_error *err)
{
    wff_projectile *p = &m->projectile;
    if (started(m))
        return wff_fail(err, "projectile shape: the run has started (step %ld); set the nose "
                        "before the first step", m->step);
    if (!(flat_width >= 0) || !isfinite(flat_width))
        return wff_fail(err, "chisel nose: flat width %g m must be >= 0", flat_width);
    if (!(bevel_degrees > 0 && bevel_degrees < 90))
        return wff_fail(err, "chisel nose: bevel angle %g deg must be in (0, 90) (from the end "
                        "face)", bevel_degrees);
    if (p->active && flat_width > 2 * p->radius)
        return wff_fail(err, "chisel nose: flat width %g m is wider than the projectile (radius "
                        "%g m)", flat_width, p->radius);
    const wff_projectile old = *p;
    p->nose = WFF_NOSE_CHISEL;
    p->edge_radius = 0;
    p->chisel_flat = flat_width;
    p->chisel_bevel = bevel_degrees * M_PI / 180;
    if (p->active && wff_model_place_projectile(m, p->tip, err)) {
        *p = old;
        return -1;
    }
    return 0;
}

int wff_model_set_obliquity(wff_model *m, double degrees, wff_error *err)
{
    wff_projectile *p = &m->projectile;
    if (started(m))
        return wff_fail(err, "obliquity: the run has started (step %ld); set it before the "
                        "first step", m->step);
    if (!(degrees >= 0 && degrees < 90))
        return wff_fail(err, "obliquity %g deg: must be in [0, 90) (from the fabric's normal)",
                        degrees);
    const wff_projectile old = *p;
    p->oblique = degrees != 0;
    p->path[0] = p->oblique ? sin(degrees * M_PI / 180) : 0;
    p->path[1] = 0;
    p->path[2] = p->oblique ? cos(degrees * M_PI / 180) : 1;
    if (wff_contact_oblique_check(m->symmetry_factor, p, err)) {
        *p = old;
        return -1;
    }
    if (p->active && wff_model_place_projectile(m, -wff_projectile_lead(p) / p->path[2], err)) {
        *p = old;
        return -1;
    }
    return 0;
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
                        "tip at z <= 0)", wff_model_user_node(m, worst) + 1, at[0], at[1], at[2],
                        deepest, tip,
                        p->radius);
    }
    return 0;
}

/* Move the projectile back along −z until no candidate node is inside it
 * (at the positions now); velocities unchanged. For a state that did not come
 * from a step, e.g. interpolated onto a new mesh whose nodes the nose had
 * reached between the old ones. Returns how far it moved, m (>= 0). */
double wff_contact_retract(wff_model *m)
{
    wff_projectile *p = &m->projectile;
    double moved = 0;
    for (int iteration = 0; iteration < 20 && p->active; iteration++) {
        double shift = 0;
        for (int c = 0; c < p->n_candidates; c++) {
            int n = p->candidates[c];
            const double *un = m->u + D * n;
            double x[3] = {m->mesh.xy[2 * n] + un[0], m->mesh.xy[2 * n + 1] + un[1], un[2]};
            double nrm[3], delta = penetration(p, x, nrm);
            const double along = p->oblique ? nrm[0] * p->path[0] + nrm[2] * p->path[2] : nrm[2];
            if (delta > 0)
                shift = fmax(shift, delta / fmax(along, 0.2));
        }
        if (shift <= 1e-12 * p->radius)
            break;
        p->tip -= shift;
        moved += shift;
    }
    return moved;
}

/* Nodes whose current in-plane position is near enough the projectile axis
 * to touch it before the next refresh. */
void wff_contact_refresh_candidates(wff_model *m)
{
    wff_projectile *p = &m->projectile;
    double reach = p->search_all ? INFINITY : 1.2 * p->radius + 2e-3;
    if (p->oblique && !p->search_all) /* round (axis, 0): the path drifts along x as it goes */
        reach = reach / p->path[2] + (fabs(p->tip) + 2 * p->radius) * p->path[0] +
                wff_projectile_lead(p);
    p->n_candidates = wff_step_candidates(m, reach, p->candidates); /* in the user's node order */
}

/* Kinematic (hard) contact with the projectile, a predictor–corrector on
 * velocities: with the trial velocities of this step, find the nodes whose
 * predicted position at t + dt lies inside the projectile, and give each an
 * impulse along the surface normal, shared with the projectile by their
 * masses, that puts it back on the surface (perfectly inelastic, like a hard
 * contact in an explicit code); then Coulomb friction limits the tangential
 * impulse to μ times the normal one. The impulses enter f as forces
 * impulse/dt_mid; their work is booked after every part's correction
 * (wff_contact_book). Returns -1 (err set) if a node is found deep inside,
 * i.e. the projectile has gone through the fabric. */
int wff_contact_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    wff_projectile *p = &m->projectile;
    p->force = 0;
    p->n_contact = 0;
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
                            "passed through the fabric", m->time, m->step,
                            wff_model_user_node(m, n) + 1, delta,
                            100 * RUNAWAY_PENETRATION);
        /* inverse mass along the normal: free node components and the projectile (z);
         * a node held in every direction along the normal (clamped, fixed) has none:
         * the projectile alone takes the correction, its support the force */
        double w_node = 0;
        for (int i = 0; i < 3; i++)
            if (m->dof_kind[D * n + i] == WFF_DOF_FREE)
                w_node += nrm[i] * nrm[i];
        w_node /= mass;
        /* the projectile moves along its path d only ((0, 0, 1) for a normal shot) */
        const double d[3] = {p->oblique ? p->path[0] : 0, 0, p->oblique ? p->path[2] : 1};
        const double nd = p->oblique ? nrm[0] * d[0] + nrm[2] * d[2] : nrm[2];
        double w_total = w_node + nd * nd / p->mass;
        if (w_total == 0)
            continue; /* neither side can move along the normal */
        double jn = delta / dt / w_total; /* N·s */
        double j[3] = {jn * nrm[0], jn * nrm[1], jn * nrm[2]};
        /* friction against the tangential relative velocity left after jn */
        if (p->mu > 0) {
            const double jd = p->oblique ? j[0] * d[0] + j[2] * d[2] : j[2];
            double rel[3] = {vn[0] + j[0] / mass, vn[1] + j[1] / mass,
                             vn[2] + j[2] / mass - (p->velocity - j[2] / p->mass)};
            if (p->oblique)
                for (int i = 0; i < 3; i++)
                    rel[i] = vn[i] + j[i] / mass - d[i] * (p->velocity - jd / p->mass);
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
        /* the projectile takes all of it along its path (its guide the rest) */
        const double j_projectile = p->oblique ? j[0] * d[0] + j[2] * d[2] : j[2];
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
    p->n_contact = touched;
    /* the impulses as forces over the step (their work: wff_contact_book) */
    for (int c = 0; c < touched; c++) {
        int n = p->contact_node[c];
        const double *jc = p->impulse + 3 * c;
        for (int i = 0; i < 3; i++)
            if (m->dof_kind[D * n + i] == WFF_DOF_FREE) {
                m->f[D * n + i] += jc[i] / dt_mid;
                if (m->contact_force)
                    m->contact_force[D * n + i] += jc[i] / dt_mid;
            }
    }
    double dv = p->velocity - v_proj_before;
    p->contact_dv = dv;
    p->force = -p->mass * dv / dt_mid;
    p->impulse_total -= p->mass * dv;
    return 0;
}

void wff_contact_book(wff_model *m, double dt_before, double dt_mid)
{
    wff_projectile *p = &m->projectile;
    if (!p->active || p->n_contact == 0)
        return;
    double work = 0;
    for (int c = 0; c < p->n_contact; c++) {
        const int n = p->contact_node[c];
        const double *jc = p->impulse + 3 * c;
        for (int i = 0; i < 3; i++) {
            const int k = D * n + i;
            if (m->dof_kind[k] != WFF_DOF_FREE || jc[i] == 0)
                continue;
            work += wff_impulse_work(m, k, jc[i], dt_before, dt_mid);
        }
    }
    /* the projectile: its own change by this contact, at its final velocity
     * and acceleration (p->force: every contact's, the plies' included) */
    work += wff_projectile_impulse_work(m, p->mass * p->contact_dv, dt_before, dt_mid);
    m->dissipated_friction -= work;
}

/* The candidates follow the stable step's refresh (the nodes the projectile can
 * reach before the next). */
static void contact_refresh(wff_model *m)
{
    if (m->projectile.active)
        wff_contact_refresh_candidates(m);
}

const wff_part_ops wff_projectile_contact_part = {
    .name = "projectile_contact",
    .refresh = contact_refresh,
    .correct = wff_contact_correct,
    .book = wff_contact_book,
};

/* projectile_shape.c: what the standard threats added to the rigid
 * projectile (docs/threats.md, docs/model.md §16): the FSP's chisel nose, the
 * oblique path (the projectile's own frame, how far its nose reaches ahead
 * of its tip, its momentum along the path). The contact (contact.c) calls
 * these, its setters too; they know the projectile, nothing of the model's
 * contact or its impulses. */
#include "contact.h"

#include <math.h>
#include <string.h>

/* The chisel (WFF_NOSE_CHISEL): the intersection of four half-spaces, each
 * with its signed depth (> 0 inside) and outward normal: the flat's plane
 * z <= tip, the shank ρ <= r and the two bevels through the flat's long
 * edges (ξ = ±w/2, z = tip), tilted by β from the end face. A point is inside
 * when every depth is > 0; the distance to the surface of a convex
 * intersection from inside is the least depth (exact), the normal its face's.
 * Outside, the largest of the signed distances (−depth) is a lower bound of
 * the distance (exact off the edges): what the ply contact's gap takes. */
double wff_chisel_depth(const wff_projectile *p, const double x[3], double normal[3])
{
    const double sb = sin(p->chisel_bevel), cb = cos(p->chisel_bevel), half = 0.5 * p->chisel_flat;
    const double dx = x[0] - p->axis[0], dy = x[1] - p->axis[1], dz = x[2] - p->tip;
    const double rho = hypot(dx, dy);
    const double depth[4] = {-dz, -((dx - half) * sb + dz * cb), -((-dx - half) * sb + dz * cb),
                             p->radius - rho};
    int k = 0;
    for (int i = 1; i < 4; i++)
        if (depth[i] < depth[k] && !(i == 3 && rho == 0))
            k = i;
    const double n[4][3] = {{0, 0, 1}, {sb, 0, cb}, {-sb, 0, cb},
                            {rho > 0 ? dx / rho : 0, rho > 0 ? dy / rho : 0, 0}};
    for (int i = 0; i < 3; i++)
        normal[i] = n[k][i];
    return depth[k];
}

double wff_chisel_penetration(const wff_projectile *p, const double x[3], double normal[3])
{
    double nrm[3], depth = wff_chisel_depth(p, x, nrm);
    if (depth <= 0)
        return 0;
    memcpy(normal, nrm, sizeof nrm);
    return depth;
}

/* An oblique projectile (path d = (sin θ, 0, cos θ)): the point in its own
 * frame, ξ along e_ξ = (cos θ, 0, −sin θ), η along y, ζ along d, from
 * (axis, 0); `local` is the projectile as a normal shot at the frame's origin. */
void wff_projectile_to_frame(const wff_projectile *p, const double x[3], double y[3],
                             wff_projectile *local)
{
    const double s = p->path[0], c = p->path[2];
    const double r[3] = {x[0] - p->axis[0], x[1] - p->axis[1], x[2]};
    y[0] = c * r[0] - s * r[2];
    y[1] = r[1];
    y[2] = s * r[0] + c * r[2];
    *local = *p;
    local->axis[0] = local->axis[1] = 0;
    local->oblique = 0;
}

/* A normal of the projectile's frame back in the fabric's: n_ξ e_ξ + n_η y + n_ζ d. */
void wff_projectile_from_frame(const wff_projectile *p, double normal[3])
{
    const double s = p->path[0], c = p->path[2], n[3] = {normal[0], normal[1], normal[2]};
    normal[0] = c * n[0] + s * n[2];
    normal[1] = n[1];
    normal[2] = -s * n[0] + c * n[2];
}

double wff_projectile_lead(const wff_projectile *p)
{
    if (!p->oblique)
        return 0;
    const double s = p->path[0], c = p->path[2], r = p->radius;
    switch (p->nose) {
    case WFF_NOSE_FLAT:
        return p->edge_radius * (1 - c) + (r - p->edge_radius) * s;
    case WFF_NOSE_CHISEL: {
        const double half = 0.5 * p->chisel_flat;
        return fmax(half * s, r * s - (r - half) * tan(p->chisel_bevel) * c);
    }
    default: /* the hemisphere and the sphere: a sphere of radius r a radius behind the tip */
        return r * (1 - c);
    }
}

void wff_projectile_momentum(const wff_projectile *p, double momentum[3])
{
    const double d[3] = {p->oblique ? p->path[0] : 0, 0, p->oblique ? p->path[2] : 1};
    for (int i = 0; i < 3; i++)
        momentum[i] = p->active ? p->mass_whole * p->velocity * d[i] : 0;
}

double wff_model_projectile_lead(const wff_model *m)
{
    return m->projectile.active ? wff_projectile_lead(&m->projectile) : 0;
}

void wff_model_projectile_momentum(const wff_model *m, double momentum[3])
{
    wff_projectile_momentum(&m->projectile, momentum);
}

/* An oblique path breaks every mirror plane of a symmetric model. */
int wff_contact_oblique_check(double symmetry, const wff_projectile *p, wff_error *err)
{
    if (p->oblique && symmetry != 1)
        return wff_fail(err, "obliquity %g deg with a symmetric model (symmetry %g): an oblique "
                        "path breaks its mirror planes; model the full specimen (symmetry 1)",
                        atan2(p->path[0], p->path[2]) * 180 / M_PI, symmetry);
    return 0;
}

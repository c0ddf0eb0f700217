/* backing_contact.c: the backing block's contacts (backing.h), kinematic as
 * the projectile's (docs/model.md §16): velocity impulses so that nothing ends
 * the step inside anything, found at the positions the step predicts and
 * solved by Gauss–Seidel sweeps in node order (the same order at any thread or
 * rank count).
 *
 * - The back ply on the block's top face, footprint to face: each back-ply
 *   node's tributary square sampled at its four quarters' centres
 *   (WFF_FOOTPRINT_POINTS, each a quarter of the node's contact: a node is
 *   not a needle on a face finer than the fabric); a point over a face quad
 *   (its bilinear point under it) closer than h to the face along the face's
 *   normal is slowed by a stiff damped spring (a penalty contact: a force,
 *   not a kinematic correction, so that a pack's column, held kinematically
 *   by the ply contact, is slowed through it over a few steps instead of
 *   being corrected back and forth between the two) on the overlap the
 *   approach made (an overlap that grew by a jump of the face under the
 *   point, more than twice its closing over the step, is held, not pushed
 *   out: pushed out, it flung nodes off a finer block's faces); the spring's
 *   F Δt_mid is the most a point's impulse may be, and no more than stops its
 *   approach is taken (projected Gauss–Seidel sweeps: the points' impulses
 *   the complementarity problem's, none pushing a face that already parts
 *   from the fabric), λ n on the node, −N_a λ n on the face's nodes; then
 *   Coulomb friction, the tangential slip stopped within μ of the normal
 *   impulse, in one pass. A node the projectile's contact holds on the nose in
 *   this step is pressed between nose and block: it moves with the
 *   projectile along the normal (the pair's mass m_s + M takes the impulse,
 *   the projectile its share along z), where the nose's correction and the
 *   block's push would squeeze it out sideways.
 * - The rigid projectile (or any rigid body moving along z) on the top face's
 *   nodes, frictionless.
 * Knows the model's arrays and the block's; nothing of cells or FreeFEM. */
#include "backing.h"
#include "contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Most Gauss–Seidel sweeps a step, and the largest change of a gap (m) by a
 * sweep below which the sweeps stop (the rigid contact). */
#define SWEEPS_MAX 100
#define SWEEP_TOLERANCE 1e-12
/* The ply-on-block contact's sweeps stop when no contact's impulse changed
 * its relative speed by more than this, m/s. */
#define CAPPED_TOLERANCE 1e-3
/* The ply-on-block contact's spring, (ω Δt)² of a contact's own mode, and its
 * dashpot's fraction of critical damping. */
#define PENALTY 0.25
#define DAMPING 0.5

/* The index i with grid[i] <= x < grid[i + 1], clamped to [0, n − 1]. */
static int interval(const double *grid, int n, double x)
{
    int lo = 0, hi = n;
    while (hi - lo > 1) {
        const int mid = (lo + hi) / 2;
        if (grid[mid] <= x)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* The predicted position of block node a after dt. */
static void block_predicted(const wff_block *b, int a, double dt, double x[3])
{
    for (int c = 0; c < 3; c++)
        x[c] = b->X[3 * a + c] + b->u[3 * a + c] + dt * b->v[3 * a + c];
}

/* The face (i, j) of the top face under (px, py) at the predicted positions:
 * its nodes, the natural coordinates of the point (Newton on the bilinear map
 * projected on x-y), walking to a neighbour while the point lies outside.
 * 0 and the face's nodes, weights, point and normal (out of the block) when
 * found; -1 when the point lies off the block, or the face under it is folded
 * over in x-y or its point does not settle (a crater whose surface tangled:
 * its plane would give a node millimetres of overlap it never travelled). */
static int locate(const wff_block *b, double dt, double px, double py, int face[4],
                  double weight[4], double point[3], double normal[3])
{
    int i = interval(b->grid[0], b->n[0], px), j = interval(b->grid[1], b->n[1], py);
    for (int walk = 0; walk < 6; walk++) {
        face[0] = wff_block_node(b, i, j, 0), face[1] = wff_block_node(b, i + 1, j, 0);
        face[2] = wff_block_node(b, i + 1, j + 1, 0), face[3] = wff_block_node(b, i, j + 1, 0);
        double x[4][3];
        for (int a = 0; a < 4; a++)
            block_predicted(b, face[a], dt, x[a]);
        static const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
        double xi = 0, eta = 0, step = INFINITY; /* Newton's last step, |Δξ| + |Δη| */
        for (int it = 0; it < 8; it++) {
            double r[2] = {-px, -py}, J[4] = {0, 0, 0, 0};
            for (int a = 0; a < 4; a++) {
                const double N = 0.25 * (1 + sx[a] * xi) * (1 + sy[a] * eta);
                const double dxi = 0.25 * sx[a] * (1 + sy[a] * eta);
                const double deta = 0.25 * sy[a] * (1 + sx[a] * xi);
                for (int c = 0; c < 2; c++) {
                    r[c] += N * x[a][c];
                    J[2 * c] += dxi * x[a][c];
                    J[2 * c + 1] += deta * x[a][c];
                }
            }
            const double det = J[0] * J[3] - J[1] * J[2];
            if (!(det > 0))
                return -1; /* the face folded over in x-y (a tangled crater): no point under */
            const double dxi = (J[3] * r[0] - J[1] * r[1]) / det;
            const double deta = (-J[2] * r[0] + J[0] * r[1]) / det;
            xi -= dxi, eta -= deta;
            step = fabs(dxi) + fabs(deta);
            if (step < 1e-12)
                break;
        }
        const double slack = 1 + 1e-9;
        int moved = 0;
        if (xi < -slack && i > 0)
            i--, moved = 1;
        else if (xi > slack && i < b->n[0] - 1)
            i++, moved = 1;
        if (eta < -slack && j > 0)
            j--, moved = 1;
        else if (eta > slack && j < b->n[1] - 1)
            j++, moved = 1;
        if (moved)
            continue;
        if (fabs(xi) > slack || fabs(eta) > slack)
            return -1; /* off the block's edge */
        if (!(step < 1e-9))
            return -1; /* Newton did not settle: no single point under (px, py) */
        double t_xi[3] = {0, 0, 0}, t_eta[3] = {0, 0, 0};
        point[0] = point[1] = point[2] = 0;
        for (int a = 0; a < 4; a++) {
            weight[a] = 0.25 * (1 + sx[a] * xi) * (1 + sy[a] * eta);
            for (int c = 0; c < 3; c++) {
                point[c] += weight[a] * x[a][c];
                t_xi[c] += 0.25 * sx[a] * (1 + sy[a] * eta) * x[a][c];
                t_eta[c] += 0.25 * sy[a] * (1 + sx[a] * xi) * x[a][c];
            }
        }
        /* x_ξ × x_η points into the block (+z): the outward normal is its opposite */
        double n[3] = {t_xi[1] * t_eta[2] - t_xi[2] * t_eta[1],
                       t_xi[2] * t_eta[0] - t_xi[0] * t_eta[2],
                       t_xi[0] * t_eta[1] - t_xi[1] * t_eta[0]};
        const double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0))
            return -1;
        for (int c = 0; c < 3; c++)
            normal[c] = -n[c] / len;
        return 0;
    }
    return -1;
}

/* x reflected into [lo, hi] at the end it passed (a side of the block: a
 * mirror plane). */
static double mirrored(double x, double lo, double hi)
{
    return x < lo ? 2 * lo - x : x > hi ? 2 * hi - x : x;
}

/* Δv on a fabric node's free translational DOFs by the impulse j (3). */
static void kick_fabric(wff_model *m, int s, const double j[3])
{
    for (int c = 0; c < 3; c++)
        if (m->dof_kind[D * s + c] == WFF_DOF_FREE)
            m->v[D * s + c] += j[c] / m->mass[D * s + c];
}

/* The same on a block node's free DOFs, the impulse added to impulse (3 a node). */
static void kick_block(wff_block *b, int a, const double j[3], double *impulse)
{
    for (int c = 0; c < 3; c++)
        if (!b->held[3 * a + c]) {
            b->v[3 * a + c] += j[c] / b->mass[3 * a + c];
            if (impulse)
                impulse[3 * a + c] += j[c];
        }
}

/* The relative velocity of contact c along its normal: (v_s − Σ N_a v_a)·n. */
static double normal_speed(const wff_model *m, const wff_block *b, const wff_face_contacts *C,
                           int c, double rel[3])
{
    const int s = C->node[c];
    for (int k = 0; k < 3; k++) {
        rel[k] = m->v[D * s + k];
        for (int a = 0; a < 4; a++)
            rel[k] -= C->weight[4 * c + a] * b->v[3 * C->face[4 * c + a] + k];
    }
    const double *n = C->normal + 3 * c;
    return rel[0] * n[0] + rel[1] * n[1] + rel[2] * n[2];
}

/* The fabric side's mass of contact c: the node's, with the projectile's when
 * the node is held on the nose. */
static double node_mass(const wff_model *m, const struct wff_backing *B, int s)
{
    return m->mass[D * s + WFF_UZ] + (B->on_nose[s] ? m->projectile.mass : 0);
}

/* 1/m_eff of contact c along a direction: 1/m_s + Σ N_a²/m_a. */
static double mobility(const wff_model *m, const struct wff_backing *B, int c)
{
    const wff_block *b = &B->block;
    const wff_face_contacts *C = &B->contacts;
    const int s = C->node[c];
    double w = 1 / node_mass(m, B, s);
    for (int a = 0; a < 4; a++) {
        const double N = C->weight[4 * c + a];
        w += N * N / b->mass[3 * C->face[4 * c + a] + 2];
    }
    return w;
}

/* Contact c takes a further impulse j (3) on its node, −N_a j on its face;
 * a node held on the nose shares it with the projectile (node_mass). */
static void apply(wff_model *m, struct wff_backing *B, int c, const double j[3])
{
    wff_face_contacts *C = &B->contacts;
    const int s = C->node[c];
    if (B->on_nose[s]) {
        const double whole = node_mass(m, B, s), own = m->mass[D * s + WFF_UZ] / whole;
        const double js[3] = {own * j[0], own * j[1], own * j[2]};
        kick_fabric(m, s, js);
        for (int k = 0; k < 3; k++)
            C->impulse[3 * c + k] += js[k];
        const double dv = j[2] / whole;
        m->projectile.velocity += dv;
        B->projectile_dv += dv;
    } else {
        kick_fabric(m, s, j);
        for (int k = 0; k < 3; k++)
            C->impulse[3 * c + k] += j[k];
    }
    for (int a = 0; a < 4; a++) {
        const double N = C->weight[4 * c + a];
        const double ja[3] = {-N * j[0], -N * j[1], -N * j[2]};
        kick_block(&B->block, C->face[4 * c + a], ja, B->block_impulse);
    }
}

double wff_backing_ply_contact(wff_model *m, struct wff_backing *B, double h, double dt,
                               double dt_mid)
{
    wff_block *b = &B->block;
    wff_face_contacts *C = &B->contacts;
    const wff_projectile *p = &m->projectile;
    C->n = 0;
    for (int k = 0; p->active && k < p->n_contact; k++)
        B->on_nose[p->contact_node[k]] = 1;
    double deepest = 0;
    /* the springs' stiffness per kg of the node, fixed at the first step (a
     * spring whose stiffness changes while compressed gives back more than it
     * took: the step shortens as the fabric is crushed, and a node held on
     * the nose carries the projectile's mass) */
    if (!(B->run.stiffness_per_mass > 0))
        B->run.stiffness_per_mass = PENALTY / (dt * dt);
    for (int t = 0; t < B->n_ply_nodes; t++) {
        const int s = B->ply_nodes[t];
        if (m->dof_kind[D * s + WFF_UZ] != WFF_DOF_FREE)
            continue;
        const double xs[3] = {m->mesh.xy[2 * s] + m->u[D * s + WFF_UX],
                              m->mesh.xy[2 * s + 1] + m->u[D * s + WFF_UY],
                              m->u[D * s + WFF_UZ]}; /* (a ply's plane is in its u_z:
                                                        include/wovenff/pack.h) */
        /* the footprint's points: the node's tributary square's quarters'
         * centres, reflected into the block's footprint at its sides (held in
         * their normal direction, frictionless: mirror planes) */
        const double quarter = 0.25 * sqrt(B->ply_area[t]);
        for (int k = 0; k < WFF_FOOTPRINT_POINTS && C->n < C->max; k++) {
            const int slot = WFF_FOOTPRINT_POINTS * t + k;
            double x[3] = {xs[0] + (k & 1 ? quarter : -quarter),
                           xs[1] + (k & 2 ? quarter : -quarter), xs[2]};
            x[0] = mirrored(x[0], b->grid[0][0], b->grid[0][b->n[0]]);
            x[1] = mirrored(x[1], b->grid[1][0], b->grid[1][b->n[1]]);
            const int c = C->n;
            double point[3];
            if (locate(b, 0, x[0], x[1], C->face + 4 * c, C->weight + 4 * c, point,
                       C->normal + 3 * c)) {
                B->ply_gap[slot] = 0, B->ply_held[slot] = 0;
                continue;
            }
            const double *n = C->normal + 3 * c;
            const double gap = (x[0] - point[0]) * n[0] + (x[1] - point[1]) * n[1] +
                               (x[2] - point[2]) * n[2] - h;
            if (gap >= 0) {
                B->ply_gap[slot] = 0, B->ply_held[slot] = 0;
                continue;
            }
            C->node[c] = s;
            C->slot[c] = slot;
            C->gap[c] = gap;
            C->lambda[c] = 0;
            C->impulse[3 * c] = C->impulse[3 * c + 1] = C->impulse[3 * c + 2] = 0;
            C->n++;
            deepest = fmax(deepest, -gap);
            /* an overlap that grew by more than the approach could make (twice
             * the normal closing speed over the step) came from a jump of the
             * face under the point: held, the spring on the rest */
            double rel[3];
            const double vn = normal_speed(m, b, C, c, rel);
            const double jump = (B->ply_gap[slot] - gap) - 2 * fmax(0, -vn) * dt;
            if (jump > 0)
                B->ply_held[slot] += jump;
            B->ply_held[slot] = fmin(B->ply_held[slot], -gap);
            B->ply_gap[slot] = gap;
            /* the spring's bound on the point's impulse (below), a quarter of the
             * node's spring on a quarter of its mass, damped at DAMPING of that */
            const double w = C->mobility[c] = mobility(m, B, c);
            const double stiffness = B->run.stiffness_per_mass * m->mass[D * s + WFF_UZ] /
                                     WFF_FOOTPRINT_POINTS;
            const double w_share = w + (WFF_FOOTPRINT_POINTS - 1) / node_mass(m, B, s);
            const double damping = 2 * DAMPING * sqrt(stiffness / w_share);
            C->bound[c] = fmax(0, stiffness * (-gap - B->ply_held[slot]) - damping * vn) * dt_mid;
        }
    }
    /* the normal force: a spring on the overlap with a dashpot, each contact's
     * stiffness PENALTY m_s / Δt_0² (its own frequency at most √PENALTY / Δt_0
     * on the node's mass, well within the step's limit beside the fabric's
     * own), damped at DAMPING of critical, never pulling; its impulse F Δt_mid
     * at most, and at most what stops the approach: projected Gauss–Seidel
     * sweeps in contact order on 0 <= λ_c <= F_c Δt_mid towards a normal
     * relative velocity of 0 (the spring slows a node against the face and
     * never throws the face ahead of the node; pushed by its neighbours'
     * springs one after the other, a light face node that had already
     * outrun the fabric was driven to twice the projectile's speed: the
     * crater's axis node, docs/backing.md) */
    for (int sweep = 0; sweep < SWEEPS_MAX; sweep++) {
        double most = 0;
        for (int c = 0; c < C->n; c++) {
            double rel[3];
            const double vn = normal_speed(m, b, C, c, rel);
            const double w = C->mobility[c];
            const double lambda = fmin(fmax(C->lambda[c] - vn / w, 0), C->bound[c]);
            const double change = lambda - C->lambda[c];
            if (change == 0)
                continue;
            C->lambda[c] = lambda;
            const double *n = C->normal + 3 * c;
            const double j[3] = {change * n[0], change * n[1], change * n[2]};
            apply(m, B, c, j);
            most = fmax(most, fabs(change) * w);
        }
        if (most <= CAPPED_TOLERANCE)
            break;
    }
    /* friction: the tangential slip stopped within μ λ, and within what the
     * clay under the face can carry in shear over the node's area (Coulomb
     * capped by the surface's yield in shear: the layer that would shear is
     * far thinner than an element, and an element dragged along by the full
     * Coulomb force is crushed where the fabric slides in toward the axis) */
    for (int c = 0; B->mu > 0 && c < C->n; c++) {
        if (!(C->lambda[c] > 0))
            continue;
        double rel[3];
        const double vn = normal_speed(m, b, C, c, rel);
        const double *n = C->normal + 3 * c;
        double vt[3] = {rel[0] - vn * n[0], rel[1] - vn * n[1], rel[2] - vn * n[2]};
        const double slip = sqrt(vt[0] * vt[0] + vt[1] * vt[1] + vt[2] * vt[2]);
        if (!(slip > 0))
            continue;
        const double w = C->mobility[c];
        const int top = C->face[4 * c], row = b->n[0] + 1; /* the face's corner (i, j, 0) */
        const double strength = wff_block_surface_shear_strength(b, top % row, top / row);
        const double area = B->ply_area[C->slot[c] / WFF_FOOTPRINT_POINTS] / WFF_FOOTPRINT_POINTS;
        const double stop = slip / w, limit = fmin(B->mu * C->lambda[c], strength * area * dt_mid);
        const double jt = stop < limit ? stop : limit;
        const double j[3] = {-jt * vt[0] / slip, -jt * vt[1] / slip, -jt * vt[2] / slip};
        apply(m, B, c, j);
    }
    for (int k = 0; p->active && k < p->n_contact; k++)
        B->on_nose[p->contact_node[k]] = 0;
    return deepest;
}

int wff_block_rigid_contact(wff_block *b, wff_rigid_penetration penetration, const void *body,
                            double mass, double *velocity, double dt, double *impulse)
{
    const double v0 = *velocity;
    int count = 0;
    for (int j = 0; j <= b->n[1]; j++)
        for (int i = 0; i <= b->n[0]; i++) {
            const int a = wff_block_node(b, i, j, 0);
            double x[3], n[3];
            block_predicted(b, a, dt, x);
            const double depth = penetration(body, dt * v0, x, n);
            if (!(depth > 0))
                continue;
            b->contact_node[count] = a;
            b->contact_depth[count] = depth;
            for (int c = 0; c < 3; c++)
                b->contact_normal[3 * count + c] = n[c];
            b->contact_speed[count] = b->v[3 * a] * n[0] + b->v[3 * a + 1] * n[1] +
                                      b->v[3 * a + 2] * n[2];
            b->contact_lambda[count] = 0;
            count++;
        }
    for (int sweep = 0; sweep < SWEEPS_MAX && count > 0; sweep++) {
        double change = 0;
        for (int c = 0; c < count; c++) {
            const int a = b->contact_node[c];
            const double *n = b->contact_normal + 3 * c;
            const double vn = b->v[3 * a] * n[0] + b->v[3 * a + 1] * n[1] + b->v[3 * a + 2] * n[2];
            /* the depth at the step's end: the body's advance in, the node's move out */
            const double depth = b->contact_depth[c] +
                                 dt * ((*velocity - v0) * n[2] - (vn - b->contact_speed[c]));
            const double w = 1 / b->mass[3 * a + 2] + n[2] * n[2] / mass;
            double next = b->contact_lambda[c] + depth / (dt * w);
            if (next < 0)
                next = 0;
            const double dl = next - b->contact_lambda[c];
            if (dl == 0)
                continue;
            b->contact_lambda[c] = next;
            const double j[3] = {dl * n[0], dl * n[1], dl * n[2]};
            kick_block(b, a, j, impulse);
            *velocity -= dl * n[2] / mass;
            change = fmax(change, fabs(dl) * w * dt);
        }
        if (change < SWEEP_TOLERANCE)
            break;
    }
    return count;
}

/* The projectile as a rigid body for wff_block_rigid_contact. */
static double projectile_penetration(const void *body, double advance, const double x[3],
                                     double normal[3])
{
    wff_projectile p = *(const wff_projectile *)body;
    p.tip += advance;
    return wff_projectile_penetration(&p, x, normal);
}

void wff_backing_projectile_contact(wff_model *m, struct wff_backing *B, double dt)
{
    wff_projectile *p = &m->projectile;
    B->projectile_contacts = 0;
    if (!p->active)
        return;
    double velocity = p->velocity;
    B->projectile_contacts = wff_block_rigid_contact(&B->block, projectile_penetration, p,
                                                     p->mass, &velocity, dt, B->block_impulse);
    B->projectile_dv += velocity - p->velocity;
    p->velocity = velocity;
}

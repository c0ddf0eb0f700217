/* backing.c: the backing block behind the pack, a part of the step (part.h,
 * backing.h; docs/backing.md). The setting `backing` (1 clay, 2 gelatin)
 * puts a solid block (plugin/solids/block.h) under the back ply, its top face
 * at the back ply's mid-plane plus half the ply's contact thickness (and
 * backing_gap), over the specimen's footprint, graded from the impact point.
 *
 * The block keeps the fabric's step: at each correction (after the fabric's
 * velocity update) it moves its nodes by the step just taken, takes its
 * internal forces there and its own velocity update, then the contacts
 * (backing_contact.c): the back ply on its top face and the projectile on
 * its top face's nodes. Its stable step joins the model's. Its term of the
 * energy balance is the energy the contacts took from the fabric and the
 * projectile (their impulses' work at the trapezoidal measure, as every
 * contact's) plus the block's own account, kinetic + stored + dissipated −
 * the work the contacts did on it, which its central difference keeps near 0:
 * so the model's energy error covers the block too. Knows the model's arrays;
 * nothing of cells or FreeFEM. */
#include "backing.h"
#include "plies.h"
#include "ply_contact.h"
#include "wall_clock.h"
#include "wovenff/backing.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The defaults: the NIJ 0101.06 box's depth (140 mm), elements of 4 mm under
 * the impact growing by 20 % a layer, Coulomb friction 0.3 between fabric and
 * clay (assumed: not measured), hourglass springs at 5 % of the shear
 * stiffness with dashpots at critical damping (docs/backing.md "Element"),
 * the pack laid on the block. */
static const struct wff_backing defaults = {
    .depth = 0.14, .finest = 4e-3, .growth = 1.2, .mu = 0.3, .hourglass = 0.05, .gap = 0,
    .hourglass_damping = 1,
};

static void release(struct wff_backing *B)
{
    wff_block_free(&B->block);
    wff_face_contacts *C = &B->contacts;
    free(C->node), free(C->slot), free(C->face), free(C->weight), free(C->normal), free(C->gap);
    free(C->lambda), free(C->bound), free(C->mobility), free(C->impulse);
    free(B->ply_nodes), free(B->ply_area), free(B->block_impulse), free(B->on_nose);
    free(B->ply_gap), free(B->ply_held);
    B->ply_gap = NULL, B->ply_held = NULL;
    memset(C, 0, sizeof *C);
    B->ply_nodes = NULL, B->ply_area = NULL, B->block_impulse = NULL, B->on_nose = NULL;
    B->built = 0;
}

/* The back ply's base z (its mid-plane's reference), m. */
static double back_ply_z(const wff_model *m)
{
    return m->pack && m->pack->n > 1 ? (m->pack->n - 1) * m->pack->gap : 0;
}

/* The block under the back ply, its contact arrays: 0 or -1 (err set). */
static int build(wff_model *m, struct wff_backing *B, wff_error *err)
{
    release(B);
    const int plies = wff_pack_plies(m), per_ply = m->n_nodes / plies;
    wff_block_shape s = {INFINITY, -INFINITY, INFINITY, -INFINITY, 0, B->depth, {0, 0},
                         B->finest, B->growth};
    for (int n = 0; n < per_ply; n++) {
        s.x0 = fmin(s.x0, m->mesh.xy[2 * n]), s.x1 = fmax(s.x1, m->mesh.xy[2 * n]);
        s.y0 = fmin(s.y0, m->mesh.xy[2 * n + 1]), s.y1 = fmax(s.y1, m->mesh.xy[2 * n + 1]);
    }
    s.top = back_ply_z(m) + 0.5 * wff_ply_thickness(m) + B->gap;
    s.centre[0] = m->projectile.active ? m->projectile.axis[0] : 0.5 * (s.x0 + s.x1);
    s.centre[1] = m->projectile.active ? m->projectile.axis[1] : 0.5 * (s.y0 + s.y1);
    if (wff_block_create(&B->block, B->law, &s, B->hourglass, err))
        return -1;
    if (B->integration && wff_block_integrate_fully(&B->block, err))
        return -1;
    wff_block_set_hourglass_damping(&B->block, B->hourglass_damping);
    wff_face_contacts *C = &B->contacts;
    const size_t n = (size_t)per_ply, points = WFF_FOOTPRINT_POINTS * n;
    C->max = (int)points;
    C->node = malloc(points * sizeof(int));
    C->slot = malloc(points * sizeof(int));
    C->face = malloc(4 * points * sizeof(int));
    C->weight = malloc(4 * points * sizeof(double));
    C->normal = malloc(3 * points * sizeof(double));
    C->gap = malloc(points * sizeof(double));
    C->lambda = malloc(points * sizeof(double));
    C->bound = malloc(points * sizeof(double));
    C->mobility = malloc(points * sizeof(double));
    C->impulse = malloc(3 * points * sizeof(double));
    B->ply_nodes = malloc(n * sizeof(int));
    B->ply_area = calloc(n, sizeof(double));
    B->ply_gap = calloc(points, sizeof(double));
    B->ply_held = calloc(points, sizeof(double));
    B->block_impulse = calloc(3 * (size_t)B->block.n_nodes, sizeof(double));
    B->on_nose = calloc((size_t)m->n_nodes, 1);
    if (!C->node || !C->slot || !C->face || !C->weight || !C->normal || !C->gap || !C->lambda || !C->bound || !C->mobility ||
        !C->impulse || !B->ply_nodes || !B->ply_area || !B->block_impulse || !B->on_nose ||
        !B->ply_gap || !B->ply_held) {
        release(B);
        return wff_fail(err, "backing: out of memory");
    }
    B->n_ply_nodes = per_ply;
    const int first = (plies - 1) * per_ply;
    for (int k = 0; k < per_ply; k++)
        B->ply_nodes[k] = first + k;
    for (int e = 0; e < m->el.n_tris + m->el.n_quads; e++) { /* the back ply's elements' areas, shared */
        const int *node, np = wff_element_nodes(&m->el, e, &node);
        const double area = wff_element_area(&m->el, e);
        for (int a = 0; a < np; a++)
            if (node[a] >= first)
                B->ply_area[node[a] - first] += area / np;
    }
    B->built = 1;
    memset(&B->run, 0, sizeof B->run);
    B->overlap = 0;
    int worst;
    B->run.block_step = wff_block_stable_step(&B->block, &worst);
    return 0;
}

/* ---- settings ---------------------------------------------------------------- */

static int check_not_started(const char *name, const wff_model *m, wff_error *err)
{
    if (m->step > 0 || m->v_half_valid)
        return wff_fail(err, "%s: the run has started (step %ld); set it before the first step",
                        name, m->step);
    return 0;
}

static struct wff_backing *backing_of(wff_model *m, wff_error *err)
{
    if (!m->backing) {
        m->backing = malloc(sizeof *m->backing);
        if (!m->backing) {
            wff_fail(err, "backing: out of memory");
            return NULL;
        }
        *m->backing = defaults;
    }
    return m->backing;
}

#define RANGE_CHECK(fn, key, test, what)                                             \
    static int fn(const wff_model *m, double value, wff_error *err)                  \
    {                                                                                \
        if (check_not_started(key, m, err))                                          \
            return -1;                                                               \
        if (!(test) || !isfinite(value))                                             \
            return wff_fail(err, key " = %g: " what, value);                         \
        return 0;                                                                    \
    }
RANGE_CHECK(check_law, "backing", value == 0 || value == 1 || value == 2,
            "must be 0 (none), 1 (clay) or 2 (gelatin)")
RANGE_CHECK(check_depth, "backing_depth", value > 0 && value <= 10, "must be in (0, 10] m")
RANGE_CHECK(check_finest, "backing_element", value > 0 && value <= 1, "must be in (0, 1] m")
RANGE_CHECK(check_growth, "backing_growth", value >= 1 && value <= 3, "must be in [1, 3]")
RANGE_CHECK(check_mu, "backing_mu", value >= 0, "must be a friction coefficient >= 0")
RANGE_CHECK(check_hourglass, "backing_hourglass", value >= 0 && value <= 1, "must be in [0, 1]")
RANGE_CHECK(check_hourglass_damping, "backing_hourglass_damping", value >= 0 && value <= 2,
            "must be in [0, 2] (a fraction of critical damping)")
RANGE_CHECK(check_integration, "backing_integration", value == 0 || value == 1,
            "must be 0 (one point, hourglass control) or 1 (fully integrated, F-bar)")
RANGE_CHECK(check_gap, "backing_gap", value >= 0 && value <= 1, "must be in [0, 1] m")

#define APPLY(fn, field, convert)                                 \
    static int fn(wff_model *m, double value, wff_error *err)     \
    {                                                             \
        struct wff_backing *B = backing_of(m, err);               \
        if (!B)                                                   \
            return -1;                                            \
        release(B);                                               \
        B->field = convert(value);                                \
        return 0;                                                 \
    }
#define AS_IS(x) (x)
#define AS_INT(x) ((int)(x))
APPLY(apply_law, law, AS_INT)
APPLY(apply_depth, depth, AS_IS)
APPLY(apply_finest, finest, AS_IS)
APPLY(apply_growth, growth, AS_IS)
APPLY(apply_mu, mu, AS_IS)
APPLY(apply_hourglass, hourglass, AS_IS)
APPLY(apply_gap, gap, AS_IS)
APPLY(apply_hourglass_damping, hourglass_damping, AS_IS)
APPLY(apply_integration, integration, AS_INT)

static const wff_setting backing_settings[] = {
    {"backing", check_law, apply_law},
    {"backing_depth", check_depth, apply_depth},
    {"backing_element", check_finest, apply_finest},
    {"backing_growth", check_growth, apply_growth},
    {"backing_mu", check_mu, apply_mu},
    {"backing_hourglass", check_hourglass, apply_hourglass},
    {"backing_gap", check_gap, apply_gap},
    {"backing_hourglass_damping", check_hourglass_damping, apply_hourglass_damping},
    {"backing_integration", check_integration, apply_integration},
    {NULL, NULL, NULL},
};

static struct wff_backing *on(const wff_model *m)
{
    return m->backing && m->backing->law != WFF_BLOCK_NONE ? m->backing : NULL;
}

/* ---- the step ------------------------------------------------------------------ */

static int backing_setup(wff_model *m, wff_error *err)
{
    struct wff_backing *B = on(m);
    if (!B)
        return 0;
    if (!B->built && build(m, B, err))
        return -1;
    const double dt = B->run.block_step;
    if (dt < m->dt_stable) { /* (the first step's: later ones take it through stable_step) */
        m->dt_stable = dt;
        m->dt = m->dt_factor * dt;
    }
    return 0;
}

static double backing_stable_step(const wff_model *m)
{
    const struct wff_backing *B = on(m);
    return B && B->built ? B->run.block_step : INFINITY; /* (as of its last force pass) */
}

/* The top face's indentation of node (i, j): its u_z (> 0 into the block), m. */
static double depth_at(const wff_block *b, int i, int j)
{
    return b->u[3 * wff_block_node(b, i, j, 0) + 2];
}

/* The block's step, central differences on the fabric's step: its nodes moved
 * by the step just taken, its internal forces there (its points' states
 * advanced over that step), its velocities kicked by Δt_mid f/m as the
 * fabric's are. The block's stable step is refreshed every STABLE_EVERY
 * passes (its elements change shape slowly against the fabric's step; the
 * model's step stays well under it: docs/backing.md). 0, or -1 (err set) on an
 * inverted element. */
#define STABLE_EVERY 16
static int block_step(wff_model *m, struct wff_backing *B, double dt_mid, wff_error *err)
{
    wff_block *b = &B->block;
    const int nd = 3 * b->n_nodes;
    if (B->run.started) /* u^{n+1} = u^n + Δt v^{n+½}, the step the fabric took */
        for (int k = 0; k < nd; k++)
            b->u[k] += B->run.dt_next * b->v[k];
    int bad;
    if (wff_block_forces(b, B->run.started ? B->run.dt_next : 0, &bad)) {
        const int i = bad % b->n[0], j = bad / b->n[0] % b->n[1], k = bad / (b->n[0] * b->n[1]);
        return wff_fail(err, "t = %.6g s (step %ld): backing block element %d (grid %d %d %d "
                        "from the top face's corner): inverted or NaN deformation", m->time,
                        m->step, bad + 1, i, j, k);
    }
    if (++B->run.samples % STABLE_EVERY == 0) {
        int worst;
        B->run.block_step = wff_block_stable_step(b, &worst);
    }
    for (int k = 0; k < nd; k++)
        if (!b->held[k])
            b->v[k] += dt_mid * b->f[k] / b->mass[k];
    return 0;
}

static int backing_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    struct wff_backing *B = on(m);
    if (!B || !B->built)
        return 0;
    const double started = wff_wall_seconds();
    if (block_step(m, B, dt_mid, err))
        return -1;
    B->projectile_dv = 0;
    B->overlap = wff_backing_ply_contact(m, B, 0.5 * wff_ply_thickness(m), dt, dt_mid);
    wff_backing_projectile_contact(m, B, dt);
    /* the impulses as forces over the step (their work: the book op) */
    const wff_face_contacts *C = &B->contacts;
    for (int c = 0; c < C->n; c++)
        for (int k = 0; k < 3; k++) {
            const double j = C->impulse[3 * c + k];
            const int dof = D * C->node[c] + k;
            if (j != 0) {
                m->f[dof] += j / dt_mid;
                if (m->contact_force)
                    m->contact_force[dof] += j / dt_mid;
            }
        }
    wff_projectile *p = &m->projectile;
    if (B->projectile_dv != 0) {
        p->force -= p->mass * B->projectile_dv / dt_mid;
        p->impulse_total -= p->mass * B->projectile_dv;
    }
    B->run.dt_next = dt;
    B->run.started = 1;
    const wff_block *b = &B->block;
    for (int j = 0; j <= b->n[1]; j++)
        for (int i = 0; i <= b->n[0]; i++)
            B->run.peak_depth = fmax(B->run.peak_depth, depth_at(b, i, j));
    B->seconds += wff_wall_seconds() - started;
    return 0;
}

/* The impulses' work at the central difference's measure (part.h's book,
 * wff_impulse_work) on the fabric and the projectile (the energy the block's
 * contacts took from the model) and on the block. The impulses cleared for
 * the next step. */
static void backing_book(wff_model *m, double dt_before, double dt_mid)
{
    struct wff_backing *B = on(m);
    if (!B || !B->built)
        return;
    wff_face_contacts *C = &B->contacts;
    for (int c = 0; c < C->n; c++)
        for (int k = 0; k < 3; k++) {
            const double j = C->impulse[3 * c + k];
            if (j != 0)
                B->run.work_fabric += wff_impulse_work(m, D * C->node[c] + k, j, dt_before, dt_mid);
            C->impulse[3 * c + k] = 0;
        }
    if (B->projectile_dv != 0)
        B->run.work_projectile += wff_projectile_impulse_work(
            m, m->projectile.mass * B->projectile_dv, dt_before, dt_mid);
    B->projectile_dv = 0;
    /* the block's side: the same measure with its own accelerations (its
     * impulses as forces over Δt_mid), and its kinetic energy at the
     * balance's measure ½ Σ m v^{n+½}·(v^{n+½} − Δt a^n_internal) */
    wff_block *b = &B->block;
    double kinetic = 0, work = 0;
    for (int k = 0; k < 3 * b->n_nodes; k++) {
        if (b->held[k])
            continue;
        const double mass = b->mass[k], v = b->v[k], j = B->block_impulse[k];
        kinetic += 0.5 * mass * v * (v - B->run.dt_next * b->f[k] / mass);
        if (j != 0) {
            const double a = (b->f[k] + j / dt_mid) / mass;
            work += dt_before > 0 ? j * (v - 0.5 * dt_before * a)
                                  : j * (v - dt_mid * a + 0.5 * j / mass);
            B->block_impulse[k] = 0;
        }
    }
    B->run.kinetic = kinetic;
    B->run.kinetic_peak = fmax(B->run.kinetic_peak, kinetic);
    B->run.work_block += work;
}

/* The block's kinetic energy now, ½ Σ m v² (model part, J). */
static double block_kinetic(const wff_block *b)
{
    double k = 0;
    for (int i = 0; i < 3 * b->n_nodes; i++)
        k += 0.5 * b->mass[i] * b->v[i] * b->v[i];
    return k;
}

/* What the ply-block and projectile-block contacts removed (their springs' damping,
 * friction): the work they took from fabric and projectile less what they did on the
 * block (part.h `loss`; backing_contact_loss). */
static double backing_loss(const wff_model *m)
{
    const struct wff_backing *B = on(m);
    if (!B || !B->built)
        return 0;
    return -B->run.work_fabric - B->run.work_projectile - B->run.work_block;
}

/* Its term of the balance (model part, J): the block's own energy and what its
 * contacts removed. */
static double backing_dissipated(const wff_model *m)
{
    const struct wff_backing *B = on(m);
    if (!B || !B->built)
        return 0;
    return B->run.kinetic + B->block.stored + B->block.dissipated + backing_loss(m);
}

/* ---- values -------------------------------------------------------------------- */

/* The crater now: the top face's indentation, the area (whole specimen) where
 * it reaches a tenth of its largest, and its volume (Σ of each face's mean
 * indentation over its area). */
static void crater(const wff_model *m, const wff_block *b, double *deepest, double *diameter,
                   double *volume)
{
    double top = 0;
    for (int j = 0; j <= b->n[1]; j++)
        for (int i = 0; i <= b->n[0]; i++)
            top = fmax(top, depth_at(b, i, j));
    double area = 0, vol = 0;
    for (int j = 0; j < b->n[1]; j++)
        for (int i = 0; i < b->n[0]; i++) {
            const double face = (b->grid[0][i + 1] - b->grid[0][i]) * (b->grid[1][j + 1] - b->grid[1][j]);
            const double d[4] = {depth_at(b, i, j), depth_at(b, i + 1, j), depth_at(b, i + 1, j + 1),
                                 depth_at(b, i, j + 1)};
            int inside = 0;
            for (int a = 0; a < 4; a++) {
                inside += top > 0 && d[a] >= 0.1 * top;
                vol += 0.25 * face * fmax(d[a], 0);
            }
            area += 0.25 * inside * face;
        }
    *deepest = top;
    *diameter = 2 * sqrt(m->symmetry_factor * area / M_PI);
    *volume = m->symmetry_factor * vol;
}

static const char *const backing_value_names[] = {
    "backing", "backface_signature", "crater_diameter", "crater_volume", "backing_peak_depth",
    "backing_kinetic", "backing_stored", "backing_dissipated", "backing_contact_loss",
    "backing_elements", "backing_contacts", "backing_seconds", "backing_step", "backing_overlap",
    "backing_kinetic_peak", "backing_hourglass_dissipated", NULL,
};

static void backing_value(const wff_model *m, const char *key, double *value)
{
    const struct wff_backing *B = on(m);
    const double s = m->symmetry_factor;
    *value = 0;
    if (!B || !B->built) {
        if (strcmp(key, "backing") == 0 && B)
            *value = B->law;
        return;
    }
    const wff_block *b = &B->block;
    double deepest, diameter, volume;
    if (strcmp(key, "backing") == 0)
        *value = B->law;
    else if (strcmp(key, "backface_signature") == 0)
        crater(m, b, value, &diameter, &volume);
    else if (strcmp(key, "crater_diameter") == 0)
        crater(m, b, &deepest, value, &volume);
    else if (strcmp(key, "crater_volume") == 0)
        crater(m, b, &deepest, &diameter, value);
    else if (strcmp(key, "backing_hourglass_dissipated") == 0)
        *value = s * b->hourglass_viscous;
    else if (strcmp(key, "backing_peak_depth") == 0)
        *value = B->run.peak_depth;
    else if (strcmp(key, "backing_kinetic") == 0)
        *value = s * block_kinetic(b);
    else if (strcmp(key, "backing_stored") == 0)
        *value = s * b->stored;
    else if (strcmp(key, "backing_dissipated") == 0)
        *value = s * b->dissipated;
    else if (strcmp(key, "backing_contact_loss") == 0)
        *value = s * backing_loss(m);
    else if (strcmp(key, "backing_elements") == 0)
        *value = b->n_elements;
    else if (strcmp(key, "backing_contacts") == 0)
        *value = B->contacts.n + B->projectile_contacts;
    else if (strcmp(key, "backing_seconds") == 0)
        *value = B->seconds;
    else if (strcmp(key, "backing_step") == 0)
        *value = B->run.block_step;
    else if (strcmp(key, "backing_overlap") == 0)
        *value = B->overlap;
    else if (strcmp(key, "backing_kinetic_peak") == 0)
        *value = s * B->run.kinetic_peak;
}

/* ---- checkpoints, transfers, free ------------------------------------------------ */

static int backing_state_fields(wff_model *m, wff_state_field *f)
{
    struct wff_backing *B = on(m);
    wff_error err;
    if (!B || (!B->built && build(m, B, &err)))
        return 0;
    wff_block *b = &B->block;
    const size_t nd = 3 * (size_t)b->n_nodes, ne = (size_t)b->n_elements * b->points;
    int k = 0;
    f[k++] = (wff_state_field){b->u, sizeof(double), nd};
    f[k++] = (wff_state_field){b->v, sizeof(double), nd};
    if (b->clay_state)
        f[k++] = (wff_state_field){b->clay_state, sizeof(wff_clay_state), ne};
    else
        f[k++] = (wff_state_field){b->gelatin_state, sizeof(wff_gelatin_state), ne};
    f[k++] = (wff_state_field){&b->stored, sizeof b->stored, 1};
    f[k++] = (wff_state_field){&b->dissipated, sizeof b->dissipated, 1};
    f[k++] = (wff_state_field){&b->viscous, sizeof b->viscous, 1};
    f[k++] = (wff_state_field){&b->hourglass_viscous, sizeof b->hourglass_viscous, 1};
    const size_t points = WFF_FOOTPRINT_POINTS * (size_t)B->n_ply_nodes;
    f[k++] = (wff_state_field){B->ply_gap, sizeof(double), points};
    f[k++] = (wff_state_field){B->ply_held, sizeof(double), points};
    f[k++] = (wff_state_field){&B->run, sizeof B->run, 1};
    return k;
}

static uint64_t backing_fingerprint(const wff_model *m, uint64_t g)
{
    const struct wff_backing *B = on(m);
    if (!B)
        return g;
    const double settings[8] = {B->law, B->depth, B->finest, B->growth, B->mu, B->hourglass,
                                B->gap, B->hourglass_damping};
    g = wff_fnv1a(g, settings, sizeof settings);
    return B->integration ? wff_fnv1a(g, &B->integration, sizeof B->integration) : g;
}

static int backing_refuses_remesh(const wff_model *m, char *why, size_t size)
{
    if (!on(m))
        return 0;
    snprintf(why, size, "a mesh transfer does not carry the backing block");
    return 1;
}

static void backing_free(wff_model *m)
{
    if (!m->backing)
        return;
    release(m->backing);
    free(m->backing);
    m->backing = NULL;
}

const wff_part_ops wff_backing_part = {
    .name = "backing",
    .setup = backing_setup,
    .stable_step = backing_stable_step,
    .correct = backing_correct,
    .book = backing_book,
    .dissipated = backing_dissipated,
    .loss = backing_loss,
    .settings = backing_settings,
    .value_names = backing_value_names,
    .value = backing_value,
    .refuses_remesh = backing_refuses_remesh,
    .state_fields = backing_state_fields,
    .fingerprint = backing_fingerprint,
    .free = backing_free,
};

int wff_model_backing_profile(const wff_model *m, int max, double *x, double *depth)
{
    const struct wff_backing *B = on(m);
    if (!B || !B->built)
        return 0;
    const wff_block *b = &B->block;
    const double y = m->projectile.active ? m->projectile.axis[1] : b->grid[1][b->n[1] / 2];
    int row = 0;
    for (int j = 1; j <= b->n[1]; j++)
        if (fabs(b->grid[1][j] - y) < fabs(b->grid[1][row] - y))
            row = j;
    int count = 0;
    for (int i = 0; i <= b->n[0] && count < max; i++, count++) {
        x[count] = b->grid[0][i];
        depth[count] = depth_at(b, i, row);
    }
    return count;
}

/* remesh.c: carry a model's whole state onto a new mesh of the same specimen
 * (wff_model_remesh, solver.h): point location in the old mesh by a bucket
 * grid over its triangles, P1 interpolation of the nodal DOFs, γᶠ per new
 * quadrature point from the old element containing it, the groups and the
 * boundary conditions set again by name, masses, forces and the stable step
 * recomputed, and the energy the transfer changed. The record of the
 * boundary conditions set by group it replays is model.c's. Knows the
 * model's arrays, the elements and the contact call; nothing of cells by
 * name, of output, of checkpoints or of FreeFEM.
 *
 * The new model is built beside the old one and swapped in only when whole:
 * a failure frees what was built and leaves the old model as it was. A
 * per-node or per-point array added to wff_model must be added here. */
#include "contact.h"
#include "part.h"
#include "zones.h"
#include "erosion.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A new node farther than this (× the old mesh's bounding-box diagonal)
 * outside the old mesh is not round-off: the meshes are not of the same
 * specimen. */
#define OUTSIDE_TOLERANCE 1e-7
/* Barycentric slack for "inside a triangle" (round-off on its edges). */
#define INSIDE_SLACK 1e-12
/* A triangle's point (a vertex) is located a little toward the triangle's
 * centre, so that the old element chosen is the one the new element lies in. */
#define NUDGE 1e-6

/* ---- the old mesh as triangles, with a bucket grid ---------------------------------- */

typedef struct locator {
    const double *xy;
    int n_tri;
    int *tri;          /* 3 per triangle (quads split 0-1-2, 0-2-3) */
    int *element;      /* old element (tris first, then quads) of each triangle */
    int *corner;       /* 3 per triangle: the element's local node of each vertex */
    double x0, y0, cell;
    int nx, ny;
    int *start, *list; /* bucket b holds list[start[b] .. start[b+1]) */
    double diagonal;
} locator;

static void locator_free(locator *L)
{
    free(L->tri);
    free(L->element);
    free(L->corner);
    free(L->start);
    free(L->list);
}

static void bucket_range(const locator *L, double lo, double hi, int n, double origin, int *a,
                         int *b)
{
    *a = (int)floor((lo - origin) / L->cell);
    *b = (int)floor((hi - origin) / L->cell);
    *a = *a < 0 ? 0 : *a >= n ? n - 1 : *a;
    *b = *b < 0 ? 0 : *b >= n ? n - 1 : *b;
}

static int locator_build(locator *L, const wff_mesh *mesh, wff_error *err)
{
    memset(L, 0, sizeof *L);
    L->xy = mesh->xy;
    L->n_tri = mesh->n_tris + 2 * mesh->n_quads;
    size_t nt = (size_t)(L->n_tri ? L->n_tri : 1);
    L->tri = malloc(3 * sizeof(int) * nt);
    L->element = malloc(sizeof(int) * nt);
    L->corner = malloc(3 * sizeof(int) * nt);
    if (!L->tri || !L->element || !L->corner)
        goto oom;
    for (int e = 0; e < mesh->n_tris; e++)
        for (int a = 0; a < 3; a++) {
            L->tri[3 * e + a] = mesh->tri[3 * e + a];
            L->corner[3 * e + a] = a;
            L->element[e] = e;
        }
    static const int split[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int q = 0; q < mesh->n_quads; q++)
        for (int h = 0; h < 2; h++) {
            int t = mesh->n_tris + 2 * q + h;
            L->element[t] = mesh->n_tris + q;
            for (int a = 0; a < 3; a++) {
                L->corner[3 * t + a] = split[h][a];
                L->tri[3 * t + a] = mesh->quad[4 * q + split[h][a]];
            }
        }
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (int n = 0; n < mesh->n_nodes; n++) {
        x0 = fmin(x0, mesh->xy[2 * n]), x1 = fmax(x1, mesh->xy[2 * n]);
        y0 = fmin(y0, mesh->xy[2 * n + 1]), y1 = fmax(y1, mesh->xy[2 * n + 1]);
    }
    L->diagonal = hypot(x1 - x0, y1 - y0);
    /* about one triangle per bucket */
    double w = fmax(x1 - x0, 1e-300), h = fmax(y1 - y0, 1e-300);
    L->cell = fmax(sqrt(w * h / (double)nt), 1e-3 * fmax(w, h));
    L->nx = (int)(w / L->cell) + 1;
    L->ny = (int)(h / L->cell) + 1;
    L->x0 = x0, L->y0 = y0;
    size_t nb = (size_t)L->nx * (size_t)L->ny;
    L->start = calloc(nb + 1, sizeof(int));
    if (!L->start)
        goto oom;
    for (int pass = 0; pass < 2; pass++) { /* count, then fill */
        if (pass == 1) {
            for (size_t b = 0; b < nb; b++)
                L->start[b + 1] += L->start[b];
            L->list = malloc(sizeof(int) * (size_t)(L->start[nb] ? L->start[nb] : 1));
            if (!L->list)
                goto oom;
        }
        for (int t = 0; t < L->n_tri; t++) {
            double lx = INFINITY, hx = -INFINITY, ly = INFINITY, hy = -INFINITY;
            for (int a = 0; a < 3; a++) {
                const double *p = mesh->xy + 2 * L->tri[3 * t + a];
                lx = fmin(lx, p[0]), hx = fmax(hx, p[0]);
                ly = fmin(ly, p[1]), hy = fmax(hy, p[1]);
            }
            double pad = 1e-9 * L->diagonal;
            int ia, ib, ja, jb;
            bucket_range(L, lx - pad, hx + pad, L->nx, L->x0, &ia, &ib);
            bucket_range(L, ly - pad, hy + pad, L->ny, L->y0, &ja, &jb);
            for (int j = ja; j <= jb; j++)
                for (int i = ia; i <= ib; i++) {
                    size_t b = (size_t)j * (size_t)L->nx + (size_t)i;
                    if (pass == 0)
                        L->start[b + 1]++;
                    else
                        L->list[L->start[b]++] = t;
                }
        }
        if (pass == 1) /* the fill moved each start to the next bucket's: shift back */
            for (size_t b = nb; b > 0; b--)
                L->start[b] = L->start[b - 1];
        if (pass == 1)
            L->start[0] = 0;
    }
    return 0;
oom:
    locator_free(L);
    return wff_fail(err, "wff_model_remesh: out of memory for the point location grid");
}

/* Barycentric coordinates of p in triangle t: each the signed area of p with
 * the opposite edge over the whole, formed with p subtracted first so that at
 * a vertex they are exactly 1, 0, 0. */
static void barycentric(const locator *L, int t, const double p[2], double lam[3])
{
    const double *a = L->xy + 2 * L->tri[3 * t], *b = L->xy + 2 * L->tri[3 * t + 1],
                 *c = L->xy + 2 * L->tri[3 * t + 2];
    double whole = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    double ax = a[0] - p[0], ay = a[1] - p[1], bx = b[0] - p[0], by = b[1] - p[1],
           cx = c[0] - p[0], cy = c[1] - p[1];
    lam[0] = (bx * cy - by * cx) / whole;
    lam[1] = (cx * ay - cy * ax) / whole;
    lam[2] = (ax * by - ay * bx) / whole;
    int big = lam[1] > lam[0] ? (lam[2] > lam[1] ? 2 : 1) : (lam[2] > lam[0] ? 2 : 0);
    lam[big] = 1 - lam[(big + 1) % 3] - lam[(big + 2) % 3]; /* exactly 1 at a vertex */
}

/* Nearest point of triangle t to p: barycentric coordinates (clamped) and the
 * distance. */
static double nearest_in_triangle(const locator *L, int t, const double p[2], double lam[3])
{
    barycentric(L, t, p, lam);
    if (lam[0] >= 0 && lam[1] >= 0 && lam[2] >= 0)
        return 0;
    double best = INFINITY, best_lam[3] = {1, 0, 0};
    for (int k = 0; k < 3; k++) { /* edge k → k+1 */
        const double *a = L->xy + 2 * L->tri[3 * t + k],
                     *b = L->xy + 2 * L->tri[3 * t + (k + 1) % 3];
        double ex = b[0] - a[0], ey = b[1] - a[1], len2 = ex * ex + ey * ey;
        double s = len2 > 0 ? ((p[0] - a[0]) * ex + (p[1] - a[1]) * ey) / len2 : 0;
        s = s < 0 ? 0 : s > 1 ? 1 : s;
        double d = hypot(a[0] + s * ex - p[0], a[1] + s * ey - p[1]);
        if (d < best) {
            best = d;
            best_lam[k] = 1 - s, best_lam[(k + 1) % 3] = s, best_lam[(k + 2) % 3] = 0;
        }
    }
    memcpy(lam, best_lam, sizeof best_lam);
    return best;
}

/* The old triangle containing p (the most inside one), or the nearest one;
 * *distance is 0 inside, else how far p lies outside. */
static int locate(const locator *L, const double p[2], double lam[3], double *distance)
{
    int i, j, ib, jb;
    bucket_range(L, p[0], p[0], L->nx, L->x0, &i, &ib);
    bucket_range(L, p[1], p[1], L->ny, L->y0, &j, &jb);
    size_t b = (size_t)j * (size_t)L->nx + (size_t)i;
    int best = -1;
    double best_min = -INFINITY, l[3];
    for (int k = L->start[b]; k < L->start[b + 1]; k++) {
        int t = L->list[k];
        barycentric(L, t, p, l);
        double lo = fmin(l[0], fmin(l[1], l[2]));
        if (lo > best_min) {
            best_min = lo;
            best = t;
            memcpy(lam, l, sizeof l);
        }
    }
    if (best >= 0 && best_min >= -INSIDE_SLACK) {
        *distance = 0;
        return best;
    }
    /* outside (by round-off, or not): the nearest triangle of all */
    double best_d = INFINITY;
    for (int t = 0; t < L->n_tri; t++) {
        double d = nearest_in_triangle(L, t, p, l);
        if (d < best_d) {
            best_d = d;
            best = t;
            memcpy(lam, l, sizeof l);
        }
    }
    *distance = best_d;
    return best;
}

/* ---- the new model ------------------------------------------------------------------ */

/* The old mesh's groups in the new one: by name, else by tag (edge label or
 * triangle region) under the old name. A group a boundary condition uses
 * that is in neither way is an error. */
static int carry_groups(const wff_model *m, wff_mesh *mesh, wff_error *err)
{
    for (int g = 0; g < m->mesh.n_groups; g++) {
        const wff_mesh_group *old = &m->mesh.groups[g];
        if (wff_mesh_group_tag(mesh, old->dim, old->name) >= 0)
            continue;
        int present = 0;
        if (old->dim == 1)
            for (int e = 0; e < mesh->n_edges && !present; e++)
                present = mesh->edge_label[e] == old->tag;
        else {
            for (int e = 0; e < mesh->n_tris && !present; e++)
                present = mesh->tri_region[e] == old->tag;
            for (int e = 0; e < mesh->n_quads && !present; e++)
                present = mesh->quad_region[e] == old->tag;
        }
        if (!present) {
            for (int b = 0; b < m->n_bc; b++)
                if (strcmp(m->bc[b].group, old->name) == 0)
                    return wff_fail(err, "wff_model_remesh: group '%s' (%s, tag %d) carries a "
                                    "boundary condition but is not in the new mesh (no %s "
                                    "labelled %d)", old->name, old->dim == 1 ? "curve" : "surface",
                                    old->tag, old->dim == 1 ? "boundary edge" : "triangle",
                                    old->tag);
            continue; /* an unused group that did not survive: dropped */
        }
        wff_mesh_group *groups = realloc(mesh->groups, sizeof *groups * (size_t)(mesh->n_groups + 1));
        if (!groups)
            return wff_fail(err, "wff_model_remesh: out of memory");
        mesh->groups = groups;
        groups[mesh->n_groups++] = *old;
    }
    for (int b = 0; b < m->n_bc; b++) /* a group of a name the old mesh did not have */
        if (wff_mesh_group_tag(mesh, 1, m->bc[b].group) < 0 &&
            wff_mesh_group_tag(mesh, 2, m->bc[b].group) < 0)
            return wff_fail(err, "wff_model_remesh: group '%s' carries a boundary condition but "
                            "is not in the new mesh", m->bc[b].group);
    return 0;
}

/* Position of quadrature point q of new element e (tris: the vertices; quads:
 * the 2×2 Gauss points) and, for a triangle's vertex, a point nudged toward
 * the element's centre to pick the old element. */
static void point_position(const wff_mesh *mesh, int e, int q, double p[2], double pick[2])
{
    if (e < mesh->n_tris) {
        const int *node = mesh->tri + 3 * e;
        double c[2] = {0, 0};
        for (int a = 0; a < 3; a++)
            c[0] += mesh->xy[2 * node[a]] / 3, c[1] += mesh->xy[2 * node[a] + 1] / 3;
        p[0] = mesh->xy[2 * node[q]], p[1] = mesh->xy[2 * node[q] + 1];
        pick[0] = p[0] + NUDGE * (c[0] - p[0]), pick[1] = p[1] + NUDGE * (c[1] - p[1]);
        return;
    }
    static const double sign[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    const double g = 0.57735026918962576451; /* 1/√3, membrane_quad.c's order */
    const int *node = mesh->quad + 4 * (e - mesh->n_tris);
    p[0] = p[1] = 0;
    for (int a = 0; a < 4; a++) {
        double N = 0.25 * (1 + sign[a][0] * g * sign[q][0]) * (1 + sign[a][1] * g * sign[q][1]);
        p[0] += N * mesh->xy[2 * node[a]], p[1] += N * mesh->xy[2 * node[a] + 1];
    }
    pick[0] = p[0], pick[1] = p[1];
}

/* Old quadrature-point index (into the points' states) and weight list for new point p in
 * old triangle t (barycentric lam at p): a triangle element's three points
 * with weights lam, or a quad's nearest Gauss point. Returns how many. */
static int old_points(const wff_model *m, const locator *L, int t, const double lam_in[3],
                      int idx[3], double w[3])
{
    int e = L->element[t];
    if (e < m->mesh.n_tris) {
        double lam[3], s = 0;
        for (int k = 0; k < 3; k++)
            s += lam[k] = lam_in[k] > 0 ? lam_in[k] : 0;
        for (int k = 0; k < 3; k++) {
            idx[k] = WFF_TRI_POINTS * e + L->corner[3 * t + k];
            w[k] = s > 0 ? lam[k] / s : 1.0 / 3;
        }
        return 3;
    }
    /* the point itself from the barycentric coordinates, then the nearest Gauss point */
    double p[2] = {0, 0}, pick[2];
    for (int k = 0; k < 3; k++)
        p[0] += lam_in[k] * L->xy[2 * L->tri[3 * t + k]],
        p[1] += lam_in[k] * L->xy[2 * L->tri[3 * t + k] + 1];
    int best = 0;
    double best_d = INFINITY;
    for (int q = 0; q < WFF_QUAD_POINTS; q++) {
        double g[2];
        point_position(&m->mesh, e, q, g, pick);
        double d = hypot(g[0] - p[0], g[1] - p[1]);
        if (d < best_d)
            best_d = d, best = q;
    }
    idx[0] = (int)wff_element_first_point(m->mesh.n_tris, e) + best;
    w[0] = 1;
    return 1;
}

static int allocate(wff_model *nm, wff_error *err)
{
    size_t nn = (size_t)nm->n_nodes;
    int ok = wff_model_alloc_arrays(nm) == 0; /* (model.c's, as a model's creation) */
    if (nm->projectile.active) {
        nm->projectile.candidates = malloc(sizeof(int) * nn);
        nm->projectile.contact_node = malloc(sizeof(int) * nn);
        nm->projectile.impulse = malloc(3 * sizeof(double) * nn);
        ok = ok && nm->projectile.candidates && nm->projectile.contact_node &&
             nm->projectile.impulse;
    }
    if (!ok)
        return wff_fail(err, "wff_model_remesh: out of memory for a model of %d nodes",
                        nm->n_nodes);
    return 0;
}

/* Interpolate the nodal state and the point state of m onto nm. Every
 * internal state of a point is the weighted mean of the old points' (the
 * weights old_points gives: barycentric over an old triangle's three points,
 * or a quad's nearest Gauss point), except a yarn damage (the cell's
 * damage_state), which must not decrease: the largest of the old points'
 * with a positive weight. (An element_length state is then set anew,
 * wff_model_set_element_lengths.) */
static int transfer_state(const wff_model *m, wff_model *nm, const locator *L,
                          wff_remesh_report *rep, wff_error *err)
{
    const double half = m->v_half_valid ? 0.5 * m->dt : 0;
    const double limit = OUTSIDE_TOLERANCE * L->diagonal;
    for (int n = 0; n < nm->n_nodes; n++) {
        const double *p = nm->mesh.xy + 2 * n;
        double lam[3], distance;
        int t = locate(L, p, lam, &distance);
        if (t < 0 || distance > limit)
            return wff_fail(err, "wff_model_remesh: new node %d at (%g, %g) m is %.3g m outside "
                            "the old mesh (more than round-off, %.3g m): not a mesh of the same "
                            "specimen", wff_model_user_node(nm, n) + 1, p[0], p[1],
                            t < 0 ? INFINITY : distance, limit);
        if (distance > 0) {
            rep->snapped_nodes++;
            rep->largest_snap = fmax(rep->largest_snap, distance);
        }
        for (int j = 0; j < D; j++) {
            double u = 0, v = 0;
            for (int k = 0; k < 3; k++) {
                int i = D * L->tri[3 * t + k] + j;
                double vn = m->v[i];
                if (m->dof_kind[i] == WFF_DOF_FREE)
                    vn -= half * m->f[i] / m->mass[i];
                u += lam[k] * m->u[i];
                v += lam[k] * vn;
            }
            nm->u[D * n + j] = u;
            nm->v[D * n + j] = v;
        }
    }
    const int ns = m->n_state;
    int is_damage[WFF_STATE_MAX] = {0};
    for (int k = 0; k < 2; k++) {
        int d = wff_cell_damage_state(m->mat.cell, k);
        if (d >= 0 && d < ns)
            is_damage[d] = 1;
    }
    int n_el = nm->el.n_tris + nm->el.n_quads;
    for (int e = 0; e < n_el; e++) {
        int np = e < nm->el.n_tris ? WFF_TRI_POINTS : WFF_QUAD_POINTS;
        int base = e < nm->el.n_tris ? WFF_TRI_POINTS * e
                                     : WFF_TRI_POINTS * nm->el.n_tris +
                                           WFF_QUAD_POINTS * (e - nm->el.n_tris);
        for (int q = 0; q < np; q++) {
            double p[2], pick[2], lam[3], distance;
            point_position(&nm->mesh, e, q, p, pick);
            int t = locate(L, pick, lam, &distance);
            barycentric(L, t, p, lam);
            int idx[3];
            double w[3];
            int k_n = old_points(m, L, t, lam, idx, w);
            double s[WFF_STATE_MAX] = {0}, dA[2] = {0, 0};
            for (int j = 0; j < ns; j++)
                s[j] = is_damage[j] ? -INFINITY : 0;
            for (int k = 0; k < k_n; k++) {
                const double *old = m->state + (size_t)ns * (size_t)idx[k];
                for (int j = 0; j < ns; j++) {
                    if (!is_damage[j])
                        s[j] += w[k] * old[j];
                    else if (w[k] > 0)
                        s[j] = fmax(s[j], old[j]);
                }
                if (m->el.point_dA)
                    dA[0] += w[k] * m->el.point_dA[2 * idx[k]],
                    dA[1] += w[k] * m->el.point_dA[2 * idx[k] + 1];
            }
            for (int j = 0; j < ns; j++) /* (a damage with no positive weight: the first's) */
                nm->state[(size_t)ns * (size_t)(base + q) + (size_t)j] =
                    s[j] == -INFINITY ? m->state[(size_t)ns * (size_t)idx[0] + (size_t)j] : s[j];
            if (nm->el.point_dA)
                nm->el.point_dA[2 * (base + q)] = dA[0],
                nm->el.point_dA[2 * (base + q) + 1] = dA[1];
        }
    }
    (void)err;
    return 0;
}

static int replay_bcs(const wff_model *m, wff_model *nm, wff_error *err)
{
    for (int b = 0; b < m->n_bc; b++) {
        const wff_bc_record *r = &m->bc[b];
        int rc = r->kind == WFF_DOF_FIXED ? wff_model_fix_group(nm, r->group, r->component, err)
                 : r->kind == WFF_DOF_PRESCRIBED
                     ? wff_model_prescribe_group(nm, r->group, r->component, r->value, err)
                     : wff_model_clamp_friction(nm, r->group, r->value, r->mu, err);
        if (rc < 0) {
            char why[WFF_ERROR_MAX];
            snprintf(why, sizeof why, "%s", err->message);
            return wff_fail(err, "wff_model_remesh: setting the boundary conditions again: %s",
                            why);
        }
    }
    /* the clamp's settings (wff_model_clamp_friction sets them to their defaults) */
    if (nm->clamp.n && m->clamp.radius > 0 &&
        wff_model_set_option(nm, "clamp_radius", m->clamp.radius, err) < 0)
        return -1;
    if (nm->clamp.n && m->clamp.edge_reaction &&
        wff_model_set_option(nm, "clamp_edge_reaction", 1, err) < 0)
        return -1;
    return 0;
}

/* Stored + kinetic energy (the balance's kinetic energy: the integer-step one
 * less the stagger (Δt²/8) Σ f²/m at the model's step, the contact impulses'
 * share of it counted back), J, whole specimen; *stagger: the stagger less that
 * share (what the integer-step reading puts back). The stagger goes as Δt²: a
 * transfer re-plans the step (from the new mesh's stable step), and its change
 * is counted in the transfer with the state's (onto the same mesh the state's
 * is 0, the step's not: the stable step is re-estimated at the state now). */
static double stored_plus_kinetic(const wff_model *m, double *stagger)
{
    wff_energies e;
    wff_model_energies(m, &e);
    *stagger = e.kinetic_stagger - e.impulse_stagger;
    return e.internal + e.kinetic_inplane + e.kinetic_transverse + e.kinetic_amplitude +
           e.kinetic_projectile - *stagger;
}

int wff_model_remesh(wff_model *m, wff_mesh *new_mesh, wff_remesh_report *report,
                     wff_error *err)
{
    wff_remesh_report rep = {0, 0, 0, 0, 0};
    char refusal[WFF_ERROR_MAX - 32];
    if (wff_parts_refuse_remesh(m, refusal, sizeof refusal)) { /* a part that does not carry over
                                                          (erosion, damage): m unchanged */
        wff_mesh_free(new_mesh);
        return wff_fail(err, "wff_model_remesh: %s", refusal);
    }
    if (m->zones) { /* (m unchanged: the new mesh is freed, as on any failure) */
        wff_mesh_free(new_mesh);
        return wff_fail(err, "wff_model_remesh: the model has zonal materials (%d zones); "
                        "a mesh transfer does not carry zones: run without -adapt or "
                        "without zones", wff_model_zone_count(m));
    }
    wff_model nm = *m; /* every scalar: settings, preload, accumulators, projectile */
    nm.dist = NULL;    /* (the new mesh's split over the ranks is made anew) */
    nm.mesh = *new_mesh;
    memset(new_mesh, 0, sizeof *new_mesh);
    memset(&nm.el, 0, sizeof nm.el);
    nm.u = nm.v = nm.f = nm.mass = nm.v_prescribed = nm.state = nm.reaction = NULL;
    nm.contact_force = NULL;
    nm.dof_kind = NULL;
    nm.projectile.candidates = nm.projectile.contact_node = NULL;
    nm.projectile.impulse = NULL;
    nm.projectile.n_candidates = 0;
    nm.clamp.node = NULL, nm.clamp.normal_force = NULL, nm.clamp.impulse = NULL, nm.clamp.n = 0;
    nm.bc = NULL, nm.n_bc = 0;
    nm.operator_scratch = NULL; /* operators.c's workspace: the new model allocates its own */
    nm.node_user = nm.node_model = nm.element_user = nm.element_model = NULL;
    nm.eroded_now = NULL, nm.eroded_now_energy = NULL, nm.n_eroded_now = 0;
    for (int k = 0; k < 2; k++) /* (another mesh's) */
        nm.snapshot[k] = NULL, nm.snapshot_size[k] = 0, nm.snapshot_step[k] = -1;
    nm.cut_since_snapshot = 0;
    locator L;
    memset(&L, 0, sizeof L);
    char why[WFF_ERROR_MAX];
    if (nm.mesh.n_nodes <= 0 || nm.mesh.n_tris + nm.mesh.n_quads <= 0) {
        wff_fail(err, "wff_model_remesh: the new mesh has no nodes or no elements");
        goto fail;
    }
    if (wff_elements_init(&nm.el, nm.mesh.xy, nm.mesh.n_tris, nm.mesh.tri, nm.mesh.n_quads,
                          nm.mesh.quad, err))
        goto fail_prefixed;
    if (m->node_user) { /* renumbered as the old one was (checked above in the caller's order) */
        wff_elements_free(&nm.el);
        if (wff_model_renumber(&nm, err) ||
            wff_elements_init(&nm.el, nm.mesh.xy, nm.mesh.n_tris, nm.mesh.tri, nm.mesh.n_quads,
                              nm.mesh.quad, err))
            goto fail_prefixed;
    }
    if (m->el.n_threads > 1 && wff_elements_set_threads(&nm.el, m->el.n_threads, err))
        goto fail_prefixed;
    if (wff_parts_carry(m, &nm, err)) /* (erosion stays on: nothing has eroded) */
        goto fail_prefixed;
    nm.n_nodes = nm.mesh.n_nodes;
    nm.n_dofs = D * nm.n_nodes;
    if (allocate(&nm, err) || carry_groups(m, &nm.mesh, err))
        goto fail;
    if (m->el.point_dA) {
        const double guess[2] = {0, 0};
        if (wff_elements_static_amplitudes(&nm.el, &nm.em, guess, err))
            goto fail_prefixed;
    }
    if (locator_build(&L, &m->mesh, err) || transfer_state(m, &nm, &L, &rep, err))
        goto fail;
    wff_model_set_element_lengths(&nm); /* the new elements' own, not the old ones' mean */
    wff_elements_masses(&nm.el, &nm.em, nm.n_nodes, nm.mass);
    nm.fabric_mass = 0;
    for (int n = 0; n < nm.n_nodes; n++)
        nm.fabric_mass += nm.mass[D * n];
    if (wff_cell_amplitudes(nm.mat.cell) == 0)
        for (int n = 0; n < nm.n_nodes; n++)
            nm.dof_kind[D * n + 3] = nm.dof_kind[D * n + 4] = WFF_DOF_FIXED;
    if (replay_bcs(m, &nm, err)) /* (they zero or set the velocities of their DOFs) */
        goto fail;
    /* a new node between old nodes on the projectile's curved surface lies
     * inside it (by ~h²/8R, more where the nose had reached between the old
     * nodes): the projectile goes back until none is. Pushing the nodes out
     * instead would stretch the stiff yarns (arc longer than chord) and lock
     * the cell; left inside, the next contact correction would throw them out
     * at ~δ/Δt. */
    if (nm.projectile.active) {
        wff_contact_refresh_candidates(&nm);
        rep.retraction = wff_contact_retract(&nm);
    }
    /* forces at uⁿ, the states held */
    wff_force_totals tot;
    wff_elements_forces(&nm.el, &nm.em, nm.mesh.xy, nm.u, nm.state, 0, nm.f, &tot);
    if (tot.bad_element >= 0) {
        wff_fail(err, "wff_model_remesh: element %d of the new mesh, quadrature point %d: the "
                 "interpolated state is degenerate or not finite",
                 wff_model_user_element(&nm, tot.bad_element) + 1,
                 tot.bad_point + 1);
        goto fail;
    }
    nm.internal_energy = tot.internal_energy;
    nm.blowup_steps = 0;
    double contact_booked = 0; /* J (model part) */
    if (nm.v_half_valid) {
        int worst;
        double dt = wff_elements_stable_step(&nm.el, &nm.em, nm.mesh.xy, nm.u, &worst);
        if (!(dt > 0) || !isfinite(dt)) {
            wff_fail(err, "wff_model_remesh: stable step %g s on the new mesh is not positive "
                     "(element %d)", dt, wff_model_user_element(&nm, worst) + 1);
            goto fail;
        }
        nm.dt_stable = dt, nm.dt_worst_element = worst, nm.dt = nm.dt_factor * dt;
        /* v^{n+½} from vⁿ with the new step, as at the start of a run */
        for (int i = 0; i < nm.n_dofs; i++) {
            if (nm.dof_kind[i] == WFF_DOF_FREE)
                nm.v[i] += 0.5 * nm.dt * nm.f[i] / nm.mass[i];
            else
                nm.reaction[i] = -nm.f[i];
        }
        nm.dt_mid = 0.5 * nm.dt;
        if (nm.projectile.active)
            nm.projectile.velocity = m->projectile.velocity +
                                     0.5 * m->dt * m->projectile.force / m->projectile.mass;
        /* the parts' corrections of the new half step (the friction clamp's, the
         * projectile's contact): what they change is the transfer's, not a
         * dissipation (their kinetic energy is in e_after): the accounts as they
         * were carried */
        const double friction = nm.dissipated_friction, parts = wff_parts_dissipated(&nm);
        if (wff_parts_correct(&nm, nm.dt, 0.5 * nm.dt, err))
            goto fail_prefixed;
        wff_parts_book(&nm, 0, 0.5 * nm.dt);
        nm.dissipated_friction = friction;
        contact_booked = wff_parts_dissipated(&nm) - parts; /* (0: a pack refuses a transfer) */
    } else if (nm.projectile.active) {
        wff_contact_refresh_candidates(&nm);
    }
    double s_before, s_after; /* (the staggers) */
    double e_before = stored_plus_kinetic(m, &s_before);
    double e_after = stored_plus_kinetic(&nm, &s_after);
    if (nm.v_half_valid) { /* a run that has not started measures its energy from here */
        /* (a part's dissipation at the new half step is the transfer's too) */
        nm.transfer_energy += (e_after - e_before) / nm.symmetry_factor + contact_booked;
        /* the integer-step balance (the detector's) carried over unchanged too */
        nm.stagger_reference += (s_after - s_before) / nm.symmetry_factor;
    }
    locator_free(&L);
    /* swap: the old model's arrays go, the rest moves over */
    wff_model old = *m;
    *m = nm;
    m->em.mat = &m->mat;
    old.comm = wff_comm_self(); /* (the communicator moved to m with the struct) */
    wff_model_free(&old); /* the old one's arrays (a copy of the struct: m keeps the rest) */
    rep.before = e_before;
    rep.after = e_after;
    if (report)
        *report = rep;
    return 0;
fail_prefixed:
    snprintf(why, sizeof why, "%s", err->message);
    wff_fail(err, "wff_model_remesh: %s", why);
fail:
    locator_free(&L);
    nm.comm = wff_comm_self(); /* (m keeps its communicator) */
    wff_model_free(&nm);
    return -1;
}

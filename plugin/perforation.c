/* perforation.c: the verdict of a shot, perforated, stopped or undecided
 * (include/wovenff/perforation.h: the rule), and the part of a ply still held
 * (wff_ply_held_nodes, which pack.c's ply apex reads too). Geometry of the
 * state now only: held connectivity through elements, the shot line against
 * each ply's elements in the current x-y positions, the footprint's nodes
 * against the nose's rear. Off the per-step path: it allocates its scratch per
 * call. A part (part.h) for its values by name. Knows the model's arrays, the
 * pack's layout and erosion's flags; nothing of FreeFEM. */
#include "perforation.h"
#include "erosion.h"
#include "plies.h"
#include "ply_contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void wff_ply_node_range(const wff_model *m, int p, int *first, int *end)
{
    int many = wff_pack_plies(m) > 1, per = many ? m->pack->nodes : m->n_nodes;
    *first = many ? p * per : 0;
    *end = *first + per;
}

/* Element e's nodes (returned: 3 or 4) at *c. */
static int element_nodes(const wff_model *m, int e, const int **c)
{
    const int nt = m->el.n_tris;
    *c = e < nt ? m->el.tri + 3 * e : m->el.quad + 4 * (e - nt);
    return e < nt ? 3 : 4;
}

/* Whether element e joins its nodes under `mode`. */
static int joins(const wff_model *m, int e, int mode)
{
    if (wff_element_eroded(&m->el, e))
        return 0;
    return mode == WFF_HELD_LIVE || !wff_element_torn(m, e);
}

int wff_ply_held_nodes(const wff_model *m, int p, int mode, unsigned char *held)
{
    int first, end;
    wff_ply_node_range(m, p, &first, &end);
    const int nn = end - first, n_el = m->el.n_tris + m->el.n_quads;
    memset(held, 0, (size_t)nn);
    int *offset = calloc((size_t)nn + 1, sizeof(int)), *queue = malloc(sizeof(int) * (size_t)(nn ? nn : 1));
    unsigned char *joining = malloc((size_t)(n_el ? n_el : 1));
    int *incident = NULL, count = -1;
    if (!offset || !queue || !joining)
        goto done;
    for (int e = 0; e < n_el; e++) { /* node -> joining elements (CSR) */
        joining[e] = wff_pack_element_ply(m, e) == p && joins(m, e, mode);
        if (!joining[e])
            continue;
        const int *c;
        for (int j = 0, k = element_nodes(m, e, &c); j < k; j++)
            offset[c[j] - first + 1]++;
    }
    for (int i = 0; i < nn; i++)
        offset[i + 1] += offset[i];
    incident = malloc(sizeof(int) * (size_t)(offset[nn] > 0 ? offset[nn] : 1));
    if (!incident)
        goto done;
    int *fill = queue; /* (the queue's room, as fill counters first) */
    memcpy(fill, offset, sizeof(int) * (size_t)nn);
    for (int e = 0; e < n_el; e++) {
        if (!joining[e])
            continue;
        const int *c;
        for (int j = 0, k = element_nodes(m, e, &c); j < k; j++)
            incident[fill[c[j] - first]++] = e;
    }
    int head = 0, tail = 0;
    for (int i = 0; i < nn; i++)
        if (offset[i + 1] > offset[i] && m->dof_kind[D * (first + i) + WFF_UZ] != WFF_DOF_FREE)
            held[i] = 1, queue[tail++] = i;
    if (tail == 0) { /* nothing held: every node of a joining element */
        for (int i = 0; i < nn; i++)
            if (offset[i + 1] > offset[i])
                held[i] = 1, tail++;
        count = tail;
        goto done;
    }
    while (head < tail) {
        const int i = queue[head++];
        for (int k = offset[i]; k < offset[i + 1]; k++) {
            const int *c;
            for (int j = 0, kn = element_nodes(m, incident[k], &c); j < kn; j++)
                if (!held[c[j] - first])
                    held[c[j] - first] = 1, queue[tail++] = c[j] - first;
        }
    }
    count = tail;
done:
    free(offset);
    free(queue);
    free(joining);
    free(incident);
    return count;
}

/* Node n's current position. */
static void position(const wff_model *m, int n, double x[3])
{
    x[0] = m->mesh.xy[2 * n] + m->u[D * n + WFF_UX];
    x[1] = m->mesh.xy[2 * n + 1] + m->u[D * n + WFF_UY];
    x[2] = m->u[D * n + WFF_UZ];
}

/* Whether the point (px, py) lies in triangle a b c projected on the x-y
 * plane (its edges included, to a relative 1e-9 of its area); then its z
 * there, interpolated, into *z. A triangle folded flat (no area) holds none. */
static int triangle_holds(const double a[3], const double b[3], const double c[3], double px,
                          double py, double *z)
{
    double area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    if (area == 0)
        return 0;
    double la = ((b[0] - px) * (c[1] - py) - (c[0] - px) * (b[1] - py)) / area;
    double lb = ((c[0] - px) * (a[1] - py) - (a[0] - px) * (c[1] - py)) / area;
    double lc = 1 - la - lb;
    const double tol = -1e-9;
    if (!(la >= tol && lb >= tol && lc >= tol))
        return 0;
    *z = la * a[2] + lb * b[2] + lc * c[2];
    return 1;
}

/* Whether element e's projection holds the point (px, py) (a quad as its two
 * triangles 0 1 2 and 0 2 3); the largest z there into *z. */
static int element_holds(const wff_model *m, int e, double px, double py, double *z)
{
    const int *c;
    int k = element_nodes(m, e, &c), any = 0;
    double x[4][3], zt;
    for (int j = 0; j < k; j++)
        position(m, c[j], x[j]);
    for (int t = 0; t + 2 < k; t++)
        if (triangle_holds(x[0], x[t + 1], x[t + 2], px, py, &zt)) {
            *z = any ? fmax(*z, zt) : zt;
            any = 1;
        }
    return any;
}

/* Whether held fabric at height z on the shot line (or a node of the footprint
 * there) stands in the projectile's way: on the nose or behind its tip (z at
 * most `reach`, a ply's thickness, ahead of the tip: a ply resting on the nose
 * has its mid-plane on the nose's surface), or further ahead and held by intact
 * yarns (`intact`). A piece lifted off the nose and held to the clamp only
 * through torn elements is a shred flung off ahead, not a ply in the way: the
 * 4-ply pack at 45 m/s (coarse) carries its strike face's torn flap on the nose
 * through the holes of the three plies behind it until 0.72 ms, when the flap
 * lifts off (0.3 mm ahead of the tip at 0.75 ms and parting at ~10 m/s) and the
 * projectile flies on at 25.2 m/s. */
static int in_the_way(double z, double tip, double reach, int intact)
{
    return z <= tip + reach || intact;
}

int wff_model_perforation(const wff_model *m, wff_perforation *out, wff_error *err)
{
    memset(out, 0, sizeof *out);
    out->verdict = WFF_VERDICT_UNDECIDED;
    const wff_projectile *pj = &m->projectile;
    if (!pj->active)
        return wff_fail(err, "perforation: the model has no projectile (set one first: "
                        "wovenffProjectile)");
    const int plies = wff_pack_plies(m), n_el = m->el.n_tris + m->el.n_quads;
    const double ax = pj->axis[0], ay = pj->axis[1], r = pj->radius;
    const double reach = wff_ply_thickness(m);
    out->plies = plies;
    out->velocity = pj->velocity;
    out->tip = pj->tip;
    out->rear = pj->tip - wff_projectile_nose_length(pj);
    int first, end;
    wff_ply_node_range(m, 0, &first, &end);
    const size_t nn = (size_t)(end - first > 0 ? end - first : 1);
    unsigned char *held = malloc(2 * nn), *intact = held + nn;
    if (!held)
        return wff_fail(err, "perforation: out of memory for %d nodes' flags", end - first);
    for (int p = 0; p < plies; p++) {
        out->shot_z[p] = NAN;
        if (wff_ply_held_nodes(m, p, WFF_HELD_LIVE, held) < 0 ||
            wff_ply_held_nodes(m, p, WFF_HELD_INTACT, intact) < 0) {
            free(held);
            return wff_fail(err, "perforation: out of memory for ply %d's connectivity", p);
        }
        wff_ply_node_range(m, p, &first, &end);
        int blocking = 0;
        for (int e = 0; e < n_el; e++) { /* the held elements over the shot line */
            const int *c;
            double z;
            if (wff_pack_element_ply(m, e) != p || wff_element_eroded(&m->el, e))
                continue;
            element_nodes(m, e, &c);
            if (!held[c[0] - first] || !element_holds(m, e, ax, ay, &z))
                continue; /* (a joining element's nodes are held together or not at all) */
            if (!in_the_way(z, out->tip, reach, intact[c[0] - first] && !wff_element_torn(m, e)))
                continue;
            out->shot_z[p] = blocking++ ? fmax(out->shot_z[p], z) : z;
        }
        int in_front = 0, rim = 0;
        double rim_z = 0;
        for (int n = first; n < end; n++) { /* the held nodes of the footprint */
            double x[3];
            if (!held[n - first])
                continue;
            position(m, n, x);
            if (hypot(x[0] - ax, x[1] - ay) > r || !in_the_way(x[2], out->tip, reach, intact[n - first]))
                continue;
            rim_z = rim++ ? fmax(rim_z, x[2]) : x[2];
            in_front += !(x[2] < out->rear);
        }
        out->holed[p] = !blocking;
        out->through[p] = !blocking && !in_front;
        if (!blocking && rim)
            out->shot_z[p] = rim_z;
        out->plies_holed += out->holed[p];
        out->plies_through += out->through[p];
    }
    free(held);
    if (out->plies_through == plies && out->velocity > 0)
        out->verdict = WFF_VERDICT_PERFORATED;
    else if (!(out->velocity > 0))
        out->verdict = WFF_VERDICT_STOPPED;
    return 0;
}

/* The part's values by name, in wovenffState's order. */
static const char *const perforation_value_names[] = {"perforation", "plies_holed",
                                                      "plies_through", NULL};

static void perforation_value(const wff_model *m, const char *key, double *value)
{
    wff_perforation verdict;
    wff_error ignored; /* (no projectile, or out of memory: undecided, nothing holed) */
    *value = 0;
    if (wff_model_perforation(m, &verdict, &ignored))
        verdict.verdict = WFF_VERDICT_UNDECIDED;
    if (strcmp(key, "perforation") == 0)
        *value = verdict.verdict;
    else if (strcmp(key, "plies_holed") == 0)
        *value = verdict.plies_holed;
    else
        *value = verdict.plies_through;
}

const wff_part_ops wff_perforation_part = {
    .name = "perforation",
    .value_names = perforation_value_names,
    .value = perforation_value,
};

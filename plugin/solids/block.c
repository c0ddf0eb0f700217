/* block.c: the backing's solid block (block.h): its graded grid, arrays and
 * held DOFs, the internal force pass over its hexahedra with the law of each,
 * its energies and stable step. Allocates at creation only. */
#include "block.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The coordinates from a to b (a < b) graded from c (a <= c <= b): sizes
 * h, h g, h g², ... away from c on each side, the last interval on a side
 * ending exactly at its end (merged with the one before when shorter than half
 * of it). Writes at most max + 1 values into out (NULL: counts only); returns
 * the number of intervals, or -1 past max. */
static int graded(double a, double b, double c, double h, double g, double *out, int max)
{
    double left[4096], right[4096];
    int nl = 0, nr = 0;
    for (int side = 0; side < 2; side++) {
        double *p = side ? right : left, end = side ? b - c : c - a, at = 0, step = h;
        int *n = side ? &nr : &nl;
        while (end > 0 && at < end * (1 - 1e-12)) {
            if (*n >= 4095)
                return -1;
            double next = at + step;
            if (next >= end || end - next < 0.5 * step * g)
                next = end;
            p[(*n)++] = next;
            at = next;
            step *= g;
        }
    }
    const int count = nl + nr;
    if (count > max)
        return -1;
    if (out) {
        int k = 0;
        for (int i = nl - 1; i >= 0; i--)
            out[k++] = c - left[i];
        out[k++] = c;
        for (int i = 0; i < nr; i++)
            out[k++] = c + right[i];
        out[0] = a, out[count] = b; /* exact ends */
    }
    return count;
}

static int check_shape(const wff_block_shape *s, wff_error *err)
{
    if (!(s->x1 > s->x0) || !(s->y1 > s->y0) || !isfinite(s->x0 + s->x1 + s->y0 + s->y1))
        return wff_fail(err, "backing block: footprint [%g, %g] x [%g, %g] m: must be a "
                        "rectangle", s->x0, s->x1, s->y0, s->y1);
    if (!(s->depth > 0) || !isfinite(s->depth))
        return wff_fail(err, "backing_depth = %g m: must be > 0", s->depth);
    if (!(s->finest > 0) || !isfinite(s->finest))
        return wff_fail(err, "backing_element = %g m: must be > 0", s->finest);
    if (!(s->growth >= 1) || !(s->growth <= 3))
        return wff_fail(err, "backing_growth = %g: must be in [1, 3]", s->growth);
    if (!isfinite(s->top))
        return wff_fail(err, "backing block: top face z = %g m: not finite", s->top);
    return 0;
}

int wff_block_create(wff_block *b, int law, const wff_block_shape *s, double hourglass,
                     wff_error *err)
{
    memset(b, 0, sizeof *b);
    if (check_shape(s, err))
        return -1;
    if (!(hourglass >= 0) || !(hourglass <= 1))
        return wff_fail(err, "backing_hourglass = %g: must be in [0, 1]", hourglass);
    b->law = law;
    b->points = 1;
    b->hourglass = hourglass;
    b->viscosity[0] = 0.06, b->viscosity[1] = 1.2;
    b->clay = wff_clay_roma_plastilina;
    b->gelatin = wff_gelatin_ordnance10;
    if (law == WFF_BLOCK_CLAY) {
        const wff_clay_params *p = &b->clay;
        b->density = p->density, b->wave_speed = wff_clay_wave_speed(p);
        b->shear = p->youngs / (2 * (1 + p->poisson));
    } else if (law == WFF_BLOCK_GELATIN) {
        const wff_gelatin_params *p = &b->gelatin;
        b->density = p->density, b->wave_speed = wff_gelatin_wave_speed(p);
        b->shear = p->shear_long + p->shear_branch;
    } else
        return wff_fail(err, "backing = %d: must be 1 (clay) or 2 (gelatin)", law);
    const double cx = fmin(fmax(s->centre[0], s->x0), s->x1);
    const double cy = fmin(fmax(s->centre[1], s->y0), s->y1);
    const double lo[3] = {s->x0, s->y0, s->top}, hi[3] = {s->x1, s->y1, s->top + s->depth};
    const double mid[3] = {cx, cy, s->top};
    for (int d = 0; d < 3; d++) {
        int count = graded(lo[d], hi[d], mid[d], s->finest, s->growth, NULL, 4000);
        if (count < 1) {
            wff_block_free(b);
            return wff_fail(err, "backing block: more than 4000 elements along %c (backing_element "
                            "= %g m, backing_growth = %g): too fine", "xyz"[d], s->finest,
                            s->growth);
        }
        b->n[d] = count;
        b->grid[d] = malloc((size_t)(count + 1) * sizeof(double));
        if (!b->grid[d]) {
            wff_block_free(b);
            return wff_fail(err, "backing block: out of memory");
        }
        graded(lo[d], hi[d], mid[d], s->finest, s->growth, b->grid[d], count);
    }
    const long elements = (long)b->n[0] * b->n[1] * b->n[2];
    if (elements > WFF_BLOCK_ELEMENTS_MAX) {
        wff_block_free(b);
        return wff_fail(err, "backing block: %ld elements (%d x %d x %d) > %d: make "
                        "backing_element or backing_growth larger", elements, b->n[0], b->n[1],
                        b->n[2], WFF_BLOCK_ELEMENTS_MAX);
    }
    b->n_elements = (int)elements;
    b->n_nodes = (b->n[0] + 1) * (b->n[1] + 1) * (b->n[2] + 1);
    const size_t nd = 3 * (size_t)b->n_nodes, ne = (size_t)b->n_elements;
    b->X = calloc(nd, sizeof(double));
    b->u = calloc(nd, sizeof(double));
    b->v = calloc(nd, sizeof(double));
    b->f = calloc(nd, sizeof(double));
    b->mass = calloc(nd, sizeof(double));
    b->held = calloc(nd, 1);
    b->hex = malloc(8 * ne * sizeof(int));
    b->ref = malloc(ne * sizeof(wff_hex8_ref));
    b->hourglass_k = malloc(ne * sizeof(double));
    b->hourglass_c = calloc(4 * ne, sizeof(double));
    const size_t top = (size_t)(b->n[0] + 1) * (b->n[1] + 1);
    b->contact_node = malloc(top * sizeof(int));
    b->contact_depth = malloc(top * sizeof(double));
    b->contact_normal = malloc(3 * top * sizeof(double));
    b->contact_speed = malloc(top * sizeof(double));
    b->contact_lambda = malloc(top * sizeof(double));
    if (law == WFF_BLOCK_CLAY)
        b->clay_state = calloc(ne, sizeof(wff_clay_state));
    else
        b->gelatin_state = calloc(ne, sizeof(wff_gelatin_state));
    if (!b->X || !b->u || !b->v || !b->f || !b->mass || !b->held || !b->hex || !b->ref ||
        !b->hourglass_k || !b->hourglass_c || !b->contact_node || !b->contact_depth ||
        !b->contact_normal || !b->contact_speed || !b->contact_lambda || (!b->clay_state && !b->gelatin_state)) {
        wff_block_free(b);
        return wff_fail(err, "backing block: out of memory (%ld elements)", elements);
    }
    for (int k = 0; k <= b->n[2]; k++)
        for (int j = 0; j <= b->n[1]; j++)
            for (int i = 0; i <= b->n[0]; i++) {
                const int n = wff_block_node(b, i, j, k);
                b->X[3 * n] = b->grid[0][i], b->X[3 * n + 1] = b->grid[1][j];
                b->X[3 * n + 2] = b->grid[2][k];
                b->held[3 * n] = i == 0 || i == b->n[0];
                b->held[3 * n + 1] = j == 0 || j == b->n[1];
                b->held[3 * n + 2] = k == b->n[2];
            }
    static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                     {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    int e = 0;
    for (int k = 0; k < b->n[2]; k++)
        for (int j = 0; j < b->n[1]; j++)
            for (int i = 0; i < b->n[0]; i++, e++) {
                double X[8][3];
                for (int a = 0; a < 8; a++) {
                    const int n = wff_block_node(b, i + corner[a][0], j + corner[a][1],
                                                 k + corner[a][2]);
                    b->hex[8 * e + a] = n;
                    memcpy(X[a], b->X + 3 * n, sizeof X[a]);
                }
                wff_hex8_reference(X, &b->ref[e]); /* (a box: never inverted) */
                b->hourglass_k[e] = wff_hex8_hourglass_stiffness(&b->ref[e], hourglass, b->shear);
                const double share = b->density * b->ref[e].volume / 8;
                for (int a = 0; a < 8; a++)
                    for (int c = 0; c < 3; c++)
                        b->mass[3 * b->hex[8 * e + a] + c] += share;
            }
    return 0;
}

void wff_block_free(wff_block *b)
{
    for (int d = 0; d < 3; d++)
        free(b->grid[d]);
    free(b->X), free(b->u), free(b->v), free(b->f), free(b->mass), free(b->held);
    free(b->hex), free(b->ref), free(b->hourglass_k), free(b->hourglass_c), free(b->full);
    free(b->clay_state), free(b->gelatin_state);
    free(b->contact_node), free(b->contact_depth), free(b->contact_normal);
    free(b->contact_speed), free(b->contact_lambda);
    memset(b, 0, sizeof *b);
}

int wff_block_integrate_fully(wff_block *b, wff_error *err)
{
    if (b->full)
        return 0; /* (already) */
    const size_t ne = (size_t)b->n_elements;
    b->full = malloc(ne * sizeof(wff_hex8_full));
    void *states = b->clay_state ? calloc(WFF_HEX_POINTS * ne, sizeof(wff_clay_state))
                                 : calloc(WFF_HEX_POINTS * ne, sizeof(wff_gelatin_state));
    if (!b->full || !states) {
        free(states);
        wff_block_free(b);
        return wff_fail(err, "backing block: out of memory (%ld fully integrated elements)",
                        (long)ne);
    }
    if (b->clay_state)
        free(b->clay_state), b->clay_state = states;
    else
        free(b->gelatin_state), b->gelatin_state = states;
    b->points = WFF_HEX_POINTS;
    for (int e = 0; e < b->n_elements; e++) {
        double X[8][3];
        for (int a = 0; a < 8; a++)
            memcpy(X[a], b->X + 3 * b->hex[8 * e + a], sizeof X[a]);
        wff_hex8_full_reference(X, &b->full[e]); /* (a box: never inverted) */
        b->hourglass_k[e] = 0;
        for (int al = 0; al < 4; al++)
            b->hourglass_c[4 * e + al] = 0;
    }
    return 0;
}

double wff_block_surface_shear_strength(const wff_block *b, int i, int j)
{
    if (!b->clay_state)
        return INFINITY;
    const int e = i + b->n[0] * j; /* (k = 0: the top layer) */
    if (b->points == 1) {
        const wff_clay_state *s = &b->clay_state[e];
        return wff_clay_yield(&b->clay, s->eq_plastic, s->plastic_rate) / sqrt(3.0);
    }
    double sum = 0; /* the points at ζ = −1, the top face (g = 0..3) */
    for (int g = 0; g < 4; g++) {
        const wff_clay_state *s = &b->clay_state[WFF_HEX_POINTS * e + g];
        sum += wff_clay_yield(&b->clay, s->eq_plastic, s->plastic_rate);
    }
    return sum / 4 / sqrt(3.0);
}

/* The law at one point: its state advanced over dt (0: held) to the strain,
 * the stress into `stress`; adds V × its dissipation so far to *dissipated;
 * returns V × its stored energy density, J. */
static double law_at(wff_block *b, int point, const double strain[6], double dt, double volume,
                     double stress[6], double *dissipated)
{
    if (b->clay_state) {
        wff_clay_state *s = &b->clay_state[point];
        if (dt > 0)
            wff_clay_update(&b->clay, strain, dt, s, s, stress);
        else
            wff_clay_stress(&b->clay, strain, s, stress);
        *dissipated += volume * s->dissipated;
        return volume * wff_clay_energy(&b->clay, strain, s);
    } else {
        wff_gelatin_state *s = &b->gelatin_state[point];
        wff_gelatin_update(&b->gelatin, strain, dt, s, s, stress);
        *dissipated += volume * s->dissipated;
        return volume * wff_gelatin_energy(&b->gelatin, strain, s);
    }
}

static int finite6(const double a[6])
{
    return isfinite(a[0] + a[1] + a[2] + a[3] + a[4] + a[5]);
}

/* The fully integrated element e's forces into fe (added) at the centre's F,
 * its det into *J_centre: 0, or -1 if the centre or a point is inverted or a
 * strain not finite. */
static int full_element(wff_block *b, int e, const double u[8][3], const double F_centre[9],
                        double dt, double fe[8][3], double *J_centre, double *stored,
                        double *dissipated)
{
    const wff_hex8_full *r = &b->full[e];
    double b_centre[8][3]; /* F_0⁻ᵀ B0_a, the same at every point */
    *J_centre = wff_hex8_current_gradients(F_centre, b->ref[e].gradient, b_centre);
    if (!(*J_centre > 0))
        return -1;
    for (int g = 0; g < WFF_HEX_POINTS; g++) {
        wff_hex8_fbar_point p;
        double strain[6], U_inv[9], stress[6];
        if (wff_hex8_fbar(r, g, u, *J_centre, &p))
            return -1;
        if (!(wff_hencky(p.F_bar, strain, U_inv) > 0) || !finite6(strain))
            return -1;
        *stored += law_at(b, WFF_HEX_POINTS * e + g, strain, dt, r->volume[g], stress, dissipated);
        wff_hex8_fbar_forces(r, g, b_centre, &p, U_inv, stress, fe);
    }
    return 0;
}

void wff_block_set_hourglass_damping(wff_block *b, double ratio)
{
    b->hourglass_damping = ratio;
    for (int e = 0; e < b->n_elements; e++)
        wff_hex8_hourglass_dashpots(&b->ref[e], b->hourglass_k[e], b->density * b->ref[e].volume / 8,
                                    ratio, b->hourglass_c + 4 * e);
}

int wff_block_forces(wff_block *b, double dt, int *bad)
{
    memset(b->f, 0, 3 * (size_t)b->n_nodes * sizeof(double));
    double stored = 0, dissipated = 0, viscous = 0, hourglass_viscous = 0;
    for (int e = 0; e < b->n_elements; e++) {
        const int *node = b->hex + 8 * e;
        const wff_hex8_ref *r = &b->ref[e];
        double u[8][3], v[8][3], F[9], strain[6], U_inv[9], stress[6], fe[8][3];
        for (int a = 0; a < 8; a++) {
            memcpy(u[a], b->u + 3 * node[a], sizeof u[a]);
            memcpy(v[a], b->v + 3 * node[a], sizeof v[a]);
        }
        wff_hex8_gradient(r, u, F);
        double J;
        if (b->full) { /* (the centre's J alone: its strain is the points') */
            memset(fe, 0, sizeof fe);
            if (full_element(b, e, u, F, dt, fe, &J, &stored, &dissipated)) {
                *bad = e;
                return -1;
            }
        } else {
            J = wff_hencky(F, strain, U_inv);
            if (!(J > 0) || !finite6(strain)) {
                *bad = e;
                return -1;
            }
            const double energy = law_at(b, e, strain, dt, r->volume, stress, &dissipated);
            wff_hex8_forces(r, F, U_inv, stress, fe);
            stored += energy + wff_hex8_hourglass(r, u, b->hourglass_k[e], fe);
        }
        if (b->hourglass_damping > 0)
            hourglass_viscous += dt * wff_hex8_hourglass_damping(r, v, b->hourglass_c + 4 * e, fe);
        if (b->viscosity[0] > 0 || b->viscosity[1] > 0)
            viscous += dt * wff_hex8_bulk_viscosity(r, F, J, v, b->density, b->wave_speed,
                                                    b->viscosity[0], b->viscosity[1], fe);
        for (int a = 0; a < 8; a++)
            for (int c = 0; c < 3; c++)
                b->f[3 * node[a] + c] += fe[a][c];
    }
    b->stored = stored;
    b->viscous += viscous + hourglass_viscous;
    b->hourglass_viscous += hourglass_viscous;
    b->dissipated = dissipated + b->viscous;
    return 0;
}

double wff_block_stable_step(const wff_block *b, int *worst)
{
    double dt = INFINITY;
    *worst = -1;
    for (int e = 0; e < b->n_elements; e++) {
        const int *node = b->hex + 8 * e;
        double u[8][3], F[9];
        for (int a = 0; a < 8; a++)
            memcpy(u[a], b->u + 3 * node[a], sizeof u[a]);
        wff_hex8_gradient(&b->ref[e], u, F);
        const double node_mass = b->density * b->ref[e].volume / 8;
        const double bare = b->full ? wff_hex8_full_stable_step(&b->ref[e], &b->full[e], u,
                                                                 b->density, b->wave_speed,
                                                                 b->shear)
                                    : wff_hex8_stable_step(&b->ref[e], F, b->wave_speed, b->hourglass_k[e],
                                                 node_mass);
        /* the damping's fraction of critical at the highest frequency 2/bare: the
         * bulk viscosity's b1 and the hourglass dashpots' ζ ω_hg/ω_max */
        const double hourglass = wff_hex8_hourglass_frequency(&b->ref[e], b->hourglass_k[e],
                                                              node_mass);
        const double damping = b->viscosity[0] + b->hourglass_damping * 0.5 * bare * hourglass;
        const double step = bare * (sqrt(1 + damping * damping) - damping);
        if (step < dt || *worst < 0) {
            dt = step;
            *worst = e;
        }
    }
    return dt;
}

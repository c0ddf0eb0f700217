/* The standard threats and the oblique shot (docs/threats.md): each steel
 * threat's shape, as the contact sees it, weighs its specification's mass
 * (its volume integrated from the penetration function × the steel's
 * density); the RCCs' derived diameters; the chisel nose's faces, normals and
 * length; an oblique projectile's foremost point against
 * wff_projectile_lead for every nose; a tilted flat face pushing the fabric
 * along its own normal, the fabric's momentum along the path what the
 * projectile lost; the energy balance of an oblique impact with each nose;
 * the momentum direction at 0 and 30 degrees; θ = 0 the normal shot bit for
 * bit; symmetric models refused. */
#include "check.h"
#include "rng.h"
#include "test_meshes.h"
#include "wovenff/solver.h"
#include "wovenff/threat.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define ELASTIC "tests/data/king_elastic.txt"
#define D WFF_DOFS_PER_NODE

static const double kPi = 3.14159265358979323846;

/* A projectile (no model) shaped as threat t, tip at z = 0 on the axis (0, 0). */
static wff_projectile shape_of(const wff_threat *t)
{
    wff_projectile p;
    memset(&p, 0, sizeof p);
    p.radius = 0.5 * t->diameter;
    p.nose = t->nose;
    p.edge_radius = t->edge_radius;
    p.chisel_flat = t->chisel_flat;
    p.chisel_bevel = t->chisel_bevel * kPi / 180;
    p.path[2] = 1;
    return p;
}

/* The volume of the shape between its tip and `length` behind it: a midpoint
 * grid of n³ cells over its bounding box. */
static double shape_volume(const wff_projectile *p, double length, int n)
{
    const double r = p->radius, hx = 2 * r / n, hz = length / n;
    long inside = 0;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            for (int k = 0; k < n; k++) {
                double x[3] = {-r + (i + 0.5) * hx, -r + (j + 0.5) * hx, -(k + 0.5) * hz}, nrm[3];
                inside += wff_projectile_penetration(p, x, nrm) > 0;
            }
    return inside * hx * hx * hz;
}

static void check_table(check_state *st)
{
    wff_error err;
    CHECK(st, wff_threat_find("fsp64", &err) == NULL && strstr(err.message, "fsp17"),
          "an unknown threat is refused, listing the known: %s", err.message);
    const wff_threat *ball = wff_threat_find("ball", &err);
    CHECK(st, ball && ball->mass == 0.104 && ball->diameter == 12.7e-3 &&
          ball->nose == WFF_NOSE_HEMISPHERE, "ball: the scene's 104 g, 12.7 mm hemisphere");
    for (int k = 0; k < wff_threat_count(); k++) {
        const wff_threat *t = wff_threat_at(k);
        CHECK(st, t->mass > 0 && t->diameter > 0 && t->source && t->source[0],
              "%s: mass %g kg, diameter %g m, a source", t->name, t->mass, t->diameter);
        if (!(t->density > 0))
            continue;
        wff_projectile p = shape_of(t);
        double volume = shape_volume(&p, t->length, 160), mass = volume * t->density;
        printf("  %-6s %-70.70s mass %.4f g, its shape in steel %.4f g (%+.2f%%)\n", t->name,
               t->what, 1e3 * t->mass, 1e3 * mass, 100 * (mass / t->mass - 1));
        /* the grid's error: ~ the surface's cells, 3 / n of the volume at most */
        CHECK(st, fabs(mass / t->mass - 1) < 0.01, "%s: the shape weighs %g kg in steel, the "
              "specification %g kg", t->name, mass, t->mass);
        if (t->nose == WFF_NOSE_FLAT && t->length == t->diameter) {
            double d = cbrt(4 * t->mass / (kPi * t->density));
            CHECK_CLOSE(st, t->diameter, d, 1e-4, 0, "RCC diameter from its mass");
        }
    }
    const wff_threat *fsp = wff_threat_find("fsp17", &err);
    CHECK(st, fsp && fabs(fsp->mass - 1.10e-3) < 0.03e-3 && fsp->diameter >= 5.385e-3 &&
          fsp->diameter <= 5.41e-3 && fsp->nose == WFF_NOSE_CHISEL,
          "fsp17: 17 grain (1.10 g), 5.385-5.41 mm, chisel");
    const wff_threat *nine = wff_threat_find("9mm", &err), *mag = wff_threat_find("44mag", &err);
    CHECK(st, nine && nine->mass == 8.0e-3 && mag && mag->mass == 15.6e-3,
          "NIJ 0101.06: 9 mm 8.0 g, .44 Magnum 15.6 g");
}

/* The chisel: a point just inside each face gives that face's depth and
 * normal; just outside, nothing; its nose length the bevel's depth. */
static void check_chisel(check_state *st)
{
    wff_error err;
    wff_projectile p = shape_of(wff_threat_find("fsp17", &err));
    p.axis[0] = 0.01, p.axis[1] = -0.02, p.tip = -1e-3;
    const double r = p.radius, w = p.chisel_flat, b = p.chisel_bevel, e = 1e-5;
    struct { double S[3], n[3]; const char *what; } face[] = {
        {{0.2 * w, 0.3 * r, 0}, {0, 0, 1}, "flat"},
        {{0.5 * w + 0.3 * (r - 0.5 * w), 0.1 * r, -0.3 * (r - 0.5 * w) * tan(b)},
         {sin(b), 0, cos(b)}, "bevel +x"},
        {{-0.5 * w - 0.5 * (r - 0.5 * w), -0.2 * r, -0.5 * (r - 0.5 * w) * tan(b)},
         {-sin(b), 0, cos(b)}, "bevel -x"},
        {{0, r, -2e-3}, {0, 1, 0}, "shank"},
    };
    for (int f = 0; f < 4; f++) {
        double in[3], out[3], nrm[3] = {0, 0, 0};
        for (int i = 0; i < 3; i++) {
            double S = face[f].S[i] + (i == 0 ? p.axis[0] : i == 1 ? p.axis[1] : p.tip);
            in[i] = S - e * face[f].n[i], out[i] = S + e * face[f].n[i];
        }
        double got = wff_projectile_penetration(&p, in, nrm), bad = fabs(got - e);
        for (int i = 0; i < 3; i++)
            bad = fmax(bad, e * fabs(nrm[i] - face[f].n[i]));
        CHECK(st, bad < 1e-12, "chisel %s: depth %g (want %g), normal (%g, %g, %g)",
              face[f].what, got, e, nrm[0], nrm[1], nrm[2]);
        CHECK(st, wff_projectile_penetration(&p, out, nrm) == 0, "chisel %s: outside is out",
              face[f].what);
    }
    CHECK_CLOSE(st, wff_projectile_nose_length(&p), (r - 0.5 * w) * tan(b), 1e-14, 0,
                "chisel nose length: the bevel's depth");
}

/* The largest z inside the projectile over the line x = const, y in [0, r]
 * (bisection along z lines); -inf if it misses. */
static double foremost(const wff_projectile *p, double x0)
{
    const double r = p->radius;
    double top = -INFINITY;
    for (int j = 0; j <= 60; j++) {
        double x[3] = {x0, r * j / 60.0, 0}, nrm[3], lo = NAN, hi = 2 * r; /* hi: outside */
        for (int k = 0; k <= 200 && isnan(lo); k++) {
            x[2] = 2 * r - 6 * r * k / 200.0;
            if (wff_projectile_penetration(p, x, nrm) > 0)
                lo = x[2];
            else
                hi = x[2];
        }
        if (isnan(lo))
            continue;
        for (int k = 0; k < 50; k++) {
            x[2] = 0.5 * (lo + hi);
            if (wff_projectile_penetration(p, x, nrm) > 0)
                lo = x[2];
            else
                hi = x[2];
        }
        top = fmax(top, lo);
    }
    return top;
}

/* An oblique projectile's foremost point (largest z with a point inside, by
 * bisection along z lines over its cross-section) against
 * wff_projectile_lead, for each nose at 20, 30 and 50 degrees. */
static void check_lead(check_state *st)
{
    wff_error err;
    const wff_threat *fsp = wff_threat_find("fsp17", &err);
    for (int nose = 0; nose < WFF_NOSE_COUNT; nose++)
        for (int a = 0; a < 3; a++) {
            const double theta = (a == 0 ? 20 : a == 1 ? 30 : 50) * kPi / 180;
            wff_projectile p = shape_of(fsp);
            p.nose = nose;
            p.edge_radius = nose == WFF_NOSE_FLAT ? 0.3 * p.radius : 0;
            p.oblique = 1, p.path[0] = sin(theta), p.path[2] = cos(theta);
            const double r = p.radius, lead = wff_projectile_lead(&p), h = 4 * r / 120;
            double best = -INFINITY, at = 0;
            for (int i = 0; i <= 120; i++) { /* a coarse scan in x, then a fine one round the best */
                const double x = -2 * r + h * i, z = foremost(&p, x);
                if (z > best)
                    best = z, at = x;
            }
            double top = best;
            for (int i = 0; i <= 400; i++)
                top = fmax(top, foremost(&p, at - h + 2 * h * i / 400.0));
            CHECK(st, top <= lead + 1e-12 && top >= lead - 2e-3 * r, "%s at %.0f deg: foremost "
                  "point z = %.6g m, wff_projectile_lead %.6g m", wff_nose_name(nose),
                  theta * 180 / kPi, top, lead);
        }
}

/* A clamped square (edges fixed) of side 2h with n x n cells. */
static int square(check_state *st, wff_model *m, double h, int n)
{
    test_rect rr = {-h, h, -h, h, n, n, TEST_MESH_QUAD, 1, 0, 0};
    wff_error err;
    int rc = test_model_rect(m, &rr, ELASTIC, &err);
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int e = 0; e < 4 && rc == 0; e++)
        for (int c = 0; c < 3 && rc == 0; c++)
            rc = wff_model_fix_group(m, edges[e], c, &err) < 0;
    CHECK(st, rc == 0, "square: %s", err.message);
    return rc;
}

/* A flat face tilted by 30 degrees, at the first contact: the fabric's
 * momentum along the path is what the projectile lost (the projectile takes
 * the impulses' component along its path; its guide the rest); the nodes
 * taken move forward along the path. */
static void check_tilted_face(check_state *st)
{
    const double M = 0.01, V = 20, theta = 30;
    wff_model m;
    if (square(st, &m, 0.03, 60))
        return;
    wff_error err;
    int rc = wff_model_set_projectile_shape(&m, WFF_NOSE_FLAT, 0.5e-3, &err) ||
             wff_model_set_obliquity(&m, theta, &err) ||
             wff_model_set_projectile(&m, 4e-3, M, V, 0, &err);
    for (int k = 0; k < 200 && rc == 0 && !(m.projectile.velocity < V); k++)
        rc = wff_model_advance(&m, 1, 1, &err); /* step by step to the first contact */
    CHECK(st, rc == 0, "tilted face: %s", err.message);
    if (rc) {
        wff_model_free(&m);
        return;
    }
    const double s = sin(theta * kPi / 180), c = cos(theta * kPi / 180);
    double along = 0, across = 0;
    int taken = 0, backward = 0;
    for (int k = 0; k < m.n_nodes; k++) {
        const double *v = m.v + D * k, vd = v[0] * s + v[2] * c;
        along += m.mass[D * k] * vd;
        across += m.mass[D * k] * (v[0] * c - v[2] * s);
        if (hypot(v[0], v[2]) > 1e-3 * V) {
            taken++;
            backward += vd <= 0;
        }
    }
    printf("  tilted flat face at %g deg, first contact (step %ld): %d nodes taken, fabric momentum along "
           "the path %.4e, across %.4e kg m/s, projectile %.4f m/s\n", theta, m.step, taken, along,
           across, m.projectile.velocity);
    CHECK(st, taken >= 1 && backward == 0, "the nodes taken move forward along the path (%d "
          "nodes, %d not)", taken, backward);
    CHECK(st, m.projectile.velocity < V, "the projectile lost speed: %g m/s", m.projectile.velocity);
    CHECK_CLOSE(st, along, M * (V - m.projectile.velocity), 1e-9, 1e-15,
                "fabric momentum along the path = the projectile's loss");
    wff_model_free(&m);
}

/* The energy balance of an oblique impact with each nose (0.5 g at 20 m/s,
 * 30 degrees, off the centre), and the momentum's direction. */
static void check_energy(check_state *st)
{
    const double M = 0.0005, V = 20;
    for (int nose = 0; nose < WFF_NOSE_COUNT; nose++) {
        wff_model m;
        if (square(st, &m, 0.05, 20))
            return;
        wff_error err;
        int rc = (nose == WFF_NOSE_CHISEL ? wff_model_set_projectile_chisel(&m, 2.6e-3, 35, &err)
                                          : wff_model_set_projectile_shape(&m, nose, 1.5e-3, &err)) ||
                 wff_model_set_impact_point(&m, 0.011, -0.006, &err) ||
                 wff_model_set_obliquity(&m, 30, &err) ||
                 wff_model_set_projectile(&m, 6.35e-3, M, V, 0.3, &err);
        CHECK(st, rc == 0, "%s", err.message);
        double worst = 0;
        wff_energies e;
        for (int block = 1; block <= 10 && rc == 0; block++) {
            rc = wff_model_advance(&m, block * 0.02e-3, 1000000, &err);
            CHECK(st, rc == 0, "%s nose: %s", wff_nose_name(nose), err.message);
            wff_model_energies(&m, &e);
            worst = fmax(worst, fabs(e.error));
        }
        double p[3];
        wff_projectile_momentum(&m.projectile, p);
        const double angle = atan2(p[0], p[2]) * 180 / kPi;
        printf("  oblique 30 deg, %-10s nose: %ld steps, max |energy error| %.2e, projectile "
               "%.3f m/s, momentum at %.6f deg from the normal\n", wff_nose_name(nose), m.step,
               worst, m.projectile.velocity, angle);
        CHECK(st, worst < 0.005, "%s nose at 30 deg: energy error %.3g", wff_nose_name(nose), worst);
        CHECK(st, m.projectile.velocity < V, "%s nose: the fabric slowed it", wff_nose_name(nose));
        CHECK(st, fabs(angle - 30) < 1e-9 && p[1] == 0, "%s: momentum at %g deg, y %g",
              wff_nose_name(nose), angle, p[1]);
        wff_model_free(&m);
    }
}

/* θ = 0 is the normal shot bit for bit; its momentum is along z; symmetric
 * models are refused in either order; angles out of [0, 90) refused. */
static void check_contracts(check_state *st)
{
    wff_model a, b;
    if (square(st, &a, 0.05, 12) || square(st, &b, 0.05, 12))
        return;
    wff_error err;
    int rc = wff_model_set_projectile(&a, 6.35e-3, 0.001, 20, 0.3, &err) ||
             wff_model_set_projectile(&b, 6.35e-3, 0.001, 20, 0.3, &err) ||
             wff_model_set_obliquity(&b, 0, &err) || wff_model_advance(&a, 0.1e-3, 0, &err) ||
             wff_model_advance(&b, 0.1e-3, 0, &err);
    CHECK(st, rc == 0, "%s", err.message);
    CHECK(st, rc == 0 && a.step == b.step &&
          memcmp(a.u, b.u, sizeof(double) * D * (size_t)a.n_nodes) == 0 &&
          a.projectile.velocity == b.projectile.velocity,
          "obliquity 0: the normal shot, bit for bit (%ld steps)", a.step);
    double p[3];
    wff_projectile_momentum(&b.projectile, p);
    CHECK(st, p[0] == 0 && p[1] == 0 && p[2] == 0.001 * b.projectile.velocity,
          "momentum at 0 deg along z: (%g, %g, %g)", p[0], p[1], p[2]);
    CHECK(st, wff_model_set_obliquity(&a, 10, &err) != 0 && strstr(err.message, "started"),
          "obliquity after the first step refused: %s", err.message);
    wff_model_free(&a);
    wff_model_free(&b);
    wff_model q;
    if (square(st, &q, 0.05, 12))
        return;
    CHECK(st, wff_model_set_obliquity(&q, 90, &err) != 0 && wff_model_set_obliquity(&q, -5, &err) != 0,
          "obliquity out of [0, 90) refused: %s", err.message);
    rc = wff_model_set_option(&q, "symmetry", 4, &err);
    CHECK(st, rc == 0 && wff_model_set_obliquity(&q, 30, &err) != 0 &&
          strstr(err.message, "symmetric"), "quarter model, then obliquity: refused: %s",
          err.message);
    wff_model_free(&q);
    if (square(st, &q, 0.05, 12))
        return;
    rc = wff_model_set_obliquity(&q, 30, &err);
    CHECK(st, rc == 0 && wff_model_set_option(&q, "symmetry", 2, &err) != 0 &&
          strstr(err.message, "obliquity"), "obliquity, then a half model: refused: %s",
          err.message);
    wff_model_free(&q);
}

int main(void)
{
    check_state st = {0, 0};
    check_table(&st);
    check_chisel(&st);
    check_lead(&st);
    check_tilted_face(&st);
    check_energy(&st);
    check_contracts(&st);
    return check_summary(&st, "test_threats");
}

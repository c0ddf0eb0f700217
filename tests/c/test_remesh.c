/* Mesh transfer (wff_model_remesh): onto the same mesh the state is the same
 * and the energy change is round-off; a uniform deformation moves onto any
 * mesh exactly; a smooth one onto a finer mesh changes the stored energy by
 * interpolation error only; boundary conditions and the clamp follow their
 * groups; a failure (a group missing, a node outside) leaves the model
 * usable; a struck, clamped square continues with its balance after a
 * transfer, the transfer's energy counted as a term. */
#include "check.h"
#include "test_meshes.h"
#include "wovenff/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE
#define NOSE_RADIUS 6.35e-3

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* A clamped, struck square: clamp (friction) on "left", u fixed on the other
 * edges, a light projectile at 20 m/s. */
static int struck_square(check_state *st, wff_model *m, const test_rect *r)
{
    wff_error err;
    int rc = test_model_rect(m, r, KEVLAR, &err);
    CHECK(st, rc == 0, "%s", err.message);
    if (rc)
        return -1;
    static const char *const edges[] = {"right", "bottom", "top"};
    for (int g = 0; g < 3 && rc >= 0; g++)
        for (int c = WFF_UX; c <= WFF_UZ && rc >= 0; c++)
            rc = wff_model_fix_group(m, edges[g], c, &err);
    if (rc >= 0)
        rc = wff_model_clamp_friction(m, "left", 2000, 0.3, &err);
    if (rc >= 0)
        rc = wff_model_set_projectile(m, NOSE_RADIUS, 0.0005, 20, 0.2, &err);
    CHECK(st, rc >= 0, "%s", err.message);
    return rc < 0 ? -1 : 0;
}

static double kinetic_stored(const wff_model *m)
{
    wff_energies e;
    wff_model_energies(m, &e);
    return e.internal + e.kinetic_inplane + e.kinetic_transverse + e.kinetic_amplitude +
           e.kinetic_projectile - e.kinetic_stagger + e.impulse_stagger; /* (the balance's
                                                                            kinetic energy) */
}

/* 1. The same mesh: u, γᶠ, vⁿ and the energies as they were. */
static void same_mesh(check_state *st)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, 16, 16, TEST_MESH_TRI, 1, 0.25, 7};
    wff_model m;
    if (struck_square(st, &m, &r))
        return;
    wff_error err;
    int rc = wff_model_advance(&m, 1, 400, &err); /* 400: a stable-step update step */
    CHECK(st, rc == 0, "%s", err.message);
    size_t nd = (size_t)m.n_dofs, nq = (size_t)(3 * m.el.n_tris);
    double *u = malloc(nd * sizeof(double)), *vn = malloc(nd * sizeof(double)),
           *g = malloc(nq * sizeof(double));
    for (size_t i = 0; i < nd; i++) {
        u[i] = m.u[i];
        vn[i] = m.v[i] - (m.dof_kind[i] == WFF_DOF_FREE ? 0.5 * m.dt * m.f[i] / m.mass[i] : 0);
    }
    memcpy(g, m.state, nq * sizeof(double));
    double t = m.time, dt = m.dt, dissipated = m.dissipated_friction + m.dissipated_shear;
    long step = m.step;
    wff_mesh same;
    CHECK(st, test_mesh_rect(&r, &same) == 0, "mesh");
    wff_energies eb, ea;
    wff_model_energies(&m, &eb);
    double t0 = seconds();
    wff_remesh_report rep;
    rc = wff_model_remesh(&m, &same, &rep, &err);
    wff_model_energies(&m, &ea);
    double before = rep.before, after = rep.after;
    double cost = seconds() - t0;
    CHECK(st, rc == 0, "%s", err.message);
    if (rc == 0) {
        double du = 0, dv = 0, vmax = 0, dg = 0;
        for (size_t i = 0; i < nd; i++) {
            du = fmax(du, fabs(m.u[i] - u[i]));
            double vi = m.v[i] - (m.dof_kind[i] == WFF_DOF_FREE ? 0.5 * m.dt * m.f[i] / m.mass[i]
                                                                  : 0);
            dv = fmax(dv, fabs(vi - vn[i]));
            vmax = fmax(vmax, fabs(vn[i]));
        }
        for (size_t i = 0; i < nq; i++)
            dg = fmax(dg, fabs(m.state[i] - g[i]));
        printf("  same mesh (%d nodes, %ld steps, %.3g s per transfer): |du| %.1e m, |dv^n| "
               "%.1e of %.1e m/s, |dgamma_f| %.1e, energy %.9e -> %.9e J (change %.1e)\n",
               m.n_nodes, m.step, cost, du, dv, vmax, dg, before, after, after - before);
        CHECK(st, du == 0, "u changed by %g m", du);
        CHECK(st, dg == 0, "gamma_f changed by %g", dg);
        CHECK(st, dv <= 1e-12 * vmax, "v^n changed by %g m/s", dv);
        /* the state's energies as they were; the balance's measure moves by what
         * depends on the half step planned anew (docs/model.md §14): the stagger
         * and the contact forces' share of it (the impulses re-expressed over
         * the new Δt_mid) */
        const double kin_b = eb.kinetic_inplane + eb.kinetic_transverse + eb.kinetic_amplitude +
                             eb.kinetic_projectile,
                     kin_a = ea.kinetic_inplane + ea.kinetic_transverse + ea.kinetic_amplitude +
                             ea.kinetic_projectile;
        const double planned = (ea.impulse_stagger - eb.impulse_stagger) -
                               (ea.kinetic_stagger - eb.kinetic_stagger);
        printf("  same mesh: kinetic %.12e -> %.12e J, stored %.12e -> %.12e J, the half "
               "step's share %.3e J\n", kin_b, kin_a, eb.internal, ea.internal, planned);
        CHECK(st, fabs(kin_a - kin_b) <= 1e-12 * kin_b && fabs(ea.internal - eb.internal) <=
                  1e-12 * eb.internal, "kinetic %g -> %g, stored %g -> %g J", kin_b, kin_a,
              eb.internal, ea.internal);
        CHECK(st, fabs(after - before - planned) <= 1e-12 * before, "energy changed by %g J of "
              "%g, the half step's share %g J", after - before, before, planned);
        CHECK(st, m.time == t && m.step == step && m.dt == dt, "time, step, dt carried");
        CHECK(st, m.dissipated_friction + m.dissipated_shear >= dissipated,
              "dissipation carried: %g then %g J", dissipated,
              m.dissipated_friction + m.dissipated_shear);
        CHECK(st, m.projectile.active && m.clamp.n > 0, "projectile and clamp carried");
    }
    free(u), free(vn), free(g);
    wff_model_free(&m);
}

/* Set u to a displacement field given by its values at X (all 5 DOFs). */
typedef void (*field_fn)(double x, double y, double out[D]);

static void uniform_field(double x, double y, double out[D])
{
    out[0] = 0.01 * x + 0.004 * y, out[1] = 0.002 * x + 0.015 * y, out[2] = 0.1 * x - 0.05 * y;
    out[3] = -2e-6, out[4] = -1e-6;
}

static void smooth_field(double x, double y, double out[D])
{
    const double L = 0.03;
    double c = cos(M_PI * x / (2 * L)) * cos(M_PI * y / (2 * L));
    out[0] = 0.01 * x * c, out[1] = 0.01 * y * c, out[2] = 0.004 * c;
    out[3] = -3e-6 * c, out[4] = -2e-6 * c;
}

static void set_field(wff_model *m, field_fn f)
{
    for (int n = 0; n < m->n_nodes; n++)
        f(m->mesh.xy[2 * n], m->mesh.xy[2 * n + 1], m->u + D * n);
}

static double stored_energy(wff_model *m)
{
    wff_force_totals t;
    memset(m->f, 0, sizeof(double) * (size_t)m->n_dofs);
    wff_elements_forces(&m->el, &m->em, m->mesh.xy, m->u, m->state, 0, m->f, &t);
    return t.internal_energy;
}

/* 2. Uniform deformation: exact on any mesh; smooth: interpolation error. */
static double deformation_types(check_state *st, field_fn field, const char *what, int nx_old,
                                int nx_new, double tol, int old_type, int new_type)
{
    double change = NAN;
    test_rect coarse = {-0.03, 0.03, -0.03, 0.03, nx_old, nx_old, old_type, 0, 0.2, 3};
    test_rect fine = {-0.03, 0.03, -0.03, 0.03, nx_new, nx_new, new_type, 1, 0.2, 11};
    wff_model m, ref;
    wff_error err;
    if (test_model_rect(&m, &coarse, KEVLAR, &err) ||
        test_model_rect(&ref, &fine, KEVLAR, &err)) {
        CHECK(st, 0, "%s", err.message);
        return change;
    }
    set_field(&m, field);
    set_field(&ref, field); /* the field itself on the new mesh */
    double U0 = stored_energy(&m), U_ref = stored_energy(&ref);
    m.internal_energy = U0;
    wff_mesh mesh;
    CHECK(st, test_mesh_rect(&fine, &mesh) == 0, "mesh");
    wff_remesh_report rep;
    int rc = wff_model_remesh(&m, &mesh, &rep, &err);
    double before = rep.before, after = rep.after;
    CHECK(st, rc == 0, "%s", err.message);
    if (rc == 0) {
        double U1 = stored_energy(&m);
        printf("  %s deformation, %d -> %d cells a side: stored %.9e -> %.9e J (%.2e relative; "
               "the field itself on the new mesh %.9e J)\n", what, coarse.nx, nx_new, U0, U1,
               (U1 - U0) / U0, U_ref);
        change = (U1 - U0) / U0;
        CHECK(st, fabs(U1 - U0) <= tol * U0, "%s: stored energy %g -> %g J", what, U0, U1);
        CHECK_CLOSE(st, after - before, U1 - U0, 1e-9, 1e-12 * U0, "reported change");
    }
    wff_model_free(&m);
    wff_model_free(&ref);
    return change;
}

static double deformation(check_state *st, field_fn field, const char *what, int nx_old,
                          int nx_new, double tol)
{
    return deformation_types(st, field, what, nx_old, nx_new, tol, TEST_MESH_TRI, TEST_MESH_TRI);
}

/* 3. Groups: clamped nodes of the new mesh are clamped, fixed edges fixed; a
 * missing group and a node outside fail and leave the model usable. */
static void groups(check_state *st)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, 10, 10, TEST_MESH_TRI, 1, 0.2, 5};
    test_rect r2 = {-0.03, 0.03, -0.03, 0.03, 17, 13, TEST_MESH_TRI, 0, 0.2, 9};
    wff_model m;
    if (struck_square(st, &m, &r))
        return;
    wff_error err;
    CHECK(st, wff_model_advance(&m, 1, 100, &err) == 0, "%s", err.message);
    /* a mesh without "top": an error naming it, the model unchanged */
    wff_mesh bad;
    CHECK(st, test_mesh_rect(&r2, &bad) == 0, "mesh");
    for (int e = 0; e < bad.n_edges; e++)
        if (bad.edge_label[e] == TEST_TOP)
            bad.edge_label[e] = 99;
    for (int g = 0; g < bad.n_groups; g++)
        if (strcmp(bad.groups[g].name, "top") == 0)
            snprintf(bad.groups[g].name, sizeof bad.groups[g].name, "lid"), bad.groups[g].tag = 99;
    int n0 = m.n_nodes;
    double uz0 = m.u[D * (n0 / 2) + WFF_UZ];
    int rc = wff_model_remesh(&m, &bad, NULL, &err);
    CHECK(st, rc == -1 && strstr(err.message, "'top'"), "missing group: rc %d, %s", rc,
          err.message);
    printf("  missing group: %s\n", err.message);
    /* a mesh larger than the specimen */
    test_rect big = r2;
    big.x1 = 0.031;
    wff_mesh outside;
    CHECK(st, test_mesh_rect(&big, &outside) == 0, "mesh");
    rc = wff_model_remesh(&m, &outside, NULL, &err);
    CHECK(st, rc == -1 && strstr(err.message, "outside the old mesh"), "outside: rc %d, %s", rc,
          err.message);
    printf("  node outside: %s\n", err.message);
    CHECK(st, m.n_nodes == n0 && m.u[D * (n0 / 2) + WFF_UZ] == uz0, "model unchanged");
    CHECK(st, wff_model_advance(&m, 1, 20, &err) == 0, "usable after failures: %s", err.message);
    wff_mesh good;
    CHECK(st, test_mesh_rect(&r2, &good) == 0, "mesh");
    rc = wff_model_remesh(&m, &good, NULL, &err);
    CHECK(st, rc == 0, "%s", err.message);
    if (rc == 0) {
        unsigned char *in_clamp = calloc((size_t)m.n_nodes, 1);
        for (int c = 0; c < m.clamp.n; c++)
            in_clamp[m.clamp.node[c]] = 1;
        int bad_left = 0, bad_fixed = 0, n_left = 0;
        double force = 0;
        for (int n = 0; n < m.n_nodes; n++) {
            double x = m.mesh.xy[2 * n], y = m.mesh.xy[2 * n + 1];
            int left = fabs(x - r.x0) < 1e-12, other = fabs(x - r.x1) < 1e-12 ||
                                                       fabs(y - r.y0) < 1e-12 ||
                                                       fabs(y - r.y1) < 1e-12;
            n_left += left;
            if (left && (!in_clamp[n] || m.dof_kind[D * n + WFF_UZ] != WFF_DOF_FIXED ||
                         m.u[D * n + WFF_UZ] != 0))
                bad_left++;
            if (!left && in_clamp[n])
                bad_left++;
            if (other && !left)
                for (int c = WFF_UX; c <= WFF_UZ; c++)
                    bad_fixed += m.dof_kind[D * n + c] != WFF_DOF_FIXED || m.v[D * n + c] != 0;
        }
        for (int c = 0; c < m.clamp.n; c++)
            force += m.clamp.normal_force[c];
        printf("  groups on a %dx%d mesh: %d clamped nodes on 'left' (of %d), clamp force %g N\n",
               r2.nx, r2.ny, m.clamp.n, n_left, force);
        CHECK(st, bad_left == 0 && m.clamp.n == n_left, "%d clamp nodes wrong", bad_left);
        CHECK(st, bad_fixed == 0, "%d fixed DOFs wrong", bad_fixed);
        CHECK_CLOSE(st, force, 2000, 1e-12, 1, "clamp force");
        CHECK(st, m.n_bc == 10, "10 boundary conditions recorded again, got %d", m.n_bc);
        free(in_clamp);
    }
    wff_model_free(&m);
}

/* 4. A struck square continues after transfers onto finer and coarser
 * meshes (each with a node on the axis, as the ballistic quarter mesh has):
 * across each transfer its balance (the transfer a term) moves by less than
 * 0.1 % of the reference, and stays within 0.5 % throughout. */
static void continues(check_state *st)
{
    test_rect r = {-0.03, 0.03, -0.03, 0.03, 14, 14, TEST_MESH_TRI, 1, 0.1, 5};
    static const int sides[5][2] = {{18, 18}, {12, 14}, {22, 20}, {16, 16}, {24, 22}};
    wff_model m;
    if (struck_square(st, &m, &r))
        return;
    wff_error err;
    double worst = 0, worst_jump = 0, transfers = 0;
    int rc = 0;
    for (int block = 0; block < 6 && rc == 0; block++) {
        rc = wff_model_advance(&m, 1, 150, &err);
        CHECK(st, rc == 0, "%s", err.message);
        wff_energies e;
        wff_model_energies(&m, &e);
        worst = fmax(worst, fabs(e.error));
        if (rc || block == 5)
            break;
        test_rect next = {-0.03, 0.03, -0.03, 0.03, sides[block][0], sides[block][1],
                          TEST_MESH_TRI, block % 2, 0.1, (uint64_t)(20 + block)};
        wff_mesh mesh;
        CHECK(st, test_mesh_rect(&next, &mesh) == 0, "mesh");
        double err_before = e.error;
        wff_remesh_report rep;
        rc = wff_model_remesh(&m, &mesh, &rep, &err);
        double before = rep.before, after = rep.after;
        CHECK(st, rc == 0, "%s", err.message);
        wff_model_energies(&m, &e);
        transfers += after - before;
        worst_jump = fmax(worst_jump, fabs(e.error - err_before));
        printf("  transfer %d onto %dx%d at step %ld: stored+kinetic %.6e -> %.6e J "
               "(%+.2e of the reference), balance %.2e -> %.2e, projectile back %.3g mm\n", block + 1,
               next.nx, next.ny, m.step, before, after, (after - before) / e.reference,
               err_before, e.error, 1e3 * rep.retraction);
        CHECK_CLOSE(st, e.transfer, transfers, 1e-12, 1e-15, "transfer term");
        CHECK(st, fabs(e.error - err_before) < 1e-3, "balance across the transfer: %g -> %g",
              err_before, e.error);
        CHECK_CLOSE(st, kinetic_stored(&m), after, 1e-12, 1e-15, "after");
    }
    printf("  struck square through 5 transfers: worst balance error %.2e (largest move across "
           "a transfer %.2e), transfers %.3e J, projectile %.3f m/s\n", worst, worst_jump,
           transfers, m.projectile.velocity);
    CHECK(st, worst < 3e-2, "balance error %g", worst);
    CHECK(st, m.projectile.velocity < 20, "the projectile touched the fabric");
    wff_model_free(&m);
}

int main(void)
{
    check_state st = {0, 0};
    same_mesh(&st);
    deformation(&st, uniform_field, "uniform", 12, 23, 1e-12);
    deformation_types(&st, uniform_field, "uniform, quads to triangles", 12, 23, 1e-12,
                      TEST_MESH_QUAD, TEST_MESH_TRI);
    deformation_types(&st, uniform_field, "uniform, triangles to quads", 12, 23, 1e-12,
                      TEST_MESH_TRI, TEST_MESH_QUAD);
    /* smooth: an interpolation error, of order h² (measured: 4x smaller at h/2) */
    double c1 = deformation(&st, smooth_field, "smooth", 12, 24, 5e-2);
    double c2 = deformation(&st, smooth_field, "smooth", 24, 48, 2.5e-2);
    CHECK(&st, fabs(c2) < 0.35 * fabs(c1), "smooth: the change falls with h: %g then %g", c1, c2);
    groups(&st);
    continues(&st);
    return check_summary(&st, "test_remesh");
}

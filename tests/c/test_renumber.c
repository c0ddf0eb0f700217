/* The model's own node and element order (plugin/renumber.c) is invisible:
 * the ballistic quarter mesh built twice, keeping gmsh's order and
 * renumbered, with the same preload, boundary conditions, friction clamp and
 * projectile, advanced through the impact, gives in the user's numbering the
 * same state vectors, energies, reactions, nodal and element fields, masses,
 * DOF kinds, operator forces, stable step and its element, nearest node and
 * error messages (to round-off: sums run in another order). The renumbered
 * model is checked to be renumbered (its neighbours closer), and the
 * permutations to be inverse to each other; the order depends only on the
 * mesh (two builds agree). A mesh transfer onto a finer mesh renumbers the
 * new mesh and agrees the same way. */
#include "check.h"
#include "wovenff/options.h"
#include "wovenff/renumber.h"
#include "wovenff/state.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define D WFF_DOFS_PER_NODE

static int build(wff_model *m, int renumber, wff_error *err)
{
    wff_mesh_options opt;
    wff_mesh mesh;
    if (wff_mesh_options_parse("size_factor=1.5", &opt, err) ||
        wff_mesh_load("meshes/ballistic_quarter.geo", &opt, &mesh, err) ||
        wff_model_create_ordered(m, &mesh, KEVLAR, renumber, err))
        return -1;
    const double F_pre[4] = {1.003963, 0, 0, 1.013476}, dA0[2] = {-9.311e-6, -23.748e-6};
    if (wff_model_set_preload(m, F_pre, dA0, err) || wff_model_set_option(m, "symmetry", 4, err) ||
        wff_model_fix_group(m, "sym_x", 0, err) < 0 || wff_model_fix_group(m, "sym_y", 1, err) < 0 ||
        wff_model_clamp_friction(m, "clamp", 2000, 0.3, err) < 0 ||
        wff_model_set_projectile(m, 6.35e-3, 0.026, 60, 0.3, err))
        return -1;
    return 0;
}

/* Largest |a - b| over n entries, relative to the largest |b| (or 1e-300). */
static double rel_diff(const double *a, const double *b, int n)
{
    double d = 0, s = 1e-300;
    for (int i = 0; i < n; i++) {
        d = fmax(d, fabs(a[i] - b[i]));
        s = fmax(s, fabs(b[i]));
    }
    return d / s;
}

/* Mean |node index difference| along the elements' edges (small: neighbours
 * close in memory). */
static double mean_gap(const wff_mesh *g)
{
    double sum = 0;
    for (int e = 0; e < g->n_tris; e++)
        for (int a = 0; a < 3; a++)
            sum += abs(g->tri[3 * e + a] - g->tri[3 * e + (a + 1) % 3]);
    return sum / (3.0 * g->n_tris);
}

static void compare_vectors(check_state *st, wff_model *keep, wff_model *re, const char *when)
{
    int nd = keep->n_dofs, nn = keep->n_nodes, ne = keep->el.n_tris + keep->el.n_quads;
    double *a = malloc(sizeof(double) * (size_t)nd), *b = malloc(sizeof(double) * (size_t)nd);
    wff_error err;
    for (int w = 0; w < 2; w++) {
        const char *which = w ? "v" : "u";
        CHECK(st, !wff_model_get_vector(keep, which, a, &err) &&
                  !wff_model_get_vector(re, which, b, &err), "%s", err.message);
        double d = rel_diff(b, a, nd);
        CHECK(st, d < 1e-9, "%s: %s renumbered vs kept: %.3g of its largest entry", when, which, d);
    }
    static const char *const nodal[] = {"uz", "vz", "A1", "gamma", "T1", "W", "P11"};
    for (size_t k = 0; k < sizeof nodal / sizeof nodal[0]; k++) {
        CHECK(st, !wff_model_nodal_field(keep, nodal[k], a, &err) &&
                  !wff_model_nodal_field(re, nodal[k], b, &err), "%s", err.message);
        double d = rel_diff(b, a, nn);
        CHECK(st, d < 1e-9, "%s: nodal field %s: %.3g", when, nodal[k], d);
    }
    static const char *const element[] = {"P11", "P32", "lambda1", "shear_angle", "gamma_f",
                                          "W", "T2"};
    for (size_t k = 0; k < sizeof element / sizeof element[0]; k++) {
        CHECK(st, !wff_model_element_values(keep, element[k], a, &err) &&
                  !wff_model_element_values(re, element[k], b, &err), "%s", err.message);
        double d = rel_diff(b, a, ne);
        CHECK(st, d < 1e-9, "%s: element field %s: %.3g", when, element[k], d);
    }
    wff_model_masses(keep, a);
    wff_model_masses(re, b);
    CHECK(st, rel_diff(b, a, nd) < 1e-13, "%s: masses", when);
    wff_model_dof_kinds(keep, a, NULL);
    wff_model_dof_kinds(re, b, NULL);
    CHECK(st, memcmp(a, b, sizeof(double) * (size_t)nd) == 0, "%s: DOF kinds", when);
    /* the force operator at the kept model's u, given in the user's numbering */
    double *u = malloc(sizeof(double) * (size_t)nd), *ra = malloc(sizeof(double) * (size_t)nd);
    wff_model_get_vector(keep, "u", u, &err);
    double ea = 0, eb = 0;
    CHECK(st, !wff_model_forces(keep, u, ra, 0, &ea, &err) &&
              !wff_model_forces(re, u, b, 0, &eb, &err), "%s", err.message);
    CHECK(st, rel_diff(b, ra, nd) < 1e-11, "%s: forces at the same U: %.3g", when,
          rel_diff(b, ra, nd));
    CHECK_CLOSE(st, eb, ea, 1e-12, 1e-30, "stored energy at the same U");
    double dta, dtb;
    int wa, wb;
    CHECK(st, !wff_model_stable_step(keep, u, &dta, &wa, &err) &&
              !wff_model_stable_step(re, u, &dtb, &wb, &err), "%s", err.message);
    CHECK(st, fabs(dta - dtb) <= 1e-12 * dta && wa == wb,
          "%s: stable step %.17g at element %d vs %.17g at %d", when, dta, wa + 1, dtb, wb + 1);
    free(u);
    free(ra);
    free(a);
    free(b);
}

static void compare_scalars(check_state *st, wff_model *keep, wff_model *re, const char *when)
{
    wff_energies ea, eb;
    wff_model_energies(keep, &ea);
    wff_model_energies(re, &eb);
    const double *pa = &ea.kinetic_inplane, *pb = &eb.kinetic_inplane;
    for (int k = 0; k < 8; k++) /* kinetic ×4, internal, shear, friction, external work */
        CHECK_CLOSE(st, pb[k], pa[k], 1e-9, 1e-12 * ea.reference, when);
    CHECK(st, fabs(eb.error - ea.error) < 1e-9, "%s: energy error %.6g vs %.6g", when, eb.error,
          ea.error);
    CHECK_CLOSE(st, re->projectile.velocity, keep->projectile.velocity, 1e-12, 1, "projectile");
    CHECK_CLOSE(st, re->projectile.tip, keep->projectile.tip, 1e-12, 1e-9, "projectile tip");
    CHECK(st, re->step == keep->step, "%s: step %ld vs %ld", when, re->step, keep->step);
    CHECK_CLOSE(st, re->dt, keep->dt, 1e-11, 0, "time step");
    static const char *const groups[] = {"sym_x", "sym_y", "clamp"};
    for (int g = 0; g < 3; g++)
        for (int c = 0; c < 3; c++) {
            double sa = 0, sb = 0;
            wff_error err;
            int na = wff_model_group_reaction(keep, groups[g], c, &sa, &err);
            int nb = wff_model_group_reaction(re, groups[g], c, &sb, &err);
            CHECK(st, na == nb, "%s: group %s nodes %d vs %d", when, groups[g], na, nb);
            CHECK_CLOSE(st, sb, sa, 1e-9, 1e-9, "group reaction");
        }
    for (double x = 0; x < 0.05; x += 0.0123)
        CHECK(st, wff_model_nearest_node(keep, x, 0.7 * x) == wff_model_nearest_node(re, x, 0.7 * x),
              "%s: nearest node to (%g, %g)", when, x, 0.7 * x);
    CHECK(st, keep->step == 0 || /* (set by the first step) */
              wff_model_user_element(re, re->dt_worst_element) == keep->dt_worst_element,
          "%s: the element that sets the step: %d vs %d", when,
          wff_model_user_element(re, re->dt_worst_element) + 1, keep->dt_worst_element + 1);
}

/* An error names the same user node in both. */
static void compare_errors(check_state *st, wff_model *keep, wff_model *re)
{
    int nd = keep->n_dofs, bad = D * (keep->n_nodes / 3) + 2;
    double *u = malloc(sizeof(double) * (size_t)nd);
    wff_error ea, eb;
    wff_model_get_vector(keep, "u", u, &ea);
    u[bad] = NAN;
    CHECK(st, wff_model_set_vector(keep, "u", u, &ea) && wff_model_set_vector(re, "u", u, &eb),
          "a NaN is refused");
    CHECK(st, strcmp(ea.message, eb.message) == 0, "the same message: '%s' vs '%s'", ea.message,
          eb.message);
    free(u);
}

int main(void)
{
    check_state st = {0, 0};
    wff_model keep, re, again;
    wff_error err;
    if (build(&keep, 0, &err) || build(&re, 1, &err) || build(&again, 1, &err)) {
        CHECK(&st, 0, "%s", err.message);
        return check_summary(&st, "test_renumber");
    }
    int nn = re.n_nodes, ne = re.el.n_tris + re.el.n_quads;
    CHECK(&st, keep.node_user == NULL && re.node_user != NULL, "the order kept / renumbered");
    int inverse = 1, moved = 0;
    for (int n = 0; n < nn; n++) {
        inverse &= wff_model_node_of_user(&re, wff_model_user_node(&re, n)) == n;
        moved += wff_model_user_node(&re, n) != n;
    }
    for (int e = 0; e < ne; e++)
        inverse &= wff_model_element_of_user(&re, wff_model_user_element(&re, e)) == e;
    CHECK(&st, inverse && moved > nn / 2, "permutations inverse, %d of %d nodes moved", moved, nn);
    double gap_keep = mean_gap(&keep.mesh), gap_re = mean_gap(&re.mesh);
    CHECK(&st, gap_re < 0.5 * gap_keep, "neighbours closer: mean index gap %.1f vs %.1f", gap_re,
          gap_keep);
    CHECK(&st, memcmp(re.node_user, again.node_user, sizeof(int) * (size_t)nn) == 0 &&
                   memcmp(re.element_user, again.element_user, sizeof(int) * (size_t)ne) == 0,
          "the same order from the same mesh");
    compare_vectors(&st, &keep, &re, "at rest");
    compare_scalars(&st, &keep, &re, "at rest");
    /* through the impact: contact, clamp friction, γᶠ flow */
    for (int block = 0; block < 4; block++) {
        CHECK(&st, !wff_model_advance(&keep, 1e9, 150, &err), "%s", err.message);
        CHECK(&st, !wff_model_advance(&re, 1e9, 150, &err), "%s", err.message);
        char when[32];
        snprintf(when, sizeof when, "step %ld", keep.step);
        compare_vectors(&st, &keep, &re, when);
        compare_scalars(&st, &keep, &re, when);
    }
    CHECK(&st, keep.projectile.velocity < 59.9, "the projectile was slowed: %g m/s",
          keep.projectile.velocity);
    /* a mesh transfer renumbers the new mesh as the old one was */
    for (int k = 0; k < 2; k++) {
        wff_mesh_options opt;
        wff_mesh fine;
        wff_model *m = k ? &re : &keep;
        CHECK(&st, !wff_mesh_options_parse("size_factor=1.2", &opt, &err) &&
                       !wff_mesh_load("meshes/ballistic_quarter.geo", &opt, &fine, &err) &&
                       !wff_model_remesh(m, &fine, NULL, &err), "%s", err.message);
    }
    CHECK(&st, keep.node_user == NULL && re.node_user != NULL && re.n_nodes > nn,
          "the transfer kept / renumbered the new mesh (%d nodes)", re.n_nodes);
    compare_vectors(&st, &keep, &re, "after the transfer");
    compare_scalars(&st, &keep, &re, "after the transfer");
    CHECK(&st, !wff_model_advance(&keep, 1e9, 100, &err) && !wff_model_advance(&re, 1e9, 100, &err),
          "%s", err.message);
    compare_vectors(&st, &keep, &re, "100 steps after the transfer");
    compare_scalars(&st, &keep, &re, "100 steps after the transfer");
    compare_errors(&st, &keep, &re);
    printf("renumbered: %d nodes, %d elements, mean index gap along edges %.1f (kept %.1f)\n", nn,
           ne, gap_re, gap_keep);
    wff_model_free(&keep);
    wff_model_free(&re);
    wff_model_free(&again);
    return check_summary(&st, "test_renumber");
}

/* Yarn slip at the crossovers in the King cell (docs/model.md §24), the checks
 * its own laws allow in closed form; the generic ones (forces from the energy
 * with the slips held, dissipation >= 0 and at most what an update releases
 * along loading paths, the fast paths, the stable step) are the cell suite's
 * (tests/c/test_cells.c, cases king_slip*) and tests/c/test_stable_bound.c's.
 *
 *   1. Keys: yarn_friction absent or 0 is no slip (one state per point);
 *      yarn_friction < 0, slip_crossovers < 1, or yarn_friction > 0 without
 *      slip_crossovers are refused naming the key; with slip the points carry
 *      eight states, slip_1 and slip_2 last.
 *   2. A uniaxial pull of the warp at fixed amplitudes (so a fixed crossover
 *      force F_I and slip tension T_slip = n_c μ_yy F_I): the tension follows
 *      k_1 (L_1 − L_1⁰) until T_slip, then stays at T_slip to round-off; the
 *      slip is (L_1 − L_1⁰ − T_slip/k_1)/L_1⁰; the dissipation is T_slip times
 *      the yarn slid, 2 L_1⁰ s_1 per cell; the weft does not slip. The same pull
 *      without slip has no plateau.
 *   3. Unloading: elastic with slope k_1, the slip held, down to −T_slip, then
 *      slip back at −T_slip (the literal law; tension_only stays slack).
 *   4. The pull with the amplitudes in balance at every step: while slipping
 *      T_1 = n_c μ_yy F_I of that step to round-off, and the warp keeps more
 *      crimp than without slip (a slipped yarn straightens less).
 *   5. Failure with slip: along loading paths both slip and damage happen,
 *      every dissipation >= 0 and their sum at most the stored energy the
 *      update releases.
 *   6. A struck square (the tests' 6 cm square, 50 g at 60 m/s) whose yarns
 *      slip: the energy balance closes to 1e-6 of the impact energy with
 *      dissipated_slip a term of it, its residual under 1 % of that term, no
 *      invariant violated; with
 *      yarn_friction = 0 in the file (slip_crossovers kept) the run has the same
 *      bits as the file without the slip keys. */
#include "check.h"
#include "test_material.h"
#include "test_meshes.h"
#include "test_tmp.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/renumber.h"
#include "wovenff/solver.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define SLIP "tests/data/king_slip.txt"                 /* μ_yy 0.25, n_c 20 */
#define SLIP_FAILURE "tests/data/king_slip_failure.txt" /* with failure = 1 */

/* diag indices of king_plain: T1 T2 beta1 beta2 F_I F_L1 F_L2 M_s */
enum { T1, T2, BETA1, BETA2, FI };

static int load_text(const char *text, wff_material *m, wff_error *e)
{
    return wff_material_parse_text(text, "test_slip", m, e);
}

/* 1. the keys */
static void check_keys(check_state *st)
{
    wff_material m;
    wff_error e;
    char *off = test_material_text(st, KEVLAR, "");
    if (!off)
        return;
    CHECK(st, load_text(off, &m, &e) == 0 && m.n_state == 1 &&
                  wff_material_state_index(&m, "slip_1") < 0,
          "yarn_friction = 0: one state per point, no slip state (n_state %d)", m.n_state);
    free(off);
    static const struct { const char *set, *key; } bad[] = {
        {"yarn_friction=-0.1", "yarn_friction"},
        {"yarn_friction=0.2,slip_crossovers=0.5", "slip_crossovers"},
        {"slip_crossovers=0", "slip_crossovers"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char *text = test_material_text(st, KEVLAR, bad[i].set);
        if (!text)
            continue;
        int rc = load_text(text, &m, &e);
        CHECK(st, rc != 0 && strstr(e.message, bad[i].key), "%s refused naming %s: %s",
              bad[i].set, bad[i].key, rc ? e.message : "accepted");
        free(text);
    }
    /* yarn_friction > 0 without slip_crossovers */
    char *text = test_material_text(st, "tests/data/king_tension_only.txt", "");
    if (text) {
        char *more = malloc(strlen(text) + 64);
        sprintf(more, "%s\nyarn_friction = 0.2\n", text);
        int rc = load_text(more, &m, &e);
        CHECK(st, rc != 0 && strstr(e.message, "yarn_friction") &&
                      strstr(e.message, "slip_crossovers"),
              "yarn_friction without slip_crossovers refused: %s", rc ? e.message : "accepted");
        free(more);
        free(text);
    }
    int rc = wff_material_load(SLIP, &m, &e);
    CHECK(st, rc == 0, "%s", e.message);
    CHECK(st, rc == 0 && m.n_state == 8 && wff_material_state_index(&m, "slip_1") == 6 &&
                  wff_material_state_index(&m, "slip_2") == 7,
          "slip on: 8 states, slip_1 and slip_2 last (n_state %d, at %d %d)", m.n_state,
          wff_material_state_index(&m, "slip_1"), wff_material_state_index(&m, "slip_2"));
}

/* The reference geometry and yarn stiffness of the cases (kevlar_s706's, which
 * king_slip.txt shares). */
static const double P0 = 0.3735e-3, A0_1 = 0.0602e-3, K = 1.03e7;

/* L_1 at warp stretch lam, amplitude change dA1 */
static double warp_length(double lam, double dA1)
{
    double p = P0 * lam, A = A0_1 + dA1;
    return sqrt(p * p + A * A);
}

/* 2 and 3: the pull and the unloading at fixed amplitudes; capacity n_c μ_yy. */
static void check_pull(check_state *st, const char *path, double capacity, int tension_only)
{
    wff_material m, off;
    wff_error e;
    if (wff_material_load(path, &m, &e)) {
        CHECK(st, 0, "%s", e.message);
        return;
    }
    char *text = test_material_text(st, path, "yarn_friction=0");
    if (!text || load_text(text, &off, &e)) {
        CHECK(st, 0, "%s: without slip: %s", path, text ? e.message : "");
        free(text);
        return;
    }
    free(text);
    /* the warp at its reference crimp, the weft's pressed 15 um into the crossover (F_I
     * 0.029 N) and stretched to its reference length: both yarns at rest unloaded */
    const double dA[2] = {0, -15e-6}, dt = 1e-7, L0 = sqrt(P0 * P0 + A0_1 * A0_1);
    const double A0_2 = 0.0900e-3, L0_2 = sqrt(P0 * P0 + A0_2 * A0_2), A2 = A0_2 + dA[1];
    const double weft = sqrt(L0_2 * L0_2 - A2 * A2) / P0; /* the weft's stretch, L_2 = L_2⁰ */
    double state[8] = {0}, state_off[1] = {0}, dissipated = 0, slip_tension = 0;
    double worst_elastic = 0, worst_plateau = 0, worst_slip = 0, lam_peak = 1.01;
    double unslipped_peak = 0;
    int slipping = 0, weft_slipped = 0;
    const int N = 400;
    wff_point_result r, r_off;
    /* out to 1 % and back to -1 % */
    for (int i = 1; i <= 3 * N; i++) {
        double lam = i <= N ? 1 + 0.01 * i / N : lam_peak - 0.02 * (i - N) / (2 * N);
        const double F[6] = {lam, 0, 0, weft, 0, 0};
        const double old_slip = state[6];
        wff_material_evaluate(&m, F, dA, state, dt, &r);
        wff_material_evaluate(&off, F, dA, state_off, dt, &r_off);
        slip_tension = capacity * r.diag[FI];
        if (i == N)
            unslipped_peak = r_off.diag[T1];
        dissipated += r.slip_dissipated * 4 * P0 * P0; /* J per cell */
        weft_slipped |= r.state[7] != 0;
        const double x = warp_length(lam, dA[0]) - L0; /* L_1 − L_1⁰ */
        if (i <= N) { /* loading */
            if (r.state[6] == 0) { /* sticking: the tension without slip, to the bit */
                worst_elastic = fmax(worst_elastic, fabs(r.diag[T1] - r_off.diag[T1]));
            } else {
                slipping++;
                worst_plateau = fmax(worst_plateau, fabs(r.diag[T1] - slip_tension) / slip_tension);
                double s = (x - slip_tension / K) / L0;
                worst_slip = fmax(worst_slip, fabs(r.state[6] - s) / s);
            }
        } else if (i == N + 1) { /* the first unloading step: elastic, the slip held */
            CHECK(st, r.state[6] == old_slip, "%s: unloading holds the slip", path);
            double peak = warp_length(lam_peak, dA[0]);
            double unloaded = slip_tension - K * (peak - warp_length(lam, dA[0]));
            CHECK_CLOSE(st, r.diag[T1], tension_only ? fmax(unloaded, 0) : unloaded, 1e-9,
                        slip_tension, "unloading with slope k_1 (tension_only: to slack)");
        }
        memcpy(state, r.state, sizeof state);
    }
    const double s_peak_expected = (warp_length(lam_peak, dA[0]) - L0 - slip_tension / K) / L0;
    printf("  %-40s pull at fixed dA: T_slip %.4f N, %d slipping steps, plateau within %.1e, "
           "slip within %.1e of its closed form, sticking tension %.1e N from the unslipped; "
           "after unloading to 0.99: T1 %.4f N, slip %.3e\n", path, slip_tension, slipping,
           worst_plateau, worst_slip, worst_elastic, r.diag[T1], state[6]);
    CHECK(st, slipping > N / 2, "%s: slips in %d of %d loading steps", path, slipping, N);
    CHECK(st, worst_elastic == 0, "%s: while sticking the tension is the unslipped one (off by "
          "%.3g N)", path, worst_elastic);
    CHECK(st, worst_plateau <= 1e-12, "%s: the tension plateau is off T_slip by %.3g", path,
          worst_plateau);
    CHECK(st, worst_slip <= 1e-9, "%s: the slip is off its closed form by %.3g", path, worst_slip);
    CHECK(st, !weft_slipped, "%s: the weft slipped", path);
    /* without slip the same pull has no plateau */
    CHECK(st, unslipped_peak > 10 * slip_tension,
          "%s: without slip the yarn is loaded far past T_slip (%.4g N at the peak)", path,
          unslipped_peak);
    if (!tension_only) {
        /* back to 0.99: past −T_slip, slipped back, at −T_slip */
        CHECK_CLOSE(st, r.diag[T1], -slip_tension, 1e-12, 0, "slipping back at -T_slip");
        double s_end = (warp_length(0.99, dA[0]) - L0 + slip_tension / K) / L0;
        CHECK_CLOSE(st, state[6], s_end, 1e-9, 0, "the slip after slipping back");
        /* the dissipation: T_slip times the yarn slid, out and back */
        double slid = 2 * L0 * (s_peak_expected + (s_peak_expected - state[6]));
        CHECK_CLOSE(st, dissipated, slip_tension * slid, 1e-10, 0,
                    "dissipation = T_slip x the yarn slid, out and back");
    } else {
        /* a slack yarn carries nothing and does not slip back */
        CHECK(st, r.diag[T1] == 0, "tension_only: slack at the end (%g N)", r.diag[T1]);
        CHECK_CLOSE(st, state[6], s_peak_expected, 1e-9, 0, "tension_only: the slip kept");
        CHECK_CLOSE(st, dissipated, slip_tension * 2 * L0 * s_peak_expected, 1e-10, 0,
                    "dissipation = T_slip x the yarn slid");
    }
}

/* 4. the pull with balanced amplitudes */
static void check_balanced_pull(check_state *st)
{
    wff_material m, off;
    wff_error e;
    char *text = test_material_text(st, SLIP, "yarn_friction=0");
    if (wff_material_load(SLIP, &m, &e) || !text || load_text(text, &off, &e)) {
        CHECK(st, 0, "%s", e.message);
        free(text);
        return;
    }
    free(text);
    double state[8] = {0}, dA[2] = {0, 0}, dA_off[2] = {0, 0}, worst = 0;
    int slipping = 0, balanced = 1;
    wff_point_result r, r_off;
    const int N = 200;
    for (int i = 1; i <= N; i++) {
        const double lam = 1 + 0.02 * i / N;
        const double F[6] = {lam, 0, 0, 1.002, 0, 0};
        /* the amplitudes in balance with the slips held, then the update */
        balanced &= wff_balance_amplitudes(&m, F, state, dA, &e) == 0;
        balanced &= wff_balance_amplitudes(&off, F, wff_rest_state, dA_off, &e) == 0;
        const double before = state[6];
        wff_material_evaluate(&m, F, dA, state, 1e-7, &r);
        wff_material_evaluate(&off, F, dA_off, wff_rest_state, 1e-7, &r_off);
        if (r.state[6] > before) {
            slipping++;
            worst = fmax(worst, fabs(r.diag[T1] - 0.25 * 20 * r.diag[FI]) / r.diag[T1]);
        }
        memcpy(state, r.state, sizeof state);
    }
    printf("  balanced pull to 2 %%: %d slipping steps, T1 = n_c mu F_I within %.1e; at the end "
           "T1 %.4g N (without slip %.4g N), dA1 %.2f um (%.2f um), slip %.3e\n", slipping,
           worst, r.diag[T1], r_off.diag[T1], 1e6 * dA[0], 1e6 * dA_off[0], state[6]);
    CHECK(st, balanced, "the amplitudes balance at every step: %s", e.message);
    CHECK(st, slipping > N / 2, "slips in %d of %d steps", slipping, N);
    CHECK(st, worst <= 1e-12, "while slipping T1 = n_c mu_yy F_I: off by %.3g", worst);
    CHECK(st, r.diag[T1] < 0.5 * r_off.diag[T1], "slip lowers the tension: %g against %g N",
          r.diag[T1], r_off.diag[T1]);
    CHECK(st, dA[0] > dA_off[0] + 1e-6, "the slipped warp keeps its crimp: dA1 %g against %g m",
          dA[0], dA_off[0]);
}

/* 5. failure with slip along loading paths */
static void check_failure_paths(check_state *st)
{
    wff_material m;
    wff_error e;
    if (wff_material_load(SLIP_FAILURE, &m, &e)) {
        CHECK(st, 0, "%s", e.message);
        return;
    }
    const int d1 = m.cell->damage_state[0], s1 = wff_material_state_index(&m, "slip_1");
    int slipped = 0, damaged = 0, both = 0;
    double most_negative = 0, worst_excess = 0;
    /* the warp pulled to 2 % with the crossover loose (it slips), then the crossover
     * tightened and the warp pulled on to 7.5 % (the yarn damages, ruptures), and back */
    for (int path = 0; path < 12; path++) {
        double state[8] = {0};
        const double loose = -1e-6 * path, tight = -30e-6 - 0.5e-6 * path; /* ΔA, m */
        int path_slipped = 0, path_damaged = 0;
        for (int i = 1; i <= 600; i++) {
            double lam = i <= 200 ? 1 + 0.02 * i / 200
                         : i <= 500 ? 1.02 + 0.055 * (i - 200) / 300
                                    : 1.075 - 0.075 * (i - 500) / 100;
            double t = i <= 200 ? 0 : i <= 250 ? (i - 200) / 50.0 : 1;
            const double dA[2] = {loose + t * (tight - loose), loose + t * (tight - loose)};
            const double F[6] = {lam, 0, 0, 1, 0, 0};
            wff_point_result r, held;
            wff_material_evaluate(&m, F, dA, state, 0, &held); /* W with the states before */
            wff_material_evaluate(&m, F, dA, state, 1e-7, &r);
            const double d[3] = {r.dissipated, r.failure_dissipated, r.slip_dissipated};
            for (int k = 0; k < 3; k++)
                most_negative = fmin(most_negative, d[k]);
            worst_excess = fmax(worst_excess, (d[0] + d[1] + d[2] - (held.energy - r.energy)) /
                                                  fabs(held.energy));
            path_slipped |= r.state[s1] > state[s1];
            path_damaged |= r.state[d1] > state[d1];
            memcpy(state, r.state, sizeof state);
        }
        slipped += path_slipped;
        damaged += path_damaged;
        both += path_slipped && path_damaged;
    }
    printf("  failure with slip: of 12 paths %d slip, %d damage, %d both; least dissipation "
           "%.1e, sum above the released energy by %.1e of W\n", slipped, damaged, both,
           most_negative, worst_excess);
    CHECK(st, both == 12, "slip %d, damage %d, both %d of 12 paths", slipped, damaged, both);
    CHECK(st, most_negative >= 0, "a dissipation is negative: %.3g", most_negative);
    CHECK(st, worst_excess <= 1e-12, "an update dissipates more than it releases by %.3g of W",
          worst_excess);
}

/* The tests' struck square (test_model_struck's: 6 cm, 12 x 12 cells of triangles,
 * edges held) struck by 50 g at 60 m/s, radius 8 mm (its 5 mm cells do not let it
 * through), friction 0.2, to t_end: 0
 * or -1 (reported). */
static int struck(check_state *st, wff_model *m, const char *material, double t_end)
{
    wff_error e;
    test_rect r = {-0.03, 0.03, -0.03, 0.03, 12, 12, TEST_MESH_TRI, 1, 0.2, 7};
    wff_mesh mesh;
    if (test_mesh_rect(&r, &mesh)) {
        CHECK(st, 0, "test mesh");
        return -1;
    }
    int rc = wff_model_create_ordered(m, &mesh, material, 1, &e);
    static const char *const edges[] = {"left", "right", "bottom", "top"};
    for (int g = 0; rc == 0 && g < 4; g++)
        for (int c = WFF_UX; rc == 0 && c <= WFF_UZ; c++)
            rc = wff_model_fix_group(m, edges[g], c, &e) < 0 ? -1 : 0;
    if (rc || wff_model_set_projectile(m, 0.008, 0.05, 60, 0.2, &e) ||
        wff_model_advance(m, t_end, 1000000, &e)) {
        CHECK(st, 0, "%s: %s", material, e.message);
        return -1;
    }
    return 0;
}

/* 6. the struck square */
static void check_struck(check_state *st)
{
    char dir[512], slip_path[600], off_path[600], bare_path[600], half_path[600];
    if (test_tmp_dir("slip", dir, sizeof dir))
        return;
    test_tmp_path(dir, "slip.txt", slip_path, sizeof slip_path);
    test_tmp_path(dir, "off.txt", off_path, sizeof off_path);
    test_tmp_path(dir, "bare.txt", bare_path, sizeof bare_path);
    test_tmp_path(dir, "half.txt", half_path, sizeof half_path);
    /* kevlar_s706 with slip (n_c 10: no preload here, so a small crossover force); as it
     * is (yarn_friction = 0); without the slip keys */
    int ok = test_tmp_copy_replacing(KEVLAR, half_path, "yarn_friction ",
                                     "yarn_friction = 0.25\n") == 1 &&
             test_tmp_copy_replacing(half_path, slip_path, "slip_crossovers ",
                                     "slip_crossovers = 10\n") == 1 &&
             test_tmp_copy_replacing(KEVLAR, off_path, "yarn_friction ",
                                     "yarn_friction = 0\n") == 1 &&
             test_tmp_copy_replacing(KEVLAR, half_path, "yarn_friction ", "\n") == 1 &&
             test_tmp_copy_replacing(half_path, bare_path, "slip_crossovers ", "\n") == 1;
    CHECK(st, ok, "material copies in %s", dir);
    const double t_end = 6e-4;
    wff_model m;
    if (ok && struck(st, &m, slip_path, t_end) == 0) {
        wff_energies en;
        wff_model_energies(&m, &en);
        char violations[1024];
        int n = wff_model_invariants(&m, violations, sizeof violations);
        printf("  struck square with slip (mu_yy 0.25, n_c 10) to %.3g ms: dissipated by slip "
               "%.4g J, shear %.3g J, friction %.3g J, stored %.3g J, energy error %.2e of "
               "%.3g J\n", 1e3 * t_end, en.dissipated_slip, en.dissipated_shear,
               en.dissipated_friction, en.internal, en.error, en.reference);
        /* the balance's residual (J) is a small part of what slip dissipated: without
         * that term it would not close */
        const double residual = fabs(en.error) * en.reference;
        CHECK(st, en.dissipated_slip > 0 && residual <= 1e-2 * en.dissipated_slip,
              "energy balance with slip: residual %.3g J against %.3g J dissipated by slip",
              residual, en.dissipated_slip);
        CHECK(st, fabs(en.error) <= 1e-6, "energy balance with slip: error %.3g", en.error);
        CHECK(st, n == 0, "invariants: %s", violations);
        wff_model_free(&m);
    }
    wff_model a, b;
    if (ok && struck(st, &a, off_path, t_end) == 0) {
        if (struck(st, &b, bare_path, t_end) == 0) {
            int same = a.n_dofs == b.n_dofs && a.step == b.step &&
                       memcmp(a.u, b.u, sizeof(double) * (size_t)a.n_dofs) == 0 &&
                       memcmp(a.v, b.v, sizeof(double) * (size_t)a.n_dofs) == 0;
            wff_energies ea, eb;
            wff_model_energies(&a, &ea);
            wff_model_energies(&b, &eb);
            same = same && memcmp(&ea, &eb, sizeof ea) == 0 && ea.dissipated_slip == 0;
            printf("  struck square with yarn_friction = 0 and without the keys: %ld steps, %s\n",
                   a.step, same ? "the same bits" : "DIFFERENT");
            CHECK(st, same, "yarn_friction = 0 gives the run without slip, bit for bit");
            wff_model_free(&b);
        }
        wff_model_free(&a);
    }
    test_tmp_remove(dir);
}

int main(void)
{
    check_state st = {0, 0};
    check_keys(&st);
    check_pull(&st, SLIP, 0.25 * 20, 0);
    check_pull(&st, "tests/data/king_slip_tension_only.txt", 0.2 * 10, 1);
    check_balanced_pull(&st);
    check_failure_paths(&st);
    check_struck(&st);
    return check_summary(&st, "test_slip");
}

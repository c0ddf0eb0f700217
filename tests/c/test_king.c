/* King plain-weave cell: checks specific to its laws (docs/model.md §3–7, §10, and the preload of §13). */
#include "check.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"

#include <math.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"

static wff_material load(check_state *st, const char *path)
{
    wff_material m;
    wff_error e;
    int rc = wff_material_load(path, &m, &e);
    CHECK(st, rc == 0, "%s", e.message);
    return m;
}

/* diag indices of king_plain: T1 T2 beta1 beta2 F_I F_L1 F_L2 M_s */
enum { T1, T2, BETA1, BETA2, FI, FL1, FL2, MS };

/* §10.5: equal tension 1 N per yarn, amplitudes balanced → the paper's preload. */
static void check_preload(check_state *st)
{
    wff_material m = load(st, KEVLAR);
    wff_biaxial_state s = {.stretch = {1, 1}};
    wff_error e;
    int rc = wff_preload_equal_force(&m, 1.0, &s, &e);
    CHECK(st, rc == 0, "%s", e.message);
    printf("  preload: stretch (%.6f, %.6f), dA (%.3f, %.3f) um, F_I %.4f N, F_L2 %.2e N\n",
           s.stretch[0], s.stretch[1], s.dA[0] * 1e6, s.dA[1] * 1e6, s.point.diag[FI],
           s.point.diag[FL2]);
    CHECK_CLOSE(st, s.stretch[0], 1.00396, 0.005, 0, "lambda_1");
    CHECK_CLOSE(st, s.stretch[1], 1.0135, 0.005, 0, "lambda_2");
    /* the strains too, at 0.5 %: stricter than the stretches */
    CHECK_CLOSE(st, s.stretch[0] - 1, 0.00396, 0.005, 0, "strain_1");
    CHECK_CLOSE(st, s.stretch[1] - 1, 0.0135, 0.005, 0, "strain_2");
    CHECK_CLOSE(st, s.dA[0], -9.3e-6, 0.005, 0, "dA_1");
    CHECK_CLOSE(st, s.dA[1], -23.8e-6, 0.005, 0, "dA_2");
    CHECK_CLOSE(st, s.point.diag[T1], 1.0, 1e-9, 0, "T_1");
    CHECK_CLOSE(st, s.point.diag[T2], 1.0, 1e-9, 0, "T_2");
    CHECK(st, fabs(s.point.residual[0]) < 1e-6 && fabs(s.point.residual[1]) < 1e-6,
          "balanced: R = (%g, %g) N/m^2", s.point.residual[0], s.point.residual[1]);
    /* docs/model.md §4: the weft spar is slightly engaged at preload, under 1 % of F_I */
    CHECK(st, s.point.diag[FL2] > 0 && s.point.diag[FL2] < 0.01 * s.point.diag[FI],
          "weft spar engaged but small: F_L2 %g, F_I %g", s.point.diag[FL2], s.point.diag[FI]);

    /* balance from F alone gives the same amplitudes */
    double F[6] = {s.stretch[0], 0, 0, s.stretch[1], 0, 0}, dA[2] = {0, 0};
    rc = wff_balance_amplitudes(&m, F, wff_rest_state, dA, &e);
    CHECK(st, rc == 0, "%s", e.message);
    CHECK_CLOSE(st, dA[0], s.dA[0], 1e-8, 0, "balance dA_1");
    CHECK_CLOSE(st, dA[1], s.dA[1], 1e-8, 0, "balance dA_2");
    /* a tiny non-zero first guess converges too (a relative FD step would not) */
    double tiny[2] = {1e-13, -1e-13};
    rc = wff_balance_amplitudes(&m, F, wff_rest_state, tiny, &e);
    CHECK(st, rc == 0, "balance from a 1e-13 m guess: %s", rc ? e.message : "");
    CHECK_CLOSE(st, tiny[0], s.dA[0], 1e-8, 0, "balance dA_1 from a tiny guess");
}

/* Pure extension along warp with no shear and idle spars (docs/model.md §6 hand check,
 * with the bending term): P_11 = (T_1 cosβ_1 − M_b1 sinβ_1/L_1)/(2 p_2⁰). */
static void check_hand_extension(check_state *st)
{
    wff_material m = load(st, KEVLAR);
    double F[6] = {1.02, 0, 0, 1, 0, 0}, dA[2] = {2e-6, 3e-6};
    wff_point_result r;
    wff_material_evaluate(&m, F, dA, wff_rest_state, 0, &r);
    double p0 = 0.3735e-3;
    CHECK(st, r.diag[FL1] == 0 && r.diag[FL2] == 0 && r.diag[MS] == 0, "idle spars and shear");
    double p = 1.02 * p0, A = 0.0602e-3 + dA[0], L = sqrt(p * p + A * A);
    double moment = 3.9e-4 * (atan2(A, p) - atan2(0.0602e-3, p0));
    CHECK_CLOSE(st, r.stress[0], (r.diag[T1] * p / L - moment * (A / L) / L) / (2 * p0), 1e-12, 0,
                "P11");
    CHECK(st, r.stress[1] == 0 && r.stress[2] == 0 && r.stress[4] == 0 && r.stress[5] == 0,
          "no shear or out-of-plane resultant");
    CHECK_CLOSE(st, r.diag[T1], 1.03e7 * (sqrt(p * p + A * A) - sqrt(p0 * p0 + 0.0602e-3 * 0.0602e-3)),
                1e-12, 0, "T1 = k (L - L0)");
}

/* n = 1 backward Euler against the exact solution for γ = γ̇ t:
 * γᶠ(t) = γ̇ (t − τ (1 − e^(−t/τ))), τ = M₀/(γ̇₀ K_s); first-order convergence. */
static double shear_run(check_state *st, const wff_material *m, double rate, double t_end,
                        int steps, double *dissipated)
{
    double gf = 0, dt = t_end / steps;
    *dissipated = 0;
    wff_point_result r;
    for (int i = 1; i <= steps; i++) {
        double g = rate * dt * i;
        double F[6] = {1, sin(g), 0, cos(g), 0, 0}, dA[2] = {0, 0};
        wff_material_evaluate(m, F, dA, &gf, dt, &r); /* King's one state: γᶠ */
        gf = r.state[0];
        *dissipated += r.dissipated;
        CHECK(st, r.dissipated >= 0, "dissipation %g at step %d", r.dissipated, i);
    }
    return gf;
}

static void check_shear_flow(check_state *st)
{
    wff_material m = load(st, KEVLAR);
    double Ks = 1.0e-4, M0 = 5.0e-6, g0 = 1.0e3, tau = M0 / (g0 * Ks);
    double rate = 100.0, t_end = 3 * tau; /* γ reaches 0.015 rad: spars idle */
    double exact = rate * (t_end - tau * (1 - exp(-t_end / tau)));
    double d1, d2;
    double e1 = fabs(shear_run(st, &m, rate, t_end, 200, &d1) - exact);
    double e2 = fabs(shear_run(st, &m, rate, t_end, 400, &d2) - exact);
    printf("  shear flow n=1: exact %.6e, error %.3e (200 steps), %.3e (400 steps)\n", exact, e1, e2);
    CHECK(st, e1 < 0.01 * exact, "backward Euler within 1 %% at 200 steps: %g", e1 / exact);
    CHECK(st, e1 / e2 > 1.8 && e1 / e2 < 2.2, "first-order convergence, ratio %g", e1 / e2);
    CHECK(st, d1 > 0, "shear flow dissipates: %g J/m^2", d1);

    /* n = 3: the implicit equation holds at the returned γᶠ */
    wff_material m3 = load(st, "tests/data/king_flow_n3.txt");
    double g = 0.05, gf = 0.01, dt = 2e-6;
    double F[6] = {1, sin(g), 0, cos(g), 0, 0}, dA[2] = {0, 0};
    wff_point_result r;
    wff_material_evaluate(&m3, F, dA, &gf, dt, &r);
    CHECK(st, m3.n_state == 1 && strcmp(m3.cell->state_names[0], "gamma_f") == 0,
          "king_plain's points carry one state, gamma_f: %d", m3.n_state);
    double Ms = Ks * (g - r.state[0]);
    double rhs = gf + dt * g0 * pow(Ms / M0, 3);
    CHECK(st, r.state[0] > gf && r.state[0] < g, "gamma_f %g between %g and %g", r.state[0], gf,
          g);
    CHECK_CLOSE(st, r.state[0], rhs, 1e-12, 0, "n=3 backward Euler equation");
    CHECK_CLOSE(st, r.diag[MS], Ms, 1e-12, 0, "M_s = K_s (gamma - gamma_f)");
}

/* λ = 1 adds 2 F_Lk sinα_k p_l|cosθ|cosβ_k/L_k to F_k^N: zero without shear, else not. */
static void check_lever(check_state *st)
{
    wff_material m0 = load(st, KEVLAR), m1 = load(st, "tests/data/king_lever.txt");
    wff_point_result a, b;
    double dA[2] = {-20e-6, -30e-6};
    double F0[6] = {0.99, 0, 0, 0.99, 0, 0};
    wff_material_evaluate(&m0, F0, dA, wff_rest_state, 0, &a);
    wff_material_evaluate(&m1, F0, dA, wff_rest_state, 0, &b);
    CHECK(st, a.diag[FL1] > 0 && a.residual[0] == b.residual[0] && a.residual[1] == b.residual[1],
          "no shear: lever changes nothing (F_L1 %g)", a.diag[FL1]);
    double g = 0.4;
    double F[6] = {1, sin(g), 0, cos(g), 0, 0};
    wff_material_evaluate(&m0, F, dA, wff_rest_state, 0, &a);
    wff_material_evaluate(&m1, F, dA, wff_rest_state, 0, &b);
    double p0 = 0.3735e-3, A1 = 0.0602e-3 + dA[0];
    double p2 = p0, cos_t = sin(g), p1 = p0, L1 = sqrt(p1 * p1 + A1 * A1);
    double s1 = p2 * cos(g), d1 = sqrt(s1 * s1 + A1 * A1);
    double extra = 2 * a.diag[FL1] * (A1 / d1) * p2 * fabs(cos_t) * (p1 / L1) / L1;
    double diff = (b.residual[0] - a.residual[0]) * (4 * p0 * p0);
    printf("  lever: under 0.4 rad shear F_L1 = %.4f N; lambda = 1 lowers F_1^N by %.4e N "
           "(F_I = %.4f N)\n", a.diag[FL1], extra, a.diag[FI]);
    CHECK(st, a.diag[FL1] > 0, "spar loaded under shear");
    CHECK_CLOSE(st, diff, extra, 1e-9, 0, "lever term");
    CHECK(st, memcmp(a.stress, b.stress, sizeof a.stress) == 0, "lever leaves P unchanged");
}

/* Compaction far past the exponential's continuation point stays finite and consistent. */
static void check_compaction_guard(check_state *st)
{
    wff_material m = load(st, KEVLAR);
    double F[6] = {1, 0, 0, 1, 0, 0};
    double dA[2] = {-250e-6, -250e-6}; /* a I = 50 */
    wff_point_result r, rp, rm;
    wff_material_evaluate(&m, F, dA, wff_rest_state, 0, &r);
    CHECK(st, isfinite(r.energy) && isfinite(r.residual[0]) && isfinite(r.stress[0]),
          "finite at a I = 50");
    double h = 1e-9;
    double dp[2] = {dA[0] + h, dA[1]}, dm[2] = {dA[0] - h, dA[1]};
    wff_material_evaluate(&m, F, dp, wff_rest_state, 0, &rp);
    wff_material_evaluate(&m, F, dm, wff_rest_state, 0, &rm);
    CHECK_CLOSE(st, -(rp.energy - rm.energy) / (2 * h), r.residual[0], 1e-6, 0,
                "R = -dW/ddA past the continuation");
    double speed, omega;
    m.cell->wave_speeds(m.params, m.areal_density, F, dA, &speed, &omega);
    CHECK(st, isfinite(omega) && omega > 1e8, "stiff compaction raises the amplitude frequency: %g",
          omega);
}

/* Stable-step estimate at rest is in the range docs/model.md §12 states. */
static void check_stable_step(check_state *st)
{
    wff_material m = load(st, KEVLAR);
    double F[6] = {1.00396, 0, 0, 1.0135, 0, 0}, dA[2] = {-9.3e-6, -23.8e-6};
    double speed, omega;
    m.cell->wave_speeds(m.params, m.areal_density, F, dA, &speed, &omega);
    printf("  stable step at preload: membrane speed %.0f m/s, amplitude 2/omega %.3f us\n", speed,
           2e6 / omega);
    CHECK(st, speed > 5000 && speed < 8000, "membrane speed %g m/s (straight yarns ~5.4 km/s)", speed);
    CHECK(st, 2 / omega > 0.05e-6 && 2 / omega < 0.36e-6, "amplitude step %g s", 2 / omega);
}

int main(void)
{
    check_state st = {0, 0};
    check_preload(&st);
    check_hand_extension(&st);
    check_shear_flow(&st);
    check_lever(&st);
    check_compaction_guard(&st);
    check_stable_step(&st);
    return check_summary(&st, "test_king");
}

/* The Phoenix–Porwal estimate (plugin/membrane_limit.c):
 *  - Γ >= 3/8: the peak at the projectile's edge, x* = 1, K_max = 1 and
 *    V50 = √2 (1 + Γ) c ε^(3/4) (closed form);
 *  - small Γ: x*² = 3/(8Γ), and K(x) = x exp(−4Γ(x² − 1)/3) is lower at
 *    x*(1 ± 1e-3) and x*(1 ± 0.1) than at x*; V50 = √2 (1+Γ) c (ε/K_max)^(3/4);
 *  - a clamp inside the peak gives K(x_o) < K_max and a higher speed; one
 *    outside it, or none, gives 0;
 *  - from a material file: linear_yarns (stress per width S_1 (λ − 1)) gives
 *    c = sqrt(S_1 / ρ_A) exactly, fail_strain_1 from the file, Γ = N ρ_A π r²/m
 *    (N plies: Γ × N, c and ε unchanged); no fail_strain_1: 0.0355; king_plain
 *    (Kevlar S706) within 5 % of the tool's c = sqrt(k_1 p0_1 / (2 p0_2) / ρ_A)
 *    and below it (the crimp: the cell's stress at 1 % is the truss's seen
 *    through the crimp angle);
 *  - bad inputs named: each of the four inputs, plies, mass, radius, opening,
 *    a missing file. */
#include "check.h"
#include "test_tmp.h"
#include "wovenff/membrane_limit.h"

#include <math.h>
#include <string.h>

#define LINEAR "freefem_scripts/materials/kevlar_linear.txt"
#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"

static double closed_form(double gamma, double c, double eps, double k)
{
    return sqrt(2.0) * (1 + gamma) * c * pow(eps / k, 0.75);
}

static void test_large_gamma(check_state *st)
{
    const double gammas[] = {0.375, 0.5, 2.0};
    for (int i = 0; i < 3; i++) {
        wff_pp_input in = {.wave_speed = 5000, .failure_strain = 0.03, .gamma = gammas[i]};
        wff_pp_result r;
        wff_error err;
        CHECK(st, wff_phoenix_porwal(&in, &r, &err) == 0, "Gamma %g: %s", gammas[i], err.message);
        CHECK_CLOSE(st, r.x_peak, 1.0, 1e-15, 1, "x* at Gamma >= 3/8");
        CHECK_CLOSE(st, r.k_max, 1.0, 1e-15, 1, "K_max at Gamma >= 3/8");
        CHECK_CLOSE(st, r.v50, closed_form(gammas[i], 5000, 0.03, 1), 1e-14, 1, "V50, K_max = 1");
        CHECK(st, r.k_clamp == 0 && r.v50_clamp == 0, "no clamp: %g %g", r.k_clamp, r.v50_clamp);
    }
}

static void test_small_gamma(check_state *st)
{
    const double gamma = 2.2e-4, c = 5334.1, eps = 0.038;
    wff_pp_input in = {.wave_speed = c, .failure_strain = eps, .gamma = gamma};
    wff_pp_result r;
    wff_error err;
    CHECK(st, wff_phoenix_porwal(&in, &r, &err) == 0, "%s", err.message);
    CHECK_CLOSE(st, r.x_peak * r.x_peak, 3 / (8 * gamma), 1e-13, 1, "x*^2 = 3/(8 Gamma)");
    CHECK_CLOSE(st, r.k_max, r.x_peak * exp(-4 * gamma * (r.x_peak * r.x_peak - 1) / 3), 1e-13,
                1, "K_max = K(x*)");
    const double offsets[] = {-0.1, -1e-3, 1e-3, 0.1};
    for (int i = 0; i < 4; i++) {
        double k = wff_pp_edge_factor(gamma, r.x_peak * (1 + offsets[i]));
        CHECK(st, k < r.k_max, "K(x* (1 %+g)) = %.12g not below K_max %.12g", offsets[i], k,
              r.k_max);
    }
    CHECK(st, r.k_max > 1, "K_max %g", r.k_max);
    CHECK_CLOSE(st, r.v50, closed_form(gamma, c, eps, r.k_max), 1e-14, 1, "V50");

    in.opening_ratio = 20; /* inside x* = 41 */
    CHECK(st, wff_phoenix_porwal(&in, &r, &err) == 0, "%s", err.message);
    CHECK_CLOSE(st, r.k_clamp, wff_pp_edge_factor(gamma, 20), 1e-15, 1, "K at the clamp");
    CHECK(st, r.k_clamp < r.k_max && r.v50_clamp > r.v50, "clamp: K %g (max %g), V %g (%g)",
          r.k_clamp, r.k_max, r.v50_clamp, r.v50);
    CHECK_CLOSE(st, r.v50_clamp, closed_form(gamma, c, eps, r.k_clamp), 1e-14, 1, "V at the clamp");
    in.opening_ratio = 60; /* outside it */
    CHECK(st, wff_phoenix_porwal(&in, &r, &err) == 0, "%s", err.message);
    CHECK(st, r.k_clamp == 0 && r.v50_clamp == 0, "clamp beyond x*: %g %g", r.k_clamp, r.v50_clamp);
}

static void test_material(check_state *st)
{
    /* kevlar_linear.txt: S_1 = 5.15e6 N/m, rho_A = 0.181, fail_strain_1 = 0.038 */
    const double S = 5.15e6, rho = 0.181, mass = 1.1016e-3, radius = 2.69875e-3;
    wff_pp_result r1, r12;
    wff_pp_input u1, u12;
    wff_error err;
    CHECK(st, wff_membrane_limit_estimate(LINEAR, 1, mass, radius, 0, &r1, &u1, &err) == 0, "%s",
          err.message);
    CHECK_CLOSE(st, u1.wave_speed, sqrt(S / rho), 1e-9, 1, "linear_yarns c");
    CHECK_CLOSE(st, u1.failure_strain, 0.038, 1e-15, 1, "fail_strain_1");
    CHECK_CLOSE(st, u1.gamma, rho * M_PI * radius * radius / mass, 1e-14, 1, "Gamma");
    CHECK(st, u1.opening_ratio == 0, "no clamp: %g", u1.opening_ratio);
    CHECK(st, wff_membrane_limit_estimate(LINEAR, 12, mass, radius, 0.127, &r12, &u12, &err) == 0,
          "%s", err.message);
    CHECK_CLOSE(st, u12.gamma, 12 * u1.gamma, 1e-14, 1, "Gamma x 12 plies");
    CHECK(st, u12.wave_speed == u1.wave_speed && u12.failure_strain == u1.failure_strain,
          "plies change c or eps: %g %g", u12.wave_speed, u12.failure_strain);
    CHECK_CLOSE(st, u12.opening_ratio, 0.127 / radius, 1e-14, 1, "opening ratio");
    CHECK(st, r12.v50 > r1.v50, "12 plies %g m/s not above 1 ply %g m/s", r12.v50, r1.v50);

    /* Kevlar S706 (king_plain): the cell's c against the tool's truss value */
    wff_pp_input uk;
    CHECK(st, wff_membrane_limit_estimate(KEVLAR, 1, 0.104, 6.35e-3, 0.127, &r1, &uk, &err) == 0,
          "%s", err.message);
    double c_tool = sqrt(1.03e7 * 0.3735e-3 / (2 * 0.3735e-3) / rho);
    CHECK(st, uk.wave_speed < c_tool && uk.wave_speed > 0.95 * c_tool,
          "king_plain c %g m/s, the tool's %g m/s", uk.wave_speed, c_tool);

    /* no fail_strain_1: the woven-yarn default */
    char dir[512], mid[600], bare[600];
    if (test_tmp_dir("test_membrane_limit", dir, sizeof dir) != 0) {
        CHECK(st, 0, "temporary folder");
        return;
    }
    test_tmp_path(dir, "mid.txt", mid, sizeof mid);
    test_tmp_path(dir, "bare.txt", bare, sizeof bare);
    CHECK(st, test_tmp_copy_replacing(LINEAR, mid, "fail_strain_", "\n") == 2, "fail strains");
    CHECK(st, test_tmp_copy_replacing(mid, bare, "rupture_strain_", "\n") == 2, "rupture strains");
    CHECK(st, wff_membrane_limit_estimate(bare, 1, mass, radius, 0, &r1, &u1, &err) == 0, "%s",
          err.message);
    CHECK(st, u1.failure_strain == WFF_PP_DEFAULT_FAIL_STRAIN, "default strain %g",
          u1.failure_strain);
    test_tmp_remove(dir);
}

static void expect_error(check_state *st, int rc, const wff_error *err, const char *name)
{
    CHECK(st, rc == -1, "%s: rc %d", name, rc);
    CHECK(st, strstr(err->message, name) != NULL, "'%s' not named in: %s", name, err->message);
}

static void test_errors(check_state *st)
{
    const double bad[] = {0, -1, NAN, INFINITY};
    for (int i = 0; i < 4; i++) {
        wff_pp_result r;
        wff_error err;
        wff_pp_input in = {5000, 0.03, 0.01, 0};
        in.wave_speed = bad[i];
        expect_error(st, wff_phoenix_porwal(&in, &r, &err), &err, "wave_speed");
        in.wave_speed = 5000;
        in.failure_strain = bad[i];
        expect_error(st, wff_phoenix_porwal(&in, &r, &err), &err, "failure_strain");
        in.failure_strain = 0.03;
        in.gamma = bad[i];
        expect_error(st, wff_phoenix_porwal(&in, &r, &err), &err, "gamma");
        in.gamma = 0.01;
        if (bad[i] != 0) { /* 0: no clamp */
            in.opening_ratio = bad[i];
            expect_error(st, wff_phoenix_porwal(&in, &r, &err), &err, "opening_ratio");
        }
    }
    wff_pp_result r;
    wff_error err;
    expect_error(st, wff_membrane_limit_estimate(LINEAR, 0, 1e-3, 3e-3, 0, &r, NULL, &err), &err,
                 "plies");
    expect_error(st, wff_membrane_limit_estimate(LINEAR, 1, -1e-3, 3e-3, 0, &r, NULL, &err), &err,
                 "mass");
    expect_error(st, wff_membrane_limit_estimate(LINEAR, 1, 1e-3, NAN, 0, &r, NULL, &err), &err,
                 "radius");
    expect_error(st, wff_membrane_limit_estimate(LINEAR, 1, 1e-3, 3e-3, 2e-3, &r, NULL, &err),
                 &err, "opening radius");
    expect_error(st, wff_membrane_limit_estimate("no_such_material.txt", 1, 1e-3, 3e-3, 0, &r,
                                                 NULL, &err), &err, "no_such_material.txt");
}

int main(void)
{
    check_state st = {0, 0};
    test_large_gamma(&st);
    test_small_gamma(&st);
    test_material(&st);
    test_errors(&st);
    return check_summary(&st, "test_membrane_limit");
}

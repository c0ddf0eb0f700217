/* One material point along a load path (plugin/point_path.c):
 * - dynamic amplitudes at a held F, released from off balance: the central
 *   differences keep their energy (W + ½ m v_{n−½}·v_{n+½}) within 1 % of
 *   the energy put in, over tens of periods of the fastest mode; the
 *   amplitudes oscillate about the static balance, and the step count is the
 *   one the cell's amplitude_omega gives;
 * - the cell's amplitude_omega bounds the true highest frequency (Hessian by
 *   finite differences) at the states the explorer visits;
 * - a static balance stays put (R = 0, no motion);
 * - shear flow with held amplitudes: 0 < gamma_f < gamma, more with a longer
 *   duration, flow_substeps steps;
 * - the record: energies per mechanism add up to W, stretches and shear angle
 *   of the symmetric shear F, K_amp = ½ (ρ_A/6) |v|²;
 * - errors: dynamic amplitudes on linear_yarns, a zero duration. */
#include "check.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/point_path.h"

#include <math.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define BASKET "freefem_scripts/materials/kevlar_basket.txt"
#define LINEAR "freefem_scripts/materials/kevlar_linear.txt"

static const wff_path_mode kDynamic = {1, 0, WFF_PATH_STEP_SAFETY, WFF_PATH_FLOW_SUBSTEPS};
static const wff_path_mode kFlow = {0, 1, WFF_PATH_STEP_SAFETY, WFF_PATH_FLOW_SUBSTEPS};

static void shear_F(double gamma, double stretch, double F[6])
{
    double c = cos(gamma / 2) * stretch, s = sin(gamma / 2) * stretch;
    const double f[6] = {c, s, s, c, 0, 0};
    memcpy(F, f, sizeof f);
}

static wff_material load(check_state *st, const char *path)
{
    wff_material m;
    wff_error e;
    CHECK(st, wff_material_load(path, &m, &e) == 0, "%s", e.message);
    return m;
}

static double energy(const wff_material *m, const double F[6], const double dA[2])
{
    wff_point_result r;
    wff_material_evaluate(m, F, dA, wff_rest_state, 0, &r);
    return r.energy;
}

static void free_oscillation(check_state *st, const char *path)
{
    wff_material m = load(st, path);
    wff_error e;
    double F[6];
    shear_F(0.3, 1.005, F);
    double balanced[2] = {0, 0};
    CHECK(st, wff_balance_amplitudes(&m, F, wff_rest_state, balanced, &e) == 0, "%s", e.message);
    wff_point_state s = {{balanced[0] + 2e-6, balanced[1] - 1e-6}, {0, 0}, {0}, 0, 0, {0, 0, 0}};
    double W0 = energy(&m, F, s.dA), Wmin = energy(&m, F, balanced);
    double speed, omega;
    m.cell->wave_speeds(m.params, m.areal_density, F, s.dA, &speed, &omega);
    double duration = 20 * 2 * M_PI / omega; /* tens of periods of the fastest mode */
    double lo[2] = {1, 1}, hi[2] = {-1, -1}, worst = 0, E1 = 0;
    for (int seg = 0; seg < 50; seg++) {
        CHECK(st, wff_point_path_segment(&m, F, F, duration / 50, &kDynamic, &s, &e) == 0,
              "%s", e.message);
        /* the state's velocity is half a step behind dA; leapfrog conserves
         * W(ΔA_n) + ½ m v_{n−½}·v_{n+½} (exactly for a quadratic W) */
        wff_point_result r;
        wff_material_evaluate(&m, F, s.dA, wff_rest_state, 0, &r);
        double mass = m.areal_density / 6, kinetic = 0;
        for (int k = 0; k < 2; k++)
            kinetic += 0.5 * mass * s.velocity[k] *
                       (s.velocity[k] + s.previous_step * r.residual[k] / mass);
        if (seg == 0) /* the start from rest sits (ω dt)²/4 off that invariant */
            E1 = r.energy + kinetic;
        worst = fmax(worst, fabs(r.energy + kinetic - E1));
        for (int k = 0; k < 2; k++) {
            lo[k] = fmin(lo[k], s.dA[k] - balanced[k]);
            hi[k] = fmax(hi[k], s.dA[k] - balanced[k]);
        }
    }
    CHECK(st, worst < 1e-2 * (W0 - Wmin), "%s: W + K drifts by %g J/m² (%g put in)", path,
          worst, W0 - Wmin);
    for (int k = 0; k < 2; k++)
        CHECK(st, lo[k] < 0 && hi[k] > 0 && hi[k] - lo[k] < 1e-5,
              "%s: dA%d - balance in [%g, %g]: no oscillation about the balance", path, k + 1,
              lo[k], hi[k]);
    /* one segment: the step count the cell's bound gives */
    wff_point_state one = {{balanced[0], balanced[1]}, {0, 0}, {0}, 0, 0, {0, 0, 0}};
    m.cell->wave_speeds(m.params, m.areal_density, F, one.dA, &speed, &omega);
    double seg = 1e-6;
    CHECK(st, wff_point_path_segment(&m, F, F, seg, &kDynamic, &one, &e) == 0, "%s", e.message);
    long want = (long)ceil(seg / (WFF_PATH_STEP_SAFETY * 2 / omega));
    CHECK(st, one.substeps == want, "%s: %ld steps, want %ld", path, one.substeps, want);
    /* at the balance nothing moves */
    for (int k = 0; k < 2; k++) {
        CHECK_CLOSE(st, one.dA[k], balanced[k], 1e-9, 1e-6, "balance stays put");
        CHECK(st, fabs(one.velocity[k]) < 1e-3, "%s: velocity %g m/s at the balance", path,
              one.velocity[k]);
    }
}

/* amplitude_omega >= sqrt(λ_max(H)/m), H = −∂R/∂ΔA by central differences. */
static void omega_bounds_frequency(check_state *st, const char *path)
{
    wff_material m = load(st, path);
    wff_error e;
    const double gammas[] = {0, 0.3, 0.6}, strains[] = {0, 0.01, 0.02};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            double F[6];
            shear_F(gammas[i], 1 + strains[j], F);
            double dA[2] = {0, 0};
            if (wff_balance_amplitudes(&m, F, wff_rest_state, dA, &e))
                continue;
            double H[2][2], h = 1e-9;
            for (int c = 0; c < 2; c++) {
                double p[2] = {dA[0], dA[1]}, q[2] = {dA[0], dA[1]};
                p[c] += h;
                q[c] -= h;
                wff_point_result rp, rq;
                wff_material_evaluate(&m, F, p, wff_rest_state, 0, &rp);
                wff_material_evaluate(&m, F, q, wff_rest_state, 0, &rq);
                for (int r = 0; r < 2; r++)
                    H[r][c] = -(rp.residual[r] - rq.residual[r]) / (2 * h);
            }
            double tr = H[0][0] + H[1][1], det = H[0][0] * H[1][1] - H[0][1] * H[1][0];
            double lmax = tr / 2 + sqrt(fmax(tr * tr / 4 - det, 0));
            double speed, omega;
            m.cell->wave_speeds(m.params, m.areal_density, F, dA, &speed, &omega);
            double true_omega = sqrt(fmax(lmax, 0) / (m.areal_density / 6));
            CHECK(st, omega >= true_omega, "%s at gamma %g, strain %g: omega %g < %g", path,
                  gammas[i], strains[j], omega, true_omega);
        }
}

static void shear_flow(check_state *st)
{
    wff_material m = load(st, KEVLAR);
    wff_error e;
    double F0[6], F1[6];
    shear_F(0, 1, F0);
    shear_F(0.4, 1, F1);
    wff_point_state fast = {{0, 0}, {0, 0}, {0}, 0, 0, {0, 0, 0}}, slow = fast;
    CHECK(st, wff_point_path_segment(&m, F0, F1, 1e-5, &kFlow, &fast, &e) == 0, "%s", e.message);
    CHECK(st, wff_point_path_segment(&m, F0, F1, 1e-3, &kFlow, &slow, &e) == 0, "%s", e.message);
    CHECK(st, fast.state[0] > 0 && fast.state[0] < slow.state[0] && slow.state[0] < 0.4,
          "gamma_f %g (1e-5 s), %g (1e-3 s), want 0 < fast < slow < 0.4", fast.state[0],
          slow.state[0]);
    CHECK(st, fast.substeps == WFF_PATH_FLOW_SUBSTEPS, "%ld flow steps", fast.substeps);
    CHECK(st, fast.dA[0] == 0 && fast.dA[1] == 0, "held amplitudes moved");
}

static void record(check_state *st, const char *path)
{
    wff_material m = load(st, path);
    wff_error e;
    double F[6];
    shear_F(0.5, 1.01, F);
    wff_point_state s = {{-3e-6, 2e-6}, {0.1, -0.2}, {0.05}, 0, 0, {0, 0, 0}};
    if (m.cell->n_amplitudes == 0)
        s.dA[0] = s.dA[1] = 0;
    wff_point_record rec;
    CHECK(st, wff_point_path_record(&m, F, &s, &rec, &e) == 0, "%s", e.message);
    double sum = 0;
    for (int i = 0; i < rec.n_mech; i++)
        sum += rec.mech_energy[i];
    CHECK(st, rec.n_mech == m.cell->n_mech, "%s: %d mechanisms", path, rec.n_mech);
    CHECK_CLOSE(st, sum, rec.point.energy, 1e-12, 1e-12, "energies per mechanism add up to W");
    CHECK_CLOSE(st, rec.stretch[0], 1.01, 1e-14, 1, "lambda1");
    CHECK_CLOSE(st, rec.stretch[1], 1.01, 1e-14, 1, "lambda2");
    CHECK_CLOSE(st, rec.shear_angle, 0.5, 1e-13, 1, "shear angle");
    CHECK_CLOSE(st, rec.amplitude_kinetic, 0.5 * m.areal_density / 6 * 0.05, 1e-14, 1e-30,
                "K_amp");
}

static void errors(check_state *st)
{
    wff_material m = load(st, LINEAR);
    wff_error e;
    double F[6];
    shear_F(0, 1.01, F);
    wff_point_state s = {{0, 0}, {0, 0}, {0}, 0, 0, {0, 0, 0}};
    CHECK(st, wff_point_path_segment(&m, F, F, 1e-6, &kDynamic, &s, &e) != 0 &&
                  strstr(e.message, "cell 'linear_yarns'") &&
                  strstr(e.message, "has no amplitudes"),
          "dynamic amplitudes on linear_yarns: '%s'", e.message);
    CHECK(st, wff_point_path_segment(&m, F, F, 0, &kFlow, &s, &e) != 0 &&
                  strstr(e.message, "duration 0 s must be > 0"),
          "zero duration: '%s'", e.message);
}

int main(void)
{
    check_state st = {0, 0};
    free_oscillation(&st, KEVLAR);
    free_oscillation(&st, BASKET);
    omega_bounds_frequency(&st, KEVLAR);
    omega_bounds_frequency(&st, BASKET);
    shear_flow(&st);
    record(&st, KEVLAR);
    record(&st, BASKET);
    record(&st, LINEAR);
    errors(&st);
    return check_summary(&st, "test_point_path");
}

/* The backing's pointwise laws (plugin/solids/solid_laws.h) against their own
 * closed-form states: the clay's uniaxial compression (E ε and the lateral
 * −ν ε up to yield, the plateau at the yield), the rate scaling of its yield
 * (σ_0 (1 + (ε̇/C)^(1/p)) at four decades), the radial return's consistency
 * (on the yield surface, flow along the deviator, volume kept, the stress the
 * state's), its dissipation >= 0; its default σ_0 against the NIJ drop-test
 * calibration it states; the gelatin's relaxation and constant-rate shear
 * against the standard linear solid's closed forms, its bulk response, its
 * dissipation >= 0 and each step's energy balance (work = stored + dissipated);
 * both laws' stress against their stored energy by finite differences. */
#include "check.h"
#include "rng.h"
#include "solids/solid_laws.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* ---- clay -------------------------------------------------------------------- */

/* One uniaxial-stress step of the clay: ε11 given, ε22 = ε33 = x with σ22 = 0
 * (secant on x), from `s` (updated); returns σ11 and the lateral strain. */
static double clay_uniaxial(const wff_clay_params *p, double e11, double dt, double *lateral,
                            wff_clay_state *s)
{
    double x0 = *lateral, x1 = *lateral - 1e-3 * fabs(e11) - 1e-9, f0, f1, sig[6];
    wff_clay_state t;
    double e[6] = {e11, x0, x0, 0, 0, 0};
    wff_clay_update(p, e, dt, s, &t, sig);
    f0 = sig[1];
    for (int k = 0; k < 100; k++) {
        e[1] = e[2] = x1;
        wff_clay_update(p, e, dt, s, &t, sig);
        f1 = sig[1];
        if (fabs(f1) <= 1e-12 * p->yield_static || f1 == f0)
            break;
        const double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
        x0 = x1, f0 = f1, x1 = x2;
    }
    *lateral = x1;
    *s = t;
    return sig[0];
}

static void check_clay_uniaxial(check_state *st)
{
    wff_clay_params p = wff_clay_roma_plastilina;
    const double rate = 1e-3, de = 2e-4; /* 1/s (compression), strain per step */
    wff_clay_state s;
    memset(&s, 0, sizeof s);
    double lateral = 0, e11 = 0, onset = NAN, plateau = 0, worst_elastic = 0;
    for (int n = 1; n <= 1000; n++) {
        e11 = -n * de;
        const double was = s.eq_plastic;
        const double sig = clay_uniaxial(&p, e11, de / rate, &lateral, &s);
        if (s.eq_plastic == was) { /* elastic: E ε, −ν ε */
            worst_elastic = fmax(worst_elastic, fabs(sig - p.youngs * e11) / p.yield_static);
            worst_elastic = fmax(worst_elastic, fabs(lateral + p.poisson * e11) / fabs(e11));
        } else if (isnan(onset)) {
            onset = e11;
        }
        plateau = sig;
    }
    const double want = wff_clay_yield(&p, 0, rate); /* H = 0: the plateau at the strain rate */
    printf("  clay, uniaxial compression at %g /s: elastic to %.4g (sigma_0/E %.4g), plateau %.6g "
           "Pa (closed form %.6g), elastic part off by %.2e\n", rate, onset,
           -p.yield_static / p.youngs, plateau, -want, worst_elastic);
    CHECK(st, worst_elastic < 1e-9, "clay elastic: sigma = E eps, lateral = -nu eps (off %g)",
          worst_elastic);
    CHECK(st, onset <= -p.yield_static / p.youngs && onset > -p.yield_static / p.youngs - de,
          "clay: yields in the step where E|eps| passes sigma_0 (%g)", onset);
    CHECK_CLOSE(st, plateau, -want, 1e-9, 0, "clay: the plateau stress at the yield");
    CHECK_CLOSE(st, -lateral / e11, 0.5, 0.02, 0, "clay: nearly incompressible flow, lateral "
                "strain -> -eps/2 at large strain");
}

/* The plateau (H = 0, steady: ε̇^p = ε̇) at four decades of rate against
 * σ_0 (1 + (ε̇/C)^(1/p)). */
static void check_clay_rates(check_state *st)
{
    wff_clay_params p = wff_clay_roma_plastilina;
    const double rates[] = {1e-3, 1, 1e2, 1e4};
    for (int r = 0; r < 4; r++) {
        wff_clay_state s;
        memset(&s, 0, sizeof s);
        double lateral = 0, sig = 0;
        for (int n = 1; n <= 1000; n++) /* (to 50 %: the transient to the plateau is gone) */
            sig = clay_uniaxial(&p, -n * 5e-4, 5e-4 / rates[r], &lateral, &s);
        const double want = p.yield_static * (1 + pow(rates[r] / p.rate_c, 1 / p.rate_p));
        printf("  clay at %8.0e /s: flow stress %.6g Pa, closed form %.6g Pa (%.3fx sigma_0)\n",
               rates[r], -sig, want, want / p.yield_static);
        CHECK_CLOSE(st, -sig, want, 1e-8, 0, "clay rate scaling");
    }
}

/* Random states and strain increments: an elastic step stays inside the
 * surface and leaves the state; a plastic one ends on it (at its own rate),
 * flows along the deviator without volume, writes the stress of the state it
 * leaves, and dissipates >= 0. */
static void check_clay_return(check_state *st)
{
    wff_clay_params p = wff_clay_roma_plastilina;
    p.hardening = 0.3e6;
    wff_rng g = {2024};
    const double c = sqrt(2.0 / 3.0);
    int plastic = 0, elastic = 0;
    double worst_surface = 0, worst_axis = 0, worst_stress = 0, least_d = INFINITY;
    for (int k = 0; k < 4000; k++) {
        wff_clay_state s;
        memset(&s, 0, sizeof s);
        double tr = 0;
        for (int i = 0; i < 6; i++)
            s.plastic_strain[i] = wff_rng_uniform(&g, -0.05, 0.05), tr += i < 3 ? s.plastic_strain[i] : 0;
        for (int i = 0; i < 3; i++)
            s.plastic_strain[i] -= tr / 3;
        s.eq_plastic = wff_rng_uniform(&g, 0, 0.3);
        double e[6], sig[6], sig2[6];
        const double size = wff_rng_uniform(&g, 0, 3) * p.yield_static / p.youngs;
        for (int i = 0; i < 6; i++)
            e[i] = s.plastic_strain[i] + wff_rng_uniform(&g, -size, size);
        const double dt = pow(10, wff_rng_uniform(&g, -7, -1));
        wff_clay_state t;
        const int yielded = wff_clay_update(&p, e, dt, &s, &t, sig);
        double dev[6];
        wff_sym_dev(sig, dev);
        const double q = sqrt(wff_sym_dot(dev, dev));
        wff_clay_stress(&p, e, &t, sig2);
        for (int i = 0; i < 6; i++)
            worst_stress = fmax(worst_stress, fabs(sig2[i] - sig[i]) / p.yield_static);
        least_d = fmin(least_d, t.dissipated - s.dissipated);
        if (!yielded) {
            elastic++;
            CHECK(st, q <= c * wff_clay_yield(&p, s.eq_plastic, 0) * (1 + 1e-12) &&
                  memcmp(&s, &t, sizeof s) == 0, "an elastic step stays inside, state kept");
            continue;
        }
        plastic++;
        double dp[6], dtr = 0;
        for (int i = 0; i < 6; i++)
            dp[i] = t.plastic_strain[i] - s.plastic_strain[i], dtr += i < 3 ? dp[i] : 0;
        const double dgamma = sqrt(wff_sym_dot(dp, dp));
        const double yield = wff_clay_yield(&p, t.eq_plastic, t.plastic_rate);
        /* (the differences of stored values carry their round-off: 1e-14 of the state's size) */
        const double scale = 0.1 + s.eq_plastic + dgamma;
        worst_surface = fmax(worst_surface, fabs(q - c * yield) / yield);
        for (int i = 0; i < 6; i++)
            worst_axis = fmax(worst_axis, fabs(dp[i] - dgamma * dev[i] / q) / scale);
        CHECK(st, fabs(dtr) <= 1e-14 * scale && fabs(t.eq_plastic - s.eq_plastic - c * dgamma) <=
              1e-14 * scale && fabs(t.plastic_rate * dt - c * dgamma) <= 1e-14 * scale,
              "plastic flow without volume (tr %g of %g), alpha and the rate's strain += sqrt(2/3) "
              "dgamma (%.17g, %.17g, %.17g)", dtr, dgamma, t.eq_plastic - s.eq_plastic,
              t.plastic_rate * dt, c * dgamma);
    }
    printf("  clay radial return, %d plastic and %d elastic steps: off the surface %.2e, off the "
           "deviator's axis %.2e, stress vs state %.2e, least dissipation %.3g J/m3\n", plastic,
           elastic, worst_surface, worst_axis, worst_stress, least_d);
    CHECK(st, plastic > 1000 && elastic > 100, "both kinds of step tried (%d, %d)", plastic, elastic);
    CHECK(st, worst_surface < 1e-10, "plastic steps end on the yield surface (off %g)", worst_surface);
    CHECK(st, worst_axis < 1e-14, "flow along the deviator (off %g of the state's size)", worst_axis);
    CHECK(st, worst_stress < 1e-10, "the stress is the state's (off %g)", worst_stress);
    CHECK(st, least_d >= 0, "dissipation >= 0 (least %g J/m3)", least_d);
}

/* The drop-test calibration the default σ_0 states (clay.c). */
static void check_clay_calibration(check_state *st)
{
    const wff_clay_params *p = &wff_clay_roma_plastilina;
    const double m = 1.043, g = 9.80665, h = 2.0, d = 0.019, R = 0.0635 / 2; /* NIJ 0101.06 */
    const double tabor = m * g * (h + d) / (3 * M_PI * (R * d * d - d * d * d / 3));
    const double rate = sqrt(2 * g * h) / (2 * sqrt(2 * R * d - d * d));
    printf("  clay calibration: NIJ drop (1.043 kg, 2.0 m, 19 mm): Tabor sigma_y %.5g Pa at %.4g /s;"
           " the law there %.5g Pa\n", tabor, rate, wff_clay_yield(p, 0, rate));
    CHECK_CLOSE(st, wff_clay_yield(p, 0, rate), tabor, 1e-4, 0, "clay default: the drop test's yield");
    wff_error err;
    CHECK(st, wff_clay_check(p, &err) == 0, "the default clay passes its checks");
    wff_clay_params bad = *p;
    bad.poisson = 0.5;
    CHECK(st, wff_clay_check(&bad, &err) != 0 && strstr(err.message, "Poisson"), "nu = 0.5 refused: %s",
          err.message);
    bad = *p;
    bad.rate_p = 0;
    CHECK(st, wff_clay_check(&bad, &err) != 0 && strstr(err.message, "Cowper"), "p = 0 refused: %s",
          err.message);
    wff_clay_state s, t;
    memset(&s, 0, sizeof s);
    double e[6] = {-0.1, 0, 0, 0, 0, 0}, sig[6];
    t = s;
    CHECK(st, wff_clay_update(p, e, 0, &s, &t, sig) == -1 && memcmp(&s, &t, sizeof s) == 0,
          "dt = 0 refused, the state untouched");
}

/* ---- gelatin ------------------------------------------------------------------- */

/* Shear: ε_xy = γ/2 ramped at rate r over t0, then held; s_xy at t against
 * the standard linear solid's closed form, the steps of random sizes. */
static void check_gelatin_shear(check_state *st)
{
    const wff_gelatin_params *p = &wff_gelatin_ordnance10;
    const double tau = p->relaxation_time, G0 = p->shear_long, G1 = p->shear_branch;
    wff_rng g = {7};
    /* constant rate: s_xy = 2 G_∞ ε + 2 G_1 τ r (1 − e^{−t/τ}) at rates a decade apart */
    const double rates[] = {1e-2 / tau, 1e-1 / tau, 1 / tau, 10 / tau, 100 / tau};
    for (int k = 0; k < 5; k++) {
        const double r = 1e-3 * rates[k]; /* the ε_xy rate, 1/s */
        wff_gelatin_state s;
        memset(&s, 0, sizeof s);
        double t = 0, worst = 0, sig[6] = {0, 0, 0, 0, 0, 0};
        const double t_end = 0.2 / (1e-3 * rates[2]) * rates[2] / rates[k]; /* to ε_xy = 0.2 */
        while (t < t_end) {
            const double dt = fmin(wff_rng_uniform(&g, 0.01, 0.5) * tau, t_end - t);
            t += dt;
            double e[6] = {0, 0, 0, 0, 0, r * t};
            wff_gelatin_update(p, e, dt, &s, &s, sig);
            const double want = 2 * G0 * r * t + 2 * G1 * tau * r * -expm1(-t / tau);
            worst = fmax(worst, fabs(sig[5] - want) / want);
        }
        const double apparent = sig[5] / (2 * r * t);
        printf("  gelatin shear at %.0e /s over %.3g s: apparent modulus %.5g Pa (G_inf %.3g, "
               "G_inf + G_1 %.3g), off the closed form %.2e\n", 2 * r, t, apparent, G0, G0 + G1,
               worst);
        CHECK(st, worst < 1e-11, "gelatin constant-rate shear against the closed form (off %g)", worst);
        CHECK(st, apparent > G0 && apparent < G0 + G1, "apparent modulus between G_inf and G_inf + G_1");
    }
    /* relaxation: a ramp over t0 = τ/100, then held for 5 τ */
    wff_gelatin_state s;
    memset(&s, 0, sizeof s);
    const double t0 = tau / 100, eps = 1e-3, r = eps / t0;
    double sig[6], e[6] = {0, 0, 0, 0, 0, eps}, worst = 0, t = t0;
    wff_gelatin_update(p, e, t0, &s, &s, sig);
    const double q0 = tau * r * -expm1(-t0 / tau);
    while (t < 5 * tau) {
        const double dt = wff_rng_uniform(&g, 0.01, 0.7) * tau;
        t += dt;
        wff_gelatin_update(p, e, dt, &s, &s, sig);
        const double want = 2 * G0 * eps + 2 * G1 * q0 * exp(-(t - t0) / tau);
        worst = fmax(worst, fabs(sig[5] - want) / want);
    }
    printf("  gelatin relaxation over 5 tau: s_xy %.5g Pa -> %.5g Pa (2 G_inf eps %.5g), off the "
           "closed form %.2e\n", 2 * G0 * eps + 2 * G1 * q0, sig[5], 2 * G0 * eps, worst);
    CHECK(st, worst < 1e-11, "gelatin relaxation against the closed form (off %g)", worst);
    /* hydrostatic: p = K tr ε, at any rate */
    memset(&s, 0, sizeof s);
    double v[6] = {-1e-4, -1e-4, -1e-4, 0, 0, 0};
    wff_gelatin_update(p, v, 1e-9, &s, &s, sig);
    CHECK_CLOSE(st, sig[0], p->bulk * -3e-4, 1e-13, 0, "gelatin: hydrostatic stress K tr eps");
    CHECK(st, s.dissipated == 0, "gelatin: no dissipation in pure volume change");
}

/* Random strain paths: each step's work ∫σ:dε (Simpson on the exact branch
 * strain, the strain linear over the step) = ΔW + ΔD; ΔD >= 0. */
static void check_gelatin_energy(check_state *st)
{
    const wff_gelatin_params *p = &wff_gelatin_ordnance10;
    const double tau = p->relaxation_time;
    wff_rng g = {99};
    wff_gelatin_state s;
    memset(&s, 0, sizeof s);
    double e0[6] = {0, 0, 0, 0, 0, 0}, worst = 0, least = INFINITY, scale = 0;
    for (int n = 0; n < 300; n++) {
        double e1[6], sig[6];
        for (int i = 0; i < 6; i++)
            e1[i] = e0[i] + wff_rng_uniform(&g, -1e-4, 1e-4);
        const double dt = pow(10, wff_rng_uniform(&g, -2, 1)) * tau;
        /* the work along the step: σ(t) = K tr ε I + 2 G_∞ dev ε + 2 G_1 q(t) */
        double d0[6], d1[6], q0[6], rr[6], de[6], work = 0;
        const double tr0 = wff_sym_dev(e0, d0), tr1 = wff_sym_dev(e1, d1);
        for (int i = 0; i < 6; i++) {
            q0[i] = s.last_dev[i] - s.viscous_strain[i];
            rr[i] = (d1[i] - d0[i]) / dt;
            de[i] = e1[i] - e0[i];
        }
        const int M = 400;
        for (int k = 0; k <= M; k++) {
            const double t = dt * k / M, w = (k == 0 || k == M) ? 1 : (k % 2 ? 4 : 2);
            double sigma[6];
            for (int i = 0; i < 6; i++) {
                const double b = tau * rr[i], q = (q0[i] - b) * exp(-t / tau) + b;
                const double dev = d0[i] + rr[i] * t, tr = tr0 + (tr1 - tr0) * t / dt;
                sigma[i] = p->bulk * (i < 3 ? tr : 0) + 2 * p->shear_long * dev + 2 * p->shear_branch * q;
            }
            work += w * wff_sym_dot(sigma, de) / dt * dt / (3 * M);
        }
        const double W0 = wff_gelatin_energy(p, e0, &s), D0 = s.dissipated;
        wff_gelatin_update(p, e1, dt, &s, &s, sig);
        const double dW = wff_gelatin_energy(p, e1, &s) - W0, dD = s.dissipated - D0;
        scale = fmax(scale, fabs(work) + fabs(dW) + dD);
        worst = fmax(worst, fabs(work - dW - dD));
        least = fmin(least, dD);
        memcpy(e0, e1, sizeof e0);
    }
    printf("  gelatin energy, 300 random steps: |work - stored - dissipated| <= %.2e J/m3 (steps "
           "up to %.3g J/m3), least dissipation %.3g J/m3\n", worst, scale, least);
    CHECK(st, worst <= 1e-9 * scale, "gelatin: work = stored + dissipated each step (off %g of %g)",
          worst, scale);
    CHECK(st, least >= 0, "gelatin: dissipation >= 0 (least %g)", least);
    wff_error err;
    CHECK(st, wff_gelatin_check(p, &err) == 0, "the default gelatin passes its checks");
    wff_gelatin_params bad = *p;
    bad.relaxation_time = 0;
    CHECK(st, wff_gelatin_check(&bad, &err) != 0 && strstr(err.message, "relaxation"),
          "tau = 0 refused: %s", err.message);
}

/* ---- both: the stress is the stored energy's derivative -------------------------- */
static void check_fd(check_state *st)
{
    wff_rng g = {5};
    double worst_clay = 0, worst_gel = 0;
    wff_clay_params cp = wff_clay_roma_plastilina;
    for (int k = 0; k < 200; k++) {
        wff_clay_state cs;
        wff_gelatin_state gs;
        memset(&cs, 0, sizeof cs);
        memset(&gs, 0, sizeof gs);
        double e[6], sc[6], sg[6];
        for (int i = 0; i < 6; i++) {
            e[i] = wff_rng_uniform(&g, -0.01, 0.01);
            cs.plastic_strain[i] = wff_rng_uniform(&g, -0.01, 0.01);
            gs.viscous_strain[i] = wff_rng_uniform(&g, -0.01, 0.01);
        }
        double vt = gs.viscous_strain[0] + gs.viscous_strain[1] + gs.viscous_strain[2];
        for (int i = 0; i < 3; i++) /* (the dashpot's strain is deviatoric) */
            gs.viscous_strain[i] -= vt / 3;
        wff_clay_stress(&cp, e, &cs, sc);
        wff_gelatin_stress(&wff_gelatin_ordnance10, e, &gs, sg);
        const double h = 1e-7;
        for (int i = 0; i < 6; i++) {
            double ep[6], em[6];
            memcpy(ep, e, sizeof ep), memcpy(em, e, sizeof em);
            ep[i] += h, em[i] -= h;
            const double w = i < 3 ? 1 : 2; /* a shear entry is ε_ij and ε_ji */
            const double fc = (wff_clay_energy(&cp, ep, &cs) - wff_clay_energy(&cp, em, &cs)) / (2 * h);
            const double fg = (wff_gelatin_energy(&wff_gelatin_ordnance10, ep, &gs) -
                               wff_gelatin_energy(&wff_gelatin_ordnance10, em, &gs)) / (2 * h);
            worst_clay = fmax(worst_clay, fabs(fc - w * sc[i]) / (cp.youngs * 0.01));
            worst_gel = fmax(worst_gel, fabs(fg - w * sg[i]) / (wff_gelatin_ordnance10.bulk * 0.01));
        }
    }
    printf("  stress vs stored energy by central differences: clay %.2e, gelatin %.2e (of the "
           "stiffness x strain)\n", worst_clay, worst_gel);
    CHECK(st, worst_clay < 1e-7 && worst_gel < 1e-7, "stress = dW/d(strain): clay %g, gelatin %g",
          worst_clay, worst_gel);
}

int main(void)
{
    check_state st = {0, 0};
    check_clay_uniaxial(&st);
    check_clay_rates(&st);
    check_clay_return(&st);
    check_clay_calibration(&st);
    check_gelatin_shear(&st);
    check_gelatin_energy(&st);
    check_fd(&st);
    return check_summary(&st, "test_solid_laws");
}

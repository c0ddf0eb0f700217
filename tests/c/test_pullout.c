/* Yarn pull-out (issue 29, item 6): one warp pulled through the crossovers of a
 * fabric strip whose weft is held at a yarn tension (the pull-out fixture's
 * pretension), against the closed form of a yarn sliding through N crossovers.
 *
 * The reference (shear lag with Coulomb crossovers; docs/model.md §24, "Pull-out"):
 * a yarn of axial stiffness EA through N crossovers 2p⁰ apart, each able to hold a
 * tension difference f = μ_yy F_I, pulled at one end. The slip spreads from the
 * pulled end: with n crossovers sliding the pull is n f, the yarn's tension falling
 * by f at each, and the end has moved u_n = (2p⁰ f/EA) n(n+1)/2; the peak is
 *   F_peak = N μ_yy F_I     (linear in the embedded length 2p⁰N: Kirkwood et al.
 *                            2004, Textile Res. J. 74(10), Part I, the peak force of a
 *                            yarn pulled from Kevlar KM2 fabric linear in fabric length)
 * reached when the slip reaches the far end; then the whole yarn slides and the
 * pull drops by f each time its tail leaves a crossover, F = (N − m) f after m
 * crossovers' length pulled through (the drop). The friction's work up to the peak
 * is Σ_n (n f)(u_n − u_{n−1})-weighted: W_friction = f Σ_i |slid_i|.
 *
 * The pointwise cell (king_plain with yarn_friction = 0.2 and slip_crossovers =
 * n_c) is the same yarn with its whole anchorage at one point: it slides when
 * T_1 = n_c μ_yy F_I, the chain's peak with N = n_c, and then holds that tension:
 * no load spreading (its tension is uniform) and no drop (its crossovers are never
 * left). What is asserted, on the explorer's pull-out path
 * (wff_point_path_pull_level, the weft at 1 N per yarn, the warp pulled 3 % past
 * its preload stretch in 60 levels), for n_c = 170 (the material's), 85 and 340:
 *   1. it sticks (no slip, T_1 below n_c μ F_I) and then slides: every sliding
 *      level's T_1 is the chain's peak N μ F_I at that level's F_I, to 1e-12;
 *   2. the weft carries its 1 N to 1e-9 N at every level;
 *   3. the dissipation: each level's is the friction's work 2 T_1 L_1⁰ Δs_1 over
 *      the cell's area 4p1⁰p2⁰ (J/m², to 1e-9 of it), never negative;
 *   4. the work balance: the work put in, ∫ P_11 dλ_1 + ∫ P_22 dλ_2 (trapezoids
 *      over the levels), equals the stored energy's change plus the dissipation
 *      within 1e-3 of the work (measured: 1e-5 to 9e-5, the trapezoids' error);
 *   5. length: with f fixed at the crossover force where the n_c = 170 cell slides,
 *      the closed form's peak is linear in N; the cell's slide tension is within
 *      15 % of it for N = 85, 170, 340 (measured 0.874, 1.000, 1.065: F_I grows with
 *      T_1 by crimp interchange, so the cell's slide tension grows faster than N),
 *      and increases with N; the cell's tension after the slide stays within 1 % of
 *      its slide tension where the chain would have dropped (the limit, printed).
 * A path of 60 static levels per n_c: well under a second. */
#include "check.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/point_path.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define LEVELS 60
#define PULL 0.03     /* the warp's strain beyond its preload stretch, - */
#define HOLD 1.0      /* the weft's yarn tension, N */
#define FRICTION 0.2  /* μ_yy, - */

static int diag_index(const wff_material *m, const char *name)
{
    for (int i = 0; i < wff_cell_n_diag(m->cell); i++)
        if (strcmp(wff_cell_diag_name(m->cell, i), name) == 0)
            return i;
    return -1;
}

/* The closed form's peak pull (N) of a yarn through `crossovers` crossovers, each
 * holding f (N), and its pull once `left` crossovers' length has been pulled through. */
static double chain_peak(int crossovers, double f) { return crossovers * f; }
static double chain_after(int crossovers, double f, int left)
{
    return left >= crossovers ? 0 : (crossovers - left) * f;
}

/* One pull-out path with slip_crossovers = n_c; its slide tension into *slide (N),
 * its crossover force there into *crossover (N), the tension at its end into *end. */
static void pull_path(check_state *st, double n_c, double *slide, double *crossover, double *end)
{
    char *text = NULL, *edited = NULL, set[160];
    wff_error err;
    wff_material m;
    *slide = *crossover = *end = NAN;
    snprintf(set, sizeof set, "yarn_friction=%g,slip_crossovers=%g", FRICTION, n_c);
    if (wff_read_text_file(KEVLAR, "material", 1 << 20, &text, &err) ||
        wff_material_text_set(text, KEVLAR, set, "test_pullout", &edited, &err) ||
        wff_material_parse_text(edited, "test_pullout", &m, &err)) {
        CHECK(st, 0, "material %s with %s: %s", KEVLAR, set, err.message);
        free(text);
        free(edited);
        return;
    }
    free(text);
    free(edited);
    const int iT1 = wff_cell_yarn_tension_diag(m.cell, 0), iT2 = wff_cell_yarn_tension_diag(m.cell, 1);
    const int iFI = diag_index(&m, "F_I"), is1 = wff_material_state_index(&m, "slip_1");
    double p0[2], A0[2];
    if (iT1 < 0 || iT2 < 0 || iFI < 0 || is1 < 0 || wff_cell_reference_geometry(&m, p0, A0)) {
        CHECK(st, 0, "the cell lacks T1, T2, F_I, slip_1 or its geometry");
        return;
    }
    const double area = 4 * p0[0] * p0[1], rest1 = sqrt(p0[0] * p0[0] + A0[0] * A0[0]);
    wff_biaxial_state pre = {{1, 1}, {0, 0}, {0, 0}, {{0}, {0}, {0}, 0, 0, 0, 0, {0}}};
    if (wff_preload_equal_force(&m, HOLD, &pre, &err)) {
        CHECK(st, 0, "preload: %s", err.message);
        return;
    }
    wff_point_state s;
    memset(&s, 0, sizeof s);
    s.dA[0] = pre.dA[0];
    s.dA[1] = pre.dA[1];
    double F[6] = {pre.stretch[0], 0, 0, pre.stretch[1], 0, 0};
    double work = 0, W0 = NAN, P_prev[2] = {0, 0}, F_prev[2] = {0, 0}, D_prev = 0, T_prev = 0;
    int stuck = 1, bad_stick = 0, bad_slide = 0, bad_hold = 0, bad_work_step = 0;
    double worst_slide = 0, worst_step = 0, worst_hold = 0;
    for (int j = 0; j <= LEVELS; j++) {
        const double lam1 = pre.stretch[0] * (1 + PULL * j / LEVELS);
        const double slip_before = s.state[is1];
        if (wff_point_path_pull_level(&m, lam1, HOLD, PULL * 1e-3 / LEVELS, &s, F, &err)) {
            CHECK(st, 0, "n_c %g, level %d: %s", n_c, j, err.message);
            return;
        }
        wff_point_result r;
        wff_material_evaluate(&m, F, s.dA, s.state, 0, &r);
        const double T1 = r.diag[iT1], FI = r.diag[iFI], peak = chain_peak((int)n_c, FRICTION * FI);
        const double slid = s.state[is1] - slip_before;
        worst_hold = fmax(worst_hold, fabs(r.diag[iT2] - HOLD));
        bad_hold += fabs(r.diag[iT2] - HOLD) > 1e-9;
        if (s.state[is1] == 0) {
            bad_stick += !stuck || !(T1 < peak);   /* sticking, below the slide tension */
        } else {
            if (stuck) {
                *slide = T1;
                *crossover = FI;
            }
            stuck = 0;
            worst_slide = fmax(worst_slide, fabs(T1 - peak) / peak);
            bad_slide += fabs(T1 - peak) > 1e-12 * peak;
        }
        /* the level's dissipation: the friction's work at this level's tension */
        const double step = s.dissipated[2] - D_prev, want = 2 * T1 * rest1 * slid / area;
        worst_step = fmax(worst_step, fabs(step - want) / fmax(want, 1e-300));
        bad_work_step += step < 0 || fabs(step - want) > 1e-9 * fmax(want, 1e-12);
        D_prev = s.dissipated[2];
        if (j == 0)
            W0 = r.energy;
        else
            work += 0.5 * (r.stress[0] + P_prev[0]) * (F[0] - F_prev[0]) +
                    0.5 * (r.stress[3] + P_prev[1]) * (F[3] - F_prev[1]);
        P_prev[0] = r.stress[0];
        P_prev[1] = r.stress[3];
        F_prev[0] = F[0];
        F_prev[1] = F[3];
        T_prev = T1;
        if (j == LEVELS) {
            const double balance = r.energy - W0 + s.dissipated[2];
            printf("  n_c %3g: slides at T1 = %.4g N (F_I %.4g N), ends at %.4g N; slip %.4g, "
                   "dissipated %.4g J/m^2, work %.6g J/m^2 = stored %.6g + dissipated (off by "
                   "%.2g of the work)\n", n_c, *slide, *crossover, T1, s.state[is1],
                   s.dissipated[2], work, r.energy - W0, fabs(work - balance) / work);
            CHECK(st, fabs(work - balance) <= 1e-3 * work, "n_c %g: work %.6g J/m^2 against "
                  "stored + dissipated %.6g", n_c, work, balance);
        }
    }
    *end = T_prev;
    CHECK(st, !stuck && s.dissipated[2] > 0, "n_c %g: the warp never slid", n_c);
    CHECK(st, bad_stick == 0, "n_c %g: %d sticking levels at or above the slide tension, or "
          "after a slide", n_c, bad_stick);
    CHECK(st, bad_slide == 0, "n_c %g: sliding tension off the chain's peak by %.3g", n_c,
          worst_slide);
    CHECK(st, bad_hold == 0, "n_c %g: the weft off its %g N by %.3g N", n_c, HOLD, worst_hold);
    CHECK(st, bad_work_step == 0, "n_c %g: a level's dissipation off the friction's work by %.3g",
          n_c, worst_step);
}

int main(void)
{
    check_state st = {0, 0};
    const double n_c[3] = {85, 170, 340};
    double slide[3], crossover[3], end[3];
    for (int i = 0; i < 3; i++)
        pull_path(&st, n_c[i], &slide[i], &crossover[i], &end[i]);
    /* 5. the closed form's peak at the cell's crossover force of n_c = 170, for the
     * three lengths, against the cell's slide tensions */
    const double f = FRICTION * crossover[1];
    for (int i = 0; i < 3; i++) {
        const double peak = chain_peak((int)n_c[i], f);
        printf("  N = %3g crossovers (%.1f mm of yarn): chain peak %.4g N at f = %.4g N, "
               "dropping to %.4g N with 10 %% of the crossovers left behind; the cell slides "
               "at %.4g N (%.3f of the chain's) and ends the path at %.4g N\n", n_c[i],
               n_c[i] * 2 * 0.3735, peak, f, chain_after((int)n_c[i], f, (int)(n_c[i] / 10)),
               slide[i], slide[i] / peak, end[i]);
        CHECK(&st, fabs(slide[i] / peak - 1) <= 0.15, "N %g: the cell slides at %.4g N, the "
              "chain's peak is %.4g N", n_c[i], slide[i], peak);
        CHECK(&st, end[i] >= 0.99 * slide[i], "N %g: the cell's tension fell from %.4g to %.4g N "
              "(the pointwise model has no drop)", n_c[i], slide[i], end[i]);
    }
    CHECK(&st, slide[0] < slide[1] && slide[1] < slide[2], "slide tensions not increasing with "
          "n_c: %g %g %g N", slide[0], slide[1], slide[2]);
    return check_summary(&st, "test_pullout");
}

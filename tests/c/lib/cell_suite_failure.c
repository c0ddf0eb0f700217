/* The cell suite's yarn-failure path (docs/model.md §10, §20), run on every
 * cell whose type names damage states for both yarn families (damage_state[k]
 * >= 0), on the case's material with failure switched on and low failure
 * strains (damage from about 1 % to 3.5 % yarn strain, so that the suite's
 * states reach it), with and without the Cowper–Symonds rate law, and with
 * the crack band (failure_band_length; random element lengths 0.3–3 mm):
 *   - the state layout: the material with failure off carries no damage state;
 *   - at fixed damage (dt = 0, random damages in [0, 1]) stress = dW/dF and
 *     residual = −dW/dΔA by fourth-order central differences, the state held,
 *     nothing released;
 *   - damage acts on tension only: a compressed point is the same at any
 *     damage, a stretched one stores less;
 *   - a loading path through failure (load, unload, reload below the
 *     largest strain, load to rupture, unload): damage never decreases and
 *     is unchanged below the largest strain, each update releases
 *     W(d_old) − W(d_new) = Δd W⁺, and work − ΔW − dissipation closes;
 *   - the fast paths (evaluate_shared, the blocks unless they decline) equal
 *     evaluate() with damage present, state update included;
 *   - a point with dynamic amplitudes driven through rupture keeps its
 *     amplitudes bounded (wff_point_path_segment);
 *   - with the band: the element_length state is never changed (dt > 0 or
 *     not), and it reaches the law (another length, another damage). */
#include "cell_suite.h"
#include "cell_suite_failure.h"
#include "rng.h"
#include "wovenff/material.h"
#include "wovenff/point_path.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define FAILURE_STATES 200

/* The failing parameter sets: low strains, and the rate law strong enough to
 * matter on the path below (φ = 1 + (ε̇/C)^(1/p) ≈ 1.16 at 25 1/s). */
static const char *const kFailureKeys[] = {"failure", "fail_strain_1", "fail_strain_2",
                                           "rupture_strain_1", "rupture_strain_2",
                                           "failure_rate_C", "failure_rate_p",
                                           "failure_band_length"};
#define FAILURE_LINES "failure = 1\nfail_strain_1 = 0.01\nfail_strain_2 = 0.012\n" \
                      "rupture_strain_1 = 0.03\nrupture_strain_2 = 0.035\n"
#define RATE_LINES "failure_rate_C = 1e3\nfailure_rate_p = 2\n"
#define BAND_LINES "failure_band_length = 1e-3\n"

/* The text of `path` without its failure keys, plus `extra` lines. */
static int failing_material(const char *path, const char *extra, const char *label,
                            wff_material *mat, wff_error *err)
{
    char *text;
    if (wff_read_text_file(path, "material file", WFF_MATERIAL_FILE_MAX, &text, err))
        return -1;
    size_t cap = strlen(text) + strlen(extra) + 2;
    char *out = malloc(cap);
    if (!out) {
        free(text);
        return wff_fail(err, "out of memory");
    }
    out[0] = '\0';
    for (const char *p = text; *p;) {
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p + 1) : strlen(p);
        const char *k = p;
        while (k < p + len && (*k == ' ' || *k == '\t'))
            k++;
        int drop = 0;
        for (size_t i = 0; i < sizeof kFailureKeys / sizeof kFailureKeys[0]; i++) {
            size_t n = strlen(kFailureKeys[i]);
            if (strncmp(k, kFailureKeys[i], n) == 0 && (k[n] == ' ' || k[n] == '=' || k[n] == '\t'))
                drop = 1;
        }
        if (!drop)
            strncat(out, p, len);
        p += len;
    }
    if (out[0] && out[strlen(out) - 1] != '\n')
        strcat(out, "\n");
    strcat(out, extra);
    int rc = wff_material_parse_text(out, label, mat, err);
    free(text);
    free(out);
    return rc;
}

static double max_abs(const double *v, int n)
{
    double m = 0;
    for (int i = 0; i < n; i++)
        m = fmax(m, fabs(v[i]));
    return m;
}

/* F = Q [U; 0] as the suite's random states: stretches 0.985–1.04, shear up to
 * ±0.6 rad, a random rotation. */
static void random_F(rng *r, double F[6])
{
    double l1 = rng_uniform(r, 0.985, 1.04), l2 = rng_uniform(r, 0.985, 1.04);
    double shear = rng_uniform(r, -0.6, 0.6);
    double U[6] = {l1, l2 * sin(shear), 0, l2 * cos(shear), 0, 0};
    double q[4], n = 0;
    for (int i = 0; i < 4; i++) {
        q[i] = rng_uniform(r, -1, 1);
        n += q[i] * q[i];
    }
    n = sqrt(n);
    double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    double Q[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                      {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                      {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    for (int i = 0; i < 3; i++)
        for (int J = 0; J < 2; J++)
            F[2 * i + J] = Q[i][0] * U[J] + Q[i][1] * U[2 + J] + Q[i][2] * U[4 + J];
}

/* A random state by the states' names: damages in [0, 1], γᶠ ±0.05 rad, a
 * strain history in [0, 0.04], an element length in [0.3, 3] mm; anything
 * else 0. */
static void random_point_state(rng *r, const wff_material *mat, double *state)
{
    const wff_cell_type *cell = mat->cell;
    for (int i = 0; i < mat->n_state; i++) {
        const char *name = cell->state_names[i];
        state[i] = 0;
        if (i == cell->damage_state[0] || i == cell->damage_state[1])
            state[i] = rng_uniform(r, 0, 1);
        else if (strcmp(name, "gamma_f") == 0)
            state[i] = rng_uniform(r, -0.05, 0.05);
        else if (strncmp(name, "yarn_strain", 11) == 0)
            state[i] = rng_uniform(r, 0, 0.04);
        else if (strcmp(name, WFF_ELEMENT_LENGTH_STATE) == 0)
            state[i] = rng_uniform(r, 0.3e-3, 3e-3);
    }
}

static double energy_at(const wff_material *m, const double F[6], const double dA[2],
                        const double *state)
{
    wff_point_result out;
    wff_material_evaluate(m, F, dA, state, 0, &out);
    return out.energy;
}

static double fd(const wff_material *m, double F[6], double dA[2], const double *state,
                 double *x, double h)
{
    double x0 = *x, w[4];
    const double offs[4] = {-2, -1, 1, 2};
    for (int i = 0; i < 4; i++) {
        *x = x0 + offs[i] * h;
        w[i] = energy_at(m, F, dA, state);
    }
    *x = x0;
    return (w[0] - 8 * w[1] + 8 * w[2] - w[3]) / (12 * h);
}

/* 1 when a yarn's tension changes sign (−, 0, +) within the difference
 * stencil of any input: the damaged energy is C¹ only at zero yarn strain
 * (its curvature jumps by d_k times the yarn stiffness there, as a
 * tension-only yarn's does by all of it), where a difference is O(h) and says
 * nothing about the derivative's consistency. */
static int stencil_crosses_zero_strain(const wff_material *m, const double F0[6],
                                       const double dA0[2], const double *state, double h_F,
                                       double h_A)
{
    const wff_cell_type *cell = m->cell;
    const double offs[5] = {-2, -1, 0, 1, 2};
    for (int input = 0; input < 6 + cell->n_amplitudes; input++)
        for (int k = 0; k < 2; k++) {
            int seen[3] = {0, 0, 0};
            for (int o = 0; o < 5; o++) {
                double F[6], dA[2] = {dA0[0], dA0[1]};
                memcpy(F, F0, sizeof F);
                if (input < 6)
                    F[input] += offs[o] * h_F;
                else
                    dA[input - 6] += offs[o] * h_A;
                wff_point_result out;
                wff_material_evaluate(m, F, dA, state, 0, &out);
                double T = out.diag[cell->yarn_tension_diag[k]];
                seen[T > 0 ? 2 : T < 0 ? 0 : 1] = 1;
            }
            if (seen[0] + seen[1] + seen[2] > 1)
                return 1;
        }
    return 0;
}

/* Fixed damage: exact derivatives, held state; the state layout. */
static void check_fixed_damage(check_state *st, const cell_case *c, const wff_material *mat,
                               const char *label, rng *r)
{
    const wff_cell_type *cell = mat->cell;
    double worst_P = 0, worst_R = 0, worst_K = 0;
    int held = 1, at_kink = 0;
    for (int s = 0; s < FAILURE_STATES; s++) {
        double F[6], dA[2], state[WFF_STATE_MAX];
        random_F(r, F);
        dA[0] = rng_uniform(r, -c->amplitude_range, c->amplitude_range / 3);
        dA[1] = rng_uniform(r, -c->amplitude_range, c->amplitude_range / 3);
        random_point_state(r, mat, state);
        wff_point_result out;
        if (wff_material_evaluate(mat, F, dA, state, 0, &out) != WFF_POINT_OK) {
            CHECK(st, 0, "%s: state %d does not evaluate", label, s);
            continue;
        }
        for (int i = 0; i < mat->n_state; i++)
            held &= out.state[i] == state[i];
        held &= out.failure_dissipated == 0 && out.dissipated == 0;
        if (!c->energy_exact)
            continue;
        if (stencil_crosses_zero_strain(mat, F, dA, state, 1e-5, 1e-5 * c->amplitude_range)) {
            at_kink++;
            continue;
        }
        double err_P = 0, err_R = 0;
        for (int i = 0; i < 6; i++)
            err_P = fmax(err_P, fabs(fd(mat, F, dA, state, &F[i], 1e-5) - out.stress[i]));
        for (int k = 0; k < cell->n_amplitudes; k++)
            err_R = fmax(err_R, fabs(-fd(mat, F, dA, state, &dA[k], 1e-5 * c->amplitude_range) -
                                     out.residual[k]));
        worst_P = fmax(worst_P, err_P / fmax(max_abs(out.stress, 6), 1e-300));
        worst_R = fmax(worst_R, cell->n_amplitudes
                                    ? err_R / fmax(max_abs(out.residual, 2), 1e-300) : 0);
        /* the exact amplitude tangent with damage: ∂R_k/∂ΔA_m by central differences of R */
        if (cell->amplitude_tangent) {
            double R[2], K[4], K_fd[4], hA = 1e-5 * c->amplitude_range;
            cell->amplitude_tangent(mat->params, F, dA, state, R, K);
            for (int m = 0; m < 2; m++) {
                double Rp[2][2];
                for (int side = 0; side < 2; side++) {
                    double d2[2] = {dA[0], dA[1]};
                    d2[m] += side ? hA : -hA;
                    wff_point_result o;
                    wff_material_evaluate(mat, F, d2, state, 0, &o);
                    Rp[side][0] = o.residual[0];
                    Rp[side][1] = o.residual[1];
                }
                for (int k = 0; k < 2; k++)
                    K_fd[2 * k + m] = (Rp[1][k] - Rp[0][k]) / (2 * hA);
            }
            double e = fmax(fabs(R[0] - out.residual[0]), fabs(R[1] - out.residual[1])) /
                       fmax(max_abs(out.residual, 2), 1e-300);
            for (int i = 0; i < 4; i++)
                e = fmax(e, fabs(K[i] - K_fd[i]) / fmax(max_abs(K_fd, 4), 1e-300));
            worst_K = fmax(worst_K, e);
        }
    }
    printf("  %-48s failure, fixed damage: FD stress %.1e, FD residual %.1e, amplitude tangent "
           "%s%.1e (%d of %d states with a yarn at zero strain within the stencil left out)\n",
           label, worst_P, worst_R, cell->amplitude_tangent ? "" : "(none) ", worst_K, at_kink,
           FAILURE_STATES);
    /* second-order differences of R (h = 1e-5 of the range): ~1e-9 (the suite's own
     * tangent check uses fourth order for 1e-6; 1e-6 holds here too) */
    CHECK(st, worst_K <= 1e-6, "%s: damaged amplitude tangent vs central differences of R: "
          "%.3g", label, worst_K);
    CHECK(st, at_kink <= FAILURE_STATES / 20, "%s: %d states at zero yarn strain: the check "
          "says little", label, at_kink);
    CHECK(st, held, "%s: dt = 0 changed a state or released energy", label);
    if (c->energy_exact) {
        CHECK(st, worst_P <= 1e-6, "%s: damaged P vs dW/dF relative error %.3g", label, worst_P);
        CHECK(st, worst_R <= 1e-6, "%s: damaged R vs -dW/ddA relative error %.3g", label,
              worst_R);
    }
}

/* Damage on tension only: compressed yarns see none of it; stretched ones store less. */
static void check_tension_only(check_state *st, const wff_material *mat, const char *label)
{
    const wff_cell_type *cell = mat->cell;
    const double F_c[6] = {0.99, 0, 0, 0.985, 0, 0}, F_t[6] = {1.02, 0, 0, 1.02, 0, 0};
    const double dA[2] = {0, 0};
    double intact[WFF_STATE_MAX] = {0}, damaged[WFF_STATE_MAX] = {0};
    damaged[cell->damage_state[0]] = 0.8;
    damaged[cell->damage_state[1]] = 0.6;
    wff_point_result a, b;
    wff_material_evaluate(mat, F_c, dA, intact, 0, &a);
    wff_material_evaluate(mat, F_c, dA, damaged, 0, &b);
    int same = a.energy == b.energy;
    for (int i = 0; i < 6; i++)
        same &= a.stress[i] == b.stress[i];
    for (int k = 0; k < cell->n_amplitudes; k++)
        same &= a.residual[k] == b.residual[k];
    CHECK(st, same, "%s: damage changed a compressed point (W %.17g vs %.17g, P11 %.17g vs "
          "%.17g)", label, a.energy, b.energy, a.stress[0], b.stress[0]);
    wff_material_evaluate(mat, F_t, dA, intact, 0, &a);
    wff_material_evaluate(mat, F_t, dA, damaged, 0, &b);
    CHECK(st, b.energy < a.energy && b.stress[0] < a.stress[0] && b.stress[3] < a.stress[3],
          "%s: damage did not soften a stretched point (W %g vs %g)", label, b.energy,
          a.energy);
}

/* A loading path through failure, F = diag(1 + e, 1 + 0.9 e), dA held at 0
 * (so the only work is P : dF), steps of dt. Work by the trapezoidal rule at
 * the step's old damage (the damage a step's strain increment sees), which
 * makes work − ΔW − dissipation exact up to the rule's error. */
static void check_path(check_state *st, const wff_material *mat, const char *label)
{
    const wff_cell_type *cell = mat->cell;
    const int dk[2] = {cell->damage_state[0], cell->damage_state[1]};
    /* legs: to mid damage, unload, reload below the max, to rupture, unload */
    const double legs[] = {0, 0.02, 0.0, 0.015, 0.06, 0.03};
    const int n_legs = (int)(sizeof legs / sizeof legs[0]) - 1, steps = 2000;
    const double dt = 1e-6, dA[2] = {0, 0};
    double state[WFF_STATE_MAX] = {0}, F[6] = {1, 0, 0, 1, 0, 0};
    wff_point_result out;
    wff_material_evaluate(mat, F, dA, state, 0, &out);
    double W0 = out.energy, P[6], work = 0, dissipated = 0, released = 0, worst_release = 0;
    double d_after_leg[8][2], W_scale = 0;
    memcpy(P, out.stress, sizeof P);
    int monotone = 1, held_below_max = 1, ok = 1;
    for (int l = 0; l < n_legs; l++) {
        for (int s = 1; s <= steps; s++) {
            double e = legs[l] + (legs[l + 1] - legs[l]) * s / steps;
            double Fn[6] = {1 + e, 0, 0, 1 + 0.9 * e, 0, 0};
            wff_point_result held, next;
            ok &= wff_material_evaluate(mat, Fn, dA, state, 0, &held) == WFF_POINT_OK;
            ok &= wff_material_evaluate(mat, Fn, dA, state, dt, &next) == WFF_POINT_OK;
            for (int i = 0; i < 6; i++)
                work += 0.5 * (P[i] + held.stress[i]) * (Fn[i] - F[i]);
            double W_new = energy_at(mat, Fn, dA, next.state);
            /* released = W(d_old) − W(d_new) at the new strain (the shear flow of
             * this path is zero: no shear) */
            worst_release = fmax(worst_release, fabs(next.failure_dissipated -
                                                     (held.energy - W_new)));
            W_scale = fmax(W_scale, held.energy);
            for (int k = 0; k < 2; k++) {
                monotone &= next.state[dk[k]] >= state[dk[k]];
                if (l == 1 || l == 2)
                    held_below_max &= next.state[dk[k]] == state[dk[k]];
            }
            monotone &= next.failure_dissipated >= 0;
            dissipated += next.dissipated;
            released += next.failure_dissipated;
            memcpy(state, next.state, sizeof(double) * (size_t)mat->n_state);
            memcpy(P, next.stress, sizeof P);
            memcpy(F, Fn, sizeof F);
        }
        for (int k = 0; k < 2; k++)
            d_after_leg[l][k] = state[dk[k]];
    }
    double W1 = energy_at(mat, F, dA, state);
    double closure = fabs(work - (W1 - W0) - dissipated - released) / fabs(work);
    printf("  %-48s failure path: d after legs (%.3f %.3f) (%.3f %.3f) (%.3f %.3f) "
           "(%.3f %.3f); released %.4g of work %.4g J/m^2, closure %.1e, release vs "
           "W(d_old) - W(d_new) %.1e\n", label, d_after_leg[0][0], d_after_leg[0][1],
           d_after_leg[2][0], d_after_leg[2][1], d_after_leg[3][0], d_after_leg[3][1],
           d_after_leg[4][0], d_after_leg[4][1], released, work, closure,
           worst_release / W_scale);
    CHECK(st, ok, "%s: the failure path does not evaluate", label);
    CHECK(st, monotone, "%s: damage decreased or negative release on the path", label);
    CHECK(st, held_below_max, "%s: damage changed on unloading and reloading below the "
          "largest strain", label);
    CHECK(st, d_after_leg[0][0] > 0.05 && d_after_leg[0][0] < 0.95,
          "%s: the first leg does not reach mid damage (d1 = %g)", label, d_after_leg[0][0]);
    CHECK(st, d_after_leg[3][0] == 1 && d_after_leg[3][1] == 1,
          "%s: the path does not rupture both families (%g %g)", label, d_after_leg[3][0],
          d_after_leg[3][1]);
    CHECK(st, worst_release <= 1e-12 * W_scale, "%s: failure_dissipated differs from "
          "W(d_old) - W(d_new) by %.3g of the largest energy", label, worst_release / W_scale);
    /* the rule's error: O(h^2) over the path (exact for a quadratic W) */
    CHECK(st, closure <= 1e-6, "%s: work - dW - dissipation over the failure path: %.3g of "
          "the work", label, closure);
}

/* The fast paths with damage present, dt = 0 and dt > 0. */
static void check_fast_paths(check_state *st, const cell_case *c, const wff_material *mat,
                             const char *label, rng *r)
{
    const wff_cell_type *cell = mat->cell;
    const int ns = mat->n_state;
    double worst_shared = 0, worst_tri = 0, worst_points = 0;
    int tri_used = 0, points_used = 0;
    for (int s = 0; s < FAILURE_STATES / WFF_BLOCK; s++) {
        const double dt = s % 2 ? 2e-7 : 0;
        double F[WFF_BLOCK][6], dA[WFF_BLOCK][3][2], state0[WFF_BLOCK][3][WFF_STATE_MAX];
        for (int j = 0; j < WFF_BLOCK; j++) {
            random_F(r, F[j]);
            for (int q = 0; q < 3; q++) {
                for (int k = 0; k < 2; k++)
                    dA[j][q][k] = rng_uniform(r, -c->amplitude_range, c->amplitude_range / 3);
                random_point_state(r, mat, state0[j][q]);
            }
        }
        /* the reference: evaluate at each point */
        wff_point_result ref[WFF_BLOCK][3];
        for (int j = 0; j < WFF_BLOCK; j++)
            for (int q = 0; q < 3; q++)
                wff_material_evaluate(mat, F[j], dA[j][q], state0[j][q], dt, &ref[j][q]);
        if (cell->evaluate_shared) {
            for (int j = 0; j < WFF_BLOCK; j++) {
                double da[6], w[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3}, st3[3 * WFF_STATE_MAX];
                double P[6] = {0}, R[6], W = 0, Dis = 0, Fail = 0, Slip = 0, Pref[6] = {0};
                double Wref = 0;
                double Fref = 0;
                int bad;
                for (int q = 0; q < 3; q++) {
                    da[2 * q] = dA[j][q][0];
                    da[2 * q + 1] = dA[j][q][1];
                    memcpy(st3 + q * ns, state0[j][q], sizeof(double) * (size_t)ns);
                }
                cell->evaluate_shared(mat->params, F[j], 3, da, w, st3, dt, P, R, &W, &Dis,
                                      &Fail, &Slip, &bad);
                double e = 0;
                for (int q = 0; q < 3; q++) {
                    for (int i = 0; i < 6; i++)
                        Pref[i] += ref[j][q].stress[i] / 3;
                    Wref += ref[j][q].energy / 3;
                    Fref += ref[j][q].failure_dissipated / 3;
                    for (int i = 0; i < ns; i++)
                        e = fmax(e, fabs(st3[q * ns + i] - ref[j][q].state[i]));
                    for (int k = 0; k < cell->n_amplitudes; k++)
                        e = fmax(e, fabs(R[2 * q + k] - ref[j][q].residual[k]) /
                                        fmax(max_abs(ref[j][q].residual, 2), 1e-300));
                }
                double sP = fmax(max_abs(Pref, 6), 1e-300);
                for (int i = 0; i < 6; i++)
                    e = fmax(e, fabs(P[i] - Pref[i]) / sP);
                e = fmax(e, fabs(W - Wref) / fmax(fabs(Wref), 1e-300));
                e = fmax(e, fabs(Fail - Fref) / fmax(fabs(Wref), 1e-300));
                worst_shared = fmax(worst_shared, e);
            }
        }
        if (cell->evaluate_tri_block) {
            wff_tri_block blk;
            memset(&blk, 0, sizeof blk);
            blk.n = WFF_BLOCK;
            for (int j = 0; j < WFF_BLOCK; j++) {
                for (int i = 0; i < 6; i++)
                    blk.F[i][j] = F[j][i];
                for (int q = 0; q < 3; q++) {
                    blk.dA[q][0][j] = dA[j][q][0];
                    blk.dA[q][1][j] = dA[j][q][1];
                    for (int i = 0; i < ns; i++)
                        blk.state[q][i][j] = state0[j][q][i];
                }
            }
            int handled = cell->evaluate_tri_block(mat->params, dt, &blk) == 0;
            CHECK(st, s == 0 || handled == tri_used, "%s: the blocked path declines some "
                  "states and not others", label);
            tri_used = handled;
            for (int j = 0; j < WFF_BLOCK && handled; j++) {
                double Pref[6] = {0}, Wref = 0, Fref = 0, e = 0;
                for (int q = 0; q < 3; q++) {
                    for (int i = 0; i < 6; i++)
                        Pref[i] += ref[j][q].stress[i] / 3;
                    Wref += ref[j][q].energy / 3;
                    Fref += ref[j][q].failure_dissipated / 3;
                    for (int i = 0; i < ns; i++)
                        e = fmax(e, fabs(blk.state[q][i][j] - ref[j][q].state[i]));
                }
                for (int i = 0; i < 6; i++)
                    e = fmax(e, fabs(blk.stress[i][j] - Pref[i]) / fmax(max_abs(Pref, 6), 1e-300));
                e = fmax(e, fabs(blk.energy[j] - Wref) / fmax(fabs(Wref), 1e-300));
                e = fmax(e, fabs(blk.failure_dissipated[j] - Fref) / fmax(fabs(Wref), 1e-300));
                worst_tri = fmax(worst_tri, e);
            }
        }
        if (cell->evaluate_point_block) {
            wff_point_block blk;
            memset(&blk, 0, sizeof blk);
            blk.n = WFF_BLOCK;
            for (int j = 0; j < WFF_BLOCK; j++) {
                for (int i = 0; i < 6; i++)
                    blk.F[i][j] = F[j][i];
                blk.dA[0][j] = dA[j][0][0];
                blk.dA[1][j] = dA[j][0][1];
                for (int i = 0; i < ns; i++)
                    blk.state[i][j] = state0[j][0][i];
            }
            int handled = cell->evaluate_point_block(mat->params, dt, &blk) == 0;
            CHECK(st, s == 0 || handled == points_used, "%s: the point block declines some "
                  "states and not others", label);
            points_used = handled;
            for (int j = 0; j < WFF_BLOCK && handled; j++) {
                const wff_point_result *o = &ref[j][0];
                double e = 0;
                for (int i = 0; i < 6; i++)
                    e = fmax(e, fabs(blk.stress[i][j] - o->stress[i]) /
                                    fmax(max_abs(o->stress, 6), 1e-300));
                for (int i = 0; i < ns; i++)
                    e = fmax(e, fabs(blk.state[i][j] - o->state[i]));
                e = fmax(e, fabs(blk.energy[j] - o->energy) / fmax(fabs(o->energy), 1e-300));
                e = fmax(e, fabs(blk.failure_dissipated[j] - o->failure_dissipated) /
                                fmax(fabs(o->energy), 1e-300));
                worst_points = fmax(worst_points, e);
            }
        }
    }
    printf("  %-48s failure, fast paths: shared %s%.1e, blocked %s%.1e, point block %s%.1e\n",
           label, cell->evaluate_shared ? "" : "(none) ", worst_shared,
           !cell->evaluate_tri_block ? "(none) " : tri_used ? "" : "(declined) ", worst_tri,
           !cell->evaluate_point_block ? "(none) " : points_used ? "" : "(declined) ",
           worst_points);
    CHECK(st, worst_shared <= 1e-11, "%s: evaluate_shared with damage differs by %.3g", label,
          worst_shared);
    CHECK(st, worst_tri <= 1e-11, "%s: blocked path with damage differs by %.3g", label,
          worst_tri);
    CHECK(st, worst_points <= 1e-11, "%s: point block with damage differs by %.3g", label,
          worst_points);
}

/* A point with dynamic amplitudes (and its state advancing) pulled through
 * rupture at a ballistic rate (1000 1/s), held, then released: its amplitudes
 * stay finite and within the quarter wavelength, the crimp geometry's limit. */
/* The largest |ΔA_k|/p_k⁰ of a point with dynamic amplitudes driven along
 * identity → F_max → held → identity → held, and its final state into *s;
 * INFINITY if a segment fails or an amplitude is not finite. */
static double drive_point(const wff_material *mat, const double pitch0[2], wff_point_state *s,
                          wff_error *err)
{
    const wff_path_mode mode = {1, 1, WFF_PATH_STEP_SAFETY, WFF_PATH_FLOW_SUBSTEPS};
    memset(s, 0, sizeof *s);
    const double I[6] = {1, 0, 0, 1, 0, 0}, Fmax[6] = {1.08, 0, 0, 1.08, 0, 0};
    const double *path[] = {I, Fmax, Fmax, I, I};
    const double durations[] = {80e-6, 20e-6, 80e-6, 20e-6}; /* 1000 1/s, as in an impact */
    const int n_seg = 40;
    double worst = 0;
    for (int leg = 0; leg < 4; leg++)
        for (int i = 0; i < n_seg; i++) {
            double Fa[6], Fb[6];
            for (int j = 0; j < 6; j++) {
                Fa[j] = path[leg][j] + (path[leg + 1][j] - path[leg][j]) * i / n_seg;
                Fb[j] = path[leg][j] + (path[leg + 1][j] - path[leg][j]) * (i + 1) / n_seg;
            }
            if (wff_point_path_segment(mat, Fa, Fb, durations[leg] / n_seg, &mode, s, err))
                return INFINITY;
            for (int k = 0; k < 2; k++)
                worst = fmax(worst, isfinite(s->dA[k]) ? fabs(s->dA[k]) / pitch0[k] : INFINITY);
        }
    return worst;
}

static void check_amplitudes_bounded(check_state *st, const wff_material *mat,
                                     const wff_material *intact, const char *label)
{
    const wff_cell_type *cell = mat->cell;
    if (cell->n_amplitudes == 0 || !cell->reference_geometry)
        return;
    double pitch0[2], amplitude0[2];
    cell->reference_geometry(mat->params, pitch0, amplitude0);
    wff_point_state s, s_intact;
    wff_error err = {{0}};
    double worst = drive_point(mat, pitch0, &s, &err);
    CHECK(st, isfinite(worst), "%s: point through failure: %s", label, err.message);
    double worst_intact = drive_point(intact, pitch0, &s_intact, &err);
    const int *dk = cell->damage_state;
    printf("  %-48s failure, point driven through rupture (1000 1/s to 8 %%, back): damage "
           "%.3f %.3f, largest |dA|/p0 %.3g over %ld steps (without failure %.3g)\n", label,
           s.state[dk[0]], s.state[dk[1]], worst, s.substeps, worst_intact);
    CHECK(st, s.state[dk[0]] == 1 && s.state[dk[1]] == 1,
          "%s: the driven point did not rupture (%g %g)", label, s.state[dk[0]], s.state[dk[1]]);
    CHECK(st, worst < 1, "%s: amplitudes of a point driven through failure reach %.3g of the "
          "quarter wavelength", label, worst);
}

/* The band: element_length held by every evaluation, and read by the law
 * (the damages at one state differ between two lengths, at some state). */
static void check_band(check_state *st, const wff_material *mat, const char *label, rng *r)
{
    const int i = wff_material_state_index(mat, WFF_ELEMENT_LENGTH_STATE);
    CHECK(st, i >= 0, "%s: no %s state", label, WFF_ELEMENT_LENGTH_STATE);
    if (i < 0)
        return;
    const int *dk = mat->cell->damage_state;
    int held = 1, differs = 0;
    for (int s = 0; s < FAILURE_STATES; s++) {
        double F[6], dA[2] = {0, 0}, state[WFF_STATE_MAX], other[WFF_STATE_MAX];
        random_F(r, F);
        random_point_state(r, mat, state);
        state[dk[0]] = state[dk[1]] = 0;
        memcpy(other, state, sizeof state);
        other[i] = 2 * state[i];
        wff_point_result a, b;
        const double dt = s % 3 ? 1e-7 : 0;
        if (wff_material_evaluate(mat, F, dA, state, dt, &a) != WFF_POINT_OK ||
            wff_material_evaluate(mat, F, dA, other, dt, &b) != WFF_POINT_OK)
            continue;
        held &= a.state[i] == state[i] && b.state[i] == other[i];
        differs |= dt > 0 && (a.state[dk[0]] != b.state[dk[0]] ||
                              a.state[dk[1]] != b.state[dk[1]]);
    }
    printf("  %-48s failure, band: element_length held over %d states (dt 0 and > 0), read by "
           "the law: %s\n", label, FAILURE_STATES, differs ? "yes" : "no");
    CHECK(st, held, "%s: an evaluation changed the element_length state", label);
    CHECK(st, differs, "%s: the element length does not reach the damage", label);
}

void cell_suite_failure(check_state *st, const cell_case *c)
{
    wff_material off;
    wff_error err;
    if (wff_material_load(c->material, &off, &err))
        return; /* cell_suite_run reports it */
    const wff_cell_type *cell = off.cell;
    /* the shared law damages both families; a cell naming one damage state only
     * (a test cell) has a failure of its own, not this one's keys */
    if (cell->damage_state[0] < 0 || cell->damage_state[1] < 0) {
        if (cell->damage_state[0] >= 0 || cell->damage_state[1] >= 0)
            printf("  %-48s failure path: not run (damage for one yarn family only: not the "
                   "shared yarn failure law)\n", c->material);
        return;
    }
    for (int k = 0; k < 2; k++)
        CHECK(st, cell->damage_state[k] >= off.n_state,
              "%s: failure off, yet the points carry damage state %d (n_state %d)", c->material,
              cell->damage_state[k], off.n_state);
    static const char *const extra[3] = {FAILURE_LINES, FAILURE_LINES RATE_LINES,
                                         FAILURE_LINES BAND_LINES};
    for (int variant = 0; variant < 3; variant++) {
        char label[160];
        snprintf(label, sizeof label, "%s +failure%s", c->material,
                 variant == 1 ? "+rate" : variant == 2 ? "+band" : "");
        wff_material mat;
        int rc = failing_material(c->material, extra[variant], label, &mat, &err);
        CHECK(st, rc == 0, "%s: %s", label, err.message);
        if (rc)
            continue;
        CHECK(st, mat.n_state <= cell->n_state_max && cell->n_state_max <= WFF_STATE_MAX &&
                      cell->damage_state[0] < mat.n_state &&
                      cell->damage_state[1] < mat.n_state && mat.n_state > off.n_state,
              "%s: state layout n_state %d (max %d, failure off %d), damage at %d %d", label,
              mat.n_state, cell->n_state_max, off.n_state, cell->damage_state[0],
              cell->damage_state[1]);
        if (!(cell->damage_state[0] < mat.n_state && cell->damage_state[1] < mat.n_state))
            continue;
        rng r = {0xD1B54A32D192ED03ULL + (unsigned)variant};
        check_fixed_damage(st, c, &mat, label, &r);
        check_tension_only(st, &mat, label);
        check_path(st, &mat, label);
        check_fast_paths(st, c, &mat, label, &r);
        if (variant == 0)
            check_amplitudes_bounded(st, &mat, &off, label);
        if (variant == 2)
            check_band(st, &mat, label, &r);
    }
}

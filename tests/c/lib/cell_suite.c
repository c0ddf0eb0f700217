#include "cell_suite.h"
#include "rng.h"
#include "wovenff/material.h"

#include <math.h>
#include <string.h>

#define N_STATES 200

static double max_abs(const double *v, int n)
{
    double m = 0;
    for (int i = 0; i < n; i++)
        m = fmax(m, fabs(v[i]));
    return m;
}

/* Random rotation from a random unit quaternion. */
static void random_rotation(rng *r, double Q[3][3])
{
    double q[4], n = 0;
    for (int i = 0; i < 4; i++) {
        q[i] = rng_uniform(r, -1, 1);
        n += q[i] * q[i];
    }
    n = sqrt(n);
    double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
    double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
                      {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
                      {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}};
    memcpy(Q, R, sizeof R);
}

static void rotate(const double Q[3][3], const double A[6], double out[6])
{
    for (int i = 0; i < 3; i++)
        for (int J = 0; J < 2; J++)
            out[2 * i + J] = Q[i][0] * A[J] + Q[i][1] * A[2 + J] + Q[i][2] * A[4 + J];
}

/* F = Q [U; 0]: in-plane stretches, shear and a rigid rotation out of plane. */
static void random_state(rng *r, const cell_case *c, double F[6], double dA[2], double *gf)
{
    double l1 = rng_uniform(r, 0.985, 1.04), l2 = rng_uniform(r, 0.985, 1.04);
    double shear = rng_uniform(r, -0.6, 0.6); /* rad, up to ~35° */
    double U[6] = {l1, l2 * sin(shear), 0, l2 * cos(shear), 0, 0};
    double Q[3][3];
    random_rotation(r, Q);
    rotate(Q, U, F);
    dA[0] = rng_uniform(r, -c->amplitude_range, c->amplitude_range / 3);
    dA[1] = rng_uniform(r, -c->amplitude_range, c->amplitude_range / 3);
    *gf = rng_uniform(r, -0.05, 0.05);
}

static double energy(const wff_material *m, const double F[6], const double dA[2], double gf)
{
    wff_point_result out;
    wff_material_evaluate(m, F, dA, gf, 0, &out);
    return out.energy;
}

/* Fourth-order central difference of W along one input. */
static double fd(const wff_material *m, double F[6], double dA[2], double gf, double *x,
                 double h)
{
    double x0 = *x, w[4];
    const double offs[4] = {-2, -1, 1, 2};
    for (int i = 0; i < 4; i++) {
        *x = x0 + offs[i] * h;
        w[i] = energy(m, F, dA, gf);
    }
    *x = x0;
    return (w[0] - 8 * w[1] + 8 * w[2] - w[3]) / (12 * h);
}

void cell_suite_run(check_state *st, const cell_case *c)
{
    wff_material mat;
    wff_error err;
    int rc = wff_material_load(c->material, &mat, &err);
    CHECK(st, rc == 0, "%s: %s", c->material, err.message);
    if (rc)
        return;
    const wff_cell_type *cell = mat.cell;
    CHECK(st, wff_cell_find(cell->name) == cell, "registry finds %s", cell->name);
    CHECK(st, cell->n_diag <= WFF_DIAG_MAX && cell->n_mech <= WFF_MECH_MAX, "table sizes");
    rng r = {0x9E3779B97F4A7C15ULL};
    wff_point_result out, out2;

    /* scales: a 1 % uniaxial warp stretch */
    const double F_ref[6] = {1, 0, 0, 1, 0, 0}, zero[2] = {0, 0};
    double F_1pc[6] = {1.01, 0, 0, 1, 0, 0};
    wff_material_evaluate(&mat, F_1pc, zero, 0, 0, &out);
    double stress_scale = max_abs(out.stress, 6);
    double dA_probe[2] = {-c->amplitude_range, -c->amplitude_range};
    wff_material_evaluate(&mat, F_ref, dA_probe, 0, 0, &out);
    double residual_scale = fmax(max_abs(out.residual, 2), 1e-300);
    CHECK(st, stress_scale > 0, "%s: 1%% stretch gives stress", c->material);

    /* 2. reference state */
    rc = wff_material_evaluate(&mat, F_ref, zero, 0, 0, &out);
    CHECK(st, rc == WFF_POINT_OK, "reference state evaluates");
    CHECK(st, max_abs(out.stress, 6) <= 1e-9 * stress_scale,
          "%s: reference stress %g (scale %g)", c->material, max_abs(out.stress, 6),
          stress_scale);
    CHECK(st, cell->n_amplitudes == 0 || max_abs(out.residual, 2) <= 1e-9 * residual_scale,
          "%s: reference residual %g (scale %g)", c->material, max_abs(out.residual, 2),
          residual_scale);
    CHECK(st, fabs(out.energy) <= 1e-12 * stress_scale, "%s: reference energy %g",
          c->material, out.energy);

    /* 1, 3, 4 at random states */
    double worst_P = 0, worst_R = 0, worst_obj = 0, worst_swap = 0, worst_split = 0;
    int active[WFF_MECH_MAX] = {0};
    wff_material swap_mat;
    int have_swap = c->swap_material && wff_material_load(c->swap_material, &swap_mat, &err) == 0;
    CHECK(st, !c->swap_material || have_swap, "%s: %s", c->swap_material, err.message);
    for (int s = 0; s < N_STATES; s++) {
        double F[6], dA[2], gf;
        random_state(&r, c, F, dA, &gf);
        rc = wff_material_evaluate(&mat, F, dA, gf, 0, &out);
        CHECK(st, rc == WFF_POINT_OK, "state %d evaluates", s);
        if (rc)
            continue;
        CHECK(st, out.gamma_f == gf && out.dissipated == 0, "dt = 0 holds gamma_f");
        if (c->energy_exact) {
            double Pfd[6], Rfd[2] = {0, 0}, err_P = 0, err_R = 0;
            for (int i = 0; i < 6; i++) {
                Pfd[i] = fd(&mat, F, dA, gf, &F[i], 1e-5);
                err_P = fmax(err_P, fabs(Pfd[i] - out.stress[i]));
            }
            for (int k = 0; k < cell->n_amplitudes; k++) {
                Rfd[k] = -fd(&mat, F, dA, gf, &dA[k], 1e-5 * c->amplitude_range);
                err_R = fmax(err_R, fabs(Rfd[k] - out.residual[k]));
            }
            err_P /= fmax(max_abs(out.stress, 6), 1e-6 * stress_scale);
            err_R /= fmax(max_abs(out.residual, 2), 1e-6 * residual_scale);
            worst_P = fmax(worst_P, err_P);
            worst_R = fmax(worst_R, err_R);
        }
        /* objectivity */
        double Q[3][3], QF[6], QP[6];
        random_rotation(&r, Q);
        rotate(Q, F, QF);
        rotate(Q, out.stress, QP);
        wff_material_evaluate(&mat, QF, dA, gf, 0, &out2);
        double e = 0;
        for (int i = 0; i < 6; i++)
            e = fmax(e, fabs(out2.stress[i] - QP[i]));
        e /= fmax(max_abs(out.stress, 6), 1e-6 * stress_scale);
        for (int k = 0; k < cell->n_amplitudes; k++)
            e = fmax(e, fabs(out2.residual[k] - out.residual[k]) /
                            fmax(max_abs(out.residual, 2), 1e-6 * residual_scale));
        e = fmax(e, fabs(out2.energy - out.energy) / fmax(fabs(out.energy), 1e-300));
        worst_obj = fmax(worst_obj, e);
        /* swap warp and weft */
        if (have_swap) {
            wff_point_result a, b;
            double Fs[6], dAs[2] = {dA[1], dA[0]};
            for (int i = 0; i < 3; i++) {
                Fs[2 * i] = F[2 * i + 1];
                Fs[2 * i + 1] = F[2 * i];
            }
            wff_material_evaluate(&swap_mat, F, dA, gf, 0, &a);
            wff_material_evaluate(&swap_mat, Fs, dAs, gf, 0, &b);
            double es = 0, sP = fmax(max_abs(a.stress, 6), 1e-6 * stress_scale);
            for (int i = 0; i < 3; i++) {
                es = fmax(es, fabs(b.stress[2 * i] - a.stress[2 * i + 1]) / sP);
                es = fmax(es, fabs(b.stress[2 * i + 1] - a.stress[2 * i]) / sP);
            }
            if (cell->n_amplitudes)
                for (int k = 0; k < 2; k++)
                    es = fmax(es, fabs(b.residual[k] - a.residual[1 - k]) /
                                      fmax(max_abs(a.residual, 2), 1e-6 * residual_scale));
            es = fmax(es, fabs(b.energy - a.energy) / fmax(fabs(a.energy), 1e-300));
            worst_swap = fmax(worst_swap, es);
        }
        /* energy split */
        if (cell->energy_split) {
            double mech[WFF_MECH_MAX], sum = 0;
            cell->energy_split(mat.params, F, dA, gf, mech);
            for (int m = 0; m < cell->n_mech; m++) {
                sum += mech[m];
                if (fabs(mech[m]) > 1e-9 * fabs(out.energy))
                    active[m]++;
            }
            worst_split = fmax(worst_split, fabs(sum - out.energy) / fmax(fabs(out.energy), 1e-300));
        }
        /* stable-step bounds */
        double speed, omega;
        cell->wave_speeds(mat.params, mat.areal_density, F, dA, &speed, &omega);
        CHECK(st, isfinite(speed) && speed > 0 && isfinite(omega) && omega >= 0 &&
                      (cell->n_amplitudes == 0 || omega > 0),
              "state %d: wave speed %g, amplitude omega %g", s, speed, omega);
    }
    /* the optional fast path equals the reference path, state update included */
    double worst_fast = 0;
    if (cell->evaluate_shared) {
        for (int s = 0; s < N_STATES; s++) {
            double F[6], dA[6], gf[3], gf_fast[3], w[3] = {0.2, 0.3, 0.5};
            random_state(&r, c, F, dA, &gf[0]);
            for (int q = 1; q < 3; q++)
                random_state(&r, c, (double[6]){0}, dA + 2 * q, &gf[q]);
            memcpy(gf_fast, gf, sizeof gf);
            double dt = s % 2 ? 2e-7 : 0;
            double P_ref[6] = {0}, W_ref = 0, D_ref = 0, P_fast[6] = {0}, R_fast[6];
            double W_fast = 0, D_fast = 0, R_ref[6];
            for (int q = 0; q < 3; q++) {
                wff_material_evaluate(&mat, F, dA + 2 * q, gf[q], dt, &out);
                for (int i = 0; i < 6; i++)
                    P_ref[i] += w[q] * out.stress[i];
                R_ref[2 * q] = out.residual[0];
                R_ref[2 * q + 1] = out.residual[1];
                W_ref += w[q] * out.energy;
                D_ref += w[q] * out.dissipated;
                gf[q] = out.gamma_f;
            }
            int bad = -1;
            rc = cell->evaluate_shared(mat.params, F, 3, dA, w, gf_fast, dt, P_fast, R_fast,
                                       &W_fast, &D_fast, &bad);
            CHECK(st, rc == WFF_POINT_OK, "fast path state %d: status %d at point %d", s, rc, bad);
            double e = 0, sP = fmax(max_abs(P_ref, 6), 1e-6 * stress_scale);
            for (int i = 0; i < 6; i++)
                e = fmax(e, fabs(P_fast[i] - P_ref[i]) / sP);
            if (cell->n_amplitudes)
                for (int i = 0; i < 6; i++)
                    e = fmax(e, fabs(R_fast[i] - R_ref[i]) /
                                    fmax(max_abs(R_ref, 6), 1e-6 * residual_scale));
            e = fmax(e, fabs(W_fast - W_ref) / fmax(fabs(W_ref), 1e-300));
            e = fmax(e, fabs(D_fast - D_ref) / fmax(fabs(W_ref), 1e-300));
            for (int q = 0; q < 3; q++)
                e = fmax(e, fabs(gf_fast[q] - gf[q]) / fmax(fabs(gf[q]), 1e-3));
            worst_fast = fmax(worst_fast, e);
        }
        CHECK(st, worst_fast <= 1e-11, "%s: fast path differs from evaluate by %.3g",
              c->material, worst_fast);
    }
    /* the optional blocked path too, lane by lane (or it declines the parameters) */
    double worst_block = 0;
    int block_used = 0;
    if (cell->evaluate_tri_block) {
        for (int s = 0; s < N_STATES / WFF_BLOCK; s++) {
            wff_tri_block blk;
            double gf0[3][WFF_BLOCK], dt = s % 2 ? 2e-7 : 0;
            blk.n = WFF_BLOCK;
            for (int j = 0; j < WFF_BLOCK; j++) {
                double F[6], dA[2], gf;
                random_state(&r, c, F, dA, &gf);
                for (int i = 0; i < 6; i++)
                    blk.F[i][j] = F[i];
                for (int q = 0; q < 3; q++) {
                    random_state(&r, c, (double[6]){0}, dA, &gf);
                    blk.dA[q][0][j] = dA[0];
                    blk.dA[q][1][j] = dA[1];
                    blk.gamma_f[q][j] = gf0[q][j] = gf;
                }
            }
            if (cell->evaluate_tri_block(mat.params, dt, &blk) != 0)
                break;
            block_used = 1;
            for (int j = 0; j < WFF_BLOCK; j++) {
                double F[6], P[6] = {0}, W = 0, Dis = 0, e = 0;
                for (int i = 0; i < 6; i++)
                    F[i] = blk.F[i][j];
                CHECK(st, !blk.degenerate[j], "block lane %d flagged degenerate", j);
                for (int q = 0; q < 3; q++) {
                    double dA[2] = {blk.dA[q][0][j], blk.dA[q][1][j]};
                    wff_material_evaluate(&mat, F, dA, gf0[q][j], dt, &out);
                    for (int i = 0; i < 6; i++)
                        P[i] += out.stress[i] / 3;
                    W += out.energy / 3;
                    Dis += out.dissipated / 3;
                    for (int k = 0; k < cell->n_amplitudes; k++)
                        e = fmax(e, fabs(blk.residual[q][k][j] - out.residual[k]) /
                                        fmax(fabs(out.residual[k]), 1e-6 * residual_scale));
                    e = fmax(e, fabs(blk.gamma_f[q][j] - out.gamma_f) / fmax(fabs(out.gamma_f), 1e-3));
                }
                double sP = fmax(max_abs(P, 6), 1e-6 * stress_scale);
                for (int i = 0; i < 6; i++)
                    e = fmax(e, fabs(blk.stress[i][j] - P[i]) / sP);
                e = fmax(e, fabs(blk.energy[j] - W) / fmax(fabs(W), 1e-300));
                e = fmax(e, fabs(blk.dissipated[j] - Dis) / fmax(fabs(W), 1e-300));
                worst_block = fmax(worst_block, e);
            }
        }
        CHECK(st, worst_block <= 1e-11, "%s: blocked path differs from evaluate by %.3g",
              c->material, worst_block);
    }
    printf("  %-48s FD stress %.1e, FD residual %.1e, objectivity %.1e, swap %.1e, split %.1e, "
           "fast path %.1e, blocked %s%.1e\n", c->material, worst_P, worst_R, worst_obj,
           worst_swap, worst_split, worst_fast,
           !cell->evaluate_tri_block ? "(none) " : block_used ? "" : "(declined) ", worst_block);
    if (c->energy_exact) {
        CHECK(st, worst_P <= 1e-6, "%s: P vs dW/dF relative error %.3g", c->material, worst_P);
        CHECK(st, worst_R <= 1e-6, "%s: R vs -dW/ddA relative error %.3g", c->material, worst_R);
    }
    CHECK(st, worst_obj <= 1e-10, "%s: objectivity error %.3g", c->material, worst_obj);
    CHECK(st, !have_swap || worst_swap <= 1e-10, "%s: swap error %.3g", c->material, worst_swap);
    if (cell->energy_split) {
        CHECK(st, worst_split <= 1e-12, "%s: split sum error %.3g", c->material, worst_split);
        for (int m = 0; m < cell->n_mech; m++)
            CHECK(st, active[m] >= N_STATES / 10, "%s: mechanism %s active in %d of %d states",
                  c->material, cell->mech_names[m], active[m], N_STATES);
    }
    /* degenerate: parallel yarn directions */
    const double F_bad[6] = {1, 1, 0, 0, 0, 0};
    rc = wff_material_evaluate(&mat, F_bad, zero, 0, 0, &out);
    CHECK(st, rc == WFF_POINT_DEGENERATE && isnan(out.stress[0]),
          "%s: parallel yarns flagged degenerate", c->material);
}

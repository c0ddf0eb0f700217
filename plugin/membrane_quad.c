/* Quads on the blocked fast path (docs/model.md §8, §11). A bilinear quad's
 * four 2×2 Gauss points each have their own F, so nothing is shared per
 * element as on triangles: a block holds WFF_BLOCK quads, one a lane; their
 * nodes are gathered once, then each Gauss point q of the block's quads goes
 * through the cell's evaluate_point_block (structure of arrays, vectorised
 * across the lanes) and its forces −w P F_preᵀ ∇N / J_pre are summed per
 * lane and node, scattered once per quad at the end.
 * Threaded like the triangle pass: static schedule, per-thread force buffers
 * (el->thread_f) added in thread order, so a thread count repeats bit for bit.
 *
 * It knows the element geometry (wff_elements) and the cell's ops table only:
 * nothing of the integrator, contact, I/O or the binding. The plain per-point
 * reference path stays in membrane.c (wff_elements_forces). */
#include "membrane_quad.h"

#include <math.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define D WFF_DOFS_PER_NODE

/* N_a at Gauss point q: corners (ξ, η) = (−1,−1), (1,−1), (1,1), (−1,1), points
 * at (±1/√3, ±1/√3) in the same order (membrane.c's quad_shape). */
static void quad_gauss_shapes(double N[WFF_QUAD_POINTS][4])
{
    static const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    const double g = 0.57735026918962576451; /* 1/√3 */
    for (int q = 0; q < WFF_QUAD_POINTS; q++)
        for (int a = 0; a < 4; a++)
            N[q][a] = 0.25 * (1 + corner[a][0] * g * corner[q][0]) *
                      (1 + corner[a][1] * g * corner[q][1]);
}

/* Sums one thread gathers over its quads. */
typedef struct quad_sums {
    double energy, dissipated;
    int bad_element, bad_point, bad_status; /* bad_element: quad index, −1 if none */
} quad_sums;

static void note_bad_point(quad_sums *s, int e, int q, int status)
{
    if (s->bad_element < 0 || e < s->bad_element ||
        (e == s->bad_element && q < s->bad_point)) {
        s->bad_element = e;
        s->bad_point = q;
        s->bad_status = status;
    }
}

/* Quads e0 .. e0 + n − 1 (n ≤ WFF_BLOCK), one quad a lane: the nodes gathered
 * once, then for each Gauss point q a block of the n quads' point q through
 * the cell, its forces summed per lane and node; one update of f per node at
 * the end. Lanes past n repeat the last quad (a valid state, results dropped). */
static void quad_block(const wff_elements *el, const wff_element_material *em,
                       const double N[WFF_QUAD_POINTS][4], const double *X, const double *u,
                       double *gamma_f, double dt, double *f, int e0, int n, quad_sums *sums)
{
    const wff_material *mat = em->mat;
    const double *Fp = em->F_pre;
    const double inv_J = 1 / em->J_pre;
    const int amplitudes = mat->cell->n_amplitudes;
    double *gf = gamma_f + WFF_TRI_POINTS * el->n_tris; /* the quads' points */
    double x[4][D][WFF_BLOCK];   /* x, y, z, ΔA1, ΔA2 at node a of each lane's quad */
    double acc[4][D][WFF_BLOCK]; /* force on node a of each lane's quad */
    double lane_energy[WFF_BLOCK], lane_dissipated[WFF_BLOCK], gf_new[WFF_QUAD_POINTS][WFF_BLOCK];
    int status[WFF_QUAD_POINTS][WFF_BLOCK]; /* WFF_POINT_* per point */
#pragma omp simd
    for (int j = 0; j < WFF_BLOCK; j++) {
        int e = e0 + (j < n ? j : n - 1);
        const int *node = el->quad + 4 * e;
        for (int a = 0; a < 4; a++) {
            const double *ua = u + D * node[a];
            x[a][0][j] = X[2 * node[a]] + ua[0];
            x[a][1][j] = X[2 * node[a] + 1] + ua[1];
            x[a][2][j] = ua[2];
            x[a][3][j] = ua[3];
            x[a][4][j] = ua[4];
            for (int c = 0; c < D; c++)
                acc[a][c][j] = 0;
        }
        lane_energy[j] = lane_dissipated[j] = 0;
    }
    wff_point_block blk;
    blk.n = n;
    for (int q = 0; q < WFF_QUAD_POINTS; q++) {
        int finite[WFF_BLOCK];
#pragma omp simd
        for (int j = 0; j < WFF_BLOCK; j++) {
            int e = e0 + (j < n ? j : n - 1);
            const double *g = el->quad_grad + 32 * e + 8 * q;
            double F0 = 0, F1 = 0, F2 = 0, F3 = 0, F4 = 0, F5 = 0, dA0 = 0, dA1 = 0;
            for (int a = 0; a < 4; a++) {
                double gx = g[2 * a], gy = g[2 * a + 1];
                F0 += x[a][0][j] * gx;
                F1 += x[a][0][j] * gy;
                F2 += x[a][1][j] * gx;
                F3 += x[a][1][j] * gy;
                F4 += x[a][2][j] * gx;
                F5 += x[a][2][j] * gy;
                dA0 += N[q][a] * x[a][3][j];
                dA1 += N[q][a] * x[a][4][j];
            }
            /* F_eff = F F_pre */
            blk.F[0][j] = F0 * Fp[0] + F1 * Fp[2];
            blk.F[1][j] = F0 * Fp[1] + F1 * Fp[3];
            blk.F[2][j] = F2 * Fp[0] + F3 * Fp[2];
            blk.F[3][j] = F2 * Fp[1] + F3 * Fp[3];
            blk.F[4][j] = F4 * Fp[0] + F5 * Fp[2];
            blk.F[5][j] = F4 * Fp[1] + F5 * Fp[3];
            blk.dA[0][j] = dA0;
            blk.dA[1][j] = dA1;
            blk.gamma_f[j] = gf[4 * e + q];
            double state = F0 + F1 + F2 + F3 + F4 + F5 + dA0 + dA1;
            finite[j] = state - state == 0; /* false for NaN and ±inf (isfinite does not vectorise) */
        }
        mat->cell->evaluate_point_block(mat->params, dt, &blk); /* accepted: asked before the pass */
        /* per lane: the point's force −w P_mesh ∇N_b (P_mesh = P F_preᵀ / J_pre) and
         * amplitude force w N_b R_k / J_pre on each node b, where the point is sound
         * (a failed point adds nothing, as on the plain path) */
#pragma omp simd
        for (int j = 0; j < WFF_BLOCK; j++) {
            int e = e0 + (j < n ? j : n - 1);
            const double *g = el->quad_grad + 32 * e + 8 * q;
            double w = el->quad_weight[4 * e + q];
            double sum = blk.energy[j] + blk.dissipated[j] + blk.residual[0][j] + blk.residual[1][j];
            for (int i = 0; i < 6; i++)
                sum += blk.stress[i][j];
            int sound = finite[j] & !blk.degenerate[j] & (sum - sum == 0);
            status[q][j] = sound ? WFF_POINT_OK
                         : !finite[j] || !blk.degenerate[j] ? WFF_POINT_NONFINITE
                                                            : WFF_POINT_DEGENERATE;
            double s = sound ? -w * inv_J : 0, wa = sound && amplitudes ? w * inv_J : 0;
            double fx[6];
            for (int i = 0; i < 3; i++) {
                double p0 = sound ? blk.stress[2 * i][j] : 0;
                double p1 = sound ? blk.stress[2 * i + 1][j] : 0;
                fx[2 * i] = s * (p0 * Fp[0] + p1 * Fp[1]);
                fx[2 * i + 1] = s * (p0 * Fp[2] + p1 * Fp[3]);
            }
            double r0 = wa * (sound ? blk.residual[0][j] : 0);
            double r1 = wa * (sound ? blk.residual[1][j] : 0);
            for (int b = 0; b < 4; b++) {
                double gx = g[2 * b], gy = g[2 * b + 1];
                acc[b][0][j] += fx[0] * gx + fx[1] * gy;
                acc[b][1][j] += fx[2] * gx + fx[3] * gy;
                acc[b][2][j] += fx[4] * gx + fx[5] * gy;
                acc[b][3][j] += N[q][b] * r0;
                acc[b][4][j] += N[q][b] * r1;
            }
            gf_new[q][j] = sound ? blk.gamma_f[j] : gf[4 * e + q];
            lane_energy[j] += sound ? w * blk.energy[j] : 0;
            lane_dissipated[j] += sound ? w * blk.dissipated[j] : 0;
        }
    }
    for (int j = 0; j < n; j++) {
        int e = e0 + j;
        const int *node = el->quad + 4 * e;
        for (int b = 0; b < 4; b++) {
            double *fb = f + D * node[b];
            for (int c = 0; c < D; c++)
                fb[c] += acc[b][c][j];
        }
        for (int q = 0; q < WFF_QUAD_POINTS; q++) {
            gf[4 * e + q] = gf_new[q][j];
            if (status[q][j] != WFF_POINT_OK)
                note_bad_point(sums, e, q, status[q][j]);
        }
        sums->energy += lane_energy[j];
        sums->dissipated += lane_dissipated[j];
    }
}

/* Whether the cell takes these parameters: one block of a valid state (the
 * unstrained preloaded point), results dropped. */
static int cell_takes_points(const wff_element_material *em, double dt)
{
    wff_point_block probe;
    memset(&probe, 0, sizeof probe);
    for (int j = 0; j < WFF_BLOCK; j++) {
        probe.F[0][j] = em->F_pre[0];
        probe.F[1][j] = em->F_pre[1];
        probe.F[2][j] = em->F_pre[2];
        probe.F[3][j] = em->F_pre[3];
    }
    probe.n = WFF_BLOCK;
    return em->mat->cell->evaluate_point_block(em->mat->params, dt, &probe) == 0;
}

int wff_quad_block_forces(const wff_elements *el, const wff_element_material *em,
                          const double *X, const double *u, double *gamma_f, double dt,
                          double *f, double *energy, double *dissipated,
                          wff_force_totals *totals)
{
    if (el->n_quads == 0 || !em->mat->cell->evaluate_point_block || em->reference_path ||
        em->static_amplitudes || !cell_takes_points(em, dt))
        return -1;
    double N[WFF_QUAD_POINTS][4];
    quad_gauss_shapes(N);
    const int n_blocks = (el->n_quads + WFF_BLOCK - 1) / WFF_BLOCK;
    /* small meshes are not worth a thread team (a quad costs about as much as
     * four triangles' points, hence the lower count than the triangle pass) */
    int threads = el->n_threads > 1 && el->n_quads >= 32 * WFF_BLOCK ? el->n_threads : 1;
    quad_sums part[WFF_MAX_THREADS];
    int team = 1;
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
#ifdef _OPENMP
        int t = omp_get_thread_num();
#pragma omp single
        team = omp_get_num_threads();
#else
        int t = 0;
#endif
        double *ft = t == 0 ? f : el->thread_f + (size_t)(t - 1) * (size_t)el->n_dofs;
        if (t > 0)
            memset(ft, 0, sizeof(double) * (size_t)el->n_dofs);
        quad_sums sums = {0, 0, -1, -1, 0};
#pragma omp for schedule(static)
        for (int blk = 0; blk < n_blocks; blk++) {
            int e0 = blk * WFF_BLOCK;
            int n = el->n_quads - e0 < WFF_BLOCK ? el->n_quads - e0 : WFF_BLOCK;
            quad_block(el, em, N, X, u, gamma_f, dt, ft, e0, n, &sums);
        }
        part[t] = sums;
        /* (past the loop's barrier) the other threads' buffers into f, a slice of
         * the DOFs per thread, buffers in thread order */
        if (team > 1) {
            const size_t n_dofs = (size_t)el->n_dofs;
#pragma omp for schedule(static)
            for (size_t i = 0; i < n_dofs; i++) {
                double extra = 0;
                for (int k = 1; k < team; k++)
                    extra += el->thread_f[(size_t)(k - 1) * n_dofs + i];
                f[i] += extra;
            }
        }
    }
    quad_sums all = {0, 0, -1, -1, 0};
    for (int t = 0; t < team; t++) { /* in thread order: the same sums every run */
        all.energy += part[t].energy;
        all.dissipated += part[t].dissipated;
        if (part[t].bad_element >= 0)
            note_bad_point(&all, part[t].bad_element, part[t].bad_point, part[t].bad_status);
    }
    *energy += all.energy;
    *dissipated += all.dissipated;
    if (all.bad_element >= 0 && totals->bad_element < 0) {
        totals->bad_element = el->n_tris + all.bad_element;
        totals->bad_point = all.bad_point;
        totals->bad_status = all.bad_status;
    }
    return 0;
}

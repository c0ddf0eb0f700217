/* Quads: their part of the internal-force pass (wff_quad_forces), on the
 * blocked fast path where the cell takes it, else point by point.
 *
 * The blocked fast path (docs/model.md §8, §11). A bilinear quad's
 * four 2×2 Gauss points each have their own F, so nothing is shared per
 * element as on triangles: a block holds WFF_BLOCK quads, one a lane; their
 * nodes are gathered once, F at each Gauss point follows from the bilinear
 * map (no stored gradients gathered), then each Gauss point q of the block's
 * quads goes through the cell's evaluate_point_block (structure of arrays,
 * vectorised across the lanes) and its forces −w P F_preᵀ ∇N / J_pre are
 * summed per lane and node, written into the quad's slots at the end (the
 * nodes sum their slots in element order after the pass, the energies per
 * block, the blocks in order: the same bits for any number of threads).
 * Threaded like the triangle pass: static schedule over the blocks.
 *
 * It knows the element geometry (wff_elements) and the cell's ops table only:
 * nothing of the integrator, contact, I/O or the binding. The plain per-point
 * reference path is wff_quad_forces, at the end. */
#include "wovenff/balance.h"
#include "membrane_quad.h"
#include "membrane_geometry.h"

#include <math.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define D WFF_DOFS_PER_NODE

/* The bilinear quad at its 2×2 Gauss points: corners (ξ_a, η_a) = (−1,−1), (1,−1),
 * (1,1), (−1,1), points (ξ_q, η_q) = (±1/√3, ±1/√3) in the same order
 * (membrane_geometry.h's quad_shape). N[q][a] = N_a, dN[q][a][r] = ∂N_a/∂ξ_r at point q. */
typedef struct quad_table {
    double xi[WFF_QUAD_POINTS], eta[WFF_QUAD_POINTS];
    double N[WFF_QUAD_POINTS][4];
    double dN[WFF_QUAD_POINTS][4][2];
} quad_table;

static void quad_table_init(quad_table *t)
{
    static const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    const double g = 0.57735026918962576451; /* 1/√3 */
    for (int q = 0; q < WFF_QUAD_POINTS; q++) {
        t->xi[q] = g * corner[q][0];
        t->eta[q] = g * corner[q][1];
        for (int a = 0; a < 4; a++) {
            t->N[q][a] = 0.25 * (1 + corner[a][0] * t->xi[q]) * (1 + corner[a][1] * t->eta[q]);
            t->dN[q][a][0] = 0.25 * corner[a][0] * (1 + corner[a][1] * t->eta[q]);
            t->dN[q][a][1] = 0.25 * corner[a][1] * (1 + corner[a][0] * t->xi[q]);
        }
    }
}

/* Sums one thread gathers over its quads. */
typedef struct quad_sums {
    double energy, dissipated, failure, slip;
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

/* Quads e0 .. e0 + n − 1 (n ≤ WFF_BLOCK), one quad a lane. The nodes are
 * gathered once; the bilinear map's derivatives are affine in (ξ, η):
 *   ∂x/∂ξ = a₁ + η a₁₂,  ∂x/∂η = a₂ + ξ a₁₂,
 *   a₁ = ¼(−x₀+x₁+x₂−x₃), a₂ = ¼(−x₀−x₁+x₂+x₃), a₁₂ = ¼(x₀−x₁+x₂−x₃),
 * the same for the reference X (the Jacobian J = ∂X/∂ξ), so at each point
 *   F = (∂x/∂ξ) J⁻¹,   w = det J (Gauss weight 1),
 *   f_b = −w P_mesh ∇_X N_b = −P_mesh adj(J)ᵀ ∇_ξ N_b   (w J⁻¹ = adj J),
 * with no stored gradients to gather (the plain path's ∇_X N_a = J⁻ᵀ ∇_ξ N_a,
 * the same to round-off). For each point q the lanes' point q goes through
 * the cell; forces are summed per lane and node, f updated once per node at
 * the end. Lanes past n repeat the last quad (a valid state, results dropped). */
static inline __attribute__((always_inline)) void
quad_block_n(const wff_elements *el, const wff_element_material *em, const quad_table *t,
             const double *X, const double *u, double *state, double dt, int e0,
             int n, quad_sums *sums, const int ns)
{
    const wff_material *mat = em->mat;
    const double *Fp = em->F_pre;
    const double inv_J = 1 / em->J_pre;
    const int amplitudes = wff_cell_amplitudes(mat->cell);
    double *sq = state + ns * WFF_TRI_POINTS * el->n_tris; /* the quads' points' states */
    const int *quad = el->quad;
    double dx[3][3][WFF_BLOCK];  /* a₁, a₂, a₁₂ of x (3 components) */
    double dX[3][2][WFF_BLOCK];  /* a₁, a₂, a₁₂ of X (2 components) */
    double amp[4][2][WFF_BLOCK]; /* ΔA1, ΔA2 at the nodes */
    double acc[4][D][WFF_BLOCK]; /* force on node a of each lane's quad */
    double lane_energy[WFF_BLOCK], lane_dissipated[WFF_BLOCK], lane_failure[WFF_BLOCK];
    double lane_slip[WFF_BLOCK];
    double state_new[WFF_QUAD_POINTS][WFF_STATE_MAX][WFF_BLOCK]; /* where the point is sound */
    int status[WFF_QUAD_POINTS][WFF_BLOCK]; /* WFF_POINT_* per point */
#pragma omp simd
    for (int j = 0; j < WFF_BLOCK; j++) {
        int e = e0 + (j < n ? j : n - 1);
        /* integer indices, not pointers: gcc turns these into vector gathers */
        double xn[4][3], Xn[4][2];
        for (int a = 0; a < 4; a++) {
            int nd = quad[4 * e + a];
            Xn[a][0] = X[2 * nd];
            Xn[a][1] = X[2 * nd + 1];
            xn[a][0] = Xn[a][0] + u[D * nd];
            xn[a][1] = Xn[a][1] + u[D * nd + 1];
            xn[a][2] = u[D * nd + 2];
            amp[a][0][j] = u[D * nd + 3];
            amp[a][1][j] = u[D * nd + 4];
            for (int c = 0; c < D; c++)
                acc[a][c][j] = 0;
        }
        for (int i = 0; i < 3; i++) {
            dx[0][i][j] = 0.25 * (-xn[0][i] + xn[1][i] + xn[2][i] - xn[3][i]);
            dx[1][i][j] = 0.25 * (-xn[0][i] - xn[1][i] + xn[2][i] + xn[3][i]);
            dx[2][i][j] = 0.25 * (xn[0][i] - xn[1][i] + xn[2][i] - xn[3][i]);
        }
        for (int i = 0; i < 2; i++) {
            dX[0][i][j] = 0.25 * (-Xn[0][i] + Xn[1][i] + Xn[2][i] - Xn[3][i]);
            dX[1][i][j] = 0.25 * (-Xn[0][i] - Xn[1][i] + Xn[2][i] + Xn[3][i]);
            dX[2][i][j] = 0.25 * (Xn[0][i] - Xn[1][i] + Xn[2][i] - Xn[3][i]);
        }
        lane_energy[j] = lane_dissipated[j] = lane_failure[j] = lane_slip[j] = 0;
    }
    wff_point_block blk;
    blk.n = n;
    for (int q = 0; q < WFF_QUAD_POINTS; q++) {
        const double xi = t->xi[q], eta = t->eta[q];
        int finite[WFF_BLOCK];
        double adj[2][2][WFF_BLOCK], det[WFF_BLOCK]; /* adj J = det J · J⁻¹ */
#pragma omp simd
        for (int j = 0; j < WFF_BLOCK; j++) {
            /* J = ∂X/∂ξ: J[i][r] = ∂X_i/∂ξ_r */
            double J00 = dX[0][0][j] + eta * dX[2][0][j], J01 = dX[1][0][j] + xi * dX[2][0][j];
            double J10 = dX[0][1][j] + eta * dX[2][1][j], J11 = dX[1][1][j] + xi * dX[2][1][j];
            double dj = J00 * J11 - J01 * J10, inv = 1 / dj;
            det[j] = dj;
            adj[0][0][j] = J11, adj[0][1][j] = -J01, adj[1][0][j] = -J10, adj[1][1][j] = J00;
            double Fm[6]; /* F = (∂x/∂ξ) J⁻¹ */
            for (int i = 0; i < 3; i++) {
                double d0 = dx[0][i][j] + eta * dx[2][i][j], d1 = dx[1][i][j] + xi * dx[2][i][j];
                Fm[2 * i] = (d0 * J11 - d1 * J10) * inv;
                Fm[2 * i + 1] = (d1 * J00 - d0 * J01) * inv;
            }
            double dA0 = 0, dA1 = 0;
            for (int a = 0; a < 4; a++) {
                dA0 += t->N[q][a] * amp[a][0][j];
                dA1 += t->N[q][a] * amp[a][1][j];
            }
            /* F_eff = F F_pre */
            for (int i = 0; i < 3; i++) {
                blk.F[2 * i][j] = Fm[2 * i] * Fp[0] + Fm[2 * i + 1] * Fp[2];
                blk.F[2 * i + 1][j] = Fm[2 * i] * Fp[1] + Fm[2 * i + 1] * Fp[3];
            }
            blk.dA[0][j] = dA0;
            blk.dA[1][j] = dA1;
            double state = Fm[0] + Fm[1] + Fm[2] + Fm[3] + Fm[4] + Fm[5] + dA0 + dA1;
            finite[j] = state - state == 0; /* false for NaN and ±inf (isfinite does not vectorise) */
        }
        for (int i = 0; i < ns; i++) { /* the points' states: a vector gather per state */
#pragma omp simd
            for (int j = 0; j < WFF_BLOCK; j++)
                blk.state[i][j] = sq[ns * (4 * (e0 + (j < n ? j : n - 1)) + q) + i];
        }
        wff_cell_point_block(mat, dt, &blk); /* accepted: asked before the pass */
        /* per lane: the point's force −P_mesh adj(J)ᵀ ∇_ξ N_b (P_mesh = P F_preᵀ / J_pre)
         * and amplitude force w N_b R_k / J_pre on each node b, where the point is
         * sound (a failed point adds nothing, as on the plain path) */
#pragma omp simd
        for (int j = 0; j < WFF_BLOCK; j++) {
            double w = det[j];
            double sum = blk.energy[j] + blk.dissipated[j] + blk.residual[0][j] + blk.residual[1][j];
            for (int i = 0; i < 6; i++)
                sum += blk.stress[i][j];
            int sound = finite[j] & !blk.degenerate[j] & (sum - sum == 0);
            status[q][j] = sound ? WFF_POINT_OK
                         : !finite[j] || !blk.degenerate[j] ? WFF_POINT_NONFINITE
                                                            : WFF_POINT_DEGENERATE;
            double s = sound ? -inv_J : 0, wa = sound && amplitudes ? w * inv_J : 0;
            double H[3][2]; /* −P_mesh adj(J)ᵀ */
            for (int i = 0; i < 3; i++) {
                double p0 = sound ? blk.stress[2 * i][j] : 0;
                double p1 = sound ? blk.stress[2 * i + 1][j] : 0;
                double m0 = s * (p0 * Fp[0] + p1 * Fp[1]), m1 = s * (p0 * Fp[2] + p1 * Fp[3]);
                H[i][0] = m0 * adj[0][0][j] + m1 * adj[0][1][j];
                H[i][1] = m0 * adj[1][0][j] + m1 * adj[1][1][j];
            }
            double r0 = wa * (sound ? blk.residual[0][j] : 0);
            double r1 = wa * (sound ? blk.residual[1][j] : 0);
            for (int b = 0; b < 4; b++) {
                double g0 = t->dN[q][b][0], g1 = t->dN[q][b][1];
                acc[b][0][j] += H[0][0] * g0 + H[0][1] * g1;
                acc[b][1][j] += H[1][0] * g0 + H[1][1] * g1;
                acc[b][2][j] += H[2][0] * g0 + H[2][1] * g1;
                acc[b][3][j] += t->N[q][b] * r0;
                acc[b][4][j] += t->N[q][b] * r1;
            }
            lane_energy[j] += sound ? w * blk.energy[j] : 0;
            lane_dissipated[j] += sound ? w * blk.dissipated[j] : 0;
            lane_failure[j] += sound ? w * blk.failure_dissipated[j] : 0;
            lane_slip[j] += sound ? w * blk.slip_dissipated[j] : 0;
        }
        for (int i = 0; i < ns; i++)
            for (int j = 0; j < WFF_BLOCK; j++)
                state_new[q][i][j] = blk.state[i][j];
    }
    const unsigned char *eroded = el->eroded ? el->eroded + el->n_tris : NULL;
    for (int j = 0; j < n; j++) {
        int e = e0 + j;
        double *slot = el->slot + D * (3 * (size_t)el->n_tris + 4 * (size_t)e);
        if (eroded && eroded[e]) { /* no force, no energy; its states kept */
            memset(slot, 0, sizeof(double) * D * 4);
            continue;
        }
        for (int b = 0; b < 4; b++)
            for (int c = 0; c < D; c++)
                slot[D * b + c] = acc[b][c][j];
        for (int q = 0; q < WFF_QUAD_POINTS; q++) {
            if (status[q][j] != WFF_POINT_OK) {
                note_bad_point(sums, e, q, status[q][j]); /* its state is kept */
                continue;
            }
            double *sp = sq + ns * (4 * e + q);
            for (int i = 0; i < ns; i++)
                sp[i] = state_new[q][i][j];
        }
        sums->energy += lane_energy[j];
        sums->dissipated += lane_dissipated[j];
        sums->failure += lane_failure[j];
        sums->slip += lane_slip[j];
    }
}

/* quad_block_n with one state per point (a constant: its loops fold away), and with
 * the material's n_state. */
static __attribute__((noinline)) void
quad_block_one(const wff_elements *el, const wff_element_material *em, const quad_table *t,
               const double *X, const double *u, double *state, double dt, int e0,
               int n, quad_sums *sums)
{
    quad_block_n(el, em, t, X, u, state, dt, e0, n, sums, 1);
}

static __attribute__((noinline)) void
quad_block_any(const wff_elements *el, const wff_element_material *em, const quad_table *t,
               const double *X, const double *u, double *state, double dt, int e0,
               int n, quad_sums *sums)
{
    quad_block_n(el, em, t, X, u, state, dt, e0, n, sums, em->mat->n_state);
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
    return wff_cell_point_block(em->mat, dt, &probe) == 0;
}

int WFF_KERNEL_NAME(wff_quad_block_forces)(const wff_elements *el,
                                           const wff_element_material *em, const double *X,
                                           const double *u, double *state, double dt,
                                           wff_force_totals *totals)
{
    if (el->n_quads == 0 || !wff_cell_has_point_block(em->mat) || em->reference_path ||
        em->static_amplitudes || !cell_takes_points(em, dt))
        return -1;
    quad_table gauss;
    quad_table_init(&gauss);
    const int n_blocks = (el->n_quads + WFF_BLOCK - 1) / WFF_BLOCK;
    /* the quads' blocks' sums follow the triangles' */
    const int tri_blocks = (el->n_tris + WFF_BLOCK - 1) / WFF_BLOCK;
    double *block_sums = el->block_sums + WFF_BLOCK_SUMS * (size_t)tri_blocks;
    /* small meshes are not worth a thread team (membrane.h, wff_elements_team) */
    int threads = wff_elements_team(el);
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
        quad_sums bad = {0, 0, 0, 0, -1, -1, 0};
#pragma omp for schedule(static)
        for (int blk = 0; blk < n_blocks; blk++) {
            if (el->block_run && !el->block_run[tri_blocks + blk])
                continue; /* (over ranks: another rank's block, plugin/distribute.c) */
            int e0 = blk * WFF_BLOCK;
            int n = el->n_quads - e0 < WFF_BLOCK ? el->n_quads - e0 : WFF_BLOCK;
            quad_sums sums = {0, 0, 0, 0, bad.bad_element, bad.bad_point, bad.bad_status};
            if (em->mat->n_state == 1) /* (King without failure: the state loops fold away) */
                quad_block_one(el, em, &gauss, X, u, state, dt, e0, n, &sums);
            else
                quad_block_any(el, em, &gauss, X, u, state, dt, e0, n, &sums);
            double *b = block_sums + WFF_BLOCK_SUMS * (size_t)blk;
            b[0] = sums.energy, b[1] = sums.dissipated, b[2] = sums.failure, b[3] = sums.slip;
            bad.bad_element = sums.bad_element;
            bad.bad_point = sums.bad_point;
            bad.bad_status = sums.bad_status;
        }
        part[t] = bad;
    }
    const double inv_J = 1 / em->J_pre;
    for (int blk = 0; blk < n_blocks; blk++) { /* each block's sums, order-free across blocks */
        if (el->block_count && !el->block_count[tri_blocks + blk])
            continue; /* (another rank's to add) */
        const double *b = block_sums + WFF_BLOCK_SUMS * (size_t)blk;
        for (int k = 0; k < WFF_BLOCK_SUMS; k++)
            wff_fixed_add(&totals->sums[k], b[k] * inv_J);
    }
    quad_sums all = {0, 0, 0, 0, -1, -1, 0};
    for (int t = 0; t < team; t++)
        if (part[t].bad_element >= 0)
            note_bad_point(&all, part[t].bad_element, part[t].bad_point, part[t].bad_status);
    if (all.bad_element >= 0 && totals->bad_element < 0) {
        totals->bad_element = el->n_tris + all.bad_element;
        totals->bad_point = all.bad_point;
        totals->bad_status = all.bad_status;
    }
    return 0;
}

/* The quads' pass: the blocked path above where it applies, else point by
 * point (evaluate, or the static amplitudes' Newton, at each Gauss point). */
void WFF_KERNEL_NAME(wff_quad_forces)(const wff_elements *el, const wff_element_material *em,
                                      const double *X, const double *u, double *state,
                                      double dt, wff_force_totals *totals)
{
    const wff_material *mat = em->mat;
    const int amplitudes = wff_cell_amplitudes(mat->cell);
    const int ns = mat->n_state;
    const int quads_blocked = WFF_KERNEL_NAME(wff_quad_block_forces)(
                                  el, em, X, u, state, dt, totals) == 0;
    const int tri_blocks = (el->n_tris + WFF_BLOCK - 1) / WFF_BLOCK;
    for (int e = 0; !quads_blocked && e < el->n_quads; e++) {
        int id = el->n_tris + e;
        const int block = tri_blocks + e / WFF_BLOCK;
        if (el->block_run && !el->block_run[block])
            continue; /* (over ranks: another rank's, plugin/distribute.c) */
        const int counted = !el->block_count || el->block_count[block];
        double *slot = el->slot + D * (3 * (size_t)el->n_tris + 4 * (size_t)e);
        memset(slot, 0, sizeof(double) * D * 4); /* (its points add into it) */
        if (wff_element_eroded(el, id))
            continue;
        for (int q = 0; q < WFF_QUAD_POINTS; q++) {
            const double *grad = el->quad_grad + 32 * e + 8 * q;
            double N[4], dA[2], F[6], Fe[6], Pm[6] = {0, 0, 0, 0, 0, 0};
            quad_point_kinematics(el, em, X, u, e, q, N, dA, F, Fe);
            wff_point_result r;
            double *ps = state + ns * (3 * el->n_tris + 4 * e + q);
            int point_amplitudes = amplitudes;
            double *pdA = dA;
            if (em->static_amplitudes) { /* the point's own balanced amplitudes, updated in place */
                pdA = quad_point_dA(el, e, q);
                point_amplitudes = 0;
            }
            int iterations = 0;
            int status = point_ok(em->static_amplitudes
                                      ? wff_balance_point(mat, Fe, pdA, ps, dt, &r, &iterations)
                                      : wff_material_evaluate(mat, Fe, dA, ps, dt, &r),
                                  Fe, pdA, &r);
            if (counted)
                totals->amplitude_iterations += iterations;
            if (status != WFF_POINT_OK) {
                if (status == WFF_POINT_UNBALANCED && totals->bad_element < 0) {
                    totals->bad_residual = fmax(fabs(r.residual[0]), fabs(r.residual[1]));
                    totals->bad_iterations = iterations;
                }
                note_bad(totals, id, q, status);
                continue;
            }
            for (int i = 0; i < ns; i++)
                ps[i] = r.state[i];
            double w = el->quad_weight[4 * e + q];
            preload_pull_add(em, r.stress, 1.0, Pm);
            for (int b = 0; b < 4; b++) {
                double *fb = slot + D * b;
                for (int i = 0; i < 3; i++)
                    fb[i] -= w * (Pm[2 * i] * grad[2 * b] + Pm[2 * i + 1] * grad[2 * b + 1]);
                for (int k = 0; k < point_amplitudes; k++)
                    fb[3 + k] += w * N[b] * r.residual[k] / em->J_pre;
            }
            if (!counted)
                continue; /* (its energies another rank's to add) */
            wff_fixed_add(&totals->sums[0], w * r.energy / em->J_pre);
            wff_fixed_add(&totals->sums[1], w * r.dissipated / em->J_pre);
            wff_fixed_add(&totals->sums[2], w * r.failure_dissipated / em->J_pre);
            wff_fixed_add(&totals->sums[3], w * r.slip_dissipated / em->J_pre);
        }
    }
}

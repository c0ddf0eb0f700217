/* Membrane elements, the linear triangles' internal-force pass (a kernel,
 * built once per variant): blocks of WFF_BLOCK triangles through the cell's
 * evaluate_tri_block where it takes them (dynamic or static amplitudes), else
 * one triangle at a time by evaluate_shared or evaluate at its three nodal
 * points; every path gathers a triangle's F by tri_deformation
 * (membrane_geometry.h). Each triangle writes its force on each of its nodes
 * into its own slots (el->slot; a skipped one, eroded or failed, zeros); the
 * nodes sum them in element order after the pass (wff_elements_gather), and
 * the energies are summed per block, the blocks in order: the same bits for
 * any number of threads. Threads: a team over the blocks. See
 * include/wovenff/membrane.h for the formulas. */
#include "wovenff/membrane.h"
#include "wovenff/balance.h"
#include "membrane_quad.h"
#include "membrane_geometry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
static int omp_thread(void) { return omp_get_thread_num(); }
static int omp_team(void) { return omp_get_num_threads(); }
#else
static int omp_thread(void) { return 0; }
static int omp_team(void) { return 1; }
#endif

#define D WFF_DOFS_PER_NODE

/* Sums one thread gathers over its triangles. */
typedef struct tri_sums {
    double energy, dissipated, failure, slip;
    wff_force_totals bad; /* only bad_element, bad_point, bad_status are used */
} tri_sums;

static void note_bad_sums(tri_sums *s, int e, int q, int status)
{
    if (s->bad.bad_element < 0 || e < s->bad.bad_element) {
        s->bad.bad_element = e;
        s->bad.bad_point = q;
        s->bad.bad_status = status;
    }
}

/* A point whose static-amplitude Newton did not converge: its residual and iterations too. */
static void note_unbalanced_sums(tri_sums *s, int e, int q, const double residual[2],
                                 int iterations)
{
    note_bad_sums(s, e, q, WFF_POINT_UNBALANCED);
    if (s->bad.bad_element == e && s->bad.bad_point == q) {
        s->bad.bad_residual = fmax(fabs(residual[0]), fabs(residual[1]));
        s->bad.bad_iterations = iterations;
    }
}

/* Triangle e's slots: its force on each of its three nodes, −A P_mesh ∇N_b
 * and the amplitude forces A/3 R_b / J_pre (0 without amplitudes). */
static inline __attribute__((always_inline)) void tri_slots(const wff_elements *el, const wff_element_material *em, int e,
                        const double P[6], const double *R, int amplitudes)
{
    const double *grad = el->tri_grad + 6 * e;
    double Pm[6] = {0, 0, 0, 0, 0, 0};
    preload_pull_add(em, P, 1.0, Pm);
    double area = el->tri_area[e], w = area / 3 / em->J_pre;
    for (int b = 0; b < 3; b++) {
        double *fb = el->slot + D * (3 * (size_t)e + b);
        for (int i = 0; i < 3; i++)
            fb[i] = -(area * (Pm[2 * i] * grad[2 * b] + Pm[2 * i + 1] * grad[2 * b + 1]));
        for (int k = 0; k < 2; k++)
            fb[3 + k] = k < amplitudes ? w * R[2 * b + k] : 0;
    }
}

/* Triangle e gives no force (eroded, or its point failed): zero slots. */
static inline void tri_slots_zero(const wff_elements *el, int e)
{
    memset(el->slot + D * 3 * (size_t)e, 0, sizeof(double) * D * 3);
}

/* One triangle by the general path: the cell's evaluate_shared if it has one
 * (and the reference path is not asked for), else evaluate() at each point. */
static void tri_forces(const wff_elements *el, const wff_element_material *em, const double *X,
                       const double *u, double *state, double dt, int e, tri_sums *sums)
{
    tri_slots_zero(el, e); /* (until it gives its force) */
    static const double third[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
    const wff_material *mat = em->mat;
    const int ns = mat->n_state;
    const int *node = el->tri + 3 * e;
    double F[6], Fe[6], dA[6], P[6] = {0, 0, 0, 0, 0, 0}, R[6] = {0, 0, 0, 0, 0, 0};
    double W = 0, Dis = 0, Fail = 0, Slip = 0, check = 0;
    tri_deformation(el, em, X, u, e, F, Fe);
    for (int q = 0; q < WFF_TRI_POINTS; q++) {
        dA[2 * q] = u[D * node[q] + 3];
        dA[2 * q + 1] = u[D * node[q] + 4];
        check += dA[2 * q] + dA[2 * q + 1];
    }
    for (int i = 0; i < 6; i++)
        check += Fe[i];
    if (!isfinite(check)) {
        note_bad_sums(sums, e, 0, WFF_POINT_NONFINITE);
        return;
    }
    if (wff_cell_has_shared(mat) && !em->reference_path) {
        int bad = 0;
        int status = wff_cell_evaluate_shared(mat, Fe, 3, dA, third,
                                                state + ns * 3 * e, dt, P, R, &W, &Dis,
                                                &Fail, &Slip, &bad);
        double sum = W + R[0] + R[1] + R[2] + R[3] + R[4] + R[5];
        for (int i = 0; i < 6; i++)
            sum += P[i];
        if (status == WFF_POINT_OK && !isfinite(sum))
            status = WFF_POINT_NONFINITE;
        if (status != WFF_POINT_OK) {
            note_bad_sums(sums, e, bad, status);
            return;
        }
    } else {
        for (int q = 0; q < WFF_TRI_POINTS; q++) {
            wff_point_result r;
            double *ps = state + ns * (3 * e + q);
            int status = point_ok(wff_material_evaluate(mat, Fe, dA + 2 * q, ps, dt, &r),
                                  Fe, dA + 2 * q, &r);
            if (status != WFF_POINT_OK) {
                note_bad_sums(sums, e, q, status);
                return;
            }
            for (int i = 0; i < ns; i++)
                ps[i] = r.state[i];
            for (int i = 0; i < 6; i++)
                P[i] += r.stress[i] / 3;
            R[2 * q] = r.residual[0];
            R[2 * q + 1] = r.residual[1];
            W += r.energy / 3;
            Dis += r.dissipated / 3;
            Fail += r.failure_dissipated / 3;
            Slip += r.slip_dissipated / 3;
        }
    }
    tri_slots(el, em, e, P, R, wff_cell_amplitudes(mat->cell));
    sums->energy += el->tri_area[e] * W;
    sums->dissipated += el->tri_area[e] * Dis;
    sums->failure += el->tri_area[e] * Fail;
    sums->slip += el->tri_area[e] * Slip;
}

/* n (≤ WFF_BLOCK) triangles from e0 through the cell's blocked kernel.
 * Returns -1 if the cell declines these parameters (nothing done). Lanes past
 * n repeat the last element (a valid state whose results are dropped). */
static inline __attribute__((always_inline)) int
tri_block_forces_n(const wff_elements *el, const wff_element_material *em, const double *X,
                   const double *u, double *state, double dt, int e0, int n,
                   tri_sums *sums, const int ns)
{
    const wff_material *mat = em->mat;
    wff_tri_block blk;
    blk.n = n;
    int finite[WFF_BLOCK];
    const double *Fp = em->F_pre;
    /* gather across the lanes (gcc turns the indexed loads into vector gathers) */
#pragma omp simd
    for (int j = 0; j < WFF_BLOCK; j++) {
        int e = e0 + (j < n ? j : n - 1);
        const int *node = el->tri + 3 * e;
        double F[6], Fe[6], check = 0;
        tri_deformation(el, em, X, u, e, F, Fe);
        for (int a = 0; a < 3; a++) {
            const double *ua = u + D * node[a];
            blk.dA[a][0][j] = ua[3];
            blk.dA[a][1][j] = ua[4];
            for (int i = 0; i < ns; i++) /* the points' states, n_state each */
                blk.state[a][i][j] = state[ns * (3 * e + a) + i];
            check += ua[3] + ua[4];
        }
        for (int i = 0; i < 6; i++)
            blk.F[i][j] = Fe[i];
        check += F[0] + F[1] + F[2] + F[3] + F[4] + F[5];
        finite[j] = check - check == 0; /* false for NaN and ±inf (isfinite does not vectorise) */
    }
    if (wff_cell_tri_block(mat, dt, &blk) != 0)
        return -1;
    /* per lane, vectorised: nodal force coefficients −A P_mesh (P_mesh = P F_preᵀ/J_pre),
     * amplitude force weights, and whether the lane is sound */
    double fx[6][WFF_BLOCK], wa[WFF_BLOCK];
    int ok[WFF_BLOCK];
    const double inv_J = 1 / em->J_pre;
#pragma omp simd
    for (int j = 0; j < WFF_BLOCK; j++) {
        int e = e0 + (j < n ? j : n - 1);
        double s = -el->tri_area[e] * inv_J;
        for (int i = 0; i < 3; i++) {
            double p0 = blk.stress[2 * i][j], p1 = blk.stress[2 * i + 1][j];
            fx[2 * i][j] = s * (p0 * Fp[0] + p1 * Fp[1]);
            fx[2 * i + 1][j] = s * (p0 * Fp[2] + p1 * Fp[3]);
        }
        wa[j] = el->tri_area[e] / 3 * inv_J;
        double sum = blk.energy[j] + blk.dissipated[j];
        for (int i = 0; i < 6; i++)
            sum += blk.stress[i][j];
        for (int q = 0; q < 3; q++)
            sum += blk.residual[q][0][j] + blk.residual[q][1][j];
        ok[j] = finite[j] & !blk.degenerate[j] & (sum - sum == 0);
    }
    const int amplitudes = wff_cell_amplitudes(mat->cell);
    const unsigned char *eroded = el->eroded;
    for (int j = 0; j < n; j++) {
        int e = e0 + j;
        if (eroded && eroded[e]) { /* no force, its states kept (a lane like any other above) */
            tri_slots_zero(el, e);
            continue;
        }
        if (!ok[j]) {
            tri_slots_zero(el, e);
            note_bad_sums(sums, e, 0, !finite[j] || !blk.degenerate[j] ? WFF_POINT_NONFINITE
                                                                     : WFF_POINT_DEGENERATE);
            continue;
        }
        const double *g = el->tri_grad + 6 * e;
        for (int b = 0; b < 3; b++) {
            double *fb = el->slot + D * (3 * (size_t)e + b);
            double gx = g[2 * b], gy = g[2 * b + 1];
            fb[0] = fx[0][j] * gx + fx[1][j] * gy;
            fb[1] = fx[2][j] * gx + fx[3][j] * gy;
            fb[2] = fx[4][j] * gx + fx[5][j] * gy;
            fb[3] = amplitudes ? wa[j] * blk.residual[b][0][j] : 0;
            fb[4] = amplitudes ? wa[j] * blk.residual[b][1][j] : 0;
            for (int i = 0; i < ns; i++)
                state[ns * (3 * e + b) + i] = blk.state[b][i][j];
        }
        sums->energy += el->tri_area[e] * blk.energy[j];
        sums->dissipated += el->tri_area[e] * blk.dissipated[j];
        sums->failure += el->tri_area[e] * blk.failure_dissipated[j];
        sums->slip += el->tri_area[e] * blk.slip_dissipated[j];
    }
    return 0;
}

/* tri_block_forces_n with n_state a constant where it is 1 (King without
 * failure: the loops over the states fold away, the gather joins the lanes'
 * vector loads as γᶠ's did), the material's otherwise. */
static __attribute__((noinline)) int
tri_block_forces_one(const wff_elements *el, const wff_element_material *em, const double *X,
                     const double *u, double *state, double dt, int e0, int n,
                     tri_sums *sums)
{
    return tri_block_forces_n(el, em, X, u, state, dt, e0, n, sums, 1);
}

static __attribute__((noinline)) int
tri_block_forces_any(const wff_elements *el, const wff_element_material *em, const double *X,
                     const double *u, double *state, double dt, int e0, int n,
                     tri_sums *sums)
{
    return tri_block_forces_n(el, em, X, u, state, dt, e0, n, sums, em->mat->n_state);
}

static int tri_block_forces(const wff_elements *el, const wff_element_material *em,
                            const double *X, const double *u, double *state, double dt,
                            int e0, int n, tri_sums *sums)
{
    return em->mat->n_state == 1
               ? tri_block_forces_one(el, em, X, u, state, dt, e0, n, sums)
               : tri_block_forces_any(el, em, X, u, state, dt, e0, n, sums);
}

/* One triangle with quasi-static amplitudes at its three points. */
static void tri_forces_static(const wff_elements *el, const wff_element_material *em,
                              const double *X, const double *u, double *state, double dt,
                              int e, tri_sums *sums)
{
    tri_slots_zero(el, e); /* (until it gives its force) */
    const wff_material *mat = em->mat;
    const int ns = mat->n_state;
    double F[6], Fe[6], P[6] = {0, 0, 0, 0, 0, 0}, R[6] = {0, 0, 0, 0, 0, 0}, W = 0, Dis = 0;
    double Fail = 0, Slip = 0;
    tri_deformation(el, em, X, u, e, F, Fe);
    for (int q = 0; q < WFF_TRI_POINTS; q++) {
        double *dA = el->point_dA + 6 * e + 2 * q;
        wff_point_result r;
        int iterations = 0;
        double *ps = state + ns * (3 * e + q);
        int status = point_ok(wff_balance_point(mat, Fe, dA, ps, dt, &r, &iterations), Fe, dA,
                              &r);
        sums->bad.amplitude_iterations += iterations;
        if (status == WFF_POINT_UNBALANCED) {
            note_unbalanced_sums(sums, e, q, r.residual, iterations);
            return;
        }
        if (status != WFF_POINT_OK) {
            note_bad_sums(sums, e, q, status);
            return;
        }
        for (int i = 0; i < ns; i++)
            ps[i] = r.state[i];
        for (int i = 0; i < 6; i++)
            P[i] += r.stress[i] / 3;
        W += r.energy / 3;
        Dis += r.dissipated / 3;
        Fail += r.failure_dissipated / 3;
        Slip += r.slip_dissipated / 3;
    }
    tri_slots(el, em, e, P, R, 0); /* no amplitude forces: balanced at the points */
    sums->energy += el->tri_area[e] * W;
    sums->dissipated += el->tri_area[e] * Dis;
    sums->failure += el->tri_area[e] * Fail;
    sums->slip += el->tri_area[e] * Slip;
}

/* n (≤ WFF_BLOCK) triangles from e0 with quasi-static amplitudes, blocked: per
 * quadrature point q, the Newton of the block's lanes at once (wff_balance_block,
 * the cell's amplitude_tangent_block), then the cell's evaluate_tri_block at the
 * balanced amplitudes; the same answer as tri_forces_static to round-off
 * (tested). Returns -1 if the cell has no blocked tangent or kernel or declines
 * these parameters (nothing done). Lanes past n repeat the last element. */
static inline __attribute__((always_inline)) int
tri_block_static_forces_n(const wff_elements *el, const wff_element_material *em,
                          const double *X, const double *u, double *state, double dt,
                          int e0, int n, tri_sums *sums, const int ns)
{
    const wff_material *mat = em->mat;
    wff_tri_block blk;
    wff_tangent_block tb;
    blk.n = n;
    int finite[WFF_BLOCK];
    for (int j = 0; j < WFF_BLOCK; j++) {
        int e = e0 + (j < n ? j : n - 1);
        double F[6], Fe[6], check = 0;
        tri_deformation(el, em, X, u, e, F, Fe);
        for (int i = 0; i < 6; i++) {
            blk.F[i][j] = tb.F[i][j] = Fe[i];
            check += Fe[i];
        }
        for (int q = 0; q < WFF_TRI_POINTS; q++) {
            for (int i = 0; i < ns; i++)
                blk.state[q][i][j] = state[ns * (3 * e + q) + i];
            check += el->point_dA[6 * e + 2 * q] + el->point_dA[6 * e + 2 * q + 1];
        }
        finite[j] = isfinite(check);
    }
    int iterations[WFF_TRI_POINTS][WFF_BLOCK], converged[WFF_TRI_POINTS][WFF_BLOCK];
    static const double rest[2] = {0, 0};
    for (int q = 0; q < WFF_TRI_POINTS; q++) {
        for (int j = 0; j < WFF_BLOCK; j++) {
            int e = e0 + (j < n ? j : n - 1);
            /* a non-finite lane is reported below; its Newton starts from a valid state */
            const double *dA = finite[j] ? el->point_dA + 6 * e + 2 * q : rest;
            tb.dA[0][j] = dA[0];
            tb.dA[1][j] = dA[1];
            for (int i = 0; i < ns; i++)
                tb.state[i][j] = blk.state[q][i][j];
            if (!finite[j])
                for (int i = 0; i < 6; i++)
                    tb.F[i][j] = i == 0 || i == 3 ? 1 : 0;
        }
        if (wff_balance_block(mat, &tb, iterations[q], converged[q]) != 0)
            return -1;
        for (int j = 0; j < WFF_BLOCK; j++) {
            blk.dA[q][0][j] = tb.dA[0][j];
            blk.dA[q][1][j] = tb.dA[1][j];
        }
    }
    if (wff_cell_tri_block(mat, dt, &blk) != 0)
        return -1;
    const double zero[6] = {0, 0, 0, 0, 0, 0};
    const unsigned char *eroded = el->eroded;
    for (int j = 0; j < n; j++) {
        int e = e0 + j;
        tri_slots_zero(el, e); /* (until it gives its force) */
        if (eroded && eroded[e]) /* no force; its states and amplitudes kept */
            continue;
        if (!finite[j]) {
            note_bad_sums(sums, e, 0, WFF_POINT_NONFINITE);
            continue;
        }
        double P[6], sum = blk.energy[j] + blk.dissipated[j];
        for (int i = 0; i < 6; i++)
            sum += P[i] = blk.stress[i][j];
        int unbalanced = -1;
        for (int q = WFF_TRI_POINTS - 1; q >= 0; q--) {
            double *dA = el->point_dA + 6 * e + 2 * q;
            dA[0] = blk.dA[q][0][j];
            dA[1] = blk.dA[q][1][j];
            sum += dA[0] + dA[1] + blk.residual[q][0][j] + blk.residual[q][1][j];
            sums->bad.amplitude_iterations += iterations[q][j];
            if (!converged[q][j])
                unbalanced = q;
        }
        if (blk.degenerate[j] || !isfinite(sum)) {
            note_bad_sums(sums, e, 0, blk.degenerate[j] ? WFF_POINT_DEGENERATE
                                                        : WFF_POINT_NONFINITE);
            continue;
        }
        if (unbalanced >= 0) {
            const double residual[2] = {blk.residual[unbalanced][0][j],
                                        blk.residual[unbalanced][1][j]};
            note_unbalanced_sums(sums, e, unbalanced, residual, iterations[unbalanced][j]);
            continue;
        }
        for (int q = 0; q < WFF_TRI_POINTS; q++)
            for (int i = 0; i < ns; i++)
                state[ns * (3 * e + q) + i] = blk.state[q][i][j];
        tri_slots(el, em, e, P, zero, 0); /* no amplitude forces: balanced at the points */
        sums->energy += el->tri_area[e] * blk.energy[j];
        sums->dissipated += el->tri_area[e] * blk.dissipated[j];
        sums->failure += el->tri_area[e] * blk.failure_dissipated[j];
        sums->slip += el->tri_area[e] * blk.slip_dissipated[j];
    }
    return 0;
}

/* tri_block_static_forces_n with one state per point (a constant: the state loops
 * fold away) or the material's n_state. */
static __attribute__((noinline)) int
tri_block_static_one(const wff_elements *el, const wff_element_material *em, const double *X,
                     const double *u, double *state, double dt, int e0, int n,
                     tri_sums *sums)
{
    return tri_block_static_forces_n(el, em, X, u, state, dt, e0, n, sums, 1);
}

static __attribute__((noinline)) int
tri_block_static_any(const wff_elements *el, const wff_element_material *em, const double *X,
                     const double *u, double *state, double dt, int e0, int n,
                     tri_sums *sums)
{
    return tri_block_static_forces_n(el, em, X, u, state, dt, e0, n, sums,
                                     em->mat->n_state);
}

static int tri_block_static_forces(const wff_elements *el, const wff_element_material *em,
                                   const double *X, const double *u, double *state,
                                   double dt, int e0, int n, tri_sums *sums)
{
    return em->mat->n_state == 1
               ? tri_block_static_one(el, em, X, u, state, dt, e0, n, sums)
               : tri_block_static_any(el, em, X, u, state, dt, e0, n, sums);
}

void WFF_KERNEL_NAME(wff_tri_forces)(const wff_elements *el, const wff_element_material *em,
                                     const double *X, const double *u, double *state,
                                     double dt, wff_force_totals *totals)
{
    const wff_material *mat = em->mat;
    /* small meshes are not worth a thread team (membrane.h, WFF_TEAM_MIN_TRIS) */
    int threads = wff_elements_team(el);
    wff_force_totals part_bad[WFF_MAX_THREADS];
    for (int t = 0; t < threads; t++) {
        part_bad[t].bad_element = -1;
        part_bad[t].amplitude_iterations = 0;
    }
    const int use_block = wff_cell_has_tri_block(mat) && !em->reference_path;
    const int n_blocks = (el->n_tris + WFF_BLOCK - 1) / WFF_BLOCK;
    int team = 1; /* OpenMP may start fewer threads than asked (thread limit, dynamic) */
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
        int t = omp_thread();
#pragma omp single nowait /* (read after the element loop's barrier: no barrier of its own) */
        team = omp_team();
        wff_force_totals bad;
        memset(&bad, 0, sizeof bad);
        bad.bad_element = bad.bad_point = -1;
        int blocked = use_block; /* a cell declines by its parameters: ask once per thread */
#pragma omp for schedule(static)
        for (int blk = 0; blk < n_blocks; blk++) {
            if (el->block_run && !el->block_run[blk])
                continue; /* (over ranks: another rank's block, plugin/distribute.c) */
            int e0 = blk * WFF_BLOCK;
            int n = el->n_tris - e0 < WFF_BLOCK ? el->n_tris - e0 : WFF_BLOCK;
            const int iterations_before = bad.amplitude_iterations;
            /* the block's own sums (its elements in order; the blocks added in
             * order after the pass) */
            tri_sums sums = {0, 0, 0, 0, bad};
            if (em->static_amplitudes) {
                if (blocked &&
                    tri_block_static_forces(el, em, X, u, state, dt, e0, n, &sums) != 0)
                    blocked = 0;
                if (!blocked)
                    for (int e = e0; e < e0 + n; e++) {
                        if (!wff_element_eroded(el, e))
                            tri_forces_static(el, em, X, u, state, dt, e, &sums);
                        else
                            tri_slots_zero(el, e);
                    }
            } else {
                if (blocked && tri_block_forces(el, em, X, u, state, dt, e0, n, &sums) != 0)
                    blocked = 0;
                if (!blocked)
                    for (int e = e0; e < e0 + n; e++) {
                        if (!wff_element_eroded(el, e))
                            tri_forces(el, em, X, u, state, dt, e, &sums);
                        else
                            tri_slots_zero(el, e);
                    }
            }
            double *b = el->block_sums + WFF_BLOCK_SUMS * (size_t)blk;
            b[0] = sums.energy, b[1] = sums.dissipated, b[2] = sums.failure, b[3] = sums.slip;
            bad = sums.bad;
            if (el->block_count && !el->block_count[blk]) /* (a block another rank counts) */
                bad.amplitude_iterations = iterations_before;
        }
        part_bad[t] = bad;
    }
    const double inv_J = 1 / em->J_pre;
    for (int blk = 0; blk < n_blocks; blk++) { /* each block's sums, order-free across blocks */
        if (el->block_count && !el->block_count[blk])
            continue; /* (another rank's to add) */
        const double *b = el->block_sums + WFF_BLOCK_SUMS * (size_t)blk;
        for (int k = 0; k < WFF_BLOCK_SUMS; k++)
            wff_fixed_add(&totals->sums[k], b[k] * inv_J);
    }
    for (int t = 0; t < team; t++) {
        totals->amplitude_iterations += part_bad[t].amplitude_iterations;
        if (part_bad[t].bad_element >= 0 &&
            (totals->bad_element < 0 || part_bad[t].bad_element < totals->bad_element)) {
            totals->bad_element = part_bad[t].bad_element;
            totals->bad_point = part_bad[t].bad_point;
            totals->bad_status = part_bad[t].bad_status;
            totals->bad_residual = part_bad[t].bad_residual;
            totals->bad_iterations = part_bad[t].bad_iterations;
        }
    }
}

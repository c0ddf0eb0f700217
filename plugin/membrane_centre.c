/* Membrane elements: the state and point evaluation at an element's centre
 * (for output), and the stable explicit step over all elements (a blocked,
 * vectorised scan of the triangles where the cell offers wave_speeds_block).
 * See include/wovenff/membrane.h for the formulas. Knows the cells' ops and
 * the element geometry; nothing of the model, integrator or FreeFEM. */
#include "wovenff/membrane.h"
#include "wovenff/balance.h"
#include "membrane_geometry.h"
#include "membrane_quad.h" /* this build's entry points */

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#define D WFF_DOFS_PER_NODE

/* wff_element_center_state, this build's own (the stable step's; out of line,
 * as the public function it was). */
static __attribute__((noinline)) void center_state(const wff_elements *el, const double *X,
                                                   const double *u, int e, double F[6],
                                                   double dA[2])
{
    if (e < el->n_tris) {
        const int *node = el->tri + 3 * e;
        tri_gradient(el, X, u, e, F);
        dA[0] = dA[1] = 0;
        for (int a = 0; a < 3; a++) {
            dA[0] += u[D * node[a] + 3] / 3;
            dA[1] += u[D * node[a] + 4] / 3;
        }
        return;
    }
    int qe = e - el->n_tris;
    const int *node = el->quad + 4 * qe;
    double grad[4][2];
    quad_gradients(X, node, 0, 0, grad);
    deformation_gradient(X, u, node, 4, &grad[0][0], F);
    dA[0] = dA[1] = 0;
    for (int a = 0; a < 4; a++) {
        dA[0] += u[D * node[a] + 3] / 4;
        dA[1] += u[D * node[a] + 4] / 4;
    }
}

/* Element mean of the points' own amplitudes (static amplitudes). */
static void static_mean_dA(const wff_elements *el, int e, double dA[2])
{
    int n = e < el->n_tris ? 3 : 4;
    const double *p = e < el->n_tris ? el->point_dA + 6 * e
                                     : el->point_dA + 6 * el->n_tris + 8 * (e - el->n_tris);
    dA[0] = dA[1] = 0;
    for (int q = 0; q < n; q++) {
        dA[0] += p[2 * q] / n;
        dA[1] += p[2 * q + 1] / n;
    }
}

/* The functions the rest of the library calls (for output): defined once, by
 * the baseline build (kernel_name.h). */
#if WFF_KERNEL_PRIMARY
void wff_element_center_state(const wff_elements *el, const double *X, const double *u, int e,
                              double F[6], double dA[2])
{
    center_state(el, X, u, e, F, dA);
}

int wff_element_center_eval(const wff_elements *el, const wff_element_material *em,
                            const double *X, const double *u, const double *state, int e,
                            wff_point_result *out)
{
    double mean[WFF_STATE_MAX] = {0};
    const int n = e < el->n_tris ? 3 : 4, ns = em->mat->n_state;
    const double *g = state + ns * wff_element_first_point(el->n_tris, e);
    for (int q = 0; q < n; q++)
        for (int i = 0; i < ns; i++)
            mean[i] += g[ns * q + i] / n;
    return wff_element_center_eval_state(el, em, X, u, mean, e, out);
}

int wff_element_center_eval_state(const wff_elements *el, const wff_element_material *em,
                                  const double *X, const double *u, const double *held, int e,
                                  wff_point_result *out)
{
    double F[6], Fe[6], dA[2];
    center_state(el, X, u, e, F, dA);
    if (em->static_amplitudes)
        static_mean_dA(el, e, dA);
    preload_apply(em, F, Fe);
    return wff_material_evaluate(em->mat, Fe, dA, held, 0, out);
}
#endif

/* An element's stable step from its size and its cell's wave speeds:
 * membrane waves alone: dt_m = h/c; amplitude oscillator alone: dt_A = 2/ω.
 * Coupled (∂R/∂F ≠ 0), the largest frequency of a positive semi-definite
 * stiffness [[K_mm, K_ma], [K_am, K_aa]] is at most the sum of the blocks'
 * (|xᵀK_ma y|² ≤ xᵀK_mm x · yᵀK_aa y), so ω² ≤ ω_m² + ω_A² and
 * dt = 1/sqrt(1/dt_m² + 1/dt_A²): a bound where min(dt_m, dt_A) was a few
 * percent optimistic when the two are close. */
static inline double element_stable_dt(double size, double speed, double omega,
                                       double amplitude_factor, int static_amplitudes)
{
    double dt = size / speed;
    if (omega > 0 && !static_amplitudes) {
        double dt_amp = 2 / omega * sqrt(amplitude_factor);
        dt = 1 / sqrt(1 / (dt * dt) + 1 / (dt_amp * dt_amp));
    }
    return dt;
}

/* The larger of a and b, NaN if b is (a NaN speed must reach the scan's test). */
static inline double max_or_nan(double a, double b)
{
    return b > a || b != b ? b : a;
}

/* The stable-step scan over triangles e0 .. e0 + n − 1 through the cell's
 * wave_speeds_block: each lane the element's F of wff_element_center_state
 * with the preload applied, at each vertex's ΔA in turn (the scalar scan's
 * order); the
 * smallest step and its element into *mine, *mine_e as the scalar scan does
 * (elements in order, a NaN step taken). Lanes past n repeat the last element.
 * Returns -1 if the cell declines these parameters (nothing done). */
static int tri_block_stable_step(const wff_elements *el, const wff_element_material *em,
                                 const double *X, const double *u, int e0, int n,
                                 double amplitude_factor, double *mine, int *mine_e)
{
    const wff_material *mat = em->mat;
    wff_wave_block blk;
    double vertex_dA[3][2][WFF_BLOCK];
#pragma omp simd
    for (int j = 0; j < WFF_BLOCK; j++) {
        int e = e0 + (j < n ? j : n - 1);
        const int *node = el->tri + 3 * e;
        double F[6], Fe[6];
        tri_deformation(el, em, X, u, e, F, Fe);
        for (int a = 0; a < 3; a++) {
            const double *ua = u + D * node[a];
            vertex_dA[a][0][j] = ua[3];
            vertex_dA[a][1][j] = ua[4];
        }
        for (int i = 0; i < 6; i++)
            blk.F[i][j] = Fe[i];
    }
    /* the points of the nodal quadrature are the vertices, each at its own ΔA:
     * the largest speed and frequency over the three (the mean's was 1.36-2.1 x
     * the critical step on node-to-node rough compaction) */
    double speed[WFF_BLOCK] = {0}, omega[WFF_BLOCK] = {0};
    for (int a = 0; a < 3; a++) {
        for (int j = 0; j < WFF_BLOCK; j++) {
            blk.dA[0][j] = vertex_dA[a][0][j];
            blk.dA[1][j] = vertex_dA[a][1][j];
        }
        if (wff_cell_wave_block(mat, &blk) != 0)
            return -1;
        for (int j = 0; j < WFF_BLOCK; j++) {
            speed[j] = max_or_nan(speed[j], blk.membrane_speed[j]);
            omega[j] = max_or_nan(omega[j], blk.amplitude_omega[j]);
        }
    }
    const unsigned char *eroded = el->eroded;
    for (int j = 0; j < n; j++) {
        if (eroded && eroded[e0 + j]) /* sets no step */
            continue;
        double dt = element_stable_dt(el->size[e0 + j], speed[j], omega[j], amplitude_factor, 0);
        if (!(dt >= *mine)) { /* also catches NaN */
            *mine = dt;
            *mine_e = e0 + j;
        }
    }
    return 0;
}

double WFF_KERNEL_NAME(wff_elements_stable_step)(const wff_elements *el,
                                                 const wff_element_material *em,
                                                 const double *X, const double *u, int *worst)
{
    const wff_material *mat = em->mat;
    double amplitude_factor = em->amplitude_mass_factor > 0 ? em->amplitude_mass_factor : 1;
    double best = INFINITY;
    int n = el->n_tris + el->n_quads, best_e = -1;
    int threads = wff_elements_team(el);
    /* triangles in blocks through the cell's vectorised wave speeds where it has them
     * (not for static amplitudes, whose mean ΔA is the points', nor the reference path) */
    const int use_block = wff_cell_has_wave_block(mat) && !em->static_amplitudes &&
                          !em->reference_path;
    const int n_blocks = use_block ? (el->n_tris + WFF_BLOCK - 1) / WFF_BLOCK : 0;
    int first_scalar = use_block ? el->n_tris : 0;
#pragma omp parallel num_threads(threads) if (threads > 1)
    {
        double mine = INFINITY;
        int mine_e = -1;
#pragma omp for schedule(static)
        for (int blk = 0; blk < n_blocks; blk++) {
            int e0 = blk * WFF_BLOCK;
            int nb = el->n_tris - e0 < WFF_BLOCK ? el->n_tris - e0 : WFF_BLOCK;
            if (tri_block_stable_step(el, em, X, u, e0, nb, amplitude_factor, &mine,
                                      &mine_e) != 0) {
#pragma omp atomic write
                first_scalar = 0; /* declined (by the parameters: every block alike) */
            }
        }
#pragma omp for schedule(static)
        for (int e = first_scalar; e < n; e++) {
            if (wff_element_eroded(el, e)) /* sets no step */
                continue;
            double F[6], Fe[6], dA[2], speed = 0, omega = 0;
            center_state(el, X, u, e, F, dA);
            preload_apply(em, F, Fe);
            if (em->static_amplitudes) { /* no amplitude limit: the points' mean ΔA */
                static_mean_dA(el, e, dA);
                wff_cell_wave_speeds(mat, Fe, dA, &speed, &omega);
            } else if (e < el->n_tris) { /* F constant; the points are the vertices (§8) */
                const int *node = el->tri + 3 * e;
                for (int a = 0; a < 3; a++) {
                    const double nodal[2] = {u[D * node[a] + 3], u[D * node[a] + 4]};
                    double s, w;
                    wff_cell_wave_speeds(mat, Fe, nodal, &s, &w);
                    speed = max_or_nan(speed, s);
                    omega = max_or_nan(omega, w);
                }
            } else { /* quads: the centre's F at each 2x2 Gauss point's ΔA (the nodes'
                      * interpolated), the largest speed and frequency of the four (the
                      * centre's mean ΔA was 0.84 x the critical step on node-to-node rough
                      * amplitudes, tests/c/test_stable_bound.c) */
                static const double xi[4] = {-1, 1, 1, -1}, eta[4] = {-1, -1, 1, 1};
                const double g = 0.57735026918962576; /* 1/sqrt(3) */
                const int *node = el->quad + 4 * (e - el->n_tris);
                for (int q = 0; q < 4; q++) {
                    double point[2] = {0, 0}, s, w;
                    for (int b = 0; b < 4; b++) {
                        double N = 0.25 * (1 + xi[b] * xi[q] * g) * (1 + eta[b] * eta[q] * g);
                        point[0] += N * u[D * node[b] + 3];
                        point[1] += N * u[D * node[b] + 4];
                    }
                    wff_cell_wave_speeds(mat, Fe, point, &s, &w);
                    speed = max_or_nan(speed, s);
                    omega = max_or_nan(omega, w);
                }
            }
            double dt = element_stable_dt(el->size[e], speed, omega, amplitude_factor,
                                          em->static_amplitudes);
            if (!(dt >= mine)) { /* also catches NaN */
                mine = dt;
                mine_e = e;
            }
        }
#pragma omp critical(wff_stable_step)
        { /* the smallest step; on a tie the lowest element, whatever the thread order */
            if (mine_e >= 0 && (best_e < 0 || !(mine >= best) ||
                                (mine == best && mine_e < best_e))) {
                best = mine;
                best_e = mine_e;
            }
        }
    }
    *worst = best_e;
    return best;
}

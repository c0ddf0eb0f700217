/* wovenff — static through-thickness balance (King 2005, eq. 2) with GSL.
 *
 * Given F, find the amplitude changes dA with R_k(F, dA) = 0: the crossover
 * force F_I balances the normal force of each yarn family. On top of it,
 * in-plane biaxial states: each direction either holds a stretch or a
 * membrane resultant P_kk (N/m), the others free of shear (F diagonal); the
 * picture-frame shear state; and the per-point Newton solve of the
 * static-amplitude path (docs/model.md §5, §13). */
#ifndef WOVENFF_BALANCE_H
#define WOVENFF_BALANCE_H

#include <math.h>

#include "wovenff/cell.h"
#include "wovenff/cell_ops.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Solve R(F, dA) = 0 for dA (in: first guess, out: solution) with the
 * point's internal state (mat->n_state values; NULL: all 0) held. Fails
 * (naming the state) if GSL does not converge. */
int wff_balance_amplitudes(const wff_material *mat, const double F[6], const double *state,
                           double dA[2], wff_error *err);

typedef enum wff_hold {
    WFF_HOLD_STRETCH = 0,      /* target is λ_k */
    WFF_HOLD_RESULTANT = 1,    /* target is P_kk, N/m */
    WFF_HOLD_YARN_TENSION = 2  /* target is the tension of one yarn of family k, N
                                  (the cell's yarn_tension_diag) */
} wff_hold;

typedef struct wff_biaxial_state {
    double stretch[2];     /* λ_1, λ_2: F = diag(λ_1, λ_2) in the plane */
    double dA[2];          /* ΔA_1, ΔA_2, m */
    double resultant[2];   /* P_11, P_22, N/m */
    wff_point_result point;/* the full point evaluation at the solution */
} wff_biaxial_state;

/* Biaxial static state: for direction k, hold[k] says whether target[k] is a
 * stretch, a resultant P_kk (N/m) or a yarn tension (N). state holds the first guess on entry
 * (stretch for free directions, dA) and the solution on return. */
int wff_biaxial_static(const wff_material *mat, const wff_hold hold[2], const double target[2],
                       const double *point_state, wff_biaxial_state *state,
                       wff_error *err);

/* Equal-force biaxial preload: every yarn of both families carries the
 * tension yarn_force (N), amplitudes balanced, no shear. This is how the paper
 * found F_pre and dA⁰ (its §4). */
int wff_preload_equal_force(const wff_material *mat, double yarn_force,
                            wff_biaxial_state *state, wff_error *err);

/* Membrane forces per mesh width σ11 = P11 / a2, σ22 = P22 / a1 (σ = P F_preᵀ /
 * J_pre for a diagonal F_pre = diag(a1, a2)) of material mat at the preload
 * diag(a), amplitudes dA, γᶠ = 0; -1 when the point fails or they are not
 * finite. */
int wff_preload_forces(const wff_material *mat, const double a[2], const double dA[2],
                       double sigma[2]);
/* The diagonal stretch diag(a1, a2) of mat (amplitudes 0) whose membrane forces
 * are target (N/m), by Newton from a0 with a central-difference Jacobian: a
 * zone's matched preload (zones.c). 0 with it in a_out, -1 if none is found. */
int wff_preload_matched(const wff_material *mat, const double target[2], const double a0[2],
                        double a_out[2]);

/* Quasi-static uniaxial strip: family `family` (0 warp, 1 weft) stretched to
 * `stretch`, the other direction free (P_ll = 0), amplitudes balanced. */
int wff_uniaxial_static(const wff_material *mat, int family, double stretch,
                        wff_biaxial_state *state, wff_error *err);

/* Picture-frame static state: symmetric pure shear
 *   F = [cos(γ/2) sin(γ/2); sin(γ/2) cos(γ/2); 0 0]
 * (yarns keep their length, the angle between them is π/2 − γ), amplitudes
 * in balance (dA: first guess in, solution out), γᶠ = 0. *shear_resultant =
 * S = ∂W/∂γ (N/m); point (may be NULL) gets the full evaluation. */
int wff_shear_static(const wff_material *mat, double gamma, double dA[2],
                     double *shear_resultant, wff_point_result *point, wff_error *err);

/* The static-amplitude Newton (membrane_tri.c, membrane_quad.c; docs/model.md §13): bounds and
 * tolerance. Converged when the Newton step's largest component is below
 * WFF_BALANCE_STEP_TOLERANCE (the step is applied: with the exact tangent the
 * error left is of the order of its square); a step is limited to
 * WFF_BALANCE_STEP_LIMIT (the compaction exponential is steep). */
#define WFF_BALANCE_MAX_ITERATIONS 50
#define WFF_BALANCE_STEP_TOLERANCE 1e-13 /* m: amplitudes are ~1e-5 m */
#define WFF_BALANCE_STEP_LIMIT 1e-5      /* m */

/* wff_amplitude_tangent (R_k and ∂R_k/∂ΔA_m at one point, the cell's op or
 * forward differences of evaluate()) is in wovenff/cell_ops.h. */

/* One Newton update ΔA −= K⁻¹R (K = tangent, row-major), limited to
 * WFF_BALANCE_STEP_LIMIT, applied to dA when `apply`. Returns the full
 * step's largest component (m), or −1 (dA unchanged) when K is singular or
 * the step not finite. Branch-free: the blocked path calls it in its lane loop
 * (so both paths make the same updates). */
static inline __attribute__((always_inline)) double
wff_balance_newton_step(const double residual[2], const double tangent[4], double dA[2],
                        int apply)
{
    double det = tangent[0] * tangent[3] - tangent[1] * tangent[2];
    double s0 = (-residual[0] * tangent[3] + residual[1] * tangent[1]) / det;
    double s1 = (-residual[1] * tangent[0] + residual[0] * tangent[2]) / det;
    double big = fmax(fabs(s0), fabs(s1));
    int ok = (fabs(det) > 0) & (big - big == 0); /* (isfinite does not vectorise) */
    double scale = big > WFF_BALANCE_STEP_LIMIT ? WFF_BALANCE_STEP_LIMIT / big : 1.0;
    int take = ok & (apply != 0);
    dA[0] += take ? scale * s0 : 0.0;
    dA[1] += take ? scale * s1 : 0.0;
    return ok ? big : -1.0;
}

/* Quasi-static amplitudes at one point, for the elements' static-amplitude
 * path (membrane_tri.c, membrane_quad.c; docs/model.md §13): Newton on R(F, ΔA) = 0 with the
 * cell's tangent (wff_amplitude_tangent, the state held), from the point's last ΔA
 * (dA: in and out), at most WFF_BALANCE_MAX_ITERATIONS tangents (their count
 * into *iterations); then the evaluation with the step dt into out. Returns
 * the evaluation's status, or WFF_POINT_UNBALANCED when Newton did not
 * converge (out then holds the evaluation at the last ΔA, its residual what
 * is left). No allocation, no GSL: it runs at every quadrature point of every
 * step. The plain reference path; the blocked one is wff_balance_block.
 * Defined here (static) so that it is compiled with its caller's flags, the
 * kernels', and kept out of line (noinline) so that the element loops that
 * call it keep their size and speed. */
static __attribute__((noinline, unused)) int
wff_balance_point(const wff_material *mat, const double Fe[6], double dA[2], const double *state,
                  double dt, wff_point_result *out, int *iterations)
{
    int it = 0, converged = 0;
    while (!converged && it < WFF_BALANCE_MAX_ITERATIONS) {
        double residual[2], tangent[4];
        it++;
        if (wff_amplitude_tangent(mat, Fe, dA, state, residual, tangent) != WFF_POINT_OK)
            break;
        double big = wff_balance_newton_step(residual, tangent, dA, 1);
        if (!(big >= 0))
            break;
        converged = big < WFF_BALANCE_STEP_TOLERANCE;
    }
    *iterations = it;
    int status = wff_material_evaluate(mat, Fe, dA, state, dt, out);
    if (status == WFF_POINT_OK && !converged && isfinite(out->residual[0] + out->residual[1]))
        return WFF_POINT_UNBALANCED;
    return status;
}

/* The same Newton for a block of WFF_BLOCK points, lanes in lockstep (a lane
 * that converged or failed holds), with the cell's amplitude_tangent_block:
 * blk holds F, the state and the first guesses ΔA on entry, the solutions on
 * return; iterations[b] the tangents lane b used, converged[b] 1 where it
 * converged (0: degenerate, singular or out of iterations; the caller
 * reports it). Returns −1, with nothing changed, when the cell has no
 * blocked tangent or declines these parameters. */
static inline int wff_balance_block(const wff_material *mat, wff_tangent_block *blk,
                                    int iterations[WFF_BLOCK], int converged[WFF_BLOCK])
{
    if (!wff_cell_has_tangent_block(mat))
        return -1;
    int active[WFF_BLOCK];
    for (int b = 0; b < WFF_BLOCK; b++) {
        active[b] = 1;
        iterations[b] = 0;
        converged[b] = 0;
    }
    for (int it = 0; it < WFF_BALANCE_MAX_ITERATIONS; it++) {
        if (wff_cell_tangent_block(mat, blk) != 0)
            return -1; /* on the parameters: only ever at the first iteration */
        int any = 0;
#ifndef __cplusplus /* (the C++ binding sees this header without OpenMP) */
#pragma omp simd reduction(| : any)
#endif
        for (int b = 0; b < WFF_BLOCK; b++) {
            const double residual[2] = {blk->residual[0][b], blk->residual[1][b]};
            const double tangent[4] = {blk->tangent[0][b], blk->tangent[1][b],
                                       blk->tangent[2][b], blk->tangent[3][b]};
            double dA[2] = {blk->dA[0][b], blk->dA[1][b]};
            int sound = active[b] & !blk->degenerate[b];
            double big = wff_balance_newton_step(residual, tangent, dA, sound);
            int done = sound & (big >= 0) & (big < WFF_BALANCE_STEP_TOLERANCE);
            iterations[b] += active[b];
            converged[b] |= done;
            active[b] = sound & (big >= 0) & !done;
            blk->dA[0][b] = dA[0];
            blk->dA[1][b] = dA[1];
            any |= active[b];
        }
        if (!any)
            break;
    }
    return 0;
}

#ifdef __cplusplus
}
#endif
#endif

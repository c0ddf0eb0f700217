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

#ifdef __cplusplus
extern "C" {
#endif

/* Solve R(F, dA) = 0 for dA (in: first guess, out: solution) with gamma_f
 * held. Fails (naming the state) if GSL does not converge. */
int wff_balance_amplitudes(const wff_material *mat, const double F[6], double gamma_f,
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
                       double gamma_f, wff_biaxial_state *state, wff_error *err);

/* Equal-force biaxial preload: every yarn of both families carries the
 * tension yarn_force (N), amplitudes balanced, no shear. This is how the paper
 * found F_pre and dA⁰ (its §4). */
int wff_preload_equal_force(const wff_material *mat, double yarn_force,
                            wff_biaxial_state *state, wff_error *err);

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

/* Quasi-static amplitudes at one point, for the elements' static-amplitude
 * path (membrane.c; docs/model.md §13): Newton on R(F, ΔA) = 0 with a
 * finite-difference Jacobian (γᶠ held), from the point's last ΔA (dA: in and
 * out); then the evaluation with the step dt into out, whose status it
 * returns. Falls back to the last ΔA if Newton fails to reduce the residual
 * (the point is then reported by its result). No allocation, no GSL: it runs
 * at every quadrature point of every step. Defined here (static) so that it
 * is compiled with its caller's flags, the kernels' (the static-amplitude
 * results stay bit-identical), and kept out of line (noinline) so that the
 * element loops that call it keep their size and speed. */
static __attribute__((noinline, unused)) int
wff_balance_point(const wff_material *mat, const double Fe[6], double dA[2], double gf, double dt,
                  wff_point_result *out)
{
    const double h = 1e-9; /* m: amplitudes are ~1e-5 m */
    for (int it = 0; it < 12; it++) {
        wff_point_result r0, r1, r2;
        if (mat->cell->evaluate(mat->params, Fe, dA, gf, 0, &r0) != WFF_POINT_OK)
            break;
        double d1[2] = {dA[0] + h, dA[1]}, d2[2] = {dA[0], dA[1] + h};
        mat->cell->evaluate(mat->params, Fe, d1, gf, 0, &r1);
        mat->cell->evaluate(mat->params, Fe, d2, gf, 0, &r2);
        double j11 = (r1.residual[0] - r0.residual[0]) / h, j21 = (r1.residual[1] - r0.residual[1]) / h;
        double j12 = (r2.residual[0] - r0.residual[0]) / h, j22 = (r2.residual[1] - r0.residual[1]) / h;
        double det = j11 * j22 - j12 * j21;
        if (!(fabs(det) > 0) || !isfinite(det))
            break;
        double s0 = (-r0.residual[0] * j22 + r0.residual[1] * j12) / det;
        double s1 = (-r0.residual[1] * j11 + r0.residual[0] * j21) / det;
        /* limit a step to 10 µm: the compaction exponential is steep */
        double big = fmax(fabs(s0), fabs(s1)), scale = big > 1e-5 ? 1e-5 / big : 1;
        dA[0] += scale * s0;
        dA[1] += scale * s1;
        if (big < 1e-13)
            break;
    }
    return mat->cell->evaluate(mat->params, Fe, dA, gf, dt, out);
}

#ifdef __cplusplus
}
#endif
#endif

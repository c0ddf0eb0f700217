/* wovenff — static through-thickness balance (King 2005, eq. 2) with GSL.
 *
 * Given F, find the amplitude changes dA with R_k(F, dA) = 0: the crossover
 * force F_I balances the normal force of each yarn family. On top of it,
 * in-plane biaxial states: each direction either holds a stretch or a
 * membrane resultant P_kk (N/m), the others free of shear (F diagonal). */
#ifndef WOVENFF_BALANCE_H
#define WOVENFF_BALANCE_H

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

#ifdef __cplusplus
}
#endif
#endif

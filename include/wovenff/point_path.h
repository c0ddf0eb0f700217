/* wovenff — one material point driven along a load path, for the unit-cell
 * explorer.
 *
 * A path is a chain of segments: over one segment the deformation gradient F
 * goes linearly in time from F_a to F_b. Along it the point's state follows
 * either or both of
 *   dynamic amplitudes   (ρ_A/6) d²ΔA_k/dt² = R_k (docs/model.md §5), central
 *                        differences without damping (§14), the step
 *                        step_safety × 2/ω with ω the cell's own amplitude_omega
 *                        (wave_speeds, §12) at the segment's start;
 *   shear flow           γᶠ by the cell's flow rule (backward Euler, §7).
 * With neither the state is left as it is (a static path balances its
 * amplitudes itself, wff_balance_amplitudes). Knows no mesh, no file, no
 * script: one point, one material. */
#ifndef WOVENFF_POINT_PATH_H
#define WOVENFF_POINT_PATH_H

#include "wovenff/cell.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Defaults the explorer uses. */
#define WFF_PATH_STEP_SAFETY 0.4  /* dt = 0.4 × 2/ω: well inside the stability limit */
#define WFF_PATH_FLOW_SUBSTEPS 10 /* γᶠ steps per segment when the amplitudes are held */

typedef struct wff_point_state {
    double dA[2];         /* ΔA_k, m */
    double velocity[2];   /* dΔA_k/dt, m/s (dynamic amplitudes; else 0) */
    double state[WFF_STATE_MAX]; /* the point's internal state (mat->n_state entries;
                                    King: state[0] = γᶠ, rad) */
    double previous_step; /* the last amplitude step, s (0 before the first: the
                             first velocity update is then a half step) */
    long substeps;        /* amplitude or flow steps taken so far */
    double dissipated[3]; /* J/m² dissipated along the path so far: by shear flow,
                             yarn failure (the stored energy damage released) and
                             yarn slip (docs/model.md §7, §20, §24) */
} wff_point_state;

typedef struct wff_path_mode {
    int dynamic_amplitudes; /* 1: amplitudes by central differences; needs a cell
                               with amplitudes (n_amplitudes > 0) */
    int shear_flow;         /* 1: γᶠ advances by the flow rule; 0: held */
    double step_safety;     /* in (0, 1]: dt = step_safety × 2/ω */
    int flow_substeps;      /* >= 1: γᶠ steps per segment with held amplitudes */
} wff_path_mode;

/* Advance state over one segment, F linear in time from F_a to F_b over
 * duration (s, > 0). Fails naming the reason (a degenerate point, a cell
 * without amplitudes asked for dynamic ones, no finite amplitude frequency). */
int wff_point_path_segment(const wff_material *mat, const double F_a[6], const double F_b[6],
                           double duration, const wff_path_mode *mode, wff_point_state *state,
                           wff_error *err);

/* A static level: the point at F with its amplitudes in balance and its
 * internal states advanced over dt (> 0) from those of the level before (the
 * slips' return map, yarn damage; γᶠ by the flow rule when shear_flow, else
 * held), the two solved in turn until neither moves: the amplitudes balanced
 * with the states held (wff_balance_amplitudes), then the states advanced
 * from the level before at those amplitudes, up to WFF_PATH_STATIC_ROUNDS
 * times. The dissipation of the states' last advance is added to
 * state->dissipated. Returns the rounds taken (>= 1), or −1 with err set (a
 * balance that fails, a degenerate point, no agreement within the rounds). */
#define WFF_PATH_STATIC_ROUNDS 200
int wff_point_path_static_level(const wff_material *mat, const double F[6], double dt,
                                int shear_flow, wff_point_state *state, wff_error *err);

/* The pull-out level: family 1 pulled to the stretch stretch1 while family 2
 * carries the yarn tension tension2 (N, the cell's yarn_tension_diag: the
 * crossing yarns held at a pretension, as a pull-out test's fixture holds
 * them), unsheared: F = diag(stretch1, λ_2) with λ_2 solved (secant, from
 * F[3] on entry as the guess) so that the static level there
 * (wff_point_path_static_level, from the states in state) gives T_2 =
 * tension2 to 1e-9 N. F (in: the last level's, out: this one's), state
 * updated. Returns 0, or −1 with err set (a cell without yarn tensions, no
 * λ_2 found in 60 trials, a static level that fails). */
int wff_point_path_pull_level(const wff_material *mat, double stretch1, double tension2,
                              double dt, wff_point_state *state, double F[6], wff_error *err);

/* What the explorer records at one level of a path. */
typedef struct wff_point_record {
    double stretch[2];        /* λ_k = |F E_k|, - */
    double shear_angle;       /* γ = asin(g_1·g_2 / λ_1λ_2), rad (θ = 90° − γ) */
    wff_point_result point;   /* P, R, W, the cell's diagnostics (γᶠ held) */
    int n_mech;               /* entries of mech_energy (0: the cell has no split) */
    double mech_energy[WFF_MECH_MAX]; /* stored energy per mechanism, J/m² */
    double amplitude_kinetic; /* ½ (ρ_A/6) |dΔA/dt|², J/m² */
} wff_point_record;

/* Evaluate the point at F with the state's amplitudes and γᶠ. Fails on a
 * degenerate point, naming F and the material. */
int wff_point_path_record(const wff_material *mat, const double F[6],
                          const wff_point_state *state, wff_point_record *rec, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

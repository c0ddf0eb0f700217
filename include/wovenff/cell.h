/* wovenff — the weave unit-cell interface.
 *
 * A unit cell turns the membrane deformation gradient F (3x2), the changes in
 * crimp amplitude dA and the point's internal state (n_state values the cell
 * names: King's dissipative shear angle gamma_f, ...) at one material point
 * into a membrane stress resultant, amplitude residuals, an updated state,
 * stored energy and diagnostics. It is pure pointwise physics: no mesh, no I/O, no
 * allocation.
 *
 * A cell is a constant ops table (in the spirit of SUNDIALS' N_Vector):
 *
 *   required   parse, evaluate, wave_speeds
 *   optional   energy_split, evaluate_shared, evaluate_tri_block,
 *              reference_geometry, amplitude_tangent, amplitude_tangent_block,
 *              evaluate_point_block (NULL when absent)
 *
 * and registers itself by name in its own source file with
 * WFF_REGISTER_CELL(table). Nothing outside that file names a cell: the
 * material file's `cell = NAME` line selects it through wff_cell_find().
 *
 * The contract (docs/model.md §10 lists the checks; tests/c/lib/cell_suite.c
 * runs them on every registered cell):
 *   - Reentrant. The ops run inside OpenMP loops, many threads at once on
 *     the same params: no static mutable state, nothing written but the
 *     outputs given; params are read only after parse().
 *   - Static names. diag_names, diag_units, mech_names, state_names and
 *     state_units (and name, summary) live as long as the program: static
 *     storage, never freed or rewritten.
 *   - Sizes. n_amplitudes is 0 or 2 (WFF_AMPLITUDES_MAX); n_diag <=
 *     WFF_DIAG_MAX; n_mech <= WFF_MECH_MAX; parse()'s struct fits in
 *     WFF_CELL_PARAMS_MAX doubles; 0 <= mat->n_state <= n_state_max <=
 *     WFF_STATE_MAX.
 *   - Internal state. A point carries mat->n_state doubles (parse sets the
 *     count: a prefix of state_names), every one 0 at the start (the
 *     reference state is state 0 everywhere). evaluate reads them and writes
 *     the updated values to out->state[0 .. n_state−1] (entries beyond are
 *     not read by callers). A state never changes in a dt = 0 evaluation
 *     (held): then out->state equals the input. damage_state[k] names the
 *     state holding yarn family k's damage (0 intact .. 1 ruptured, never
 *     decreasing) or is −1. A state named "element_length" (unit m;
 *     WFF_ELEMENT_LENGTH_STATE) is not the cell's: the element code sets it,
 *     for every point, to the characteristic length of the point's element
 *     (yarn failure's crack band, docs/model.md §20: sqrt(2 × area) for a
 *     triangle, sqrt(area) for a quad) when the model is built, a zone
 *     assigned or the mesh transferred; the cell reads it and never changes
 *     it (dt > 0 or not), and 0 (a point outside any mesh: the cell suite,
 *     the explorer, wff_rest_state) means no element size. A cell with
 *     n_state 0 gets a valid pointer it must not read.
 *   - Statuses. evaluate and evaluate_shared return WFF_POINT_OK or
 *     WFF_POINT_DEGENERATE; the element code adds WFF_POINT_NONFINITE for a
 *     NaN or infinite state or result (a cell need not check for it).
 *   - Exact derivatives. With dt = 0, stress = dW/dF and residual = −dW/d(dA)
 *     (central differences), zero at the reference state; objective; the
 *     energy split adds up to the energy.
 *   - Fast paths agree. evaluate_shared, evaluate_tri_block and
 *     evaluate_point_block give evaluate()'s results to round-off, state
 *     update included. The blocked ops may decline a block (return −1)
 *     depending on the parameters only, never on the state: a caller asks
 *     once per pass.
 *   - Exact tangent. amplitude_tangent gives evaluate()'s residual (dt = 0)
 *     and its Jacobian ∂R_k/∂ΔA_m (central differences of R, tested on
 *     random states); amplitude_tangent_block the same per lane, to
 *     round-off. A cell without it gets forward differences of evaluate()
 *     (wff_amplitude_tangent, balance.h).
 *   - Stable step. wave_speeds returns upper bounds: an explicit run at 0.9
 *     of the step they give stays bounded (and at 1.1, where the bound is
 *     tight, grows).
 *
 * Conventions (all SI):
 *   F        row-major 3x2: F11 F12 F21 F22 F31 F32, F_iJ = dx_i/dX_J; X_1 is
 *            the warp direction E1, X_2 the weft direction E2.
 *   stress   first Piola-Kirchhoff membrane resultant P, N/m (force per unit
 *            reference length), same layout as F; P = dW/dF for the elastic
 *            part.
 *   residual amplitude residual R_k = -dW/d(dA_k), N/m^2 (force per unit
 *            reference area on the amplitude degree of freedom).
 *   energy   stored energy W per unit reference area, J/m^2.
 */
#ifndef WOVENFF_CELL_H
#define WOVENFF_CELL_H

#include "wovenff/error.h"
#include "wovenff/kernel_name.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Storage for one cell's parameters, in doubles. A cell keeps its own struct
 * there (checked with a static assertion in the cell's file). 64 doubles hold
 * a plain weave with all its derived reference quantities twice over. */
#define WFF_CELL_PARAMS_MAX 64
/* Most diagnostics one cell may report per point. */
#define WFF_DIAG_MAX 12
/* Most mechanisms an energy split may name. */
#define WFF_MECH_MAX 8
/* Most amplitude degrees of freedom per node (the two crimp amplitudes). */
#define WFF_AMPLITUDES_MAX 2
/* Most internal state variables per material point (γᶠ, damage, ...). */
#define WFF_STATE_MAX 6

typedef struct wff_cell_type wff_cell_type;
typedef struct wff_kv wff_kv; /* parsed material file, see material.h */

/* Lanes of the blocked fast path: a block holds this many triangles in
 * structure-of-arrays form (8 doubles = one AVX-512 register). */
#define WFF_BLOCK 8

/* A block of linear triangles with nodal quadrature (three points sharing
 * one F per element), structure of arrays: index [component][lane]. Lanes
 * from n to WFF_BLOCK − 1 are padding the caller fills with a valid state. */
typedef struct wff_tri_block {
    int n;                                  /* lanes in use */
    double F[6][WFF_BLOCK];                 /* F seen by the cell (preload applied) */
    double dA[3][2][WFF_BLOCK];             /* amplitudes at the three points, m */
    double state[3][WFF_STATE_MAX][WFF_BLOCK]; /* in: point p's state i at [p][i], out:
                                               updated (entries i < n_state only) */
    double stress[6][WFF_BLOCK];            /* out: mean P of the three points, N/m */
    double residual[3][2][WFF_BLOCK];       /* out: R_k at each point, N/m² */
    double energy[WFF_BLOCK];               /* out: mean W of the three points, J/m² */
    double dissipated[WFF_BLOCK];           /* out: mean shear dissipation, J/m² */
    double failure_dissipated[WFF_BLOCK];   /* out: mean energy released by yarn damage,
                                               J/m² */
    int degenerate[WFF_BLOCK];              /* out: 1 where a yarn collapsed or the yarns
                                               are parallel (outputs then meaningless) */
} wff_tri_block;

/* A block of independent material points, each with its own F (the Gauss
 * points of bilinear quads), structure of arrays: index [component][lane].
 * Lanes from n to WFF_BLOCK − 1 are padding the caller fills with a valid
 * state. */
typedef struct wff_point_block {
    int n;                                  /* lanes in use */
    double F[6][WFF_BLOCK];                 /* F seen by the cell (preload applied) */
    double dA[2][WFF_BLOCK];                /* amplitude changes ΔA_k, m */
    double state[WFF_STATE_MAX][WFF_BLOCK]; /* in: state i at [i], out: updated
                                               (entries i < n_state only) */
    double stress[6][WFF_BLOCK];            /* out: P, N/m */
    double residual[2][WFF_BLOCK];          /* out: R_k, N/m² */
    double energy[WFF_BLOCK];               /* out: W, J/m² */
    double dissipated[WFF_BLOCK];           /* out: shear dissipation of this update, J/m² */
    double failure_dissipated[WFF_BLOCK];   /* out: energy released by yarn damage in this
                                               update, J/m² */
    int degenerate[WFF_BLOCK];              /* out: 1 where a yarn collapsed or the yarns
                                               are parallel (outputs then meaningless) */
} wff_point_block;

/* A block of WFF_BLOCK material points for amplitude_tangent_block, structure
 * of arrays: index [component][lane], every lane a point of its own (all
 * lanes are evaluated; the caller fills unused ones with a valid state). */
typedef struct wff_tangent_block {
    double F[6][WFF_BLOCK];          /* F seen by the cell (preload applied) */
    double dA[2][WFF_BLOCK];         /* ΔA_k, m */
    double state[WFF_STATE_MAX][WFF_BLOCK]; /* the point's state (n_state entries), held */
    double residual[2][WFF_BLOCK];   /* out: R_k, N/m² */
    double tangent[4][WFF_BLOCK];    /* out: ∂R_k/∂ΔA_m at [2k + m], N/m³ */
    int degenerate[WFF_BLOCK];       /* out: 1 where evaluate() would say degenerate */
} wff_tangent_block;

/* A block of WFF_BLOCK states for wave_speeds_block, structure of arrays:
 * index [component][lane]. */
typedef struct wff_wave_block {
    double F[6][WFF_BLOCK];                 /* in: F seen by the cell (preload applied) */
    double dA[2][WFF_BLOCK];                /* in: amplitudes, m */
    double membrane_speed[WFF_BLOCK];       /* out: as wave_speeds, m/s */
    double amplitude_omega[WFF_BLOCK];      /* out: as wave_speeds, rad/s */
} wff_wave_block;

/* A material: the cell that models it and that cell's parameters. */
typedef struct wff_material {
    const wff_cell_type *cell;
    double areal_density;                /* rho_A = rho_f t_f, kg/m^2 */
    double yarn_spacing[2];              /* distance between neighbouring yarns of
                                            family k, m: one yarn carries
                                            P_kk * yarn_spacing[k] (set by parse) */
    int n_state;                         /* internal state variables per point, a prefix
                                            of the cell's state_names (set by parse;
                                            <= the cell's n_state_max) */
    double params[WFF_CELL_PARAMS_MAX];  /* the cell's own parameter struct */
    char source[256];                    /* where it came from, for messages */
} wff_material;

/* What one evaluation returns. */
typedef struct wff_point_result {
    double stress[6];             /* P, N/m, row-major 3x2 */
    double residual[WFF_AMPLITUDES_MAX]; /* R_k, N/m^2 (0 for cells without amplitudes) */
    double state[WFF_STATE_MAX];  /* updated internal state (entries < n_state), named by
                                     state_names (King: state[0] = γᶠ, rad) */
    double energy;                /* stored energy W, J/m^2 */
    double dissipated;            /* energy dissipated by shear flow in this update,
                                     J/m^2 (>= 0) */
    double failure_dissipated;    /* stored energy released by yarn damage in this update,
                                     J/m^2 (>= 0; 0 for cells without failure) */
    double diag[WFF_DIAG_MAX];    /* cell-specific, named by diag_names */
} wff_point_result;

/* Point statuses. */
enum {
    WFF_POINT_OK = 0,
    WFF_POINT_DEGENERATE = 1, /* a yarn direction has zero length or the yarns are parallel */
    WFF_POINT_NONFINITE = 2,  /* NaN or infinity in the state or the result (set by the
                                 element code, not by cells) */
    WFF_POINT_UNBALANCED = 3  /* static amplitudes: the point's Newton did not converge
                                 (set by the element code, not by cells) */
};

struct wff_cell_type {
    const char *name;      /* the `cell = ` value in material files */
    const char *summary;   /* one line for listings */
    int n_amplitudes;      /* amplitude DOFs per node this cell uses: 0 or 2 */

    int n_diag;                         /* entries of diag[] that are filled */
    const char *const *diag_names;      /* e.g. "T1" */
    const char *const *diag_units;      /* e.g. "N" */

    int yarn_tension_diag[2];           /* index in diag[] of the tension of a yarn of
                                           each family (N), or -1: used to impose
                                           a yarn force (preload, strip loads) */

    int n_mech;                         /* mechanisms in energy_split */
    const char *const *mech_names;      /* e.g. "yarn_stretch" */

    int n_state_max;                    /* most internal states a point of this cell
                                           carries (a material's n_state <= this) */
    const char *const *state_names;     /* n_state_max names, e.g. "gamma_f" (the field
                                           names of the state in outputs) */
    const char *const *state_units;     /* e.g. "rad" */
    int damage_state[2];                /* index in a point's state of yarn family k's
                                           damage (0 intact .. 1 ruptured), or −1 when
                                           the cell has no yarn failure */

    /* Required. Read this cell's keys from kv (wff_kv_number and friends),
     * validate them, compute derived reference quantities into mat->params.
     * Keys the cell does not take are reported by the caller as unknown.
     * Sets mat->n_state (the caller presets it to n_state_max). */
    int (*parse)(wff_kv *kv, wff_material *mat, wff_error *err);

    /* Required. One material point with state[0 .. n_state−1]. dt > 0 advances
     * the state (King: γᶠ by the flow rule, backward Euler) into out->state;
     * dt = 0 holds it fixed, which makes stress and residual the exact
     * derivatives of energy. Returns WFF_POINT_OK or WFF_POINT_DEGENERATE (out
     * is then filled with NaN). */
    int (*evaluate)(const void *params, const double F[6], const double dA[2],
                    const double *state, double dt, wff_point_result *out);

    /* Required. Upper bounds for the stable explicit step at this state:
     * membrane_speed, m/s, the fastest in-plane wave (dt <= h / speed), and
     * amplitude_omega, rad/s, the highest frequency of the amplitude
     * oscillator with lumped mass rho_A/6 (dt <= 2 / omega; 0 when the cell
     * has no amplitudes). */
    void (*wave_speeds)(const void *params, double areal_density,
                        const double F[6], const double dA[2],
                        double *membrane_speed, double *amplitude_omega);

    /* Optional. Stored energy per mechanism, J/m^2, n_mech values that add up
     * to evaluate()'s energy. */
    void (*energy_split)(const void *params, const double F[6], const double dA[2],
                         const double *state, double *mech_energy);

    /* Optional fast path: n_points material points sharing one F (a linear
     * triangle with nodal quadrature), so the F-dependent kinematics are done
     * once. Point q has amplitudes dA[2q], dA[2q+1], weight weight[q] and state
     * state[q n_state .. q n_state + n_state − 1] (n_state the material's;
     * updated in place with step dt). Adds Σ_q weight[q] P_q into stress_sum,
     * writes residual[2q + k] = R_k at point q (unweighted), and adds
     * Σ weight[q] W_q to *energy, Σ weight[q] × dissipated_q to *dissipated
     * and Σ weight[q] × failure_dissipated_q to *failure_dissipated. Must
     * agree with evaluate() to round-off (tested). Returns WFF_POINT_OK, or
     * the status of the first failing point, whose index goes to *bad_point. */
    int (*evaluate_shared)(const void *params, const double F[6], int n_points,
                           const double *dA, const double *weight, double *state, double dt,
                           double stress_sum[6], double *residual, double *energy,
                           double *dissipated, double *failure_dissipated, int *bad_point);

    /* Optional, faster still: a whole block of triangles at once, written so
     * the compiler vectorises across the lanes. Returns 0 when it handled the
     * block, −1 when these parameters need the general path (the caller then
     * uses evaluate_shared or evaluate); the answer depends on params only,
     * never on the block's state. Must agree with evaluate() to round-off
     * (tested). */
    int (*evaluate_tri_block)(const void *params, double dt, wff_tri_block *block);

    /* Optional. The reference geometry of the crimped-yarn picture, for
     * drawing the cell: quarter wavelengths p_k⁰ and crimp amplitudes A_k⁰
     * (m) of the two families; a point's amplitudes are A_k⁰ + ΔA_k. NULL when
     * the cell has no such geometry (nothing is drawn). */
    void (*reference_geometry)(const void *params, double pitch0[2], double amplitude0[2]);

    /* Optional: a block of independent points (each its own F, ΔA, state; the
     * Gauss points of quads), vectorised across the lanes like
     * evaluate_tri_block. Returns 0 when it handled the block, −1 when these
     * parameters need evaluate() (params only, never the state). Must agree
     * with evaluate() to round-off, state update included (tested). */
    int (*evaluate_point_block)(const void *params, double dt, wff_point_block *block);

    /* Optional (cells with amplitudes). The amplitude residual R_k at one
     * point with its state held, as evaluate() gives it with dt = 0, into residual,
     * and its exact tangent ∂R_k/∂ΔA_m into tangent[2k + m] (N/m³): the
     * static-amplitude Newton's Jacobian (balance.h). Returns WFF_POINT_OK or
     * WFF_POINT_DEGENERATE, as evaluate() would. When NULL, callers use
     * wff_amplitude_tangent's forward differences of evaluate(). */
    int (*amplitude_tangent)(const void *params, const double F[6], const double dA[2],
                             const double *state, double residual[2], double tangent[4]);

    /* Optional, the same for a block of points, vectorised across the lanes.
     * Returns 0, or −1 when these parameters need the general path (on params
     * only, never the state). Agrees with amplitude_tangent to round-off. */
    int (*amplitude_tangent_block)(const void *params, wff_tangent_block *block);

    /* Optional: wave_speeds for a whole block of states at once, vectorised
     * across the lanes (the stable-step scan). Returns 0 when it handled the
     * block, −1 when these parameters need wave_speeds (the answer depends on
     * params only). Must agree with wave_speeds to round-off, lane by lane
     * (tested); a table that replaces wave_speeds must replace or clear this
     * too. */
    int (*wave_speeds_block)(const void *params, double areal_density, wff_wave_block *block);
};

/* Registry. Cells register with WFF_REGISTER_CELL in their own file; the
 * linker gathers the entries (constant data, no start-up code) into the
 * section WFF_CELLS_SECTION: "wff_cells", the registry's, or a kernel
 * variant's own ("wff_cells__avx2", ...; kernel_name.h). */
const wff_cell_type *wff_cell_find(const char *name);   /* NULL if unknown */
int wff_cell_count(void);
const wff_cell_type *wff_cell_at(int index);            /* 0 <= index < count */

#define WFF_REGISTER_CELL(table)                                              \
    static const wff_cell_type *const wff_cell_entry_##table                  \
        __attribute__((used, section(WFF_CELLS_SECTION), aligned(sizeof(void *)))) \
        = &(table)

/* Evaluate a material point with a loaded material: its cell's evaluate
 * (plugin/cell_ops.c; the other ops' wrappers are in wovenff/cell_ops.h). */
int wff_material_evaluate(const wff_material *mat, const double F[6], const double dA[2],
                          const double *state, double dt, wff_point_result *out);

/* The state every point starts from (all zeros), for evaluations at rest. */
static const double wff_rest_state[WFF_STATE_MAX] = {0};

/* The name of the state the element code fills with the element's length
 * (the contract above). */
#define WFF_ELEMENT_LENGTH_STATE "element_length"

/* Index of the state named `name` in mat's points (< mat->n_state), or −1. */
int wff_material_state_index(const wff_material *mat, const char *name);

#ifdef __cplusplus
}
#endif

/* The wrappers through which everything else uses a cell (plugin/cell_ops.c). */
#include "wovenff/cell_ops.h"
#endif

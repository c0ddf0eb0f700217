/* wovenff — membrane elements with crimp-amplitude DOFs (paper §2.2, docs/model.md §8).
 *
 * Each node carries five DOFs, interleaved node-major: u_x, u_y, u_z, ΔA1, ΔA2
 * (the layout of FreeFEM's fespace [P1,P1,P1,P1,P1]). Two element types:
 *
 *   tri3   three-point nodal quadrature (weights A/3 at the vertices): F is
 *          constant, the amplitudes are the nodal values, so each vertex
 *          is one material point; F_I is purely nodal.
 *   quad4  bilinear, 2×2 Gauss.
 *
 * Internal forces (eqs. 7, 9), per unit mesh area:
 *   f_a^u  = −∫ P ∇_X N_a dA₀          f_a^Ak = ∫ R_k N_a dA₀
 * A preload F_pre (2×2) acts at the material point: the cell sees
 * F_eff = F F_pre, and stress, residual, energy and mass per mesh area are
 * divided by J_pre = det F_pre (the mesh is the preloaded configuration).
 *
 * Orientation (docs/model.md "Ply orientation"): the warp E1 at an angle θ to
 * the mesh's x axis. R(θ) = [cos θ  −sin θ; sin θ  cos θ] takes material axes
 * to mesh axes (X_mesh = R X_mat), so the cell's F is F_mat = F_mesh R and its
 * stress goes back as P_mesh = P_mat Rᵀ (R is a rotation: J = 1, energies and
 * residuals per area unchanged). The preload is a material-frame state (the
 * yarn families' stretches): the cell sees F_mesh R F_pre,mat. The element
 * code applies both as one 2×2 map, em->F_pre = R(θ) F_pre,mat
 * (wff_orientation_map), through the same gather, kernels and scatter as a
 * preload alone; at θ = 0 the map is the preload itself, bit for bit.
 *
 * Kernels only read the geometry and state they are given and add into the
 * force array: no allocation, no I/O. */
#ifndef WOVENFF_MEMBRANE_H
#define WOVENFF_MEMBRANE_H

#include "wovenff/cell.h"
#include "wovenff/fixed_sum.h"

#include <stddef.h>

#include <math.h>

#ifdef __cplusplus
extern "C" {
#endif

#define WFF_DOFS_PER_NODE 5
#define WFF_TRI_POINTS 3
#define WFF_QUAD_POINTS 4

/* Reference geometry of a mesh, precomputed once. */
/* The sums a force pass keeps per block of elements: stored energy, shear,
 * failure and slip dissipation. */
#define WFF_BLOCK_SUMS 4

typedef struct wff_elements {
    int n_tris, n_quads;
    const int *tri;       /* 3 per triangle */
    const int *quad;      /* 4 per quad */
    double *tri_grad;     /* 6 per triangle: dN_a/dX, dN_a/dY, a = 0..2 */
    double *tri_area;     /* 1 per triangle, m² */
    double *quad_grad;    /* 32 per quad: point q, node a: dN_a/dX, dN_a/dY */
    double *quad_weight;  /* 4 per quad: Gauss weight × det J, m² */
    double *size;         /* characteristic length per element (tris, then quads), m */
    int n_dofs;           /* 5 × nodes referenced */
    int n_threads;        /* threads for the triangle force pass (OpenMP), 1 by default */
    int max_threads;      /* most threads a pass takes (OpenMP's, or the processors) */
    int team_min_tris;    /* least work (triangles + 3 x quads) for which the passes take
                             a thread team (WFF_TEAM_MIN_TRIS at init; a test of the
                             threaded path on a small mesh sets 0); wff_elements_team */
    double *slot;         /* the force pass's element-vertex slots: element e's force on its
                             k-th node's 5 DOFs at D (3e + k) (triangles) and D (3 n_tris +
                             4 (e − n_tris) + k) (quads), N: each element writes its own,
                             and each node sums its slots in ascending element order
                             (node_slot), so a node's force has the same bits whatever
                             the threads or ranks that computed its elements (the
                             OpenRadioss PARITH/ON order; docs/architecture.md) */
    int *node_slot_start; /* per node of node_list, n_gather + 1: its slots' range in
                             node_slot */
    int *node_slot;       /* the slots (element-vertex incidences) of each node, in
                             ascending element order (triangles, then quads) */
    int *node_list;       /* the nodes the elements reference, ascending, n_gather */
    int n_gather;
    double *block_sums;   /* the force pass's stored, shear, failure and slip energies per
                             block of WFF_BLOCK elements (WFF_BLOCK_SUMS each; triangles'
                             blocks, then quads'), added in block order after it (the same
                             bits for any threads) */
    double *point_dA;     /* static amplitudes: 2 per quadrature point (6 per triangle,
                             then 8 per quad), or NULL while amplitudes are dynamic */
    unsigned char *eroded; /* per element (tris, then quads): 1 once eroded (no force, no
                             stable-step limit, no stored energy), or NULL while erosion is
                             off (every pass then runs as before erosion existed); owned,
                             freed by wff_elements_free (plugin/erosion.c) */
    unsigned char *block_run;   /* over ranks (plugin/distribute.c): per block (triangles'
                                   blocks, then quads'), 1 if this rank computes it (its own
                                   blocks and those touching a node it owns), or NULL: every
                                   block (one rank) */
    unsigned char *block_count; /* per block, 1 if its energies are this rank's to add (each
                                   block counted on one rank), or NULL: every block */
    int gather_begin, gather_end; /* the range of node_list whose forces this rank gathers
                                     (its own nodes; 0 and n_gather on one rank) */
    int erosion;          /* erosion rule: WFF_EROSION_OFF, _BOTH (every point of the element
                             has both yarn families ruptured), _EITHER (one family ruptured
                             at every point) */
} wff_elements;

enum { WFF_EROSION_OFF = 0, WFF_EROSION_BOTH = 1, WFF_EROSION_EITHER = 2 };

/* 1 if element e (tris first, then quads) has been eroded. */
static inline int wff_element_eroded(const wff_elements *el, int e)
{
    return el->eroded && el->eroded[e];
}

/* Index of element e's first quadrature point in a mesh of n_tris triangles
 * (tris first, 3 points each, then quads, 4 each): where its per-point state
 * starts, in points (× n_state for doubles). */
static inline size_t wff_element_first_point(int n_tris, int e)
{
    return e < n_tris ? (size_t)WFF_TRI_POINTS * (size_t)e
                      : (size_t)WFF_TRI_POINTS * (size_t)n_tris +
                            (size_t)WFF_QUAD_POINTS * (size_t)(e - n_tris);
}

/* Quadrature points of the whole mesh (the length of a per-point array, in points). */
static inline size_t wff_elements_point_count(const wff_elements *el)
{
    return wff_element_first_point(el->n_tris, el->n_tris + el->n_quads);
}

/* Element e's nodes (tris first, then quads): their count, 3 or 4, *nodes
 * pointed at them. */
static inline int wff_element_nodes(const wff_elements *el, int e, const int **nodes)
{
    const int nt = el->n_tris;
    *nodes = e < nt ? el->tri + 3 * e : el->quad + 4 * (e - nt);
    return e < nt ? 3 : 4;
}

/* Element e's reference area, m²: a triangle's, a quad's quadrature weights summed. */
static inline double wff_element_area(const wff_elements *el, int e)
{
    if (e < el->n_tris)
        return el->tri_area[e];
    const double *w = el->quad_weight + WFF_QUAD_POINTS * (e - el->n_tris);
    double area = 0;
    for (int q = 0; q < WFF_QUAD_POINTS; q++)
        area += w[q];
    return area;
}

/* Element e's characteristic length for yarn failure's crack band
 * (docs/model.md §20), m, from its reference area A: sqrt(2 A) for a
 * triangle, the legs of a right isosceles triangle (the side of the square two
 * of them make, so a mesh of squares split in two has the length its quads
 * would have, and 0.93 of the side of an equilateral one), sqrt(A) for a quad
 * (its side when square). Not el->size (the smallest altitude, for the
 * stable step): a band crosses an element at any angle. */
static inline double wff_element_band_length(const wff_elements *el, int e)
{
    return sqrt((e < el->n_tris ? 2 : 1) * wff_element_area(el, e));
}

/* Most threads a force pass uses. */
#define WFF_MAX_THREADS 64
/* Least work, in triangles (a quad counts as 3), for which a mesh's passes
 * take a thread team by default (below, one thread whatever n_threads says):
 * with sleeping threads (tools/ff.sh's passive wait) every parallel region
 * costs a wake-up, tens of µs here, which outweighs a smaller pass (the
 * paper's 2288 triangles: 2 threads 6.3-7.2 s, 1 thread 5.6 s; the strip's
 * 640 quads: 113 s against 54 s; 9004 triangles: 27.7 s against 14 s spinning). */
#define WFF_TEAM_MIN_TRIS 16384

/* Preload and material as the element sees them. */
typedef struct wff_element_material {
    const wff_material *mat;
    double F_pre[4];      /* row-major 2×2: the map the cell's F passes through,
                             F_cell = F_mesh F_pre; the preload (material frame) with
                             the orientation in front, R(θ) F_pre,mat (the preload as
                             given at θ = 0) */
    double J_pre;         /* det F_pre (= det of the preload: R is a rotation) */
    int reference_path;   /* 1: always the cell's plain evaluate(), even where it offers
                             evaluate_shared (for checks and benchmarks), and its plain
                             wave_speeds() in the stable-step scan */
    double amplitude_mass_factor; /* scales the amplitude masses (eq. 12's 1/6); 0 means 1.
                             Larger is cheaper (the amplitude step limit grows as its
                             square root) and less faithful to the amplitude inertia */
    int static_amplitudes; /* 1: amplitudes in static balance at every quadrature point
                             (King 2005) instead of dynamic nodal DOFs; see
                             wff_elements_static_amplitudes */
    double orientation;   /* θ, rad: the warp E1 at θ to the mesh's x axis
                             (counter-clockwise; 0 by default); F_pre holds R(θ) */
} wff_element_material;

/* The element map for a preload Fp (material frame, row-major 2×2) at
 * orientation θ (rad): map = R(θ) Fp, R exact (entries 0, ±1) at multiples of
 * 90°; θ = 0 copies Fp (no multiply: the results without orientation, bit for
 * bit). */
static inline void wff_orientation_map(double theta, const double Fp[4], double map[4])
{
    if (theta == 0) {
        for (int i = 0; i < 4; i++)
            map[i] = Fp[i];
        return;
    }
    double c = cos(theta), s = sin(theta);
    double quarter = theta / (2 * atan(1.0)); /* θ in right angles */
    if (quarter == nearbyint(quarter)) { /* exactly 0, 90, 180, 270 degrees mod 360 */
        double k = fmod(nearbyint(quarter), 4); /* (no integer cast: any size) */
        if (k < 0)
            k += 4;
        c = k == 0 ? 1 : k == 2 ? -1 : 0;
        s = k == 1 ? 1 : k == 3 ? -1 : 0;
    }
    map[0] = c * Fp[0] - s * Fp[2];
    map[1] = c * Fp[1] - s * Fp[3];
    map[2] = s * Fp[0] + c * Fp[2];
    map[3] = s * Fp[1] + c * Fp[3];
}

/* What one force pass sums (per mesh, J or J/step). */
typedef struct wff_force_totals {
    double internal_energy;  /* Σ ∫ W dA, J */
    double dissipated;       /* shear-flow dissipation in this pass, J */
    double failure_dissipated; /* stored energy released by yarn damage in this pass, J */
    double slip_dissipated;  /* energy dissipated by yarn slip at the crossovers in this pass,
                                J */
    int bad_element;         /* −1, or the first element whose point failed */
    int bad_point;           /* quadrature point of bad_element */
    int bad_status;          /* WFF_POINT_DEGENERATE, WFF_POINT_NONFINITE or
                                WFF_POINT_UNBALANCED */
    double bad_residual;     /* WFF_POINT_UNBALANCED: largest |R_k| left, N/m² */
    int bad_iterations;      /* WFF_POINT_UNBALANCED: the Newton iterations spent */
    long amplitude_iterations; /* static amplitudes: Newton iterations (tangents) over all
                                  points of the pass */
    wff_fixed sums[WFF_BLOCK_SUMS]; /* the four energies above as order-free sums of the
                                blocks' (fixed_sum.h): the doubles are their values; a model
                                over ranks adds the ranks' before taking them */
} wff_force_totals;

/* The threads a pass over el's elements (or the model's DOFs) uses: n_threads,
 * or 1 when the mesh is below team_min_tris. */
static inline int wff_elements_team(const wff_elements *el)
{
    long work = (long)el->n_tris + 3L * el->n_quads;
    return el->n_threads > 1 && work >= el->team_min_tris ? el->n_threads : 1;
}

/* Allocate and compute the reference geometry; -1 with the element named if
 * an element has zero or negative area. X holds 2 coordinates per node. */
int wff_elements_init(wff_elements *el, const double *X, int n_tris, const int *tri,
                      int n_quads, const int *quad, wff_error *err);
void wff_elements_free(wff_elements *el);

/* Threads for the force pass (1 .. max_threads, where max_threads is
 * OpenMP's maximum at init). Results are the same for a given count (sums in
 * a fixed order) and agree to round-off between counts. */
int wff_elements_set_threads(wff_elements *el, int n_threads, wff_error *err);

/* Add internal forces of every element at displacement u (5 per node) into f
 * (eroded elements, el->eroded, give none and their points' states are kept),
 * update the points' internal state (em->mat->n_state per quadrature point,
 * 3 points per tri then 4 per quad: point p's state i at state[n_state p + i])
 * with step dt (0: hold it). */
void wff_elements_forces(const wff_elements *el, const wff_element_material *em, const double *X,
                         const double *u, double *state, double dt, double *f,
                         wff_force_totals *totals);

/* Switch to quasi-static amplitudes (King 2005): every quadrature point keeps
 * its own ΔA, solved for R = 0 (Newton, 2×2) at each force pass, starting from
 * the last solution; the nodal amplitude DOFs then get no force and the
 * amplitude oscillator sets no step limit. dA0 is the first guess everywhere.
 * Allocates once; -1 if out of memory. */
int wff_elements_static_amplitudes(wff_elements *el, wff_element_material *em,
                                   const double dA0[2], wff_error *err);

/* Stored energy per mechanism summed over the mesh, J (model part), in the
 * order of the cell's mech_names (n_mech values into mech); all zeros if the
 * cell has no energy_split. Quadrature as in the force pass, state held. */
void wff_elements_energy_split(const wff_elements *el, const wff_element_material *em,
                               const double *X, const double *u, const double *state,
                               double *mech);

/* Lumped masses: each element's ρ_A A / J_pre shared equally among its
 * nodes; amplitude DOFs get 1/6 of that (eqs. 10–12). mass has 5 per node,
 * zeroed first. */
void wff_elements_masses(const wff_elements *el, const wff_element_material *em, int n_nodes,
                         double *mass);

/* Stored energy of element e (J, model part: Σ w W / J_pre, every point at
 * dt = 0 with its own state, n_state per point in state), as the force pass
 * integrates it (plugin/membrane_energy.c; erosion's measure of what an eroded
 * element held). */
double wff_element_stored_energy(const wff_elements *el, const wff_element_material *em,
                                 const double *X, const double *u, const double *state,
                                 int n_state, int e);

/* Stable explicit step over all elements at the current state: per element
 * 1/sqrt(1/dt_m² + 1/dt_A²) with dt_m = size/c (membrane waves) and
 * dt_A = 2/ω (amplitude oscillator), the bound for the two coupled; c and ω
 * the largest over a triangle's vertices (its F, each vertex's ΔA: the nodal
 * quadrature's points), at a quad's centre state (docs/model.md §12).
 * *worst gets the element that sets it. Eroded elements set none (every
 * element eroded: INFINITY, *worst −1). */
double wff_elements_stable_step(const wff_elements *el, const wff_element_material *em,
                                const double *X, const double *u, int *worst);

/* Deformation gradient (F, 3×2 row-major, mesh reference) at the centre of
 * element e (tris first, then quads), and the element's mean amplitudes. */
void wff_element_center_state(const wff_elements *el, const double *X, const double *u, int e,
                              double F[6], double dA[2]);

/* Point evaluation at the centre of element e with the preload applied
 * (every state held at the mean of the element's points); for output.
 * Returns the status. */
int wff_element_center_eval(const wff_elements *el, const wff_element_material *em,
                            const double *X, const double *u, const double *state, int e,
                            wff_point_result *out);
/* The same with the given state (em->mat->n_state values, e.g. a mean the
 * caller formed) instead of the mean of the element's points. */
int wff_element_center_eval_state(const wff_elements *el, const wff_element_material *em,
                                  const double *X, const double *u, const double *held, int e,
                                  wff_point_result *out);

#ifdef __cplusplus
}
#endif
#endif

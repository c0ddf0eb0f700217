/* block.h — the backing's solid block (issue 30 item 1): a box of 8-node
 * hexahedra (hex8.h) on a structured grid graded from a point of its top face
 * (the impact point) outwards and downwards, lumped masses, one of the
 * pointwise laws of solid_laws.h per element, held as the standards' box
 * holds it (each side and the bottom fixed in its normal direction,
 * frictionless; the top free).
 *
 * The block is a solid on its own: arrays, the internal force pass, its
 * energies and its stable step. It knows nothing of the fabric, the
 * projectile or the step's parts: the backing part (plugin/backing.c)
 * advances it with the fabric's step and puts it in contact
 * (plugin/backing_contact.c). The top face is at z = top, the block below it
 * at z >= top (the projectile moves along +z). SI units. */
#ifndef WFF_BLOCK_H
#define WFF_BLOCK_H

#include "hex8.h"
#include "solid_laws.h"

enum { WFF_BLOCK_NONE = 0, WFF_BLOCK_CLAY = 1, WFF_BLOCK_GELATIN = 2 };

/* Most elements a block takes (its arrays: ~1 kB an element). */
#define WFF_BLOCK_ELEMENTS_MAX 4000000

typedef struct wff_block_shape {
    double x0, x1, y0, y1; /* the footprint, m (x0 < x1, y0 < y1) */
    double top;            /* z of the top face, m */
    double depth;          /* m (> 0) */
    double centre[2];      /* the grid's finest point on the top face, m (clamped into the
                              footprint) */
    double finest;         /* element size there, m (> 0) */
    double growth;         /* size ratio of neighbouring elements away from it (>= 1) */
} wff_block_shape;

typedef struct wff_block {
    int law;                     /* WFF_BLOCK_CLAY or WFF_BLOCK_GELATIN */
    wff_clay_params clay;
    wff_gelatin_params gelatin;
    double hourglass;            /* κ of the hourglass springs */
    double hourglass_damping;    /* ζ of the hourglass dashpots (hex8.h; 0 by default: none;
                                    wff_block_set_hourglass_damping) */
    double viscosity[2];         /* the bulk viscosity's linear and quadratic factors b1, b2
                                    (hex8.h; 0.06, 1.2 by default) */
    double density, wave_speed, shear; /* of the law: kg/m³, m/s, Pa */
    int n[3];                    /* elements along x, y, z */
    double *grid[3];             /* the grid's coordinates along x, y, z (n + 1 each), m */
    int n_nodes, n_elements;
    double *X;                   /* reference positions, 3 a node */
    double *u, *v, *f, *mass;    /* 3 a node: m, m/s, N, kg */
    unsigned char *held;         /* 3 a node: 1 where the box holds the DOF */
    int *hex;                    /* 8 nodes an element (hex8.h's order) */
    wff_hex8_ref *ref;           /* an element's reference shape */
    int points;                  /* law states an element: 1 (the one-point element) or
                                    WFF_HEX_POINTS (fully integrated, wff_block_integrate_fully) */
    wff_hex8_full *full;         /* an element's Gauss points (fully integrated), or NULL */
    double *hourglass_k;         /* an element's hourglass stiffness, N/m */
    double *hourglass_c;         /* an element's 4 hourglass dashpots, N s/m */
    wff_clay_state *clay_state;  /* `points` an element (clay), or NULL */
    wff_gelatin_state *gelatin_state; /* `points` an element (gelatin), or NULL */
    /* the top face's contacts with a rigid body (backing_contact.c), a slot a top node */
    int *contact_node;
    double *contact_depth, *contact_normal, *contact_speed, *contact_lambda;
    double stored;               /* of the last pass: Σ V0 W + hourglass energy, J */
    double dissipated;           /* Σ V0 × the law's dissipation so far (states) + the bulk
                                    viscosity's, J */
    double viscous;              /* the bulk viscosity's and the hourglass dashpots' dissipation
                                    so far, J */
    double hourglass_viscous;    /* the hourglass dashpots' share of it, J */
} wff_block;

/* A block of the law (WFF_BLOCK_CLAY / GELATIN, with the default parameters
 * wff_clay_roma_plastilina / wff_gelatin_ordnance10) and shape, at rest,
 * unstrained; κ the hourglass factor. -1 (err set, naming the parameter) on a
 * bad shape or out of memory (nothing left allocated). */
int wff_block_create(wff_block *b, int law, const wff_block_shape *shape, double hourglass,
                     wff_error *err);
void wff_block_free(wff_block *b);

/* The block's elements made fully integrated (hex8.h's wff_hex8_full: eight
 * Gauss points with F-bar, a law state at each, no hourglass springs or
 * dashpots), at rest, before its first force pass. 0, or -1 (err set) out of
 * memory (the block then freed). */
int wff_block_integrate_fully(wff_block *b, wff_error *err);

/* Node (i, j, k) of the grid, k = 0 the top face. */
static inline int wff_block_node(const wff_block *b, int i, int j, int k)
{
    return i + (b->n[0] + 1) * (j + (b->n[1] + 1) * k);
}

/* The shear stress the top face's element under top node (i, j) (its corner
 * of least i, j) can carry before its clay yields, Pa: the J2 law's yield
 * in shear σ_y / √3 at the element's plastic strain and last rate (fully
 * integrated: the mean of its four top points'); INFINITY for gelatin (no
 * yield). */
double wff_block_surface_shear_strength(const wff_block *b, int i, int j);

/* The internal forces at b->u into b->f (written), with the bulk viscosity's
 * at the velocities b->v, the elements' states advanced over dt (s; 0: held,
 * the stress of the states as they are; the viscosity's work over dt at that
 * power); b->stored and b->dissipated follow. -1 with *bad the element (from 0) whose
 * deformation is inverted or not finite, nothing of the states changed. */
/* The hourglass dashpots at the fraction ζ (>= 0) of critical damping
 * (hex8.h), their coefficients set once for every element. */
void wff_block_set_hourglass_damping(wff_block *b, double ratio);

int wff_block_forces(wff_block *b, double dt, int *bad);

/* The block's stable step, s, at b->u (INFINITY for no element), the element
 * setting it into *worst: each element's wff_hex8_stable_step lowered by the
 * linear bulk viscosity's damping b1 of the highest mode, × (√(1 + b1²) − b1)
 * (the central difference's limit with damping). */
double wff_block_stable_step(const wff_block *b, int *worst);

#endif

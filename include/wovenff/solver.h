/* wovenff — explicit central-difference solver for a fabric membrane.
 *
 * A model owns a mesh, a material and the state (u, v per DOF; γᶠ per
 * quadrature point), and advances with lumped masses:
 *
 *   v^{n+½} = v^{n−½} + Δt M⁻¹ (f_int + f_contact + f_friction)(u^n)
 *   u^{n+1} = u^n + Δt v^{n+½}
 *
 * Boundary conditions are per DOF: free, fixed (held at its value) or moved
 * at a prescribed velocity (its reaction does external work). A friction
 * clamp presses chosen nodes flat (u_z = 0) and resists in-plane motion by
 * Coulomb friction up to μ N_a on each face. A rigid projectile moving along
 * +z with its axis at (x, y) (a cylinder with a hemispherical nose by
 * default; also a flat-faced cylinder with an edge radius, or a sphere)
 * touches the fabric by kinematic (hard, inelastic) contact with Coulomb
 * friction: a velocity predictor–corrector that keeps nodes on its surface.
 *
 * Whole-specimen convention: every mass, force and energy passed in or read
 * out is the whole specimen's. The model stores the whole values and derives
 * the modelled part's (whole / symmetry_factor, 4 for a quarter model) where
 * it uses them, so the order of the calls does not matter.
 *
 * Implemented by plugin/model.c (set-up, boundary conditions, settings),
 * contact.c (the projectile), integrator.c (the step, energies), fields.c
 * (output) and checkpoint.c (save and load). */
#ifndef WOVENFF_SOLVER_H
#define WOVENFF_SOLVER_H

#include "wovenff/comm.h"
#include "wovenff/membrane.h"
#include "wovenff/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { WFF_DOF_FREE = 0, WFF_DOF_FIXED = 1, WFF_DOF_PRESCRIBED = 2 };
enum { WFF_UX = 0, WFF_UY = 1, WFF_UZ = 2, WFF_DA1 = 3, WFF_DA2 = 4 };
/* Nose shapes (docs/model.md §16): a cylinder of radius r with a
 * hemispherical nose; a flat-faced cylinder, face of radius r − r_e joined to
 * the shank by a torus of tube radius r_e; a sphere of radius r; the chisel of
 * a fragment-simulating projectile (MIL-DTL-46593B): a cylinder of radius r
 * whose front is a flat strip |ξ| <= w/2 across the diameter (along y before
 * any -orientation of the fabric: the strip's length along the projectile's
 * η = y) with two bevel planes falling back from its long edges at the angle
 * β from the end face (docs/threats.md). */
enum { WFF_NOSE_HEMISPHERE = 0, WFF_NOSE_FLAT = 1, WFF_NOSE_SPHERE = 2, WFF_NOSE_CHISEL = 3 };
#define WFF_NOSE_COUNT 4

typedef struct wff_projectile {
    int active;
    double radius;        /* shank radius r (sphere: its radius), m */
    int nose;             /* WFF_NOSE_* (0, the hemisphere, by default) */
    double edge_radius;   /* flat nose: edge (torus tube) radius r_e, 0 <= r_e <= r, m */
    double chisel_flat;   /* chisel: width w of the flat strip across the tip, 0 <= w <= 2r, m */
    double chisel_bevel;  /* chisel: bevel angle β from the end face, 0 < β < π/2, rad */
    double path[3];       /* unit direction of travel: (sin θ, 0, cos θ) for the obliquity θ
                             (wff_model_set_obliquity); (0, 0, 1) by default */
    int oblique;          /* 1 once an obliquity θ != 0 is set: the shapes are evaluated in
                             the projectile's frame (0: the code of the normal shot, bit for bit) */
    double mass_whole;    /* as given: the whole projectile's, kg */
    double mass;          /* of the modelled part (mass_whole / symmetry_factor), kg */
    double tip;           /* z of the nose tip, m (oblique: its coordinate along the path
                             from (axis, 0): the tip point is (axis, 0) + tip path) */
    double velocity;      /* along +z (oblique: along the path), m/s */
    double mu;            /* Coulomb friction with the fabric */
    double axis[2];       /* x, y of the projectile axis, m */
    int n_candidates;     /* nodes that may touch it, refreshed as it moves */
    int *candidates;
    int search_all;       /* 1: every node is a candidate (the contact_search knob off) */
    int *contact_node;    /* nodes corrected in the last step (workspace, n_nodes) */
    int n_contact;        /* how many (the ply contact of a pack reads them: pack.h) */
    double *impulse;      /* their contact impulses, 3 each, N·s (workspace) */
    double contact_dv;    /* the projectile's velocity change by its own contact in the
                             last step, m/s (its share, booked by the part's book op) */
    double max_penetration;  /* largest penetration left after a contact correction, m */
    double force;         /* mean contact force on the projectile along −z over the last
                             step, N (model part) */
    double impulse_total; /* contact impulse on the projectile along −z since the start,
                             N·s (model part): the sum of force × step, = mass × (initial −
                             current velocity); a frame's mean force is its increase over
                             the frame / the frame's length */
} wff_projectile;

typedef struct wff_clamp {
    int n;                /* nodes held between the clamp faces */
    int *node;
    double *normal_force; /* clamping force on each node, N (modelled part) */
    double *impulse;      /* each node's friction impulse in the last step, x and y, N·s
                             (workspace, 2 per clamp node) */
    double force_whole;   /* total clamping force as given, whole specimen, N */
    double mu;            /* Coulomb friction, each of two faces */
    int region;           /* physical surface tag the force is shared over by area (-1: a
                             curve group, shared by lumped mass) */
    double radius;        /* the plates press only within this distance of (0, 0), m
                             (0: everywhere; setting clamp_radius) */
    int edge_reaction;    /* 1: the out-of-plane reaction of a node presses it on one face
                             and adds mu |R_z| to its friction limit (setting
                             clamp_edge_reaction) */
} wff_clamp;

typedef struct wff_energies {
    double kinetic_inplane, kinetic_transverse, kinetic_amplitude, kinetic_projectile;
    double internal;          /* stored energy of the cells */
    double dissipated_shear;
    double dissipated_friction;  /* clamp friction, projectile friction and the inelastic
                                    normal contact */
    double dissipated_failure;   /* stored energy released by yarn damage */
    double dissipated_slip;      /* dissipated by yarn slip at the crossovers (docs/model.md
                                    §24) */
    double eroded;               /* stored energy of eroded elements at their erosion */
    double external_work;     /* work done on the model by prescribed-velocity DOFs */
    double transfer;          /* stored + kinetic energy changed by mesh transfers
                                 (wff_model_remesh), a term of the balance like W */
    double error;             /* (E_now + D − W) − E_0, relative to the reference energy
                                 (D: shear, friction and failure dissipation and the
                                 eroded energy); the kinetic energy in E_now is the
                                 staggered one (kinetic_stagger) */
    double error_integer_step; /* the same balance with the integer-step kinetic energy
                                 (the instability detector's: the staggered balance is kept
                                 by a growing linear mode too, its kinetic and stored
                                 energies running apart with opposite signs) */
    double reference;         /* normaliser: the largest of the initial kinetic energy,
                                 the external work, the kinetic energy now and the change
                                 of stored energy since the start */
    double dissipated_ply_contact; /* the kinetic energy ply-to-ply contact removed (pack.h),
                                 a term of D in error */
    double kinetic_stagger;   /* (Δt²/8) Σ f²/m over the free DOFs and the projectile: the
                                 kinetic energies above (at the integer step, v^{n+½} −
                                 ½Δt a^n) less this is ½ Σ m v^{n−½}·v^{n+½}, the kinetic
                                 energy of the balance in error (docs/model.md §12) */
    double impulse_stagger;   /* the contact impulses' part of that stagger, ½Δt Σ v^{n+½}·g
                                 (g the contact forces): the balance's kinetic measure is
                                 the kinetic energies less kinetic_stagger plus this, i.e.
                                 with the elastic forces alone in the stagger (the contact
                                 forces' work booked by the trapezoidal rule instead:
                                 docs/model.md §14) */
} wff_energies;

/* A boundary condition as it was set, by group name, so that a mesh
 * transfer (wff_model_remesh) can set it again on the new mesh. */
enum { WFF_BC_CLAMP = 3 };
typedef struct wff_bc_record {
    char group[WFF_MESH_NAME_MAX];
    int kind;             /* WFF_DOF_FIXED, WFF_DOF_PRESCRIBED or WFF_BC_CLAMP */
    int component;        /* WFF_UX..WFF_DA2 (not used by the clamp) */
    double value;         /* prescribed velocity, m/s, or the clamp's normal force, N */
    double mu;            /* the clamp's friction coefficient */
} wff_bc_record;

typedef struct wff_model wff_model;
#ifndef WFF_MODEL_OPAQUE
struct wff_model {
    wff_comm comm;            /* the ranks the model runs over (comm.h; one by default) */
    struct wff_dist *dist;    /* its split over them (plugin/distribute.c), NULL on one rank */
    wff_mesh mesh;
    wff_material mat;
    wff_elements el;
    wff_element_material em;
    int n_nodes, n_dofs;
    double *u, *v, *f, *mass;
    unsigned char *dof_kind;
    double *v_prescribed;     /* per DOF, used where dof_kind is PRESCRIBED */
    double *state;            /* internal state of the quadrature points (3 per tri, then
                                 4 per quad), n_state per point: point p's state i at
                                 state[n_state p + i] (cell.h; King: gamma_f first) */
    int n_state;              /* states per point (mat.n_state; with zones the largest
                                 of the zones' materials') */
    double *reaction;         /* per DOF: −f_int on fixed and prescribed DOFs, last step */
    double fabric_mass;       /* Σ nodal (displacement) masses, kg (model part) */
    double preload[4];        /* the preload F_pre as given (material frame, row-major 2×2;
                                 the identity by default); em.F_pre = R(θ) preload with
                                 θ = em.orientation (membrane.h) */

    double time, dt, dt_stable, dt_factor;
    double t_stop;            /* the time the model steps no further than, landing on it
                                 exactly (setting "t_stop"; 0: none), s */
    int travel_off;           /* setting travel_limit 0: the step is dtfactor × the stable
                                 step only (the amplitudes' travel not limited) */
    double travel_fraction;   /* setting travel_fraction: the share of its cell's amplitude
                                 length a free amplitude may travel in one step, × dtfactor
                                 (WFF_TRAVEL by default; docs/model.md §12) */
    double travel_share;      /* the amplitudes' kinetic energy's share of the balance's
                                 reference, held (its largest, decaying by TRAVEL_SHARE_HOLD
                                 a step; 1 before the first step): the travel limit's
                                 fraction follows it */
    long travel_steps;        /* steps the travel limit shortened */
    double dt_travel;         /* the travel limit at the last step, s (0: none yet) */
    int adaptive;             /* setting adaptive_step: an instability halves dtfactor and
                                 the run goes on from the last good state */
    long step_cuts;           /* the halvings so far */
    int growth_steps;         /* consecutive steps of geometric growth of the error */
    void *snapshot[2];        /* the last two good states (checkpoint.c's fields), adaptive
                                 only */
    size_t snapshot_size[2];
    long snapshot_step[2];    /* their steps (-1: none) */
    int snapshot_newest;      /* which of the two is the newer */
    int cut_since_snapshot;   /* a cut went back to the newer since it was kept */
    long step;
    int dt_interval;          /* steps between stable-step updates */
    int dt_worst_element;
    double symmetry_factor;

    wff_projectile projectile;
    wff_clamp clamp;

    /* accumulated */
    double internal_energy;   /* at the last force pass, J (model part) */
    double dissipated_shear, dissipated_friction, external_work;
    double dissipated_failure; /* stored energy released by yarn damage, J (model part) */
    double dissipated_slip;   /* dissipated by yarn slip at the crossovers, J (model part) */
    double eroded_energy;     /* stored energy of eroded elements at erosion, J (model part) */
    int n_eroded;             /* elements eroded so far */
    int *eroded_now;          /* the elements the last force pass eroded (plugin/erosion.c;
                                 model numbering, in element order; NULL while erosion is
                                 off), n_eroded_now of them */
    double *eroded_now_energy; /* their stored energy at erosion, J (model part) */
    int n_eroded_now;
    double initial_total;     /* kinetic + internal at the start, J (model part) */
    double initial_kinetic;   /* the balance's (staggered) kinetic energy at the start */
    double stagger_reference; /* the stagger (Δt²/8)Σf²/m counted out of initial_total, J
                                 (model part): error_integer_step puts it back */
    double stagger_shift;     /* Σ over the steps of the stagger's change with the step,
                                 (Δt_{n+½}² − Δt_{n−½}²)/8 Σ f_n²/m, J (model part): the
                                 staggered balance's term for a step that changes (with it,
                                 exact on a linear system at any sequence of steps) */
    double *contact_force;    /* per DOF, N: the last step's impulses j of every part that
                                 gives them (contacts, the friction clamp) as forces
                                 j/Δt_mid, also in f; the balance keeps them out of its
                                 stagger and books their work instead (docs/model.md §14) */
    double dt_mid;            /* the last velocity update's Δt_mid, s */
    int v_half_valid;         /* 1 once v holds a half-step velocity */
    long element_steps;       /* elements × steps done, for cost figures */
    double force_seconds;     /* wall time in the steps' force passes (with their exchange
                                 over ranks), s: a timer (summary.json force_seconds) */
    long amplitude_iterations; /* static amplitudes: Newton iterations over all points and
                                  steps since the model was built (not checkpointed) */
    int blowup_steps;         /* consecutive steps with more than half the reference
                                 energy created (instability detector) */
    double last_error;        /* energy balance error at the last step */
    double *operator_scratch; /* operators.c's copy of γᶠ and the static amplitudes for a
                                 force pass without side effect (allocated on first use) */
    double transfer_energy;   /* Σ (after − before) of stored + kinetic energy over mesh
                                 transfers since the start, J (model part) */
    int n_bc;                 /* boundary conditions set so far, in order (remesh.c) */
    wff_bc_record *bc;
    struct wff_zones *zones;  /* per-region materials (plugin/zones.c); NULL: the model's
                                 material everywhere, the plain path */
    /* The model's own order (plugin/renumber.c, include/wovenff/renumber.h):
     * every array above is in it; NULL when the mesh's own order is kept. */
    int *node_user;           /* per model node: the caller's node (0-based) */
    int *node_model;          /* per caller's node: the model's */
    int *element_user;        /* per model element (tris, then quads): the caller's */
    int *element_model;       /* per caller's element: the model's */
    struct wff_pack *pack;    /* plies and their contact (include/wovenff/pack.h); NULL:
                                 one ply, the plain path */
    struct wff_cutting *cutting; /* the nose's contact pressure (plugin/cutting.c); NULL
                                    until the first step with a projectile */
    struct wff_backing *backing; /* the backing block behind the pack (plugin/backing.c);
                                    NULL until a backing setting is given */
};
#endif /* WFF_MODEL_OPAQUE */

/* For a caller that keeps the model behind a pointer (the FreeFEM binding,
 * which does not see the struct: WFF_MODEL_OPAQUE): an empty model to create
 * into (NULL if out of memory), and wff_model_free and free together. */
wff_model *wff_model_new(void);
void wff_model_delete(wff_model *m);
/* Its sizes and parts, read through calls: DOFs (5 per node), nodes,
 * triangles and quadrilaterals, steps taken, threads (resolved), whether a projectile is set, its
 * mesh and material (the model's order; include/wovenff/renumber.h maps to the
 * caller's). */
int wff_model_dof_count(const wff_model *m);
int wff_model_node_count(const wff_model *m);
int wff_model_triangle_count(const wff_model *m);
int wff_model_quad_count(const wff_model *m);
long wff_model_step_count(const wff_model *m);
int wff_model_thread_count(const wff_model *m);
int wff_model_has_projectile(const wff_model *m);
const wff_mesh *wff_model_mesh(const wff_model *m);
const wff_material *wff_model_material(const wff_model *m);

/* Create a model from a mesh file (.geo or .msh, see mesh.h; mesh_options
 * may be NULL) and a material file: at rest, no preload (wff_model_set_preload
 * sets one), every DOF free except the amplitudes of a cell without any,
 * dtfactor 0.8, dtinterval 20, symmetry 1. On failure nothing is allocated. */
int wff_model_create(wff_model *m, const char *mesh_path, const wff_mesh_options *mesh_options,
                     const char *material_path, wff_error *err);
/* The same from a mesh already in memory; the model takes the mesh's arrays
 * over (mesh is emptied, also on failure, when they are freed). A model from
 * a file renumbers its nodes and elements for speed (include/wovenff/renumber.h:
 * the API keeps the file's numbering); this one keeps the caller's order, so
 * that a C caller may index the model's arrays with its own numbers
 * (wff_model_create_ordered renumbers on request, as the FreeFEM binding does). */
int wff_model_create_from_mesh(wff_model *m, wff_mesh *mesh, const char *material_path,
                               wff_error *err);
void wff_model_free(wff_model *m);

/* Preload: F_pre (row-major 2×2, det > 0) applied at every material point
 * (the masses follow it) and uniform initial amplitude changes dA0 (m; not
 * used by a cell without amplitudes). Before the first step only (an error
 * after it). */
int wff_model_set_preload(wff_model *m, const double F_pre[4], const double dA0[2],
                          wff_error *err);

/* Orientation: the warp direction E1 at `theta` (rad, counter-clockwise) to
 * the mesh's x axis, the weft at theta + 90° (membrane.h: the cell sees
 * F_mesh R(θ) F_pre, its stress goes back through R(θ)ᵀ; the preload is a
 * material-frame state). Every zone's material takes the model's orientation.
 * Before the first step (setting it again to the value it has is allowed
 * after, as a restart does); theta must be finite and at most
 * WFF_ANGLE_MAX_DEG degrees in size. 0 by default: exactly the
 * results without orientation. The setting "orientation" of
 * wff_model_set_option takes degrees. */
int wff_model_set_orientation(wff_model *m, double theta, wff_error *err);

/* The largest angle the model takes, degrees: beyond it an angle reduced
 * modulo 360 keeps less than ~1e-10 degree of what was meant (a double's
 * spacing grows with its size; at 1e30 degrees it is 1e14 degrees). */
#define WFF_ANGLE_MAX_DEG 1e6

/* An angle in degrees (an orientation, a ply's) as the model takes it: -1
 * and a message naming `what` when it is not finite or beyond
 * ±WFF_ANGLE_MAX_DEG; else *reduced = deg modulo 360 (exact: fmod, in
 * (-360, 360), the sign kept, -0 as 0) and *theta its radians, exactly
 * k π/2 at multiples of 90 degrees. Every angle the model takes goes through
 * it before any test (the quarter model's multiple of 90 among them). */
int wff_angle_degrees(double deg, const char *what, double *reduced, double *theta,
                      wff_error *err);

/* Fix DOF `component` (WFF_UX..WFF_DA2) of every node on the physical curve
 * named `curve` (dim 1) or in the physical surface (dim 2) named so. Returns
 * the number of nodes, or -1 if no group has that name (an error). Fixing a
 * fixed DOF again does nothing; fixing a prescribed one is an error (naming
 * the node), as is prescribing a fixed one (the clamp's u_z and the
 * amplitudes of a cell without any are fixed); prescribing a prescribed DOF
 * again sets its new velocity. Nothing is changed when it fails. */
int wff_model_fix_group(wff_model *m, const char *group, int component, wff_error *err);

/* Move DOF `component` of the group's nodes at velocity `velocity` (m/s). */
int wff_model_prescribe_group(wff_model *m, const char *group, int component, double velocity,
                              wff_error *err);

/* Friction clamp on the nodes of a group (docs/clamp.md): pressed flat
 * (u_z = 0), total clamping force `normal_force` (N, the whole specimen's: the
 * modelled part takes normal_force / symmetry_factor) shared by the group's
 * own nodal area (a physical surface: the area of its elements only, not of
 * the free fabric next to its boundary; a curve: by lumped mass), Coulomb
 * friction μ on each face on the node's free in-plane components: a node
 * sticks while |f| < 2 μ N_a. The settings clamp_radius and
 * clamp_edge_reaction (wff_model_set_option, after this call) change where the
 * force acts and the limit. */
int wff_model_clamp_friction(wff_model *m, const char *group, double normal_force, double mu,
                             wff_error *err);

/* Rigid projectile of shank radius `radius` (m), moving along +z at
 * `velocity` (m/s, >= 0) with Coulomb friction mu against the fabric, placed
 * with its nose tip at z = 0 touching the fabric plane (move it with
 * wff_model_place_projectile). mass (kg) is the whole projectile's. Its shape
 * (wff_model_set_projectile_shape) and axis (wff_model_set_impact_point) may
 * be set before or after. One projectile per model: a second call is an
 * error. */
int wff_model_set_projectile(wff_model *m, double radius, double mass, double velocity,
                             double mu, wff_error *err);

/* Nose shape (WFF_NOSE_*) and, for the flat nose, its edge radius r_e (m,
 * 0 <= r_e <= radius; ignored, and 0 accepted, for the others). Before the
 * first step; with a projectile set, refused (naming the node) if the fabric
 * would be inside the new shape. */
int wff_model_set_projectile_shape(wff_model *m, int nose, double edge_radius, wff_error *err);
/* The chisel nose (WFF_NOSE_CHISEL) with its flat's width w (m, 0 <= w <= 2r
 * once the radius is known) and bevel angle β from the end face (degrees, in
 * (0, 90)). Before the first step; refused like the other shapes if the fabric
 * would be inside it. */
int wff_model_set_projectile_chisel(wff_model *m, double flat_width, double bevel_degrees,
                                    wff_error *err);
/* Obliquity θ (degrees, 0 <= θ < 90): the path of the projectile tilted by θ
 * from the fabric's normal toward +x, the nose's axis along the path; the
 * projectile then moves along the path only (held to its line of flight: the
 * fabric's push across the path is taken by that guide, which does no work;
 * docs/limits.md). Before the first step; a symmetric model (symmetry 2 or 4)
 * is refused (the tilt breaks its mirror planes), here or when the symmetry is
 * set, whichever comes second. θ = 0 is the normal shot, bit for bit. With a
 * projectile set, it is put back touching (wff_projectile_lead). */
int wff_model_set_obliquity(wff_model *m, double degrees, wff_error *err);
/* How far (along z, m) the projectile's surface reaches ahead of its tip point
 * (0 for a normal shot): the tip along the path that puts its foremost point
 * at z = −gap is −(lead + gap) / cos θ. */
double wff_projectile_lead(const wff_projectile *p);
/* The whole projectile's momentum (kg m/s): mass_whole × velocity × path. */
void wff_projectile_momentum(const wff_projectile *p, double momentum[3]);
/* The same for a model's projectile (0 without one), for callers that do not
 * see the model's struct (the binding). */
double wff_model_projectile_lead(const wff_model *m);
void wff_model_projectile_momentum(const wff_model *m, double momentum[3]);
/* WFF_NOSE_* for "hemisphere", "flat", "sphere" or "chisel"; -1 (err set,
 * listing them) otherwise. */
int wff_nose_from_name(const char *name, wff_error *err);
const char *wff_nose_name(int nose);

/* Projectile axis at (x, y) (m, reference configuration; 0, 0 by default).
 * Before the first step. A symmetric model (symmetry 2 or 4) can only be
 * struck on its symmetry planes x = 0 (and) y = 0: an axis off them is an
 * error here or when the symmetry is set, whichever comes second. */
int wff_model_set_impact_point(wff_model *m, double x, double y, wff_error *err);

/* Penetration δ (m, > 0 inside, 0 outside) of point x (current position, m)
 * into the projectile as it is now, and the outward surface normal at the
 * nearest surface point (set only when δ > 0). */
double wff_projectile_penetration(const wff_projectile *p, const double x[3], double normal[3]);
/* The length of the nose along the axis, m: its rear is at tip − this
 * (hemisphere r, flat nose its edge radius r_e, sphere 2r, chisel its bevel's
 * depth (r − w/2) tan β). */
double wff_projectile_nose_length(const wff_projectile *p);

/* Advance until time >= t_end (or max_steps). t_end must be finite and not
 * before the current time (an error otherwise; t_end == time does nothing).
 * Stops with -1 and a message
 * naming what, where and when on NaN, a degenerate element, an unstable
 * step or a projectile that passes through the fabric. The instability check
 * (every step: energy created > 50 % of the reference energy on 3 steps in a
 * row, or > 5000 % at once; a force failure while it counts is reported as
 * the instability)
 * names the element that sets the stable step and suggests a step and a
 * dtfactor. */
int wff_model_advance(wff_model *m, double t_end, long max_steps, wff_error *err);

/* Sum of the reactions (−f_int, N, model part) on DOF `component` of the
 * group's fixed or prescribed nodes at the last step; returns the node count. */
int wff_model_group_reaction(wff_model *m, const char *group, int component, double *sum,
                             wff_error *err);

/* Solver settings by name: dtfactor (0, 2], dtinterval (steps between
 * stable-step updates, >= 1), symmetry (1, 2 or 4, before the first step:
 * the modelled part is 1/symmetry of the specimen; masses and forces given
 * are divided by it, energies and the projectile force read are multiplied
 * by it; an impact point off the symmetry planes is an error), reference_path (1: the cell's plain
 * evaluate() everywhere, 0: its fast path where it has one; results agree to
 * round-off), threads (every per-step pass: forces, updates, clamp, energies,
 * contact search, stable step; 0: wff_default_threads()), amplitude_mass_factor
 * (>= 1: heavier amplitudes, longer steps), static_amplitudes (1: balanced at
 * every point instead of dynamic DOFs), contact_search (1: only nodes the
 * projectile can reach; 0: every node), erosion (0 off; 1 an element is
 * eroded once both yarn families have ruptured, damage 1, at every point of
 * it, the default when the material has failure; 2 either family: one family
 * ruptured at every point; refused for a cell without yarn failure or a
 * material with failure = 0, and 0 once elements have eroded; plugin/erosion.h:
 * an eroded element gives no force, no stable step, no stored energy, and its
 * stored energy then goes to the eroded energy); for a friction clamp (set first):
 * clamp_radius (m, >= 0: the clamping force is shared only over the clamp's
 * nodes within this distance of (0, 0), e.g. a ring at the opening's edge;
 * the others stay flat without friction; 0: all of them, the default) and
 * clamp_edge_reaction (1: a node's out-of-plane reaction R_z, e.g. where the
 * fabric bends over the plates' edge at the opening, adds mu |R_z| to its
 * friction limit; 0: the default), orientation (degrees: the warp at that angle to
 * the mesh's x axis, wff_model_set_orientation; exact at multiples of 90). */
int wff_model_set_option(wff_model *m, const char *key, double value, wff_error *err);

/* The model's state quantities by name (plugin/values.c): time, step, dt,
 * the projectile's, the energies (whole specimen), element and node counts,
 * erosion's, then those of the step's parts (a pack's: plies, back_face,
 * ply_*). wff_model_value_count() of them, named wff_model_value_name(i) in
 * a fixed order; wff_model_values writes them all in that order (the energies
 * only with with_energies, the parts' only with with_parts: else 0);
 * wff_model_value one, -1 (err set) for an unknown name. */
int wff_model_value_count(void);
const char *wff_model_value_name(int index);
void wff_model_values(const wff_model *m, int with_energies, int with_parts, double *out);
int wff_model_value(const wff_model *m, const char *key, double *value, wff_error *err);

/* The default thread count: OMP_NUM_THREADS's (its first level) when it is
 * set, else the processors this process may run on (its affinity mask),
 * at most WFF_MAX_THREADS. The setting threads = 0 takes it (threads: every
 * per-step pass; the count a model holds, m->el.n_threads, is the resolved
 * number, and a checkpoint records that). */
int wff_default_threads(void);

/* Energies now (whole specimen: model part × symmetry_factor). */
void wff_model_energies(const wff_model *m, wff_energies *out);

/* The physical invariants now (plugin/invariants.c): every dissipation not
 * negative (the shear flow's, the failure's, the eroded energy; the contacts'
 * and friction's, the model's and each part's, as one sum: two contacts acting
 * on one node share its velocity change by the accounting's convention), the
 * projectile's kinetic energy not
 * above all the energy the run was given; beyond round-off (1e-9 of the
 * balance's reference energy). Returns the number violated and describes them
 * in out[size] ("" when none), "; "-separated, each naming the quantity and
 * its value. A violation does not stop the run. */
int wff_model_invariants(const wff_model *m, char *out, size_t size);

/* The time step the next advance would take from the current state (s):
 * dtfactor × the stable step over the elements (the state is not changed; a
 * scene checks with it, before the loop, that a run takes at least one step). */
double wff_model_step_estimate(const wff_model *m);

/* Stored energy per mechanism of the cell (names: wff_cell_mech_name),
 * whole specimen (× symmetry_factor), J, at the current state with γᶠ held.
 * Fills out[0 .. n_mech−1] (all zeros if the cell has no energy split) and
 * returns n_mech (at most WFF_MECH_MAX). */
int wff_model_energy_split(const wff_model *m, double *out);

/* Name of state i (0 <= i < m->n_state) of the model's points: the cell's
 * state_names (with zones, those of the material carrying the most states;
 * every zone's are a prefix of them), e.g. "gamma_f". */
const char *wff_model_state_name(const wff_model *m, int i);

/* Move the projectile (set with wff_model_set_projectile) so that its nose
 * tip is at z = tip (m; < 0: a stand-off in front of the fabric at z = 0).
 * An error, naming the node, if a fabric node would be inside it. */
int wff_model_place_projectile(wff_model *m, double tip, wff_error *err);

/* Checkpoints. wff_model_save writes the whole evolving state (u, v, f, every
 * internal state of every point, reactions, prescribed velocities, time, step, Δt, stable-step estimate,
 * projectile state and contact candidates, energy accumulators, initial
 * energies) to `path`, binary, atomically (path.tmp, fsync, rename):
 *
 *   header   magic "WFFSTATE", format version, byte-order mark, the model's
 *            sizes (nodes, triangles, quads, quadrature points, candidates),
 *            the points' state layout (n_state and the states' names: a
 *            checkpoint of another layout is refused, naming both),
 *            64-bit FNV-1a fingerprints of the mesh (coordinates and
 *            connectivity), the material (cell and parameters), the lumped
 *            masses (material and preload) and the boundary conditions
 *            (DOF kinds, friction clamp), the solver settings (dtfactor,
 *            dtinterval, symmetry, reference_path), the orientation (a
 *            checkpoint of another is refused, naming both), the projectile's
 *            radius, mass and friction;
 *   payload  the state;
 *   trailer  FNV-1a 64 checksum of everything before it.
 *
 * wff_model_load_state reads it into a model built the same way (same mesh,
 * material, preload, boundary conditions, settings and projectile) and fails,
 * saying which of these differs, otherwise; a truncated or altered file fails
 * its checksum. Advancing after a load gives the same numbers, bit for bit, as
 * the run that wrote the checkpoint. Same machine type only (native doubles,
 * checked by the byte-order mark). */
#define WFF_CHECKPOINT_VERSION 11 /* 2: the projectile's impulse_total added; 3: the points'
                                    generic state (n_state and names in the header, every
                                    state saved), failure and eroded energies; 4: the
                                    erosion rule (header) and the eroded flags; 5: the
                                    orientation (header); 6: the amplitudes' travel limit and its
                                    count; 7: the initial kinetic energy the staggered one,
                                    its stagger kept (stagger_reference); 8: the stagger's
                                    shift with the step (stagger_shift); 9: the contact
                                    forces (contact_force) and the last Δt_mid; 10: the
                                    yarn slip's dissipation (dissipated_slip); 11: the backing
                                    block's law states a point (fully integrated: eight an
                                    element) and its contact's overlaps a footprint point */
int wff_model_save(const wff_model *m, const char *path, wff_error *err);
int wff_model_load_state(wff_model *m, const char *path, wff_error *err);

/* Node nearest (x, y) in the reference configuration. */
int wff_model_nearest_node(const wff_model *m, double x, double y);

/* Per-node output: value of a named field at every node into out (n_nodes).
 * Names: ux uy uz dA1 dA2 vx vy vz (the stored velocity, see state.h), A1 A2
 * (absolute amplitudes A_k0 + dA_k, m), the cell's diagnostics (e.g. T1 T2
 * F_I), gamma (shear angle, rad) and every element field of state.h (P11 ..
 * lambda1 .. gamma_f, every internal state by name ...). Element values are averaged to nodes by area (the
 * area-weighted mean over the elements around the node).
 * Returns -1 for an unknown name (listing the known ones). */
int wff_model_nodal_field(const wff_model *m, const char *name, double *out, wff_error *err);

/* Element operators for a caller's own explicit loop (plugin/operators.c).
 * Arrays of states and forces have 5 entries per node, node-major
 * (ux uy uz dA1 dA2: FreeFEM's [P1,P1,P1,P1,P1]); forces in N, states in m.
 *
 * wff_model_forces: internal nodal forces and amplitude residual forces
 * (f_a^u = −∫ P ∇N_a, f_a^A = ∫ R N_a; the force the built-in step divides by
 * the mass) at displacement U into R. dt = 0: γᶠ held and nothing in the
 * model changes. dt > 0: γᶠ flows over dt and the model's stored energy,
 * shear dissipation and element-step count advance, exactly as the force pass
 * of a built-in step of length dt (the model's u is not touched). *energy:
 * the stored energy at U, J, whole specimen (× symmetry; NULL: not wanted). */
int wff_model_forces(wff_model *m, const double *U, double *R, double dt, double *energy,
                     wff_error *err);
/* The lumped mass of every DOF (kg; amplitude DOFs 1/6 of the nodal mass ×
 * amplitude_mass_factor, in kg as the amplitude equation of motion uses it). */
void wff_model_masses(const wff_model *m, double *M);
/* The stable explicit step (s, factor 1) at displacement U (NULL: the model's
 * u); *worst (may be NULL) the element that sets it. -1 with err if it is not
 * positive (degenerate or NaN state). No side effect. */
int wff_model_stable_step(const wff_model *m, const double *U, double *dt, int *worst,
                          wff_error *err);
/* The amplitudes' travel limit (s, factor 1; docs/model.md §12) for a
 * caller's own loop: the longest step in which no free amplitude DOF moving
 * at V (m/s) under the forces R (N; both in the caller's order, 5 per node)
 * travels more than 0.625 of the cells' amplitude length; INFINITY for cells
 * without one. -1 with err for a value that is not finite. */
int wff_model_travel_step(const wff_model *m, const double *V, const double *R, double *dt,
                          wff_error *err);
/* One built-in step (wff_model_advance by exactly one step); *dt_taken the
 * step length, s. */
int wff_model_step(wff_model *m, double *dt_taken, wff_error *err);
/* DOF kinds (WFF_DOF_FREE 0, FIXED 1, PRESCRIBED 2) into kind and the
 * prescribed velocities (m/s, 0 elsewhere) into v_prescribed (NULL: not wanted). */
void wff_model_dof_kinds(const wff_model *m, double *kind, double *v_prescribed);
/* The projectile's candidate nodes refreshed at displacement U, as the
 * built-in step does every dtinterval steps; returns their number (0 without
 * a projectile). */
int wff_model_contact_search(wff_model *m, const double *U);
/* The projectile's kinematic contact and friction (the built-in correction)
 * on a caller's state: the projectile put at tip[0] (nose tip z, m) moving at
 * tip[1] (m/s, along +z); nodes predicted at U + dt V inside it get impulses:
 * V is corrected in place, the impulses enter R as forces impulse/dt_mid
 * (N), the projectile's velocity is updated in tip[1] and in the model, and
 * its mean force over the step is the model's projectile force. *dissipated:
 * the energy the contact dissipates, J, whole specimen (added to the model's
 * dissipated_friction too). -1 (err set) if the projectile has passed through
 * the fabric or there is no projectile. */
int wff_model_contact(wff_model *m, const double *U, double *V, double *R, double tip[2],
                      double dt, double dt_mid, double *dissipated, wff_error *err);
/* The friction clamp's Coulomb correction on a caller's velocities V over
 * dt_mid; returns the energy dissipated, J, whole specimen (added to the
 * model's dissipated_friction too). No-op (0) without a friction clamp. */
double wff_model_clamp_correct(wff_model *m, double *V, double dt_mid);
/* The same as the built-in step does it: the friction impulses also added to
 * the caller's forces R as forces over dt_mid, and the energy dissipated at the
 * balance's measure, the work j·(V − ½Δt_before R/M) with Δt_before = 2 dt_mid −
 * dt (docs/model.md §14; dt the step to be taken next), J, whole specimen. -1
 * (err set) on bad steps or out of memory. */
int wff_model_clamp_correct_booked(wff_model *m, double *V, double *R, double dt,
                                   double dt_mid, double *dissipated, wff_error *err);
/* Mesh transfer (plugin/remesh.c): carry the whole state of m onto new_mesh,
 * a new mesh of the same specimen (every new node inside the old mesh, to
 * 1e-7 of its bounding-box diagonal; nearer than that a node outside snaps
 * to the nearest old element). The model takes the new mesh's arrays over
 * (new_mesh is emptied, also on failure, when they are freed).
 *
 *   u and the integer-step velocity vⁿ (v^{n+½} − ½Δt f/M, the kinetic
 *   energy's velocity) of all 5 DOFs per node: P1 interpolation on the old
 *   triangles (a quad as its two triangles 0-1-2, 0-2-3) found by a bucket
 *   grid; γᶠ (and static amplitudes) per new quadrature point from the old
 *   element containing it (a triangle: P1 between its three point values; a
 *   quad: its nearest Gauss point); time, step, accumulators, settings,
 *   preload, projectile; the groups of the old mesh by name, found in the new
 *   mesh by name or by tag (edge label, triangle region); the boundary
 *   conditions and the clamp set again by group in the order they were set
 *   (a group they use missing in the new mesh is an error). A new node the
 *   projectile's nose had reached between the old nodes would be inside it:
 *   the projectile is moved back along z until none is (report->retraction;
 *   its velocity is kept). Then masses, the forces at uⁿ (γᶠ held), the
 *   stable step, v^{n+½} = vⁿ + ½Δt_new f/M and the contact correction, as
 *   at the start of a run.
 *
 * The energy: stored + kinetic (whole specimen) before and after; after −
 * before is added to the balance as a transfer term (wff_energies.transfer),
 * so energies.error measures the integration only. On failure m is
 * unchanged and usable. report may be NULL. */
typedef struct wff_remesh_report {
    double before, after;   /* stored + kinetic energy (the balance's, K − S), whole specimen, J */
    double retraction;      /* the projectile moved back by this, m */
    int snapped_nodes;      /* new nodes outside the old mesh by round-off */
    double largest_snap;    /* the farthest of them, m */
} wff_remesh_report;
int wff_model_remesh(wff_model *m, wff_mesh *new_mesh, wff_remesh_report *report,
                     wff_error *err);

/* Zonal materials (plugin/zones.c, docs/model.md "Zonal materials"). Every element
 * starts with the model's material (zone 0); each call gives the elements it
 * selects (tris first, then quads, as everywhere) a material of their own, a new
 * zone (a later call wins where two select the same element). Before the first
 * step; the masses, the clamp's share by mass and the stored energy follow.
 * preload: WFF_ZONE_PRELOAD_SHARED, the zone's cell sees the model's preload
 * F_pre; WFF_ZONE_PRELOAD_MATCHED, it sees its own diagonal preload, solved so
 * that its membrane forces per mesh width (P F_preᵀ / J_pre) equal the model's
 * cell's at the model's preload (only for a cell without amplitudes and a
 * diagonal model preload): the zones' boundary is in equilibrium at t = 0, and
 * it is solved again when the preload is set again. The lumped masses of every
 * zone are its ρ_A / J_pre of the model's preload (the mesh is the fabric's
 * preloaded configuration whichever preload a zone's cell sees). Refused: a zone
 * cell with amplitudes where the model's cell has none, static amplitudes,
 * more than WFF_ZONES_MAX zones; a mesh transfer (wff_model_remesh) of a model
 * with zones is refused too. Returns the number of elements selected (0 is
 * allowed: the zone is empty) or -1 (err set). */
#define WFF_ZONES_MAX 512 /* (a pack's zone is one per ply: pack.h) */
enum { WFF_ZONE_PRELOAD_SHARED = 0, WFF_ZONE_PRELOAD_MATCHED = 1 };
/* selected: one flag per element (nonzero: in the zone), in the caller's element
 * order (tris then quads of the mesh given; the model maps it to its own). */
int wff_model_zone_elements(wff_model *m, const unsigned char *selected,
                            const char *material_path, int preload, wff_error *err);
/* The elements of the physical surface named `group` (or of region tag
 * group_tag when group is NULL or empty: a FreeFEM region label). */
int wff_model_zone_region(wff_model *m, const char *group, int group_tag,
                          const char *material_path, int preload, wff_error *err);
/* The elements whose centre (mean of its nodes, reference configuration) is
 * farther than `radius` (m) from (x, y) (outside = 1) or within it (0). */
int wff_model_zone_disc(wff_model *m, double x, double y, double radius, int outside,
                        const char *material_path, int preload, wff_error *err);
/* Zones (1 + the calls so far: zone 0 is the model's material) and the elements
 * of zone k (0 for k out of range); the material of zone k (NULL outside). */
int wff_model_zone_count(const wff_model *m);
int wff_model_zone_size(const wff_model *m, int zone);
const wff_material *wff_model_zone_material(const wff_model *m, int zone);

#ifdef __cplusplus
}
#endif
#endif

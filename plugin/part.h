/* part.h: the step's spine. Every participant in a step beyond the element
 * force pass and the velocity update (the projectile's contact, element
 * erosion, a pack's per-ply accounts, the ply-to-ply contact, ...) is a
 * *part*: one constant ops table of its own, in the manner of a cell's
 * (include/wovenff/cell.h), defined in the part's own file. The ordered list
 * of parts is plugin/parts.c; the model, the integrator and the whole-model
 * operations run the list and name no part (docs/architecture.md, "The
 * step's spine"; the order of a step, docs/model.md §14).
 *
 * Every op is optional (NULL: the part takes no part in that pass). An op
 * is called for every model: a part that is not switched on for this model
 * (no projectile, no pack, erosion off) returns at once, with nothing done
 * and 0 returned, so that a model without it runs exactly as before the part
 * existed. */
#ifndef WFF_PART_H
#define WFF_PART_H

#include "solver_internal.h"

#include <stddef.h>
#include <stdint.h>

/* A setting by name (wff_model_set_option): check (NULL: none) refuses a value
 * with a message naming it and changes nothing; apply sets it (after check),
 * -1 (err set) when the model's state refuses it. */
typedef struct wff_setting {
    const char *name;
    int (*check)(const wff_model *m, double value, wff_error *err);
    int (*apply)(wff_model *m, double value, wff_error *err);
} wff_setting;

/* One field of the evolving state: data, element size, count (the
 * checkpoint's file order; state_fields.h). */
typedef struct wff_state_field { void *data; size_t size, count; } wff_state_field;
#define WFF_PART_FIELDS_MAX 16 /* a part's own fields at most (state_fields below) */

typedef struct wff_part_ops {
    const char *name;   /* for messages and docs: "projectile_contact", ... */

    /* The run starts (the first step, before its first force pass): set up
     * what the step needs. -1 (err set) on failure. */
    int (*setup)(wff_model *m, wff_error *err);

    /* The longest stable step of what the part itself integrates (a backing
     * block's elements), s; INFINITY when it has none. The model's step is the
     * smallest of the elements' and these. */
    double (*stable_step)(const wff_model *m);

    /* The stable step was updated, or an advance begins: refresh what depends
     * on the step or the positions (the projectile's contact candidates). */
    void (*refresh)(wff_model *m);

    /* After an accumulating element force pass at displacement u that
     * advanced the points' states `state` by dt_flow (0: held): returns the
     * stored energy the part took out of the pass's total (J, model part;
     * erosion: the eroded elements'); `stored` is the pass's total so far. */
    double (*after_forces)(wff_model *m, const double *u, const double *state, double dt_flow);

    /* After the velocity update: correct the velocities v^{n+½} (impulses,
     * added to f as forces over dt_mid); dt is the step to be taken next.
     * -1 (err set) on a failure the run must stop for. */
    int (*correct)(wff_model *m, double dt, double dt_mid, wff_error *err);

    /* After every part's correction (the step's velocities and forces final):
     * book the work of the impulses j this part gave in this step into its
     * dissipation, at the central difference's measure j·(v^{n+½} − ½Δt_before
     * a^n) (a^n = f/m, every part's impulses in f as j/dt_mid; dt_before the
     * step just taken, 0 at a start: wff_impulse_work, solver_internal.h): the
     * trapezoidal work of an impulsive
     * force, exact in the staggered balance at any sequence of steps
     * (docs/model.md §14). (The part also adds its impulses to
     * m->contact_force, where it adds them to f.) */
    void (*book)(wff_model *m, double dt_before, double dt_mid);

    /* Its term of the energy balance: the energy it has dissipated so far,
     * J (model part), a term of D in wff_energies.error. */
    double (*dissipated)(const wff_model *m);

    /* What its contacts alone have removed so far, J (model part), where its
     * `dissipated` holds more than dissipation (a backing block's own energy):
     * never negative (wff_model_invariants checks it: a contact that puts
     * energy in would hide in the block's term of the balance). NULL: none. */
    double (*loss)(const wff_model *m);

    /* A model-wide setting changed that the part follows (`what`:
     * "orientation", the warp direction in rad as value). */
    void (*follow)(wff_model *m, const char *what, double value);

    /* Its settings by name (wff_model_set_option), rows ending in a NULL name. */
    const wff_setting *settings;

    /* Its values by name (wff_model_value, values.c): their names (NULL-
     * terminated; after the model's own and the parts' before it in the list,
     * in wovenffState's order), and the value of one of them into *value. */
    const char *const *value_names;
    void (*value)(const wff_model *m, const char *key, double *value);

    /* Checkpoints and mesh transfers: 0 when the part carries over (or has
     * nothing to carry); 1 when it cannot, with a sentence saying why in
     * why[size] for the refusal's message. */
    int (*refuses_checkpoint)(const wff_model *m, char *why, size_t size);
    int (*refuses_remesh)(const wff_model *m, char *why, size_t size);

    /* Its evolving state, what a checkpoint saves and the adaptive step keeps
     * beyond the model's own (state_fields.c): its fields (pointer, element
     * size, count) into f, returning how many (at most WFF_PART_FIELDS_MAX); 0
     * when it has none for this model. A value the part recomputes from the
     * model's state every step is not state. */
    int (*state_fields)(wff_model *m, wff_state_field *f);

    /* Its settings that change the numbers, hashed into g (64-bit FNV-1a,
     * wff_fnv1a) for a checkpoint's fingerprint: a checkpoint loads only into a
     * model whose parts hash alike. g unchanged when the part is off. */
    uint64_t (*fingerprint)(const wff_model *m, uint64_t g);

    /* A mesh transfer (remesh.c) that no part refused: carry the part onto the
     * new model `to`, whose elements are set up (its arrays of the part are
     * NULL); -1 (err set) on failure. */
    int (*carry)(const wff_model *from, wff_model *to, wff_error *err);

    /* Free what the part allocated in m (wff_model_free). */
    void (*free)(wff_model *m);
} wff_part_ops;

/* parts.c: the parts in the order a step runs them (NULL-terminated). */
extern const wff_part_ops *const wff_parts[];

/* Convenience loops over the list (parts.c), each in the list's order. */
int wff_parts_setup(wff_model *m, wff_error *err);
void wff_parts_refresh(wff_model *m);
/* The smallest of the parts' stable steps (INFINITY: none). */
double wff_parts_stable_step(const wff_model *m);
double wff_parts_after_forces(wff_model *m, const double *u, const double *state,
                              double dt_flow);
int wff_parts_correct(wff_model *m, double dt, double dt_mid, wff_error *err);
/* After wff_parts_correct: every part's book op. */
void wff_parts_book(wff_model *m, double dt_before, double dt_mid);
double wff_parts_dissipated(const wff_model *m);
void wff_parts_follow(wff_model *m, const char *what, double value);
/* The part's setting row named key (NULL: none); the parts' setting names,
 * ", "-separated (led by ", " when `comma`), into out[size]. */
const wff_setting *wff_parts_setting(const char *key);
void wff_parts_setting_names(char *out, size_t size, int comma);
/* 1 with the first refusing part's reason in why[size], 0 when every part
 * carries over. */
int wff_parts_refuse_checkpoint(const wff_model *m, char *why, size_t size);
int wff_parts_refuse_remesh(const wff_model *m, char *why, size_t size);
/* Every part's state fields, in the list's order, into f; returns their number. */
int wff_parts_state_fields(wff_model *m, wff_state_field *f);
uint64_t wff_parts_fingerprint(const wff_model *m, uint64_t g);
int wff_parts_carry(const wff_model *from, wff_model *to, wff_error *err);
void wff_parts_free(wff_model *m);

#endif

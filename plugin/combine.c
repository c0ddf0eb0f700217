/* combine.c: which run-level features a model as configured takes, answered
 * once, with a reason (include/wovenff/combine.h).
 *
 * One table of rules. A rule refuses a feature either because of something
 * the model has (a predicate on the model: erosion on, a pack, zones, a cell
 * without amplitudes) or because of another feature of the same run (a pair).
 * The predicates ask the core's own queries (wff_model_damaged, wff_pack_plies,
 * wff_model_zone_count, the cell's n_amplitudes); `core` names the core's
 * refusal of the same thing, which stays as the guard of the state reached
 * (NULL: the rule is this table's alone, it was only in the scene scripts).
 * The table is in the order the rules are tried; the first that applies is
 * the answer. Where a part of the step answers for itself (part.h: a
 * checkpoint refused by the pack), the row asks the parts, as the core does. */
#include "wovenff/combine.h"

#include <stdio.h>
#include <string.h>

#include "erosion.h"
#include "pack.h"
#include "part.h"
#include "solver_internal.h"

/* What the model has that a rule may refuse; 1 with a description in what. */
typedef int (*model_has_fn)(const wff_model *m, char *what, size_t size);

static int has_erosion(const wff_model *m, char *what, size_t size)
{
    if (!m->el.eroded && !wff_model_damaged(m))
        return 0;
    snprintf(what, size, "the model has yarn failure with erosion on (a material with "
             "failure = 1)");
    return 1;
}

static int has_pack(const wff_model *m, char *what, size_t size)
{
    if (wff_pack_plies(m) <= 1)
        return 0;
    snprintf(what, size, "the model is a pack of %d plies", wff_pack_plies(m));
    return 1;
}

/* A backing block behind the pack (backing.c). */
static int has_backing(const wff_model *m, char *what, size_t size)
{
    double law = 0;
    wff_error err;
    if (wff_model_value(m, "backing", &law, &err) || law == 0)
        return 0;
    snprintf(what, size, "the model has a backing block (%s)", law == 1 ? "clay" : "gelatin");
    return 1;
}

/* A part of the step that a checkpoint cannot hold (part.h: the pack's ply
 * contact): the parts' own answer, the one checkpoint.c refuses with. */
static int parts_refuse_checkpoint(const wff_model *m, char *what, size_t size)
{
    return wff_parts_refuse_checkpoint(m, what, size);
}

static int has_zones(const wff_model *m, char *what, size_t size)
{
    if (!m->zones)
        return 0;
    snprintf(what, size, "the model has zonal materials (%d zones)", wff_model_zone_count(m));
    return 1;
}

/* One model over MPI ranks (distribute.c): its part refuses a mesh transfer. */
static int has_ranks(const wff_model *m, char *what, size_t size)
{
    if (m->comm.size <= 1)
        return 0;
    snprintf(what, size, "the model runs over %d MPI ranks", m->comm.size);
    return 1;
}

static int has_no_amplitudes(const wff_model *m, char *what, size_t size)
{
    if (wff_cell_amplitudes(m->mat.cell) > 0)
        return 0;
    snprintf(what, size, "the model's cell '%s' has no crimp amplitudes", wff_cell_name(m->mat.cell));
    return 1;
}

typedef struct combine_rule {
    const char *feature;  /* the feature refused */
    model_has_fn model;   /* refused when the model has this ... */
    const char *with;     /* ... or when the run also asks this feature */
    const char *reason;
    const char *core;     /* where the core refuses it too (NULL: only here) */
} combine_rule;

static const char *const transfer_no_erosion =
    "a mesh transfer does not carry the eroded elements (nor yarn damage); use one or the other";
static const char *const transfer_no_zones =
    "a mesh transfer does not carry the zones; use one or the other";
static const char *const checkpoint_no_part = "run it whole";
static const char *const checkpoint_no_transfer =
    "a checkpoint holds one mesh's state, and a restart rebuilds the model from the mesh "
    "file; use one or the other";
static const char *const zones_dynamic = "zones keep the amplitudes dynamic";

static const combine_rule rules[] = {
    {"remesh", has_erosion, NULL, transfer_no_erosion, "remesh.c wff_model_remesh"},
    {"remesh", has_pack, NULL, "a mesh transfer does not carry a pack; use one or the other",
     "remesh.c wff_model_remesh (a pack's zones)"},
    {"remesh", has_zones, NULL, transfer_no_zones, "remesh.c wff_model_remesh"},
    {"remesh", NULL, "zones", transfer_no_zones, "remesh.c wff_model_remesh"},
    {"remesh", has_ranks, NULL,
     "a mesh transfer over ranks is not built (the points' states would have to be gathered "
     "first); run -adapt on one rank", "distribute.c distributed_refuses_remesh (wff_model_remesh)"},
    {"remesh", has_backing, NULL, "a mesh transfer does not carry the backing block; use one "
     "or the other", "backing.c refuses_remesh"},
    {"remesh", NULL, "checkpoint", checkpoint_no_transfer, NULL},
    {"remesh", NULL, "restart", checkpoint_no_transfer, NULL},
    {"checkpoint", parts_refuse_checkpoint, NULL, checkpoint_no_part,
     "checkpoint.c wff_model_save (the same parts' answer)"},
    {"restart", parts_refuse_checkpoint, NULL, checkpoint_no_part,
     "checkpoint.c wff_model_load_state (the same parts' answer)"},
    {"static_amplitudes", has_erosion, NULL,
     "the balanced amplitudes of a point whose yarns have failed are not solved for; keep the "
     "amplitudes dynamic", NULL},
    {"static_amplitudes", has_pack, NULL,
     "a pack keeps a zone per ply, and zones keep the amplitudes dynamic",
     "model.c static_amplitudes (a pack's zones)"},
    {"static_amplitudes", has_zones, NULL, zones_dynamic, "model.c static_amplitudes, zones.c"},
    {"static_amplitudes", NULL, "zones", zones_dynamic, "model.c static_amplitudes, zones.c"},
    {"static_amplitudes", has_no_amplitudes, NULL, "there are no amplitudes to balance",
     "model.c static_amplitudes"},
    {"zones", has_erosion, NULL,
     "a far-field zone of a cell without yarn failure (the fitted linear_yarns) would never "
     "break; use one or the other", "erosion.c wff_erosion_set (a zone's cell without failure)"},
    {"zones", has_pack, NULL, "the far field's zone is a single ply's; use one or the other",
     NULL},
    {"obliquity", has_pack, NULL,
     "the ply contact holds the strike face on the nose along z (docs/threats.md); an oblique "
     "shot on a single ply", NULL},
    {"obliquity", has_erosion, NULL,
     "the perforation verdict is judged along z (docs/threats.md); an oblique shot without "
     "yarn failure", NULL},
    {"obliquity", has_backing, NULL,
     "the backing's contacts work along z (docs/backing.md); an oblique shot without a backing",
     NULL},
    {"adaptive_step", has_backing, NULL,
     "going back to a kept state does not take the backing block's step back; run it at a "
     "smaller -dtfactor", NULL},
    {"adaptive_step", parts_refuse_checkpoint, NULL,
     "the adaptive step goes back to a state the checkpoint's fields hold; run it at a smaller "
     "-dtfactor", "integrator.c start_adaptive (the same parts' answer)"},
};

static const char *const known =
    "remesh checkpoint restart static_amplitudes zones adaptive_step obliquity";

const char *wff_combine_features(void) { return known; }

/* 1 if the space-separated list holds word. */
static int has_word(const char *list, const char *word)
{
    size_t n = strlen(word);
    for (const char *p = list; *p;) {
        while (*p == ' ')
            p++;
        size_t k = strcspn(p, " ");
        if (k == n && strncmp(p, word, n) == 0)
            return 1;
        p += k;
    }
    return 0;
}

int wff_model_refuses(const wff_model *m, const char *features, char *why, size_t size)
{
    if (size)
        why[0] = '\0';
    if (!features)
        features = "";
    for (const char *p = features; *p;) { /* every name is known */
        while (*p == ' ')
            p++;
        size_t k = strcspn(p, " ");
        char name[40];
        snprintf(name, sizeof name, "%.*s", (int)(k < 39 ? k : 39), p);
        if (k && (k >= sizeof name || !has_word(known, name))) {
            snprintf(why, size, "unknown feature '%.*s' (known: %s)", (int)k, p, known);
            return -1;
        }
        p += k;
    }
    for (size_t r = 0; r < sizeof rules / sizeof rules[0]; r++) {
        const combine_rule *rule = &rules[r];
        if (!has_word(features, rule->feature))
            continue;
        char what[160];
        if (rule->model && rule->model(m, what, sizeof what)) {
            snprintf(why, size, "%s: %s: %s", rule->feature, what, rule->reason);
            return 1;
        }
        if (rule->with && has_word(features, rule->with)) {
            snprintf(why, size, "%s with %s: %s", rule->feature, rule->with, rule->reason);
            return 1;
        }
    }
    return 0;
}

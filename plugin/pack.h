/* pack.h: a multi-ply pack (plugin/pack.c, the part: per-ply accounts,
 * settings and values; plugin/pack_build.c, the stacked model's set-up; the
 * public calls are in include/wovenff/pack.h). The layout is plies.h's; the
 * ply-to-ply contact is ply_contact.h's. */
#ifndef WFF_PACK_INTERNAL_H
#define WFF_PACK_INTERNAL_H

#include "part.h"
#include "plies.h"

/* The pack's part (part.h): after the force pass, the per-ply energies of
 * the pass (the elements erosion took go to their ply's eroded energy); the
 * settings ply_mu and ply_thickness; the model-wide orientation followed by
 * every ply; its values; checkpoints refused; free. */
extern const wff_part_ops wff_pack_part;

/* 0, or -1 (err set, naming `what`) when ply is not one of the model's. */
int wff_pack_check_ply(const wff_model *m, int ply, const char *what, wff_error *err);

#endif

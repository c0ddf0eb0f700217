/* perforation.h: the part of a ply still held, and the shot's verdict
 * (plugin/perforation.c; the public call is include/wovenff/perforation.h). */
#ifndef WFF_PERFORATION_INTERNAL_H
#define WFF_PERFORATION_INTERNAL_H

#include "part.h"
#include "wovenff/perforation.h"

/* Which elements join a ply's nodes to its held edge (wff_ply_held_nodes). */
enum {
    WFF_HELD_LIVE = 0,   /* every element not eroded */
    WFF_HELD_INTACT = 1, /* not eroded, and no yarn family ruptured (damage 1) at a point:
                            every yarn of it still carries load, so a node held through such
                            elements is no further from the held edge than the yarns' rupture
                            strain lets it be */
};

/* Ply p's nodes held (held[i] = 1, i the node's index in the ply, 0 .. its
 * node count − 1; zeroed first): those reached from a node whose u_z is held
 * (the clamp, a fixed edge) through the elements `mode` lets join them; with no
 * such node in the ply, every node of such an element. Returns the number of
 * held nodes (0: none, every element gone), -1 if out of memory. */
int wff_ply_held_nodes(const wff_model *m, int p, int mode, unsigned char *held);

/* Ply p's node range in the model's order [*first, *end). */
void wff_ply_node_range(const wff_model *m, int p, int *first, int *end);

/* The part (part.h): the verdict's values by name, perforation (1 perforated,
 * 0 stopped, −1 undecided; −1 without a projectile), plies_holed and
 * plies_through; nothing else. */
extern const wff_part_ops wff_perforation_part;

#endif

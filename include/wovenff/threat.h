/* wovenff — the standard threats (-threat NAME): each projectile's mass,
 * dimensions and nose from its specification, with the source beside each
 * number (plugin/threat.c; the table and what each value rests on:
 * docs/threats.md). Rigid projectiles only: a bullet that deforms or a
 * fragment that yaws is out of scope (docs/limits.md "Threats"). */
#ifndef WOVENFF_THREAT_H
#define WOVENFF_THREAT_H

#include "wovenff/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wff_threat {
    const char *name;      /* the -threat value */
    const char *what;      /* one line: what it is */
    double mass;           /* kg, the nominal of its specification */
    double diameter;       /* m */
    double length;         /* m, overall; 0 where the specification gives none (bullets) */
    int nose;              /* WFF_NOSE_* (include/wovenff/solver.h) */
    double edge_radius;    /* flat nose: edge (torus tube) radius, m */
    double chisel_flat;    /* chisel: the flat's width across the tip, m */
    double chisel_bevel;   /* chisel: bevel angle from the end face, degrees */
    double density;        /* kg/m³ of a solid steel projectile (its volume × this is its
                              mass: checked by tests/c/test_threats.c); 0 for a jacketed bullet */
    const char *source;    /* where the numbers come from (docs/threats.md: each one) */
} wff_threat;

/* The threat named `name`; NULL (err set, listing the names) if none. */
const wff_threat *wff_threat_find(const char *name, wff_error *err);
/* How many threats the table has, and the k-th (0 <= k < count; NULL otherwise). */
int wff_threat_count(void);
const wff_threat *wff_threat_at(int k);

#ifdef __cplusplus
}
#endif

#endif

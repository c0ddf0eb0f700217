/* threat.c: the table of standard threats (include/wovenff/threat.h), each
 * number with its source. Where a value is derived rather than read from the
 * specification, the comment says how. Pure data and a lookup: nothing of the
 * model, contact or FreeFEM. */
#include "wovenff/threat.h"
#include "wovenff/solver.h"

#include <stdio.h>
#include <string.h>

#define GRAIN 64.79891e-6 /* kg: the grain (exact by definition, 64.79891 mg) */
#define INCH 25.4e-3      /* m */
#define STEEL 7850.0      /* kg/m³: 4340 / 1020 steel (the FSPs' and RCCs' material) */

/* A right circular cylinder of L/D = 1 of steel: the diameter from its mass,
 * (4 m / (π ρ))^(1/3), precomputed (tests/c/test_threats.c checks it). */
static const wff_threat threats[] = {
    {"ball", "the paper's steel projectile: 12.7 mm, hemispherical nose (the scene's default)",
     0.104,        /* kg: the ballistic scene's -mass default (Parsons et al., the seed) */
     12.7e-3,      /* m: the scene's nose diameter (2 × 6.35 mm) */
     0,            /* m: not modelled (the shank is unbounded behind the nose) */
     WFF_NOSE_HEMISPHERE, 0, 0, 0, 0, "Parsons, Socrate, Arata & Weerasooriya (the seed paper)"},
    {"fsp17", ".22 cal 17-grain fragment-simulating projectile (FSP), chisel nose",
     17.0 * GRAIN, /* kg: 17 ± 0.5 grain (1.10 g), MIL-DTL-46593B Table/Fig. 1, .22 cal */
     5.3975e-3,    /* m: the middle of 5.385–5.410 mm, MIL-DTL-46593B .22 cal (as quoted in
                      issue 30's brief; the drawing itself not re-read here) */
     6.30e-3,      /* m: overall length, as commonly quoted for the .22 cal FSP (not verified
                      against the drawing here) */
     WFF_NOSE_CHISEL, 0,
     2.5885e-3,    /* m: the flat's width: DERIVED so that this shape in 4340 steel weighs 17
                      grain (1.1016 g) with the diameter, length and bevel above */
     35.0,         /* deg: the chisel's bevel, MIL-DTL-46593B Fig. 1 (35°, taken from the end
                      face) */
     STEEL, "MIL-DTL-46593B (.22 cal FSP): mass, diameter, bevel; length as commonly quoted; "
            "flat width derived from the mass"},
    {"rcc", "4-grain right circular cylinder (RCC), L/D = 1, flat faces",
     4.0 * GRAIN,  /* kg: 4 grain (0.259 g), the RCC series 2, 4, 16, 64 grain (STANAG 2920) */
     3.4771e-3, 3.4771e-3, /* m: DERIVED: L = D of a steel cylinder of that mass */
     WFF_NOSE_FLAT, 0, 0, 0, STEEL,
     "STANAG 2920 RCC series (mass, L/D = 1); diameter derived from the mass in steel"},
    {"rcc2", "2-grain right circular cylinder (RCC), L/D = 1", 2.0 * GRAIN, 2.7598e-3,
     2.7598e-3, WFF_NOSE_FLAT, 0, 0, 0, STEEL,
     "STANAG 2920 RCC series (mass, L/D = 1); diameter derived from the mass in steel"},
    {"rcc16", "16-grain right circular cylinder (RCC), L/D = 1", 16.0 * GRAIN, 5.5196e-3,
     5.5196e-3, WFF_NOSE_FLAT, 0, 0, 0, STEEL,
     "STANAG 2920 RCC series (mass, L/D = 1); diameter derived from the mass in steel"},
    {"rcc64", "64-grain right circular cylinder (RCC), L/D = 1", 64.0 * GRAIN, 8.7619e-3,
     8.7619e-3, WFF_NOSE_FLAT, 0, 0, 0, STEEL,
     "STANAG 2920 RCC series (mass, L/D = 1); diameter derived from the mass in steel"},
    {"9mm", "9 mm Luger full metal jacket round nose (FMJ RN), rigid; nose as a hemisphere",
     8.0e-3,       /* kg: 8.0 g (124 grain), NIJ Standard-0101.06 Table 2 (levels IIA, II) */
     0.355 * INCH, /* m: 9.02 mm, the 9 mm Luger bullet's diameter (SAAMI Z299.3) */
     0,            /* m: the standard gives none (the shank is unbounded behind the nose) */
     WFF_NOSE_HEMISPHERE, 0, 0, 0, 0,
     "NIJ 0101.06 (mass); SAAMI (diameter); round nose approximated by a hemisphere"},
    {"44mag", ".44 Magnum semi-jacketed hollow point (SJHP), rigid; flat meplat, rounded shoulder",
     15.6e-3,      /* kg: 15.6 g (240 grain), NIJ Standard-0101.06 Table 2 (level IIIA) */
     0.429 * INCH, /* m: 10.90 mm, the .44 Rem. Magnum bullet's diameter (SAAMI Z299.3) */
     0,            /* m: the standard gives none */
     WFF_NOSE_FLAT,
     0.4 * 0.5 * 0.429 * INCH, /* m: an ASSUMED profile: the meplat a flat face of 60 % of the
                                  diameter, the shoulder a torus of 40 % of the radius */
     0, 0, 0, "NIJ 0101.06 (mass); SAAMI (diameter); nose profile assumed (docs/threats.md)"},
};

#define N_THREATS ((int)(sizeof threats / sizeof threats[0]))

int wff_threat_count(void)
{
    return N_THREATS;
}

const wff_threat *wff_threat_at(int k)
{
    return k >= 0 && k < N_THREATS ? &threats[k] : NULL;
}

const wff_threat *wff_threat_find(const char *name, wff_error *err)
{
    char known[256] = "";
    for (int k = 0; k < N_THREATS; k++) {
        if (name && strcmp(name, threats[k].name) == 0)
            return &threats[k];
        size_t used = strlen(known);
        snprintf(known + used, sizeof known - used, "%s%s", k ? ", " : "", threats[k].name);
    }
    wff_fail(err, "unknown threat '%s' (known: %s; docs/threats.md)", name ? name : "(null)", known);
    return NULL;
}

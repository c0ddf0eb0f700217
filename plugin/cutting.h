/* cutting.h: the nose's contact pressure on the fabric (plugin/cutting.c), a
 * part of the step (part.h): what yarn failure's transverse cutting reads
 * (plugin/cells/yarn_failure.h, docs/model.md §25). */
#ifndef WFF_CUTTING_H
#define WFF_CUTTING_H

#include "part.h"

/* The part: after the contacts' corrections (the projectile's and a pack's
 * ply solve), each node the nose touched gets its contact pressure, the
 * magnitude of the nose's force on it over its tributary reference area (Pa),
 * and every point at such a node whose material carries the contact_pressure
 * state gets that pressure (0 again once the nose leaves it), read by the
 * next force pass. Its values contact_pressure_max (the largest nodal
 * pressure of the last step, Pa) and contact_pressure_peak (the largest
 * since the start, Pa), measured with or without cutting. Nothing without a
 * projectile. */
extern const wff_part_ops wff_cutting_part;

#endif

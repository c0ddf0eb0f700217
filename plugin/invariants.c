/* invariants.c: the physical invariants a run keeps whatever its numerics
 * (wff_model_invariants, solver.h): every dissipation, the model's and each
 * part's (part.h: its `dissipated` op), is never negative; the projectile's
 * kinetic energy never exceeds all the energy the run was given (the initial
 * kinetic and stored energy, the external work, the mesh transfers'). A
 * violation is a fact about the numbers a user reads (a contact that put
 * energy in, a projectile faster than it struck), not an instability: the run
 * goes on, and the scenes report it (summary.json "invariants"). Reads the
 * energies; changes nothing. */
#include "part.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* Round-off allowance: this fraction of the balance's reference energy. */
#define INVARIANT_ROUND_OFF 1e-9

static void add(char *out, size_t size, int *n, const char *text)
{
    size_t used = strlen(out);
    if (used + 3 < size)
        snprintf(out + used, size - used, "%s%s", *n ? "; " : "", text);
    (*n)++;
}

static void check_dissipation(const char *name, double value, double tol, char *out,
                              size_t size, int *n)
{
    if (!(value >= -tol)) {
        char text[160];
        snprintf(text, sizeof text, "%s %.4g J is negative (dissipation cannot be: the "
                 "numerics put that energy in)", name, value);
        add(out, size, n, text);
    }
}

int wff_model_invariants(const wff_model *m, char *out, size_t size)
{
    int n = 0;
    if (size)
        out[0] = 0;
    wff_energies e;
    wff_model_energies(m, &e);
    const double s = m->symmetry_factor, tol = INVARIANT_ROUND_OFF * e.reference;
    check_dissipation("dissipated_shear", e.dissipated_shear, tol, out, size, &n);
    check_dissipation("dissipated_friction", e.dissipated_friction, tol, out, size, &n);
    check_dissipation("dissipated_failure", e.dissipated_failure, tol, out, size, &n);
    check_dissipation("eroded_energy", e.eroded, tol, out, size, &n);
    for (const wff_part_ops *const *p = wff_parts; *p; p++)
        if ((*p)->dissipated) {
            char name[64];
            snprintf(name, sizeof name, "%s_dissipated", (*p)->name);
            check_dissipation(name, s * (*p)->dissipated(m), tol, out, size, &n);
        }
    if (m->projectile.active && m->v_half_valid) {
        /* all the energy given: the start's kinetic (the balance's) and stored,
         * the work done on the model and the transfers' changes, whole specimen */
        const double given = s * (m->initial_total + fmax(m->external_work, 0) +
                                  fmax(m->transfer_energy, 0));
        /* (no allowance for the balance's error: a projectile given energy by
         * the numerics is what the check is for) */
        if (e.kinetic_projectile > given + tol) {
            char text[200];
            snprintf(text, sizeof text, "the projectile's kinetic energy %.6g J exceeds all the "
                     "energy the run was given, %.6g J (it moves faster than it struck)",
                     e.kinetic_projectile, given);
            add(out, size, &n, text);
        }
    }
    return n;
}

/* invariants.c: the physical invariants a run keeps whatever its numerics
 * (wff_model_invariants, solver.h): every dissipation is never negative (the
 * shear flow's, the failure's, the eroded energy; the contacts' and friction's,
 * the model's and each part's `dissipated` op (part.h), as one sum); the projectile's
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
        char text[WFF_ERROR_MAX / 2 + 100];
        snprintf(text, sizeof text, "%s, %.4g J, is negative (dissipation cannot be: the "
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
    check_dissipation("dissipated_failure", e.dissipated_failure, tol, out, size, &n);
    check_dissipation("dissipated_slip", e.dissipated_slip, tol, out, size, &n);
    check_dissipation("eroded_energy", e.eroded, tol, out, size, &n);
    /* contact and friction: the model's (clamp, the projectile's contact) and
     * each part's, as one sum. (Each is its own constraints' work since the
     * ply contact books the nose contacts its solve holds as the projectile
     * contact's: before, a node on the nose that the next ply pushed back had
     * its velocity change shared between the two accounts, the projectile's
     * -3.0 mJ and the ply contact's +11.8 mJ at 0.5 ms on 8 plies at 22 m/s;
     * the sum is what is checked here, each account by the pack's tests.) */
    char name[WFF_ERROR_MAX / 2];
    int used = snprintf(name, sizeof name, "the contacts' and friction's dissipation "
                        "(dissipated_friction %.4g J", e.dissipated_friction);
    double contacts = e.dissipated_friction;
    for (const wff_part_ops *const *p = wff_parts; *p; p++)
        if ((*p)->dissipated) {
            const double d = s * (*p)->dissipated(m);
            contacts += d;
            if (used > 0 && (size_t)used < sizeof name)
                used += snprintf(name + used, sizeof name - (size_t)used, " + %s_dissipated %.4g J",
                                 (*p)->name, d);
        }
    if (used > 0 && (size_t)used < sizeof name)
        snprintf(name + used, sizeof name - (size_t)used, ")");
    check_dissipation(name, contacts, tol, out, size, &n);
    /* a part whose term holds more than dissipation (a backing block's energy):
     * its contacts' own loss, which a contact putting energy in would make
     * negative while the term stayed positive */
    for (const wff_part_ops *const *p = wff_parts; *p; p++)
        if ((*p)->loss) {
            char what[96];
            snprintf(what, sizeof what, "%s_contact_loss (what its contacts removed)", (*p)->name);
            check_dissipation(what, s * (*p)->loss(m), tol, out, size, &n);
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

/* parts.c: the step's parts in the order a step runs them (part.h;
 * docs/model.md §14), and the loops the model, the integrator and the
 * whole-model operations run over them. A new per-step phenomenon is a new
 * file with its wff_part_ops and one line here. */
#include "part.h"
#include "backing.h"
#include "clamp.h"
#include "contact.h"
#include "cutting.h"
#include "distribute.h"
#include "erosion.h"
#include "pack.h"
#include "perforation.h"
#include "ply_contact.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* After the force pass: erosion first (the elements that go, their stored
 * energy out of the pass's), then the pack's per-ply accounts (which read the
 * elements erosion just took). After the velocity update: the friction
 * clamp's correction first, then the projectile's contact, then the plies'
 * (which reads the projectile's impulses), then the nose's contact pressure
 * (which reads both). The shot's verdict has values
 * only (no pass of the step). */
const wff_part_ops *const wff_parts[] = {
    &wff_erosion_part,
    &wff_pack_part,
    &wff_clamp_part,
    &wff_projectile_contact_part,
    &wff_backing_part,
    &wff_ply_contact_part,
    &wff_cutting_part,
    &wff_perforation_part,
    &wff_distributed_part,
    NULL,
};

#define EACH_PART(ops) for (const wff_part_ops *const *ops = wff_parts; *ops; ops++)

int wff_parts_setup(wff_model *m, wff_error *err)
{
    EACH_PART(p)
        if ((*p)->setup && (*p)->setup(m, err))
            return -1;
    return 0;
}

void wff_parts_refresh(wff_model *m)
{
    EACH_PART(p)
        if ((*p)->refresh)
            (*p)->refresh(m);
}

double wff_parts_stable_step(const wff_model *m)
{
    double dt = INFINITY;
    EACH_PART(p)
        if ((*p)->stable_step) {
            const double step = (*p)->stable_step(m);
            if (step < dt)
                dt = step;
        }
    return dt;
}

double wff_parts_after_forces(wff_model *m, const double *u, const double *state,
                              double dt_flow)
{
    double removed = 0;
    EACH_PART(p)
        if ((*p)->after_forces)
            removed += (*p)->after_forces(m, u, state, dt_flow);
    return removed;
}

int wff_parts_correct(wff_model *m, double dt, double dt_mid, wff_error *err)
{
    EACH_PART(p)
        if ((*p)->correct && (*p)->correct(m, dt, dt_mid, err))
            return -1;
    return 0;
}

void wff_parts_book(wff_model *m, double dt_before, double dt_mid)
{
    EACH_PART(p)
        if ((*p)->book)
            (*p)->book(m, dt_before, dt_mid);
}

double wff_parts_dissipated(const wff_model *m)
{
    double sum = 0;
    EACH_PART(p)
        if ((*p)->dissipated)
            sum += (*p)->dissipated(m);
    return sum;
}

void wff_parts_follow(wff_model *m, const char *what, double value)
{
    EACH_PART(p)
        if ((*p)->follow)
            (*p)->follow(m, what, value);
}

const wff_setting *wff_parts_setting(const char *key)
{
    EACH_PART(p)
        for (const wff_setting *s = (*p)->settings; s && s->name; s++)
            if (strcmp(s->name, key) == 0)
                return s;
    return NULL;
}

void wff_parts_setting_names(char *out, size_t size, int comma)
{
    size_t used = 0;
    EACH_PART(p)
        for (const wff_setting *s = (*p)->settings; s && s->name; s++) {
            if (used >= size)
                return;
            used += (size_t)snprintf(out + used, size - used, "%s%s", comma ? ", " : "",
                                     s->name);
            comma = 1;
        }
}

int wff_parts_refuse_checkpoint(const wff_model *m, char *why, size_t size)
{
    EACH_PART(p)
        if ((*p)->refuses_checkpoint && (*p)->refuses_checkpoint(m, why, size))
            return 1;
    return 0;
}

int wff_parts_refuse_remesh(const wff_model *m, char *why, size_t size)
{
    EACH_PART(p)
        if ((*p)->refuses_remesh && (*p)->refuses_remesh(m, why, size))
            return 1;
    return 0;
}

int wff_parts_state_fields(wff_model *m, wff_state_field *f)
{
    int k = 0;
    EACH_PART(p)
        if ((*p)->state_fields)
            k += (*p)->state_fields(m, f + k);
    return k;
}

uint64_t wff_parts_fingerprint(const wff_model *m, uint64_t g)
{
    EACH_PART(p)
        if ((*p)->fingerprint)
            g = (*p)->fingerprint(m, g);
    return g;
}

int wff_parts_carry(const wff_model *from, wff_model *to, wff_error *err)
{
    EACH_PART(p)
        if ((*p)->carry && (*p)->carry(from, to, err))
            return -1;
    return 0;
}

void wff_parts_free(wff_model *m)
{
    EACH_PART(p)
        if ((*p)->free)
            (*p)->free(m);
}

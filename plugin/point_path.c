/* One material point along a load path: dynamic amplitudes by central
 * differences and/or γᶠ by the flow rule over a segment with F linear in
 * time, and the record of one level (include/wovenff/point_path.h). Pointwise
 * like the cells: no mesh, no file, no script, no allocation. */
#include "wovenff/point_path.h"
#include "wovenff/balance.h"

#include <math.h>
#include <string.h>

/* A segment that would need more steps than this is a wrong input (a duration
 * of seconds for a microsecond oscillator), not a computation to wait for. */
#define MAX_SEGMENT_STEPS 100000000L

static void lerp_F(const double F_a[6], const double F_b[6], double fraction, double F[6])
{
    for (int i = 0; i < 6; i++)
        F[i] = F_a[i] + fraction * (F_b[i] - F_a[i]);
}

static int degenerate(const wff_material *mat, const double F[6], wff_error *err)
{
    return wff_fail(err, "degenerate point (a yarn direction has zero length or the yarns "
                    "are parallel): F = [%g %g %g %g %g %g], material %s",
                    F[0], F[1], F[2], F[3], F[4], F[5], mat->source);
}

/* The dissipation of one update r into the path's sums (J/m²). */
static void add_dissipated(const wff_point_result *r, wff_point_state *s)
{
    s->dissipated[0] += r->dissipated;
    s->dissipated[1] += r->failure_dissipated;
    s->dissipated[2] += r->slip_dissipated;
}

/* (ρ_A/6) d²ΔA/dt² = R (docs/model.md §5) by central differences (§14): the
 * velocity takes the mean of the last and this step (a half step at the
 * start), the amplitudes a whole step. One step for the whole segment, from
 * the cell's amplitude frequency bound at its start (§12). */
static int dynamic_segment(const wff_material *mat, const double F_a[6], const double F_b[6],
                           double duration, const wff_path_mode *mode, wff_point_state *s,
                           wff_error *err)
{
    double membrane_speed, omega;
    wff_cell_wave_speeds(mat, F_a, s->dA, &membrane_speed,
                           &omega);
    if (!(omega > 0) || !isfinite(omega))
        return wff_fail(err, "no finite amplitude frequency (omega = %g rad/s) at F = "
                        "[%g %g %g %g %g %g], material %s", omega, F_a[0], F_a[1], F_a[2],
                        F_a[3], F_a[4], F_a[5], mat->source);
    double steps = ceil(duration / (mode->step_safety * 2 / omega));
    if (steps > MAX_SEGMENT_STEPS)
        return wff_fail(err, "a segment of %g s needs %.3g amplitude steps (omega = %g rad/s): "
                        "shorten the duration", duration, steps, omega);
    long n = steps < 1 ? 1 : (long)steps;
    double dt = duration / (double)n;
    double mass = mat->areal_density / 6; /* lumped amplitude mass, kg/m² */
    for (long i = 0; i < n; i++) {
        double F[6];
        lerp_F(F_a, F_b, (double)i / (double)n, F);
        wff_point_result r;
        if (wff_material_evaluate(mat, F, s->dA, s->state, mode->shear_flow ? dt : 0, &r))
            return degenerate(mat, F, err);
        if (mode->shear_flow) {
            memcpy(s->state, r.state, sizeof(double) * (size_t)mat->n_state);
            add_dissipated(&r, s);
        }
        double half = 0.5 * (s->previous_step + dt);
        for (int k = 0; k < 2; k++) {
            s->velocity[k] += half * r.residual[k] / mass;
            s->dA[k] += dt * s->velocity[k];
        }
        s->previous_step = dt;
    }
    s->substeps += n;
    return 0;
}

/* γᶠ by the flow rule (§7) with the amplitudes held: flow_substeps backward
 * Euler steps, each at the F of its end. */
static int flow_segment(const wff_material *mat, const double F_a[6], const double F_b[6],
                        double duration, const wff_path_mode *mode, wff_point_state *s,
                        wff_error *err)
{
    int n = mode->flow_substeps;
    double dt = duration / n;
    for (int i = 1; i <= n; i++) {
        double F[6];
        lerp_F(F_a, F_b, (double)i / n, F);
        wff_point_result r;
        if (wff_material_evaluate(mat, F, s->dA, s->state, dt, &r))
            return degenerate(mat, F, err);
        memcpy(s->state, r.state, sizeof(double) * (size_t)mat->n_state);
        add_dissipated(&r, s);
    }
    s->substeps += n;
    return 0;
}

int wff_point_path_static_level(const wff_material *mat, const double F[6], double dt,
                                int shear_flow, wff_point_state *s, wff_error *err)
{
    if (!(dt > 0) || !isfinite(dt))
        return wff_fail(err, "static level: dt = %g s must be > 0", dt);
    const int n = mat->n_state, gamma = wff_material_state_index(mat, "gamma_f");
    double trial[WFF_STATE_MAX];
    memcpy(trial, s->state, sizeof(double) * (size_t)n);
    double dA[2] = {s->dA[0], s->dA[1]};
    wff_point_result r;
    for (int round = 1; round <= WFF_PATH_STATIC_ROUNDS; round++) {
        const double before[2] = {dA[0], dA[1]};
        if (wff_balance_amplitudes(mat, F, trial, dA, err))
            return -1;
        if (wff_material_evaluate(mat, F, dA, s->state, dt, &r))
            return degenerate(mat, F, err);
        if (!shear_flow && gamma >= 0)
            r.state[gamma] = s->state[gamma]; /* γᶠ held */
        double moved = 0; /* the largest change of a state since the last round */
        for (int i = 0; i < n; i++)
            moved = fmax(moved, fabs(trial[i] - r.state[i]));
        memcpy(trial, r.state, sizeof(double) * (size_t)n);
        /* agreed: the amplitudes within a femtometre of the last round's and the states
         * within 1e-14 of the last round's (what the balance was solved with) */
        if (round > 1 && moved <= 1e-14 && fabs(dA[0] - before[0]) <= 1e-15 &&
            fabs(dA[1] - before[1]) <= 1e-15) {
            memcpy(s->state, trial, sizeof(double) * (size_t)n);
            s->dA[0] = dA[0];
            s->dA[1] = dA[1];
            if (!shear_flow)
                r.dissipated = 0;
            add_dissipated(&r, s);
            return round;
        }
    }
    return wff_fail(err, "static level: the amplitudes balanced with the states held and the "
                    "states advanced at them do not agree within %d rounds (dA = %g, %g m) at "
                    "F = [%g %g %g %g %g %g], material %s", WFF_PATH_STATIC_ROUNDS, dA[0], dA[1],
                    F[0], F[1], F[2], F[3], F[4], F[5], mat->source);
}

/* T_2 − tension2 (N) at the static level F = diag(stretch1, stretch2) from *from
 * into *to. */
static int pull_trial(const wff_material *mat, double stretch1, double stretch2, double tension2,
                      double dt, int tension_diag, const wff_point_state *from,
                      wff_point_state *to, double *misfit, wff_error *err)
{
    const double F[6] = {stretch1, 0, 0, stretch2, 0, 0};
    *to = *from;
    if (wff_point_path_static_level(mat, F, dt, 0, to, err) < 0)
        return -1;
    wff_point_result r;
    if (wff_material_evaluate(mat, F, to->dA, to->state, 0, &r))
        return degenerate(mat, F, err);
    *misfit = r.diag[tension_diag] - tension2;
    return 0;
}

int wff_point_path_pull_level(const wff_material *mat, double stretch1, double tension2,
                              double dt, wff_point_state *state, double F[6], wff_error *err)
{
    const int diag = wff_cell_yarn_tension_diag(mat->cell, 1);
    if (diag < 0)
        return wff_fail(err, "pull-out level: cell '%s' (material %s) reports no yarn tension "
                        "of family 2", wff_cell_name(mat->cell), mat->source);
    /* secant on λ_2 from the last level's, a first step of 1e-4 */
    double x0 = F[3], x1 = F[3] + 1e-4, f0, f1;
    wff_point_state s1; /* (the trials' states: only the last one's kept) */
    if (pull_trial(mat, stretch1, x0, tension2, dt, diag, state, &s1, &f0, err) ||
        pull_trial(mat, stretch1, x1, tension2, dt, diag, state, &s1, &f1, err))
        return -1;
    for (int trial = 0; trial < 60; trial++) {
        if (fabs(f1) <= 1e-9) {
            *state = s1;
            const double out[6] = {stretch1, 0, 0, x1, 0, 0};
            memcpy(F, out, sizeof out);
            return 0;
        }
        if (f1 == f0)
            break;
        double x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
        x0 = x1;
        f0 = f1;
        x1 = x2;
        if (pull_trial(mat, stretch1, x1, tension2, dt, diag, state, &s1, &f1, err))
            return -1;
    }
    return wff_fail(err, "pull-out level: no stretch of family 2 gives it the tension %g N at "
                    "the stretch %g of family 1 (last: lambda2 = %.12g, T2 off by %g N), "
                    "material %s", tension2, stretch1, x1, f1, mat->source);
}

int wff_point_path_segment(const wff_material *mat, const double F_a[6], const double F_b[6],
                           double duration, const wff_path_mode *mode, wff_point_state *state,
                           wff_error *err)
{
    if (!(duration > 0) || !isfinite(duration))
        return wff_fail(err, "segment duration %g s must be > 0", duration);
    if (!(mode->step_safety > 0 && mode->step_safety <= 1) || mode->flow_substeps < 1)
        return wff_fail(err, "step safety %g must be in (0, 1] and flow substeps %d >= 1",
                        mode->step_safety, mode->flow_substeps);
    if (mode->dynamic_amplitudes) {
        if (wff_cell_amplitudes(mat->cell) == 0)
            return wff_fail(err, "cell '%s' (material %s) has no amplitudes to make dynamic",
                            wff_cell_name(mat->cell), mat->source);
        return dynamic_segment(mat, F_a, F_b, duration, mode, state, err);
    }
    if (mode->shear_flow)
        return flow_segment(mat, F_a, F_b, duration, mode, state, err);
    return 0;
}

int wff_point_path_record(const wff_material *mat, const double F[6],
                          const wff_point_state *state, wff_point_record *rec, wff_error *err)
{
    const wff_cell_type *cell = mat->cell;
    if (wff_material_evaluate(mat, F, state->dA, state->state, 0, &rec->point))
        return degenerate(mat, F, err);
    double g1g2 = F[0] * F[1] + F[2] * F[3] + F[4] * F[5]; /* g_1·g_2 */
    rec->stretch[0] = sqrt(F[0] * F[0] + F[2] * F[2] + F[4] * F[4]);
    rec->stretch[1] = sqrt(F[1] * F[1] + F[3] * F[3] + F[5] * F[5]);
    rec->shear_angle = asin(g1g2 / (rec->stretch[0] * rec->stretch[1]));
    rec->n_mech = wff_cell_has_energy_split(cell) ? wff_cell_n_mech(cell) : 0;
    if (rec->n_mech)
        wff_cell_energy_split(mat, F, state->dA, state->state, rec->mech_energy);
    double v2 = state->velocity[0] * state->velocity[0] + state->velocity[1] * state->velocity[1];
    rec->amplitude_kinetic = 0.5 * (mat->areal_density / 6) * v2;
    return 0;
}

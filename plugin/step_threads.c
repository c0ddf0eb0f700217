/* step_threads.c: the per-step passes over DOFs and nodes, threaded
 * (OpenMP) with sums in a fixed order: the position update with the first
 * half of the prescribed DOFs' external work and the force vector zeroed
 * for the force pass (one pass), the zeroing alone, the velocity update
 * with the boundary conditions, the kinetic energies
 * and the contact candidates. Each pass splits its items into parts whose
 * bounds depend on the item count alone (never on the thread count); a part
 * sums its items in order and the parts are added in order, so a result is
 * the same bit for bit whatever the number of threads (the split:
 * step_parts.h). Knows the model's arrays (solver_internal.h); nothing of
 * cells, elements, FreeFEM or the clamp. */
#include "step_parts.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <string.h>

/* v^{n+½} of DOF i from f^n and its reaction (docs/model.md §12, §14); on a
 * prescribed DOF returns the second half of its trapezoidal external work
 * over the step just taken, ½ Rⁿ⁺¹·Δu (0 elsewhere). */
static inline double update_dof(wff_model *m, int i, double dt_mid, double dt_done)
{
    double work = 0;
    switch (m->dof_kind[i]) {
    case WFF_DOF_FREE:
        m->v[i] += dt_mid * m->f[i] / m->mass[i];
        m->reaction[i] = 0;
        break;
    case WFF_DOF_FIXED:
        m->v[i] = 0;
        m->reaction[i] = -m->f[i];
        break;
    default:
        work = 0.5 * (-m->f[i]) * dt_done * m->v[i];
        m->v[i] = m->v_prescribed[i];
        m->reaction[i] = -m->f[i];
        break;
    }
    return work;
}

double wff_step_positions(wff_model *m, double dt)
{
    const int n = m->n_dofs, parts = wff_part_count(n, DOF_GRAIN);
    double work[MAX_PARTS];
#pragma omp parallel for schedule(static) num_threads(wff_pass_threads(m, parts)) if (wff_pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int end = wff_part_begin(n, parts, k + 1);
        double w = 0;
        for (int i = wff_part_begin(n, parts, k); i < end; i++) {
            double du = dt * m->v[i];
            if (m->dof_kind[i] == WFF_DOF_PRESCRIBED)
                w += 0.5 * m->reaction[i] * du;
            m->u[i] += du;
            m->f[i] = 0; /* the force pass that follows adds into it */
            m->contact_force[i] = 0; /* (and the parts' impulses after it) */
        }
        work[k] = w;
    }
    return wff_sum_parts(work, parts);
}

void wff_step_zero(const wff_model *m, double *f, int n)
{
    const int parts = wff_part_count(n, DOF_GRAIN);
#pragma omp parallel for schedule(static) num_threads(wff_pass_threads(m, parts)) if (wff_pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int begin = wff_part_begin(n, parts, k);
        memset(f + begin, 0, sizeof(double) * (size_t)(wff_part_begin(n, parts, k + 1) - begin));
    }
}

double wff_step_velocities(wff_model *m, double dt_mid, double dt_done)
{
    const int n = m->n_dofs, parts = wff_part_count(n, DOF_GRAIN);
    double part_work[MAX_PARTS];
#pragma omp parallel for schedule(static) num_threads(wff_pass_threads(m, parts)) if (wff_pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int end = wff_part_begin(n, parts, k + 1);
        double w = 0;
        for (int i = wff_part_begin(n, parts, k); i < end; i++)
            w += update_dof(m, i, dt_mid, dt_done);
        part_work[k] = w;
    }
    return wff_sum_parts(part_work, parts);
}

double wff_step_travel(const wff_model *m, double reach)
{
    const double *v = m->v, *f = m->f, *mass = m->mass;
    const unsigned char *kind = m->dof_kind;
    const int n = m->n_nodes, parts = wff_part_count(n, NODE_GRAIN);
    double part_min[MAX_PARTS];
#pragma omp parallel for schedule(static) num_threads(wff_pass_threads(m, parts)) if (wff_pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int end = wff_part_begin(n, parts, k + 1);
        double shortest = INFINITY;
        for (int node = wff_part_begin(n, parts, k); node < end; node++)
            for (int j = D - 2; j < D; j++) {
                const int i = D * node + j;
                /* (a DOF no element acts on, a node whose elements have all
                 * eroded, has no stiffness to outrun: it sets no limit) */
                if (kind[i] != WFF_DOF_FREE || f[i] == 0)
                    continue;
                const double dt = wff_travel_dt(fabs(v[i]), fabs(f[i] / mass[i]), reach);
                shortest = dt < shortest || dt != dt ? dt : shortest;
            }
        part_min[k] = shortest;
    }
    double shortest = INFINITY;
    for (int k = 0; k < parts; k++)
        shortest = part_min[k] < shortest || part_min[k] != part_min[k] ? part_min[k] : shortest;
    return shortest;
}

void wff_step_kinetic(const wff_model *m, double half, double k4[5])
{
    const double *v = m->v, *f = m->f, *mass = m->mass, *g = m->contact_force;
    const unsigned char *kind = m->dof_kind;
    const int n = m->n_nodes, parts = wff_part_count(n, NODE_GRAIN);
    double part_e[MAX_PARTS][5];
#pragma omp parallel for schedule(static) num_threads(wff_pass_threads(m, parts)) if (wff_pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int end = wff_part_begin(n, parts, k + 1);
        double inplane = 0, transverse = 0, amplitude = 0, force = 0, contact = 0;
        for (int node = wff_part_begin(n, parts, k); node < end; node++) {
            const int i = D * node; /* branch-free over the 5 DOFs of a node */
            double e[D], q[D], c[D];
            for (int j = 0; j < D; j++) {
                const int free = kind[i + j] == WFF_DOF_FREE;
                double vn = v[i + j] - half * f[i + j] / mass[i + j];
                e[j] = free ? mass[i + j] * vn * vn : 0;
                q[j] = free ? f[i + j] * f[i + j] / mass[i + j] : 0;
                c[j] = free ? v[i + j] * g[i + j] : 0;
            }
            force += q[0] + q[1] + q[2] + q[3] + q[4];
            contact += c[0] + c[1] + c[2] + c[3] + c[4];
            inplane += e[0] + e[1];
            transverse += e[2];
            amplitude += e[3] + e[4];
        }
        part_e[k][0] = inplane;
        part_e[k][1] = transverse;
        part_e[k][2] = amplitude;
        part_e[k][3] = force;
        part_e[k][4] = contact;
    }
    k4[0] = k4[1] = k4[2] = k4[3] = k4[4] = 0;
    for (int k = 0; k < parts; k++)
        for (int j = 0; j < 5; j++)
            k4[j] += part_e[k][j];
}

int wff_step_candidates(const wff_model *m, double reach, int *candidates)
{
    const int n = m->n_nodes, parts = wff_part_count(n, NODE_GRAIN);
    const double ax = m->projectile.axis[0], ay = m->projectile.axis[1];
    int found[MAX_PARTS];
    /* each part lists its nodes from its own first index on, then the lists
     * are closed up in part order: the user's node order (the contact correction
     * is sequential, renumber.h), as one thread gives */
#pragma omp parallel for schedule(static) num_threads(wff_pass_threads(m, parts)) if (wff_pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int begin = wff_part_begin(n, parts, k), end = wff_part_begin(n, parts, k + 1);
        int count = 0;
        for (int user = begin; user < end; user++) {
            const int node = wff_model_node_of_user(m, user);
            double dx = m->mesh.xy[2 * node] + m->u[D * node] - ax;
            double dy = m->mesh.xy[2 * node + 1] + m->u[D * node + 1] - ay;
            if (dx * dx + dy * dy < reach * reach)
                candidates[begin + count++] = node;
        }
        found[k] = count;
    }
    int total = found[0];
    for (int k = 1; k < parts; k++) {
        memmove(candidates + total, candidates + wff_part_begin(n, parts, k),
                sizeof(int) * (size_t)found[k]);
        total += found[k];
    }
    return total;
}

/* The balance's kinetic measure at the half-step velocities and the step
 * planned, ½ Σ_free m v·(v − Δt (f − g)/m) + ½ M v_p² (the contact forces g
 * out of its stagger; the projectile has no other force), J (model part). A
 * serial pass: for a re-planned step only. */
static double kinetic_measure(const wff_model *m)
{
    double sum = 0;
    for (int i = 0; i < m->n_dofs; i++)
        if (m->dof_kind[i] == WFF_DOF_FREE)
            sum += 0.5 * m->v[i] * (m->mass[i] * m->v[i] - m->dt * (m->f[i] - m->contact_force[i]));
    if (m->projectile.active)
        sum += 0.5 * m->projectile.mass * m->projectile.velocity * m->projectile.velocity;
    return sum;
}

/* The step planned changed between two advances (a set of dtfactor, the
 * adaptive step's cut): v^{n+½} re-planned for it, v^{n−½} + ½(Δt_{n−½} +
 * Δt_new) aⁿ with the elastic forces (the contact impulses j are jumps of the
 * velocity and stay as they were, re-expressed as forces j/Δt_mid over the new
 * Δt_mid), and the measure's move booked as the advance books a step that
 * changes (stagger_shift): exact on a linear system again (docs/model.md §14;
 * without contact forces the move is (Δt_new² − Δt_old²)/8 Σ f²/m). Before the
 * first step, only the step. */
void wff_step_replan(wff_model *m, double dt_new)
{
    const double dt_old = m->dt;
    if (!m->v_half_valid || !(dt_old > 0) || dt_new == dt_old) {
        m->dt = dt_new;
        return;
    }
    const double before = kinetic_measure(m);
    const double dv = 0.5 * (dt_new - dt_old), mid_old = m->dt_mid, mid_new = mid_old + dv;
    const double scale = mid_new > 0 ? mid_old / mid_new : 1;
    for (int i = 0; i < m->n_dofs; i++)
        if (m->dof_kind[i] == WFF_DOF_FREE) {
            const double contact = m->contact_force[i], elastic = m->f[i] - contact;
            m->v[i] += dv * elastic / m->mass[i];
            m->contact_force[i] = scale * contact;
            m->f[i] = elastic + m->contact_force[i];
        }
    m->projectile.force *= scale; /* (all contact: its velocity stays) */
    m->dt_mid = mid_new;
    m->dt = dt_new;
    m->stagger_shift += before - kinetic_measure(m);
}

/* step_threads.c: the per-step passes over DOFs and nodes, threaded
 * (OpenMP) with sums in a fixed order: the position update with the first
 * half of the prescribed DOFs' external work and the force vector zeroed
 * for the force pass (one pass), the zeroing alone, the velocity update
 * with the boundary conditions and the friction clamp's correction (one
 * parallel region for both), the kinetic energies
 * and the contact candidates. Each pass splits its items into parts whose
 * bounds depend on the item count alone (never on the thread count); a part
 * sums its items in order and the parts are added in order, so a result is
 * the same bit for bit whatever the number of threads. Knows the model's
 * arrays (solver_internal.h); nothing of cells, elements, FreeFEM; a
 * clamped node's friction is clamp.c's (wff_clamp_node). */
#include "clamp.h"
#include "wovenff/renumber.h"

#include <math.h>
#include <string.h>

/* Most parts a pass is split into (their partial sums live on the stack). */
#define MAX_PARTS 64
/* Items per part (the parts fix the sums' order; small parts balance the
 * threads) */
#define DOF_GRAIN 2048
#define NODE_GRAIN 512
#define CLAMP_GRAIN 64
/* Fewest DOFs for which a pass over the DOFs or nodes takes a team: a pass
 * costs ~1 ns a DOF, a team's start and end ~10 µs when its threads sleep
 * between passes (OMP_WAIT_POLICY=passive, tools/ff.sh's default) */
#define TEAM_MIN_DOFS 16384

/* Parts for n items at `grain` items a part: depends on n alone. */
static int part_count(int n, int grain)
{
    int parts = n / grain;
    return parts < 1 ? 1 : parts > MAX_PARTS ? MAX_PARTS : parts;
}

static int part_begin(int n, int parts, int k)
{
    return (int)((long long)n * k / parts);
}

/* Threads for a pass of `parts` parts: the model's, at most one a part;
 * one for a model too small to repay a team. */
static int pass_threads(const wff_model *m, int parts)
{
    int t = m->n_dofs < TEAM_MIN_DOFS ? 1 : wff_elements_team(&m->el);
    return t > parts ? parts : t < 1 ? 1 : t;
}

/* Sum of the parts' partials in part order. */
static double sum_parts(const double *partial, int parts)
{
    double s = 0;
    for (int k = 0; k < parts; k++)
        s += partial[k];
    return s;
}

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
    const int n = m->n_dofs, parts = part_count(n, DOF_GRAIN);
    double work[MAX_PARTS];
#pragma omp parallel for schedule(static) num_threads(pass_threads(m, parts)) if (pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int end = part_begin(n, parts, k + 1);
        double w = 0;
        for (int i = part_begin(n, parts, k); i < end; i++) {
            double du = dt * m->v[i];
            if (m->dof_kind[i] == WFF_DOF_PRESCRIBED)
                w += 0.5 * m->reaction[i] * du;
            m->u[i] += du;
            m->f[i] = 0; /* the force pass that follows adds into it */
        }
        work[k] = w;
    }
    return sum_parts(work, parts);
}

void wff_step_zero(const wff_model *m, double *f, int n)
{
    const int parts = part_count(n, DOF_GRAIN);
#pragma omp parallel for schedule(static) num_threads(pass_threads(m, parts)) if (pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int begin = part_begin(n, parts, k);
        memset(f + begin, 0, sizeof(double) * (size_t)(part_begin(n, parts, k + 1) - begin));
    }
}

void wff_step_velocities(wff_model *m, double dt_mid, double dt_done, double *work,
                         double *dissipated)
{
    const int n = m->n_dofs, parts = part_count(n, DOF_GRAIN);
    const int n_clamp = m->clamp.n, clamp_parts = part_count(n_clamp, CLAMP_GRAIN);
    double part_work[MAX_PARTS], part_dissipated[MAX_PARTS];
    /* one region: the clamp reads the reactions the update writes (the loop's
     * barrier between) */
#pragma omp parallel num_threads(pass_threads(m, parts)) if (pass_threads(m, parts) > 1)
    {
#pragma omp for schedule(static)
        for (int k = 0; k < parts; k++) {
            const int end = part_begin(n, parts, k + 1);
            double w = 0;
            for (int i = part_begin(n, parts, k); i < end; i++)
                w += update_dof(m, i, dt_mid, dt_done);
            part_work[k] = w;
        }
#pragma omp for schedule(static) nowait /* (the region's end waits) */
        for (int k = 0; k < clamp_parts; k++) {
            const int end = part_begin(n_clamp, clamp_parts, k + 1);
            double d = 0;
            for (int c = part_begin(n_clamp, clamp_parts, k); c < end; c++)
                d += wff_clamp_node(m, m->v, c, dt_mid);
            part_dissipated[k] = d;
        }
    }
    *work = sum_parts(part_work, parts);
    *dissipated = sum_parts(part_dissipated, clamp_parts);
}

double wff_step_clamp(const wff_model *m, double *v, double dt_mid)
{
    const int n_clamp = m->clamp.n, parts = part_count(n_clamp, CLAMP_GRAIN);
    double part_dissipated[MAX_PARTS];
#pragma omp parallel for schedule(static) num_threads(pass_threads(m, parts)) if (pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int end = part_begin(n_clamp, parts, k + 1);
        double d = 0;
        for (int c = part_begin(n_clamp, parts, k); c < end; c++)
            d += wff_clamp_node(m, v, c, dt_mid);
        part_dissipated[k] = d;
    }
    return sum_parts(part_dissipated, parts);
}

void wff_step_kinetic(const wff_model *m, double half, double k3[3])
{
    const double *v = m->v, *f = m->f, *mass = m->mass;
    const unsigned char *kind = m->dof_kind;
    const int n = m->n_nodes, parts = part_count(n, NODE_GRAIN);
    double part_e[MAX_PARTS][3];
#pragma omp parallel for schedule(static) num_threads(pass_threads(m, parts)) if (pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int end = part_begin(n, parts, k + 1);
        double inplane = 0, transverse = 0, amplitude = 0;
        for (int node = part_begin(n, parts, k); node < end; node++) {
            const int i = D * node; /* branch-free over the 5 DOFs of a node */
            double e[D];
            for (int j = 0; j < D; j++) {
                double vn = v[i + j] - half * f[i + j] / mass[i + j];
                e[j] = kind[i + j] == WFF_DOF_FREE ? mass[i + j] * vn * vn : 0;
            }
            inplane += e[0] + e[1];
            transverse += e[2];
            amplitude += e[3] + e[4];
        }
        part_e[k][0] = inplane;
        part_e[k][1] = transverse;
        part_e[k][2] = amplitude;
    }
    k3[0] = k3[1] = k3[2] = 0;
    for (int k = 0; k < parts; k++)
        for (int j = 0; j < 3; j++)
            k3[j] += part_e[k][j];
}

int wff_step_candidates(const wff_model *m, double reach, int *candidates)
{
    const int n = m->n_nodes, parts = part_count(n, NODE_GRAIN);
    const double ax = m->projectile.axis[0], ay = m->projectile.axis[1];
    int found[MAX_PARTS];
    /* each part lists its nodes from its own first index on, then the lists
     * are closed up in part order: the user's node order (the contact correction
     * is sequential, renumber.h), as one thread gives */
#pragma omp parallel for schedule(static) num_threads(pass_threads(m, parts)) if (pass_threads(m, parts) > 1)
    for (int k = 0; k < parts; k++) {
        const int begin = part_begin(n, parts, k), end = part_begin(n, parts, k + 1);
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
        memmove(candidates + total, candidates + part_begin(n, parts, k),
                sizeof(int) * (size_t)found[k]);
        total += found[k];
    }
    return total;
}

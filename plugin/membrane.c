/* Membrane elements: reference geometry, internal forces, lumped masses and
 * stable step. See include/wovenff/membrane.h for the formulas. */
#include "wovenff/membrane.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define D WFF_DOFS_PER_NODE

/* Bilinear quad: corners (ξ, η) = (−1,−1), (1,−1), (1,1), (−1,1); Gauss points ±1/√3. */
static const double quad_corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
static const double gauss_1d = 0.57735026918962576451; /* 1/√3 */
static const double quad_gauss[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}; /* × gauss_1d */

static double quad_shape(int a, double xi, double eta)
{
    return 0.25 * (1 + quad_corner[a][0] * xi) * (1 + quad_corner[a][1] * eta);
}

/* dN_a/dX at (ξ, η); returns det J. */
static double quad_gradients(const double *X, const int *node, double xi, double eta,
                             double grad[4][2])
{
    double dxi[4][2], J[2][2] = {{0, 0}, {0, 0}};
    for (int a = 0; a < 4; a++) {
        dxi[a][0] = 0.25 * quad_corner[a][0] * (1 + quad_corner[a][1] * eta);
        dxi[a][1] = 0.25 * quad_corner[a][1] * (1 + quad_corner[a][0] * xi);
        for (int i = 0; i < 2; i++)
            for (int r = 0; r < 2; r++)
                J[i][r] += X[2 * node[a] + i] * dxi[a][r]; /* ∂X_i/∂ξ_r */
    }
    double det = J[0][0] * J[1][1] - J[0][1] * J[1][0];
    for (int a = 0; a < 4; a++) {
        /* ∇_X N = J^{-T} ∇_ξ N */
        grad[a][0] = (J[1][1] * dxi[a][0] - J[1][0] * dxi[a][1]) / det;
        grad[a][1] = (-J[0][1] * dxi[a][0] + J[0][0] * dxi[a][1]) / det;
    }
    return det;
}

static double dist(const double *X, int a, int b)
{
    return hypot(X[2 * a] - X[2 * b], X[2 * a + 1] - X[2 * b + 1]);
}

int wff_elements_init(wff_elements *el, const double *X, int n_tris, const int *tri,
                      int n_quads, const int *quad, wff_error *err)
{
    memset(el, 0, sizeof *el);
    el->n_tris = n_tris;
    el->n_quads = n_quads;
    el->tri = tri;
    el->quad = quad;
    el->tri_grad = malloc(sizeof(double) * 6 * (size_t)(n_tris ? n_tris : 1));
    el->tri_area = malloc(sizeof(double) * (size_t)(n_tris ? n_tris : 1));
    el->quad_grad = malloc(sizeof(double) * 32 * (size_t)(n_quads ? n_quads : 1));
    el->quad_weight = malloc(sizeof(double) * 4 * (size_t)(n_quads ? n_quads : 1));
    el->size = malloc(sizeof(double) * (size_t)(n_tris + n_quads + 1));
    if (!el->tri_grad || !el->tri_area || !el->quad_grad || !el->quad_weight || !el->size) {
        wff_elements_free(el);
        return wff_fail(err, "out of memory for %d triangles and %d quads", n_tris, n_quads);
    }
    for (int e = 0; e < n_tris; e++) {
        const int *n = tri + 3 * e;
        double x0 = X[2 * n[0]], y0 = X[2 * n[0] + 1];
        double x1 = X[2 * n[1]] - x0, y1 = X[2 * n[1] + 1] - y0;
        double x2 = X[2 * n[2]] - x0, y2 = X[2 * n[2] + 1] - y0;
        double twice = x1 * y2 - x2 * y1;
        if (!(twice > 0)) {
            wff_elements_free(el);
            return wff_fail(err, "triangle %d (nodes %d %d %d): area %.3g m^2 is not positive",
                            e + 1, n[0] + 1, n[1] + 1, n[2] + 1, 0.5 * twice);
        }
        double *g = el->tri_grad + 6 * e;
        g[0] = (y1 - y2) / twice, g[1] = (x2 - x1) / twice; /* node 0 */
        g[2] = y2 / twice, g[3] = -x2 / twice;              /* node 1 */
        g[4] = -y1 / twice, g[5] = x1 / twice;              /* node 2 */
        el->tri_area[e] = 0.5 * twice;
        double longest = fmax(dist(X, n[0], n[1]), fmax(dist(X, n[1], n[2]), dist(X, n[2], n[0])));
        el->size[e] = twice / longest; /* smallest altitude */
    }
    for (int e = 0; e < n_quads; e++) {
        const int *n = quad + 4 * e;
        double area = 0;
        for (int q = 0; q < 4; q++) {
            double grad[4][2];
            double det = quad_gradients(X, n, gauss_1d * quad_gauss[q][0],
                                        gauss_1d * quad_gauss[q][1], grad);
            if (!(det > 0)) {
                wff_elements_free(el);
                return wff_fail(err, "quadrilateral %d (nodes %d %d %d %d): Jacobian %.3g at "
                                "Gauss point %d is not positive (inverted or degenerate)",
                                e + 1, n[0] + 1, n[1] + 1, n[2] + 1, n[3] + 1, det, q + 1);
            }
            memcpy(el->quad_grad + 32 * e + 8 * q, grad, sizeof grad);
            el->quad_weight[4 * e + q] = det;
            area += det;
        }
        double diag = fmax(dist(X, n[0], n[2]), dist(X, n[1], n[3]));
        el->size[n_tris + e] = area / diag;
    }
    return 0;
}

void wff_elements_free(wff_elements *el)
{
    free(el->tri_grad);
    free(el->tri_area);
    free(el->quad_grad);
    free(el->quad_weight);
    free(el->size);
    el->tri_grad = el->tri_area = el->quad_grad = el->quad_weight = el->size = NULL;
}

/* F_eff = F F_pre */
static void preload_apply(const wff_element_material *em, const double F[6], double Fe[6])
{
    const double *Fp = em->F_pre;
    for (int i = 0; i < 3; i++) {
        Fe[2 * i] = F[2 * i] * Fp[0] + F[2 * i + 1] * Fp[2];
        Fe[2 * i + 1] = F[2 * i] * Fp[1] + F[2 * i + 1] * Fp[3];
    }
}

/* P_mesh = P F_preᵀ / J_pre, added with weight w into acc */
static void preload_pull_add(const wff_element_material *em, const double P[6], double w,
                             double acc[6])
{
    const double *Fp = em->F_pre;
    double s = w / em->J_pre;
    for (int i = 0; i < 3; i++) {
        acc[2 * i] += s * (P[2 * i] * Fp[0] + P[2 * i + 1] * Fp[1]);
        acc[2 * i + 1] += s * (P[2 * i] * Fp[2] + P[2 * i + 1] * Fp[3]);
    }
}

/* 2 for a NaN or infinite state (F_eff, ΔA) or result, else the cell's status:
 * a NaN state is not a degenerate one (cells report both as degenerate). */
static int point_ok(int status, const double Fe[6], const double dA[2],
                    const wff_point_result *r)
{
    double state = dA[0] + dA[1];
    for (int i = 0; i < 6; i++)
        state += Fe[i];
    if (!isfinite(state))
        return 2;
    if (status != WFF_POINT_OK)
        return status;
    double sum = r->energy + r->residual[0] + r->residual[1];
    for (int i = 0; i < 6; i++)
        sum += r->stress[i];
    return isfinite(sum) ? WFF_POINT_OK : 2;
}

static void note_bad(wff_force_totals *t, int e, int q, int status)
{
    if (t->bad_element < 0) {
        t->bad_element = e;
        t->bad_point = q;
        t->bad_status = status;
    }
}

/* F = Σ_a x_a ⊗ ∇N_a with x = X + u */
static void deformation_gradient(const double *X, const double *u, const int *node, int n,
                                 const double *grad, double F[6])
{
    memset(F, 0, 6 * sizeof(double));
    for (int a = 0; a < n; a++) {
        const double *ua = u + D * node[a];
        double x[3] = {X[2 * node[a]] + ua[0], X[2 * node[a] + 1] + ua[1], ua[2]};
        for (int i = 0; i < 3; i++) {
            F[2 * i] += x[i] * grad[2 * a];
            F[2 * i + 1] += x[i] * grad[2 * a + 1];
        }
    }
}

void wff_elements_forces(const wff_elements *el, const wff_element_material *em, const double *X,
                         const double *u, double *gamma_f, double dt, double *f,
                         wff_force_totals *totals)
{
    const wff_material *mat = em->mat;
    const int amplitudes = mat->cell->n_amplitudes;
    totals->internal_energy = totals->dissipated = 0;
    totals->bad_element = -1;
    totals->bad_point = -1;
    totals->bad_status = 0;
    double energy = 0, dissipated = 0;

    const int fast = mat->cell->evaluate_shared && !em->reference_path;
    static const double third[3] = {1.0 / 3, 1.0 / 3, 1.0 / 3};
    for (int e = 0; e < el->n_tris; e++) {
        const int *node = el->tri + 3 * e;
        const double *grad = el->tri_grad + 6 * e;
        double F[6], Fe[6], Pm[6] = {0, 0, 0, 0, 0, 0};
        deformation_gradient(X, u, node, 3, grad, F);
        preload_apply(em, F, Fe);
        double w = el->tri_area[e] / 3;
        if (fast) {
            /* one F for the three nodal points: the cell's shared-kinematics path */
            double dA[6], P[6] = {0, 0, 0, 0, 0, 0}, R[6] = {0, 0, 0, 0, 0, 0}, W = 0, Dis = 0;
            double state = 0;
            for (int q = 0; q < WFF_TRI_POINTS; q++) {
                dA[2 * q] = u[D * node[q] + 3];
                dA[2 * q + 1] = u[D * node[q] + 4];
                state += dA[2 * q] + dA[2 * q + 1];
            }
            for (int i = 0; i < 6; i++)
                state += Fe[i];
            int bad = 0, status = isfinite(state)
                                      ? mat->cell->evaluate_shared(mat->params, Fe, 3, dA,
                                                                   third, gamma_f + 3 * e, dt, P,
                                                                   R, &W, &Dis, &bad)
                                      : 2;
            double sum = W + R[0] + R[1] + R[2] + R[3] + R[4] + R[5];
            for (int i = 0; i < 6; i++)
                sum += P[i];
            if (status == WFF_POINT_OK && !isfinite(sum))
                status = 2;
            if (status != WFF_POINT_OK) {
                note_bad(totals, e, bad, status);
                continue;
            }
            preload_pull_add(em, P, 1.0, Pm);
            for (int q = 0; q < WFF_TRI_POINTS; q++)
                for (int k = 0; k < amplitudes; k++)
                    f[D * node[q] + 3 + k] += w * R[2 * q + k] / em->J_pre;
            energy += el->tri_area[e] * W;
            dissipated += el->tri_area[e] * Dis;
        }
        for (int q = 0; q < WFF_TRI_POINTS && !fast; q++) {
            const double *ua = u + D * node[q];
            double dA[2] = {ua[3], ua[4]};
            wff_point_result r;
            double *gf = gamma_f + 3 * e + q;
            int status = point_ok(mat->cell->evaluate(mat->params, Fe, dA, *gf, dt, &r), Fe, dA, &r);
            if (status != WFF_POINT_OK) {
                note_bad(totals, e, q, status);
                continue;
            }
            *gf = r.gamma_f;
            preload_pull_add(em, r.stress, 1.0 / 3.0, Pm);
            for (int k = 0; k < amplitudes; k++)
                f[D * node[q] + 3 + k] += w * r.residual[k] / em->J_pre;
            energy += w * r.energy;
            dissipated += w * r.dissipated;
        }
        double area = el->tri_area[e];
        for (int b = 0; b < 3; b++) {
            double *fb = f + D * node[b];
            for (int i = 0; i < 3; i++)
                fb[i] -= area * (Pm[2 * i] * grad[2 * b] + Pm[2 * i + 1] * grad[2 * b + 1]);
        }
    }

    for (int e = 0; e < el->n_quads; e++) {
        const int *node = el->quad + 4 * e;
        int id = el->n_tris + e;
        for (int q = 0; q < WFF_QUAD_POINTS; q++) {
            const double *grad = el->quad_grad + 32 * e + 8 * q;
            double xi = gauss_1d * quad_gauss[q][0], eta = gauss_1d * quad_gauss[q][1];
            double N[4], dA[2] = {0, 0}, F[6], Fe[6], Pm[6] = {0, 0, 0, 0, 0, 0};
            for (int a = 0; a < 4; a++) {
                N[a] = quad_shape(a, xi, eta);
                dA[0] += N[a] * u[D * node[a] + 3];
                dA[1] += N[a] * u[D * node[a] + 4];
            }
            deformation_gradient(X, u, node, 4, grad, F);
            preload_apply(em, F, Fe);
            wff_point_result r;
            double *gf = gamma_f + 3 * el->n_tris + 4 * e + q;
            int status = point_ok(mat->cell->evaluate(mat->params, Fe, dA, *gf, dt, &r), Fe, dA, &r);
            if (status != WFF_POINT_OK) {
                note_bad(totals, id, q, status);
                continue;
            }
            *gf = r.gamma_f;
            double w = el->quad_weight[4 * e + q];
            preload_pull_add(em, r.stress, 1.0, Pm);
            for (int b = 0; b < 4; b++) {
                double *fb = f + D * node[b];
                for (int i = 0; i < 3; i++)
                    fb[i] -= w * (Pm[2 * i] * grad[2 * b] + Pm[2 * i + 1] * grad[2 * b + 1]);
                for (int k = 0; k < amplitudes; k++)
                    fb[3 + k] += w * N[b] * r.residual[k] / em->J_pre;
            }
            energy += w * r.energy;
            dissipated += w * r.dissipated;
        }
    }
    totals->internal_energy = energy / em->J_pre;
    totals->dissipated = dissipated / em->J_pre;
}

void wff_elements_energy_split(const wff_elements *el, const wff_element_material *em,
                               const double *X, const double *u, const double *gamma_f,
                               double *mech)
{
    const wff_cell_type *cell = em->mat->cell;
    for (int k = 0; k < cell->n_mech; k++)
        mech[k] = 0;
    if (!cell->energy_split)
        return;
    double point[WFF_MECH_MAX];
    for (int e = 0; e < el->n_tris; e++) {
        const int *node = el->tri + 3 * e;
        double F[6], Fe[6];
        deformation_gradient(X, u, node, 3, el->tri_grad + 6 * e, F);
        preload_apply(em, F, Fe);
        double w = el->tri_area[e] / 3 / em->J_pre;
        for (int q = 0; q < WFF_TRI_POINTS; q++) {
            double dA[2] = {u[D * node[q] + 3], u[D * node[q] + 4]};
            cell->energy_split(em->mat->params, Fe, dA, gamma_f[3 * e + q], point);
            for (int k = 0; k < cell->n_mech; k++)
                mech[k] += w * point[k];
        }
    }
    for (int e = 0; e < el->n_quads; e++) {
        const int *node = el->quad + 4 * e;
        for (int q = 0; q < WFF_QUAD_POINTS; q++) {
            const double *grad = el->quad_grad + 32 * e + 8 * q;
            double xi = gauss_1d * quad_gauss[q][0], eta = gauss_1d * quad_gauss[q][1];
            double dA[2] = {0, 0}, F[6], Fe[6];
            for (int a = 0; a < 4; a++) {
                double N = quad_shape(a, xi, eta);
                dA[0] += N * u[D * node[a] + 3];
                dA[1] += N * u[D * node[a] + 4];
            }
            deformation_gradient(X, u, node, 4, grad, F);
            preload_apply(em, F, Fe);
            cell->energy_split(em->mat->params, Fe, dA,
                               gamma_f[3 * el->n_tris + 4 * e + q], point);
            double w = el->quad_weight[4 * e + q] / em->J_pre;
            for (int k = 0; k < cell->n_mech; k++)
                mech[k] += w * point[k];
        }
    }
}

void wff_elements_masses(const wff_elements *el, const wff_element_material *em, int n_nodes,
                         double *mass)
{
    memset(mass, 0, sizeof(double) * D * (size_t)n_nodes);
    double density = em->mat->areal_density / em->J_pre;
    for (int e = 0; e < el->n_tris; e++)
        for (int a = 0; a < 3; a++)
            mass[D * el->tri[3 * e + a]] += density * el->tri_area[e] / 3;
    for (int e = 0; e < el->n_quads; e++) {
        double area = 0;
        for (int q = 0; q < 4; q++)
            area += el->quad_weight[4 * e + q];
        for (int a = 0; a < 4; a++)
            mass[D * el->quad[4 * e + a]] += density * area / 4;
    }
    for (int n = 0; n < n_nodes; n++) {
        double m = mass[D * n];
        mass[D * n + 1] = mass[D * n + 2] = m;
        mass[D * n + 3] = mass[D * n + 4] = m / 6; /* eq. 12 */
    }
}

void wff_element_center_state(const wff_elements *el, const double *X, const double *u, int e,
                              double F[6], double dA[2])
{
    if (e < el->n_tris) {
        const int *node = el->tri + 3 * e;
        deformation_gradient(X, u, node, 3, el->tri_grad + 6 * e, F);
        dA[0] = dA[1] = 0;
        for (int a = 0; a < 3; a++) {
            dA[0] += u[D * node[a] + 3] / 3;
            dA[1] += u[D * node[a] + 4] / 3;
        }
        return;
    }
    int qe = e - el->n_tris;
    const int *node = el->quad + 4 * qe;
    double grad[4][2];
    quad_gradients(X, node, 0, 0, grad);
    deformation_gradient(X, u, node, 4, &grad[0][0], F);
    dA[0] = dA[1] = 0;
    for (int a = 0; a < 4; a++) {
        dA[0] += u[D * node[a] + 3] / 4;
        dA[1] += u[D * node[a] + 4] / 4;
    }
}

int wff_element_center_eval(const wff_elements *el, const wff_element_material *em,
                            const double *X, const double *u, const double *gamma_f, int e,
                            wff_point_result *out)
{
    double F[6], Fe[6], dA[2], gf = 0;
    wff_element_center_state(el, X, u, e, F, dA);
    preload_apply(em, F, Fe);
    int n = e < el->n_tris ? 3 : 4;
    const double *g = e < el->n_tris ? gamma_f + 3 * e : gamma_f + 3 * el->n_tris + 4 * (e - el->n_tris);
    for (int q = 0; q < n; q++)
        gf += g[q] / n;
    return em->mat->cell->evaluate(em->mat->params, Fe, dA, gf, 0, out);
}

double wff_elements_stable_step(const wff_elements *el, const wff_element_material *em,
                                const double *X, const double *u, int *worst)
{
    const wff_material *mat = em->mat;
    double best = INFINITY;
    int n = el->n_tris + el->n_quads;
    *worst = -1;
    for (int e = 0; e < n; e++) {
        double F[6], Fe[6], dA[2], speed, omega;
        wff_element_center_state(el, X, u, e, F, dA);
        preload_apply(em, F, Fe);
        mat->cell->wave_speeds(mat->params, mat->areal_density, Fe, dA, &speed, &omega);
        double dt = el->size[e] / speed;
        if (omega > 0)
            dt = fmin(dt, 2 / omega);
        if (!(dt >= best)) { /* also catches NaN */
            best = dt;
            *worst = e;
        }
    }
    return best;
}

/* Element kinematics internal to the membrane code: the bilinear quad's
 * reference geometry (shape functions, Gauss points, gradients), the
 * deformation gradient and the preload (a triangle's written once:
 * tri_deformation), and the checks of a point's result every force pass
 * makes; the force passes (membrane_tri.c, membrane_quad.c), the centre state
 * and stable step (membrane_centre.c) and the energy sums use them. */
#ifndef WOVENFF_MEMBRANE_GEOMETRY_H
#define WOVENFF_MEMBRANE_GEOMETRY_H

#include "wovenff/membrane.h"

#include <math.h>

/* Bilinear quad: corners (ξ, η) = (−1,−1), (1,−1), (1,1), (−1,1); Gauss points ±1/√3. */
static const double quad_corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
static const double gauss_1d __attribute__((unused)) = 0.57735026918962576451; /* 1/√3 */
static const double quad_gauss[4][2] __attribute__((unused)) = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}; /* × gauss_1d */

static inline double quad_shape(int a, double xi, double eta)
{
    return 0.25 * (1 + quad_corner[a][0] * xi) * (1 + quad_corner[a][1] * eta);
}

/* dN_a/dX at (ξ, η); returns det J. */
static inline double quad_gradients(const double *X, const int *node, double xi, double eta,
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

#include <string.h>

/* F_eff = F F_pre */
static inline __attribute__((always_inline)) void preload_apply(const wff_element_material *em, const double F[6], double Fe[6])
{
    const double *Fp = em->F_pre;
    for (int i = 0; i < 3; i++) {
        Fe[2 * i] = F[2 * i] * Fp[0] + F[2 * i + 1] * Fp[2];
        Fe[2 * i + 1] = F[2 * i] * Fp[1] + F[2 * i + 1] * Fp[3];
    }
}

/* F = Σ_a x_a ⊗ ∇N_a with x = X + u */
static inline __attribute__((always_inline)) void deformation_gradient(const double *X, const double *u, const int *node, int n,
                                 const double *grad, double F[6])
{
    memset(F, 0, 6 * sizeof(double));
    for (int a = 0; a < n; a++) {
        const double *ua = u + WFF_DOFS_PER_NODE * node[a];
        double x[3] = {X[2 * node[a]] + ua[0], X[2 * node[a] + 1] + ua[1], ua[2]};
        for (int i = 0; i < 3; i++) {
            F[2 * i] += x[i] * grad[2 * a];
            F[2 * i + 1] += x[i] * grad[2 * a + 1];
        }
    }
}

/* Triangle e at the displacement u: F = Σ_a x_a ⊗ ∇N_a over its three nodes
 * (x = X + u). The one gather of a triangle's deformation gradient: every
 * triangle pass calls it, most through tri_deformation. */
static inline __attribute__((always_inline)) void
tri_gradient(const wff_elements *el, const double *X, const double *u, int e, double F[6])
{
    /* in scalars, deformation_gradient's sums in its order (the same bits): inside
     * the blocked passes' `omp simd` gathers the lanes' loads stay vector gathers */
    const int *node = el->tri + 3 * e;
    const double *g = el->tri_grad + 6 * e;
    double F0 = 0, F1 = 0, F2 = 0, F3 = 0, F4 = 0, F5 = 0;
    for (int a = 0; a < 3; a++) {
        const double *ua = u + WFF_DOFS_PER_NODE * node[a];
        const double x = X[2 * node[a]] + ua[0], y = X[2 * node[a] + 1] + ua[1], z = ua[2];
        F0 += x * g[2 * a];
        F1 += x * g[2 * a + 1];
        F2 += y * g[2 * a];
        F3 += y * g[2 * a + 1];
        F4 += z * g[2 * a];
        F5 += z * g[2 * a + 1];
    }
    F[0] = F0, F[1] = F1, F[2] = F2, F[3] = F3, F[4] = F4, F[5] = F5;
}

/* tri_gradient's F and F_eff = F F_pre: what the triangle passes (forces
 * plain, blocked and static, the stable step's blocks, the energy split)
 * evaluate the cell at. */
static inline __attribute__((always_inline)) void
tri_deformation(const wff_elements *el, const wff_element_material *em, const double *X,
                const double *u, int e, double F[6], double Fe[6])
{
    tri_gradient(el, X, u, e, F);
    preload_apply(em, F, Fe);
}

/* P_mesh = P F_preᵀ / J_pre, added with weight w into acc */
static inline __attribute__((always_inline)) void preload_pull_add(const wff_element_material *em, const double P[6], double w,
                             double acc[6])
{
    const double *Fp = em->F_pre;
    double s = w / em->J_pre;
    for (int i = 0; i < 3; i++) {
        acc[2 * i] += s * (P[2 * i] * Fp[0] + P[2 * i + 1] * Fp[1]);
        acc[2 * i + 1] += s * (P[2 * i] * Fp[2] + P[2 * i + 1] * Fp[3]);
    }
}

/* WFF_POINT_NONFINITE for a NaN or infinite state (F_eff, ΔA) or result, else the cell's status:
 * a NaN state is not a degenerate one (cells report both as degenerate). */
static inline int point_ok(int status, const double Fe[6], const double dA[2],
                           const wff_point_result *r)
{
    double state = dA[0] + dA[1];
    for (int i = 0; i < 6; i++)
        state += Fe[i];
    if (!isfinite(state))
        return WFF_POINT_NONFINITE;
    if (status != WFF_POINT_OK)
        return status;
    double sum = r->energy + r->residual[0] + r->residual[1];
    for (int i = 0; i < 6; i++)
        sum += r->stress[i];
    return isfinite(sum) ? WFF_POINT_OK : WFF_POINT_NONFINITE;
}

/* The first bad point of a pass (the lowest element, then point, in its order). */
static inline void note_bad(wff_force_totals *t, int e, int q, int status)
{
    if (t->bad_element < 0) {
        t->bad_element = e;
        t->bad_point = q;
        t->bad_status = status;
    }
}

/* Quad qe's static amplitudes at its point q (el->point_dA: 6 per triangle, then 8 per quad). */
static inline double *quad_point_dA(const wff_elements *el, int qe, int q)
{
    return el->point_dA + 6 * el->n_tris + 8 * qe + 2 * q;
}

/* Kinematics at Gauss point q of quad qe, (ξ, η) = quad_gauss[q] / √3: the shape
 * functions N_a, the amplitudes ΔA = Σ_a N_a ΔA_a (with static amplitudes the
 * point's own balanced ones instead, a copy of quad_point_dA), F = Σ_a x_a ⊗ ∇N_a
 * and F_eff = F F_pre. */
static inline __attribute__((always_inline)) void
quad_point_kinematics(const wff_elements *el, const wff_element_material *em, const double *X,
                      const double *u, int qe, int q, double N[4], double dA[2], double F[6],
                      double Fe[6])
{
    const int *node = el->quad + 4 * qe;
    double xi = gauss_1d * quad_gauss[q][0], eta = gauss_1d * quad_gauss[q][1];
    dA[0] = dA[1] = 0;
    for (int a = 0; a < 4; a++) {
        N[a] = quad_shape(a, xi, eta);
        dA[0] += N[a] * u[WFF_DOFS_PER_NODE * node[a] + 3];
        dA[1] += N[a] * u[WFF_DOFS_PER_NODE * node[a] + 4];
    }
    deformation_gradient(X, u, node, 4, el->quad_grad + 32 * qe + 8 * q, F);
    preload_apply(em, F, Fe);
    if (em->static_amplitudes)
        memcpy(dA, quad_point_dA(el, qe, q), 2 * sizeof(double));
}

#endif

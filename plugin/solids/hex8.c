/* hex8.c: the backing block's one-point hexahedron at finite strain
 * (hex8.h): reference gradients, the Hencky strain through the eigenvectors
 * of C, the nodal forces of a material-frame stress, the hourglass springs
 * and the element's stable step. Pure: no allocation. */
#include "hex8.h"

#include <math.h>
#include <string.h>

/* The natural coordinates of node a (hex8.h's order). */
static const double natural[WFF_HEX_NODES][3] = {
    {-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
    {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1},
};

static double det3(const double A[9])
{
    return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
           A[2] * (A[3] * A[7] - A[4] * A[6]);
}

/* inv = A⁻¹ (row-major), given det A != 0 */
static void inverse3(const double A[9], double det, double inv[9])
{
    inv[0] = (A[4] * A[8] - A[5] * A[7]) / det;
    inv[1] = (A[2] * A[7] - A[1] * A[8]) / det;
    inv[2] = (A[1] * A[5] - A[2] * A[4]) / det;
    inv[3] = (A[5] * A[6] - A[3] * A[8]) / det;
    inv[4] = (A[0] * A[8] - A[2] * A[6]) / det;
    inv[5] = (A[2] * A[3] - A[0] * A[5]) / det;
    inv[6] = (A[3] * A[7] - A[4] * A[6]) / det;
    inv[7] = (A[1] * A[6] - A[0] * A[7]) / det;
    inv[8] = (A[0] * A[4] - A[1] * A[3]) / det;
}

/* The reference gradients B_a = J⁻ᵀ ∂N_a/∂ξ at a point from the shape
 * functions' natural derivatives dN there (J = Σ_a X_a ⊗ dN_a); returns
 * det J, <= 0 (B unset) if the point is inverted or flat. */
static double reference_gradients(const double X[WFF_HEX_NODES][3],
                                  const double dN[WFF_HEX_NODES][3], double B[WFF_HEX_NODES][3])
{
    double J0[9] = {0};
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                J0[3 * i + j] += X[a][i] * dN[a][j];
    const double det = det3(J0);
    if (!(det > 0))
        return det;
    double inv[9];
    inverse3(J0, det, inv);
    /* (B_a)_i = Σ_j inv[j][i] dN_aj */
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++)
            B[a][i] = inv[i] * dN[a][0] + inv[3 + i] * dN[a][1] + inv[6 + i] * dN[a][2];
    return det;
}

int wff_hex8_reference(const double X[WFF_HEX_NODES][3], wff_hex8_ref *r)
{
    /* at the centre ∂N_a/∂ξ_j = ξ_aj / 8 */
    double dN[WFF_HEX_NODES][3];
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int j = 0; j < 3; j++)
            dN[a][j] = natural[a][j] / 8;
    const double det = reference_gradients(X, dN, r->gradient);
    if (!(det > 0))
        return -1;
    r->volume = 8 * det;
    /* h_α: ξη, ηζ, ξζ, ξηζ at the nodes; γ_α = h_α − (Σ_b h_αb X_b)·B0_a */
    for (int al = 0; al < 4; al++) {
        double h[WFF_HEX_NODES], hx[3] = {0, 0, 0};
        for (int a = 0; a < WFF_HEX_NODES; a++) {
            const double *n = natural[a];
            h[a] = al == 0 ? n[0] * n[1] : al == 1 ? n[1] * n[2] : al == 2 ? n[0] * n[2]
                                                                       : n[0] * n[1] * n[2];
            for (int i = 0; i < 3; i++)
                hx[i] += h[a] * X[a][i];
        }
        for (int a = 0; a < WFF_HEX_NODES; a++)
            r->gamma[al][a] = h[a] - (hx[0] * r->gradient[a][0] + hx[1] * r->gradient[a][1] +
                                      hx[2] * r->gradient[a][2]);
    }
    return 0;
}

void wff_hex8_gradient(const wff_hex8_ref *r, const double u[WFF_HEX_NODES][3], double F[9])
{
    double G[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                G[3 * i + j] += u[a][i] * r->gradient[a][j];
    memcpy(F, G, sizeof G);
}

/* The eigenvalues lambda and eigenvectors (columns of Q, row-major) of the
 * symmetric A, by cyclic Jacobi rotations (converges quadratically; a few
 * sweeps reach round-off for 3×3). */
static void eigen_symmetric(const double A_in[9], double lambda[3], double Q[9])
{
    double A[9];
    memcpy(A, A_in, sizeof A);
    const double I[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    memcpy(Q, I, sizeof I);
    for (int sweep = 0; sweep < 30; sweep++) {
        const double off = A[1] * A[1] + A[2] * A[2] + A[5] * A[5];
        const double diag = A[0] * A[0] + A[4] * A[4] + A[8] * A[8];
        if (off <= 1e-36 * diag || off == 0)
            break;
        for (int p = 0; p < 2; p++)
            for (int q = p + 1; q < 3; q++) {
                const double apq = A[3 * p + q];
                if (apq == 0)
                    continue;
                const double theta = (A[3 * q + q] - A[3 * p + p]) / (2 * apq);
                const double t = (theta >= 0 ? 1 : -1) / (fabs(theta) + sqrt(theta * theta + 1));
                const double c = 1 / sqrt(t * t + 1), s = t * c;
                /* A ← Jᵀ A J with J the rotation in the (p, q) plane */
                for (int k = 0; k < 3; k++) {
                    const double akp = A[3 * k + p], akq = A[3 * k + q];
                    A[3 * k + p] = c * akp - s * akq;
                    A[3 * k + q] = s * akp + c * akq;
                }
                for (int k = 0; k < 3; k++) {
                    const double apk = A[3 * p + k], aqk = A[3 * q + k];
                    A[3 * p + k] = c * apk - s * aqk;
                    A[3 * q + k] = s * apk + c * aqk;
                }
                for (int k = 0; k < 3; k++) {
                    const double qkp = Q[3 * k + p], qkq = Q[3 * k + q];
                    Q[3 * k + p] = c * qkp - s * qkq;
                    Q[3 * k + q] = s * qkp + c * qkq;
                }
            }
    }
    lambda[0] = A[0], lambda[1] = A[4], lambda[2] = A[8];
}

/* out = Q diag(d) Qᵀ as 6 entries (xx yy zz yz xz xy) or as a 3×3 */
static void spectral6(const double Q[9], const double d[3], double out[6])
{
    static const int row[6] = {0, 1, 2, 1, 0, 0}, col[6] = {0, 1, 2, 2, 2, 1};
    for (int k = 0; k < 6; k++) {
        double s = 0;
        for (int m = 0; m < 3; m++)
            s += Q[3 * row[k] + m] * d[m] * Q[3 * col[k] + m];
        out[k] = s;
    }
}

static void sym6_to_3(const double s[6], double A[9])
{
    A[0] = s[0], A[4] = s[1], A[8] = s[2];
    A[5] = A[7] = s[3];
    A[2] = A[6] = s[4];
    A[1] = A[3] = s[5];
}

double wff_hencky(const double F[9], double strain[6], double U_inv[9])
{
    const double J = det3(F);
    if (!(J > 0))
        return J;
    double C[9];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C[3 * i + j] = F[i] * F[j] + F[3 + i] * F[3 + j] + F[6 + i] * F[6 + j];
    double lambda[3], Q[9];
    eigen_symmetric(C, lambda, Q);
    double log_half[3], root_inv[3];
    for (int k = 0; k < 3; k++) {
        if (!(lambda[k] > 0))
            return 0;
        log_half[k] = 0.5 * log(lambda[k]);
        root_inv[k] = 1 / sqrt(lambda[k]);
    }
    spectral6(Q, log_half, strain);
    double u6[6];
    spectral6(Q, root_inv, u6);
    sym6_to_3(u6, U_inv);
    return J;
}

/* C = A B (3×3 row-major) */
static void mul3(const double A[9], const double B[9], double C[9])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            C[3 * i + j] = A[3 * i] * B[j] + A[3 * i + 1] * B[3 + j] + A[3 * i + 2] * B[6 + j];
}

void wff_hex8_forces(const wff_hex8_ref *r, const double F[9], const double U_inv[9],
                     const double stress[6], double f[WFF_HEX_NODES][3])
{
    double T[9], A[9], S[9], P[9];
    sym6_to_3(stress, T);
    mul3(U_inv, T, A);
    mul3(A, U_inv, S); /* S = U⁻¹ τ̄ U⁻¹ */
    mul3(F, S, P);     /* P = F S */
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++)
            f[a][i] = -r->volume * (P[3 * i] * r->gradient[a][0] + P[3 * i + 1] * r->gradient[a][1] +
                                    P[3 * i + 2] * r->gradient[a][2]);
}

double wff_hex8_bulk_viscosity(const wff_hex8_ref *r, const double F[9], double J,
                               const double v[WFF_HEX_NODES][3], double density,
                               double wave_speed, double linear, double quadratic,
                               double f[WFF_HEX_NODES][3])
{
    double inv[9];
    inverse3(F, J, inv);
    double b[WFF_HEX_NODES][3], rate = 0;
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++) {
            b[a][i] = inv[i] * r->gradient[a][0] + inv[3 + i] * r->gradient[a][1] +
                      inv[6 + i] * r->gradient[a][2];
            rate += v[a][i] * b[a][i];
        }
    const double volume = J * r->volume, length = cbrt(volume);
    double q = density * length * linear * wave_speed * -rate;
    if (rate < 0)
        q += density * length * length * quadratic * quadratic * rate * rate;
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++)
            f[a][i] += volume * q * b[a][i];
    return q * -rate * volume;
}

static double gradient_square(const wff_hex8_ref *r)
{
    double s = 0;
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++)
            s += r->gradient[a][i] * r->gradient[a][i];
    return s;
}

double wff_hex8_hourglass_stiffness(const wff_hex8_ref *r, double kappa, double shear)
{
    return kappa * shear * r->volume * gradient_square(r) / 8;
}

double wff_hex8_hourglass(const wff_hex8_ref *r, const double u[WFF_HEX_NODES][3], double k,
                          double f[WFF_HEX_NODES][3])
{
    if (k == 0)
        return 0;
    double energy = 0;
    for (int al = 0; al < 4; al++) {
        double q[3] = {0, 0, 0};
        for (int a = 0; a < WFF_HEX_NODES; a++)
            for (int i = 0; i < 3; i++)
                q[i] += r->gamma[al][a] * u[a][i];
        energy += 0.5 * k * (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
        for (int a = 0; a < WFF_HEX_NODES; a++)
            for (int i = 0; i < 3; i++)
                f[a][i] -= k * r->gamma[al][a] * q[i];
    }
    return energy;
}

void wff_hex8_hourglass_dashpots(const wff_hex8_ref *r, double k, double node_mass, double ratio,
                                 double c[4])
{
    const int none = k == 0 || ratio == 0 || node_mass <= 0;
    const double critical = none ? 0 : 2 * sqrt(k * node_mass);
    for (int al = 0; al < 4; al++) {
        double norm = 0;
        for (int a = 0; a < WFF_HEX_NODES; a++)
            norm += r->gamma[al][a] * r->gamma[al][a];
        c[al] = none ? 0 : ratio * critical / sqrt(norm);
    }
}

double wff_hex8_hourglass_damping(const wff_hex8_ref *r, const double v[WFF_HEX_NODES][3],
                                  const double c[4], double f[WFF_HEX_NODES][3])
{
    double power = 0;
    for (int al = 0; al < 4; al++) {
        if (c[al] == 0)
            continue;
        double rate[3] = {0, 0, 0};
        for (int a = 0; a < WFF_HEX_NODES; a++)
            for (int i = 0; i < 3; i++)
                rate[i] += r->gamma[al][a] * v[a][i];
        power += c[al] * (rate[0] * rate[0] + rate[1] * rate[1] + rate[2] * rate[2]);
        for (int a = 0; a < WFF_HEX_NODES; a++)
            for (int i = 0; i < 3; i++)
                f[a][i] -= c[al] * r->gamma[al][a] * rate[i];
    }
    return power;
}

double wff_hex8_hourglass_frequency(const wff_hex8_ref *r, double k, double node_mass)
{
    double gamma_max = 0;
    for (int al = 0; al < 4; al++) {
        double g = 0;
        for (int a = 0; a < WFF_HEX_NODES; a++)
            g += r->gamma[al][a] * r->gamma[al][a];
        gamma_max = fmax(gamma_max, g);
    }
    return node_mass > 0 ? sqrt(k * gamma_max / node_mass) : 0;
}

double wff_hex8_stable_step(const wff_hex8_ref *r, const double F[9], double wave_speed,
                            double k, double node_mass)
{
    const double J = det3(F);
    if (!(J > 0))
        return 0;
    double inv[9];
    inverse3(F, J, inv);
    /* b_a = F⁻ᵀ B0_a: (b_a)_i = Σ_j inv[j][i] B0_aj */
    double sum = 0;
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++) {
            const double b = inv[i] * r->gradient[a][0] + inv[3 + i] * r->gradient[a][1] +
                             inv[6 + i] * r->gradient[a][2];
            sum += b * b;
        }
    const double hourglass = wff_hex8_hourglass_frequency(r, k, node_mass);
    const double omega2 = 8 * wave_speed * wave_speed * sum + hourglass * hourglass;
    return omega2 > 0 ? 2 / sqrt(omega2) : INFINITY;
}

/* ---- the fully integrated element (2×2×2 Gauss points, F-bar) ---- */

int wff_hex8_full_reference(const double X[WFF_HEX_NODES][3], wff_hex8_full *r)
{
    const double at = 1 / sqrt(3.0);
    for (int g = 0; g < WFF_HEX_POINTS; g++) {
        double dN[WFF_HEX_NODES][3];
        for (int a = 0; a < WFF_HEX_NODES; a++)
            for (int j = 0; j < 3; j++) {
                /* ∂N_a/∂ξ_j = ξ_aj / 8 Π_{k≠j} (1 + ξ_ak ξ_gk) */
                double d = natural[a][j] / 8;
                for (int k = 0; k < 3; k++)
                    if (k != j)
                        d *= 1 + natural[a][k] * natural[g][k] * at;
                dN[a][j] = d;
            }
        const double det = reference_gradients(X, dN, r->gradient[g]);
        if (!(det > 0))
            return -1;
        r->volume[g] = det;
    }
    return 0;
}

double wff_hex8_current_gradients(const double F[9], const double B[WFF_HEX_NODES][3],
                                  double b[WFF_HEX_NODES][3])
{
    const double J = det3(F);
    if (!(J > 0))
        return J;
    double inv[9];
    inverse3(F, J, inv);
    /* (F⁻ᵀ B)_i = Σ_j inv[j][i] B_j */
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++)
            b[a][i] = inv[i] * B[a][0] + inv[3 + i] * B[a][1] + inv[6 + i] * B[a][2];
    return J;
}

int wff_hex8_fbar(const wff_hex8_full *r, int g, const double u[WFF_HEX_NODES][3],
                  double J_centre, wff_hex8_fbar_point *p)
{
    double G[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++)
                G[3 * i + j] += u[a][i] * r->gradient[g][a][j];
    memcpy(p->F, G, sizeof G);
    p->J = det3(G);
    if (!(p->J > 0))
        return -1;
    p->scale = cbrt(J_centre / p->J);
    for (int k = 0; k < 9; k++)
        p->F_bar[k] = p->scale * G[k];
    return 0;
}

void wff_hex8_fbar_forces(const wff_hex8_full *r, int g, const double b_centre[WFF_HEX_NODES][3],
                          const wff_hex8_fbar_point *p, const double U_inv[9],
                          const double stress[6], double f[WFF_HEX_NODES][3])
{
    double T[9], A[9], S[9], P[9], b[WFF_HEX_NODES][3];
    sym6_to_3(stress, T);
    mul3(U_inv, T, A);
    mul3(A, U_inv, S);      /* S̄ = U⁻¹ τ̄ U⁻¹ */
    mul3(p->F_bar, S, P);   /* P̄ = F̄ S̄ */
    wff_hex8_current_gradients(p->F, r->gradient[g], b);
    const double third_trace = (stress[0] + stress[1] + stress[2]) / 3, V = r->volume[g];
    for (int a = 0; a < WFF_HEX_NODES; a++) {
        const double *B = r->gradient[g][a];
        for (int i = 0; i < 3; i++) {
            const double direct = P[3 * i] * B[0] + P[3 * i + 1] * B[1] + P[3 * i + 2] * B[2];
            f[a][i] -= V * (p->scale * direct + third_trace * (b_centre[a][i] - b[a][i]));
        }
    }
}

/* Σ_a |F⁻ᵀ B_a|², the current gradients' squares (0 if F is inverted) */
static double current_gradient_square(const double F[9], const double B[WFF_HEX_NODES][3])
{
    double b[WFF_HEX_NODES][3], sum = 0;
    if (!(wff_hex8_current_gradients(F, B, b) > 0))
        return 0;
    for (int a = 0; a < WFF_HEX_NODES; a++)
        for (int i = 0; i < 3; i++)
            sum += b[a][i] * b[a][i];
    return sum;
}

double wff_hex8_full_stable_step(const wff_hex8_ref *centre, const wff_hex8_full *r,
                                 const double u[WFF_HEX_NODES][3], double density,
                                 double wave_speed, double shear)
{
    double F0[9];
    wff_hex8_gradient(centre, u, F0);
    const double J_centre = det3(F0);
    if (!(J_centre > 0))
        return 0;
    const double bulk = fmax(density * wave_speed * wave_speed - 4 * shear / 3, 0);
    double volume = 0; /* (Σ_g V_g, the element's exact volume; 8 det J0 only on a parallelepiped) */
    for (int g = 0; g < WFF_HEX_POINTS; g++)
        volume += r->volume[g];
    double omega2 = bulk * volume * current_gradient_square(F0, centre->gradient);
    for (int g = 0; g < WFF_HEX_POINTS; g++) {
        wff_hex8_fbar_point p;
        if (wff_hex8_fbar(r, g, u, J_centre, &p))
            return 0;
        omega2 += 2 * shear * r->volume[g] * current_gradient_square(p.F, r->gradient[g]);
    }
    omega2 /= density * centre->volume / 8;
    return omega2 > 0 ? 2 / sqrt(omega2) : INFINITY;
}

/* The backing block's fully integrated element (plugin/solids/hex8.h,
 * wff_hex8_full: eight Gauss points with F-bar): its nodal forces against
 * its stored energy Σ_g V_g W(ε̄_g) by central differences on distorted
 * elements at large strain (the derivative through the centre's J_0 and the
 * points' J_g included); an affine field's forces equal to the one-point
 * element's (F̄_g = F at every point) and a rigid rotation's nil; the four
 * hourglass modes of a cube, free in the one-point element without its
 * springs, resisted here (their energy a fraction of a uniform shear's of
 * the same size); the element's stiffness at rest has exactly six zero
 * modes; the stable-step bound against
 * the element's own largest frequency (a power iteration on M⁻¹K). The
 * patch test and the NIJ drop test of a fully integrated block: test_hex8. */
#include "check.h"
#include "power_iteration.h"
#include "rng.h"
#include "solids/block.h"
#include "solids/hex8.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <gsl/gsl_sort_vector.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

static const double unit_cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                       {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

/* The fully integrated element's energy at u (the clay elastic: no plastic
 * strain), its forces into f. */
static double full_energy(const wff_hex8_ref *ref, const wff_hex8_full *full,
                          const wff_clay_params *p, const double u[8][3], double f[8][3])
{
    double F0[9], b0[8][3], energy = 0;
    wff_hex8_gradient(ref, u, F0);
    const double J0 = wff_hex8_current_gradients(F0, ref->gradient, b0);
    memset(f, 0, 24 * sizeof(double));
    const wff_clay_state s = {{0}, 0, 0, 0};
    for (int g = 0; g < WFF_HEX_POINTS; g++) {
        wff_hex8_fbar_point pt;
        double strain[6], U_inv[9], stress[6];
        wff_hex8_fbar(full, g, u, J0, &pt);
        wff_hencky(pt.F_bar, strain, U_inv);
        wff_clay_stress(p, strain, &s, stress);
        wff_hex8_fbar_forces(full, g, b0, &pt, U_inv, stress, f);
        energy += full->volume[g] * wff_clay_energy(p, strain, &s);
    }
    return energy;
}

static void distorted(wff_rng *r, double h, double X[8][3])
{
    for (int a = 0; a < 8; a++)
        for (int c = 0; c < 3; c++)
            X[a][c] = h * (unit_cube[a][c] + wff_rng_uniform(r, -0.15, 0.15));
}

static void forces_against_energy(check_state *st)
{
    wff_rng r = {2024};
    const wff_clay_params *p = &wff_clay_roma_plastilina;
    double worst = 0, volume_off = 0;
    for (int trial = 0; trial < 20; trial++) {
        double X[8][3], u[8][3], f[8][3], fp[8][3];
        const double h = wff_rng_uniform(&r, 1e-3, 5e-3), size = trial < 10 ? 0.12 : 0.3;
        distorted(&r, h, X);
        for (int a = 0; a < 8; a++)
            for (int c = 0; c < 3; c++)
                u[a][c] = h * wff_rng_uniform(&r, -size, size);
        wff_hex8_ref ref;
        wff_hex8_full full;
        CHECK(st, wff_hex8_reference(X, &ref) == 0 && wff_hex8_full_reference(X, &full) == 0,
              "distorted element refused");
        if (trial == 0) { /* the points' volumes sum to a cube's */
            double Xc[8][3];
            for (int a = 0; a < 8; a++)
                for (int c = 0; c < 3; c++)
                    Xc[a][c] = h * unit_cube[a][c];
            wff_hex8_full cube;
            wff_hex8_full_reference(Xc, &cube);
            double v = 0;
            for (int g = 0; g < WFF_HEX_POINTS; g++)
                v += cube.volume[g];
            volume_off = fabs(v - h * h * h) / (h * h * h);
        }
        full_energy(&ref, &full, p, u, f);
        double scale = 0;
        for (int a = 0; a < 8; a++)
            for (int c = 0; c < 3; c++)
                scale = fmax(scale, fabs(f[a][c]));
        for (int a = 0; a < 8; a++)
            for (int c = 0; c < 3; c++) {
                const double e = 1e-7 * h, keep = u[a][c];
                u[a][c] = keep + e;
                const double up = full_energy(&ref, &full, p, u, fp);
                u[a][c] = keep - e;
                const double down = full_energy(&ref, &full, p, u, fp);
                u[a][c] = keep;
                worst = fmax(worst, fabs(-(up - down) / (2 * e) - f[a][c]) / scale);
            }
    }
    CHECK(st, volume_off < 1e-14, "the cube's volume from its points off by %g", volume_off);
    CHECK(st, worst < 1e-6, "forces off -dE/du by %g of the largest", worst);
    printf("F-bar forces against the energy's central differences (strains to ~30 %%): %.2e of "
           "the largest force\n", worst);
}

/* An affine field: F̄_g = F at every point, so on a parallelepiped (V_g sum
 * to the one-point V0) the forces are the one-point element's; a rigid
 * rotation: none. */
static void affine_and_rotation(check_state *st)
{
    wff_rng r = {31337};
    const wff_clay_params *p = &wff_clay_roma_plastilina;
    double X[8][3], u[8][3], f[8][3], f1[8][3];
    double L[9]; /* a parallelepiped: X = L ξ' of the unit cube */
    for (int k = 0; k < 9; k++)
        L[k] = 2e-3 * ((k % 4 == 0) + wff_rng_uniform(&r, -0.2, 0.2));
    for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++)
            X[a][i] = L[3 * i] * unit_cube[a][0] + L[3 * i + 1] * unit_cube[a][1] +
                      L[3 * i + 2] * unit_cube[a][2];
    wff_hex8_ref ref;
    wff_hex8_full full;
    wff_hex8_reference(X, &ref);
    wff_hex8_full_reference(X, &full);
    double A[9];
    for (int k = 0; k < 9; k++)
        A[k] = wff_rng_uniform(&r, -0.1, 0.1);
    for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++)
            u[a][i] = A[3 * i] * X[a][0] + A[3 * i + 1] * X[a][1] + A[3 * i + 2] * X[a][2];
    const double energy = full_energy(&ref, &full, p, u, f);
    double F[9], strain[6], U_inv[9], stress[6];
    wff_hex8_gradient(&ref, u, F);
    wff_hencky(F, strain, U_inv);
    const wff_clay_state s = {{0}, 0, 0, 0};
    wff_clay_stress(p, strain, &s, stress);
    wff_hex8_forces(&ref, F, U_inv, stress, f1);
    double off = 0, most = 0;
    for (int a = 0; a < 8; a++)
        for (int c = 0; c < 3; c++)
            off = fmax(off, fabs(f[a][c] - f1[a][c])), most = fmax(most, fabs(f1[a][c]));
    CHECK(st, off < 1e-10 * most, "affine field: F-bar forces off the one-point's by %g of %g N",
          off, most);
    CHECK_CLOSE(st, energy, ref.volume * wff_clay_energy(p, strain, &s), 1e-12, 0,
                "affine field: the energy against V0 W(F)");
    /* a rigid rotation strains nothing */
    const double c = cos(0.7), sn = sin(0.7);
    const double R[9] = {c, -sn, 0, sn, c, 0, 0, 0, 1};
    for (int a = 0; a < 8; a++)
        for (int i = 0; i < 3; i++)
            u[a][i] = R[3 * i] * X[a][0] + R[3 * i + 1] * X[a][1] + R[3 * i + 2] * X[a][2] - X[a][i];
    full_energy(&ref, &full, p, u, f);
    double rigid = 0;
    for (int a = 0; a < 8; a++)
        for (int k = 0; k < 3; k++)
            rigid = fmax(rigid, fabs(f[a][k]));
    CHECK(st, rigid < 1e-10 * p->youngs * 0.01 * 4e-6, "a rigid rotation's forces %g N", rigid);
}

/* The element's stiffness at rest by central differences of its forces. */
static void stiffness(const wff_hex8_ref *ref, const wff_hex8_full *full,
                      const wff_clay_params *p, double K[24][24])
{
    double u[8][3] = {{0}}, f1[8][3], f2[8][3];
    for (int col = 0; col < 24; col++) {
        const double e = 1e-9;
        u[col / 3][col % 3] = e;
        full_energy(ref, full, p, u, f1);
        u[col / 3][col % 3] = -e;
        full_energy(ref, full, p, u, f2);
        u[col / 3][col % 3] = 0;
        for (int row = 0; row < 24; row++)
            K[row][col] = -(f1[row / 3][row % 3] - f2[row / 3][row % 3]) / (2 * e);
    }
}

/* No hourglass mode: a cube's stiffness has six zero eigenvalues (rigid
 * motions) and the seventh well above round-off; each of the one-point
 * element's hourglass fields u_a = h_α(a) e_c stores energy. */
static void no_hourglass(check_state *st)
{
    const wff_clay_params *p = &wff_clay_roma_plastilina;
    double X[8][3], K[24][24];
    for (int a = 0; a < 8; a++)
        for (int c = 0; c < 3; c++)
            X[a][c] = 2e-3 * unit_cube[a][c];
    wff_hex8_ref ref;
    wff_hex8_full full;
    wff_hex8_reference(X, &ref);
    wff_hex8_full_reference(X, &full);
    stiffness(&ref, &full, p, K);
    gsl_matrix *M = gsl_matrix_alloc(24, 24);
    gsl_vector *eval = gsl_vector_alloc(24);
    gsl_eigen_symm_workspace *w = gsl_eigen_symm_alloc(24);
    for (int i = 0; i < 24; i++)
        for (int j = 0; j < 24; j++)
            gsl_matrix_set(M, i, j, 0.5 * (K[i][j] + K[j][i]));
    gsl_eigen_symm(M, eval, w);
    gsl_sort_vector(eval);
    const double largest = gsl_vector_get(eval, 23), sixth = gsl_vector_get(eval, 5);
    const double seventh = gsl_vector_get(eval, 6);
    CHECK(st, fabs(gsl_vector_get(eval, 0)) < 1e-6 * largest && fabs(sixth) < 1e-6 * largest,
          "six rigid modes: eigenvalues %g .. %g of %g", gsl_vector_get(eval, 0), sixth, largest);
    CHECK(st, seventh > 1e-3 * largest, "the seventh eigenvalue %g of the largest %g: a zero-energy"
          " mode", seventh, largest);
    printf("fully integrated cube: eigenvalues of K at rest 6 x ~0 (|.| <= %.1e), then %.4g .. %.4g "
           "N/m\n", fmax(fabs(gsl_vector_get(eval, 0)), fabs(sixth)), seventh, largest);
    gsl_eigen_symm_free(w), gsl_vector_free(eval), gsl_matrix_free(M);
    /* the hourglass fields against a uniform shear of the same nodal size */
    static const double natural[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                         {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
    double u[8][3], f[8][3], shear_energy;
    for (int a = 0; a < 8; a++)
        u[a][0] = 1e-6 * natural[a][1], u[a][1] = 0, u[a][2] = 0; /* a shear, |u_a| = 1 µm */
    shear_energy = full_energy(&ref, &full, p, u, f);
    for (int al = 0; al < 4; al++)
        for (int c = 0; c < 3; c++) {
            for (int a = 0; a < 8; a++) {
                const double *n = natural[a];
                const double hg = al == 0 ? n[0] * n[1] : al == 1 ? n[1] * n[2]
                                : al == 2 ? n[0] * n[2] : n[0] * n[1] * n[2];
                for (int k = 0; k < 3; k++)
                    u[a][k] = k == c ? 1e-6 * hg : 0;
            }
            const double energy = full_energy(&ref, &full, p, u, f);
            CHECK(st, energy > 0.05 * shear_energy, "hourglass field %d along %c: %g J against a"
                  " shear's %g J", al, "xyz"[c], energy, shear_energy);
        }
}

/* The stable-step bound against 2/ω_max of M⁻¹K (power iteration). */
static void stable_step_bound(check_state *st)
{
    wff_rng r = {515};
    const wff_clay_params *p = &wff_clay_roma_plastilina;
    const double G = p->youngs / (2 * (1 + p->poisson)), c = wff_clay_wave_speed(p);
    for (int trial = 0; trial < 4; trial++) {
        double X[8][3], K[24][24], u[8][3] = {{0}};
        const double stretch = trial == 0 ? 1 : wff_rng_uniform(&r, 0.3, 3);
        for (int a = 0; a < 8; a++)
            for (int k = 0; k < 3; k++)
                X[a][k] = 2e-3 * unit_cube[a][k] * (k == 2 ? stretch : 1) +
                          (trial ? 2e-4 * wff_rng_uniform(&r, -1, 1) : 0);
        wff_hex8_ref ref;
        wff_hex8_full full;
        wff_hex8_reference(X, &ref);
        wff_hex8_full_reference(X, &full);
        stiffness(&ref, &full, p, K);
        const double m = p->density * ref.volume / 8;
        const double exact = 2 / sqrt(test_largest_frequency_squared(K, m, &r));
        const double bound = wff_hex8_full_stable_step(&ref, &full, u, p->density, c, G);
        CHECK(st, bound <= exact * (1 + 1e-6) && bound >= 0.5 * exact,
              "stable step bound %g s against the element's 2/omega_max %g s", bound, exact);
        printf("fully integrated stable step: bound %.4g s, 2/omega_max %.4g s (ratio %.3f)\n",
               bound, exact, bound / exact);
    }
}

int main(void)
{
    check_state st = {0, 0};
    forces_against_energy(&st);
    affine_and_rotation(&st);
    no_hourglass(&st);
    stable_step_bound(&st);
    return check_summary(&st, "test_hex8_full");
}

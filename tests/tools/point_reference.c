/* Generator of tests/data/point_reference.txt: material points evaluated
 * through the C API (wff_material_load + wff_material_evaluate, dt = 0), in
 * wovenffPoint's output layout. The fixture is checked against the C API by
 * tests/c/test_point_fixture.c (so it cannot go stale silently) and against
 * the FreeFEM module by tests/edp/point_vs_c.edp.
 *
 * Not built by make. Regenerate from the repository root after `make`:
 *   gcc -std=gnu11 -O2 -Wall -Wextra -Werror -Iinclude tests/tools/point_reference.c \
 *       $(find build/plugin -name '*.o') -lgsl -lgslcblas -lgmsh -lm -o build/point_reference
 *   build/point_reference > tests/data/point_reference.txt
 *
 * Format: lines starting with '#' are comments; then the number of states;
 * then one line per state:
 *   name material gammaf F11 F12 F21 F22 F31 F32 dA1 dA2 nout out[0] ... out[nout-1]
 * with out = P11 P12 P21 P22 P31 P32 R1 R2 W diag[0..n_diag-1]; material paths
 * are relative to the repository root. */
#include "wovenff/material.h"

#include <stdio.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"

typedef struct state {
    const char *name;     /* what it exercises; tests look some up by name */
    const char *material;
    double gamma_f;
    double F[6];
    double dA[2];
} state;

static const state kStates[] = {
    /* F = I, dA = 0: P and R vanish */
    {"reference", KEVLAR, 0, {1, 0, 0, 1, 0, 0}, {0, 0}},
    /* stretched, sheared and out of plane, amplitudes compacted */
    {"general", KEVLAR, 0, {1.01, 0.05, 0.02, 1.005, 0.03, -0.02}, {-5e-6, -10e-6}},
    /* the same with a dissipative shear angle held */
    {"general_gammaf", KEVLAR, 0.02, {1.01, 0.05, 0.02, 1.005, 0.03, -0.02}, {-5e-6, -10e-6}},
    /* 35 degrees of shear: both locking spars engaged */
    {"spars", KEVLAR, 0, {1, 0.7, 0, 1, 0, 0}, {-2e-6, -4e-6}},
    /* large shear, out of plane, gamma_f held: spars and shear flow together */
    {"spars_gammaf", KEVLAR, 0.3, {1.02, 0.6, 0.1, 0.95, -0.05, 0.08}, {3e-6, -2e-6}},
    /* in-plane compression, amplitudes opened: negative interference */
    {"compressed", KEVLAR, 0, {0.97, -0.1, 0, 0.99, 0, 0}, {4e-6, 2e-6}},
    /* the paper's literal lever factor (lever = 1) with spars engaged */
    {"lever_spars", "tests/data/king_lever.txt", 0.05, {1, 0.7, 0, 1, 0, 0}, {-2e-6, -4e-6}},
    /* tension-only yarns under compression: T_k = 0 */
    {"tension_only_compressed", "tests/data/king_tension_only.txt", 0,
     {0.97, -0.1, 0, 0.99, 0, 0}, {4e-6, 2e-6}},
};

int main(void)
{
    int n = (int)(sizeof kStates / sizeof kStates[0]);
    printf("# wovenffPoint reference values from the C API, written by tests/tools/point_reference.c\n"
           "# (see there to regenerate). Checked by tests/c/test_point_fixture.c and\n"
           "# tests/edp/point_vs_c.edp. After the count, one line per state:\n"
           "# name material gammaf F11 F12 F21 F22 F31 F32 dA1 dA2 nout "
           "P11 P12 P21 P22 P31 P32 R1 R2 W diag...\n");
    printf("%d\n", n);
    for (int s = 0; s < n; s++) {
        const state *st = &kStates[s];
        wff_material mat;
        wff_error err;
        if (wff_material_load(st->material, &mat, &err)) {
            fprintf(stderr, "point_reference: %s\n", err.message);
            return 1;
        }
        wff_point_result r;
        double point_state[WFF_STATE_MAX] = {0}; /* gamma_f: the cell's state of that name */
        int g = wff_material_state_index(&mat, "gamma_f");
        if (g >= 0)
            point_state[g] = st->gamma_f;
        if (wff_material_evaluate(&mat, st->F, st->dA, point_state, 0, &r) != WFF_POINT_OK) {
            fprintf(stderr, "point_reference: state %s is degenerate\n", st->name);
            return 1;
        }
        double out[9 + WFF_DIAG_MAX];
        int nout = 9 + mat.cell->n_diag;
        for (int i = 0; i < 6; i++)
            out[i] = r.stress[i];
        out[6] = r.residual[0];
        out[7] = r.residual[1];
        out[8] = r.energy;
        for (int i = 0; i < mat.cell->n_diag; i++)
            out[9 + i] = r.diag[i];
        printf("%s %s %.17g", st->name, st->material, st->gamma_f);
        for (int i = 0; i < 6; i++)
            printf(" %.17g", st->F[i]);
        printf(" %.17g %.17g %d", st->dA[0], st->dA[1], nout);
        for (int i = 0; i < nout; i++)
            printf(" %.17g", out[i]);
        printf("\n");
    }
    return 0;
}

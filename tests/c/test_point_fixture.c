/* tests/data/point_reference.txt (wovenffPoint's reference values, written by
 * tests/tools/point_reference.c) still matches the C API: every state is
 * re-evaluated and every output compared to 1e-12 relative, so the fixture
 * that tests/edp/point_vs_c.edp trusts can never go stale silently. Also
 * checks that the states still exercise what their names say. */
#include "check.h"
#include "wovenff/material.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define FIXTURE "tests/data/point_reference.txt"
#define MAX_STATES 32
#define OUT_MAX (9 + WFF_DIAG_MAX)
#define REL_TOL 1e-12
/* absolute floor of a component, relative to its largest size over all states */
#define FLOOR_OF_COLUMN 1e-6

typedef struct fixture_state {
    char name[64], material[256];
    double gamma_f, F[6], dA[2];
    int nout;
    double out[OUT_MAX];
} fixture_state;

static int read_fixture(check_state *st, fixture_state *s, int *count)
{
    FILE *f = fopen(FIXTURE, "r");
    CHECK(st, f != NULL, "cannot open %s (run from the repository root)", FIXTURE);
    if (!f)
        return -1;
    int c;
    while ((c = fgetc(f)) == '#') /* comment lines */
        while ((c = fgetc(f)) != '\n' && c != EOF)
            ;
    ungetc(c, f);
    int ok = fscanf(f, "%d", count) == 1 && *count > 0 && *count <= MAX_STATES;
    CHECK(st, ok, "%s: bad state count", FIXTURE);
    for (int i = 0; ok && i < *count; i++) {
        fixture_state *x = &s[i];
        ok = fscanf(f, "%63s %255s %lf", x->name, x->material, &x->gamma_f) == 3;
        for (int k = 0; ok && k < 6; k++)
            ok = fscanf(f, "%lf", &x->F[k]) == 1;
        ok = ok && fscanf(f, "%lf %lf %d", &x->dA[0], &x->dA[1], &x->nout) == 3 &&
             x->nout > 9 && x->nout <= OUT_MAX;
        for (int k = 0; ok && k < x->nout; k++)
            ok = fscanf(f, "%lf", &x->out[k]) == 1;
        CHECK(st, ok, "%s: state %d unreadable", FIXTURE, i + 1);
    }
    char extra[8];
    CHECK(st, !ok || fscanf(f, "%7s", extra) == EOF, "%s: more data than %d states", FIXTURE,
          *count);
    fclose(f);
    return ok ? 0 : -1;
}

static const fixture_state *find(const fixture_state *s, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(s[i].name, name) == 0)
            return &s[i];
    return NULL;
}

static int diag_index(const wff_cell_type *cell, const char *name)
{
    for (int i = 0; cell && i < cell->n_diag; i++)
        if (strcmp(cell->diag_names[i], name) == 0)
            return 9 + i;
    return -1;
}

int main(void)
{
    check_state st = {0, 0};
    static fixture_state s[MAX_STATES];
    int n = 0;
    if (read_fixture(&st, s, &n))
        return check_summary(&st, "test_point_fixture");

    double colmax[OUT_MAX] = {0};
    for (int i = 0; i < n; i++)
        for (int k = 0; k < s[i].nout; k++)
            colmax[k] = fmax(colmax[k], fabs(s[i].out[k]));

    const wff_cell_type *cell = NULL; /* of the first state, for diagnostic names */
    wff_error e;
    for (int i = 0; i < n; i++) {
        wff_material m;
        int rc = wff_material_load(s[i].material, &m, &e);
        CHECK(&st, rc == 0, "state %s: %s", s[i].name, e.message);
        if (rc)
            continue;
        if (i == 0)
            cell = m.cell;
        CHECK(&st, s[i].nout == 9 + m.cell->n_diag, "state %s: %d outputs, cell has %d",
              s[i].name, s[i].nout, 9 + m.cell->n_diag);
        wff_point_result r;
        double state[WFF_STATE_MAX] = {0}; /* the fixture's gamma_f is the cell's state of
                                              that name (as the binding's gammaf) */
        int g = wff_material_state_index(&m, "gamma_f");
        if (g >= 0)
            state[g] = s[i].gamma_f;
        rc = wff_material_evaluate(&m, s[i].F, s[i].dA, state, 0, &r);
        CHECK(&st, rc == WFF_POINT_OK, "state %s degenerate", s[i].name);
        double out[OUT_MAX];
        memcpy(out, r.stress, sizeof r.stress);
        out[6] = r.residual[0];
        out[7] = r.residual[1];
        out[8] = r.energy;
        memcpy(out + 9, r.diag, sizeof r.diag);
        for (int k = 0; k < s[i].nout && k < 9 + m.cell->n_diag; k++) {
            char what[96];
            snprintf(what, sizeof what, "state %.60s, out[%d]", s[i].name, k);
            CHECK_CLOSE(&st, out[k], s[i].out[k], REL_TOL, FLOOR_OF_COLUMN * colmax[k], what);
        }
    }

    /* the states still exercise what their names say */
    const fixture_state *x;
    CHECK(&st, n >= 8, "%d states, want the 8 of point_reference.c", n);
    if ((x = find(s, n, "reference")))
        for (int k = 0; k < 8; k++) /* P and R vanish */
            CHECK(&st, fabs(x->out[k]) <= 1e-12 * colmax[k], "reference out[%d] = %g", k,
                  x->out[k]);
    else
        CHECK(&st, 0, "no state 'reference'");
    const char *spar_states[] = {"spars", "spars_gammaf", "lever_spars"};
    int fl1 = diag_index(cell, "F_L1"), fl2 = diag_index(cell, "F_L2");
    int t1 = diag_index(cell, "T1"), t2 = diag_index(cell, "T2");
    int ms = diag_index(cell, "M_s");
    CHECK(&st, fl1 > 0 && fl2 > 0 && t1 > 0 && t2 > 0 && ms > 0, "diagnostic names changed");
    for (int i = 0; i < 3 && fl1 > 0 && fl2 > 0; i++) {
        x = find(s, n, spar_states[i]);
        CHECK(&st, x && x->out[fl1] > 0 && x->out[fl2] > 0, "state %s: spars not engaged",
              spar_states[i]);
    }
    const fixture_state *g = find(s, n, "general"), *gf = find(s, n, "general_gammaf");
    CHECK(&st, g && fabs(g->out[4]) > 0 && fabs(g->out[5]) > 0, "general: P31, P32 zero");
    CHECK(&st, g && gf && ms > 0 && gf->gamma_f != 0 && gf->out[ms] != g->out[ms],
          "general_gammaf: gamma_f changes nothing");
    x = find(s, n, "compressed");
    CHECK(&st, x && x->out[6] > 0 && x->out[7] > 0, "compressed: amplitudes not pushed back");
    x = find(s, n, "tension_only_compressed");
    CHECK(&st, x && t1 > 0 && t2 > 0 && x->out[t1] == 0 && x->out[t2] == 0,
          "tension_only_compressed: yarns carry compression");
    return check_summary(&st, "test_point_fixture");
}

/* Straight linear yarns: closed-form checks of the cell (plugin/cells/linear_yarns.c).
 * The generic suite (test_cells.c) checks P = dW/dF by finite differences; here
 * the values themselves: uniaxial stretch, shear, tension-only clipping, the
 * ignored amplitudes and shear-flow state, the static uniaxial state, and the
 * material-file errors. */
#include "check.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"

#include <math.h>
#include <string.h>

/* Unequal families, so that a warp/weft mix-up shows. */
#define S1 5.0e6       /* N/m */
#define S2 2.0e6       /* N/m */
#define G 300.0        /* N/m */
#define SPACING1 0.7e-3 /* m */
#define SPACING2 0.8e-3 /* m */
static const char *const text_unequal =
    "cell = linear_yarns\n"
    "S_1 = 5.0e6\n"
    "S_2 = 2.0e6\n"
    "G = 300\n"
    "yarn_spacing_1 = 0.7e-3\n"
    "yarn_spacing_2 = 0.8e-3\n"
    "rho_A = 0.2\n";

/* diag of linear_yarns: T1 T2 lambda1 lambda2 */
enum { T1, T2, LAMBDA1, LAMBDA2 };

static wff_material parse(check_state *st, const char *text, const char *name)
{
    wff_material m;
    wff_error e;
    int rc = wff_material_parse_text(text, name, &m, &e);
    CHECK(st, rc == 0, "%s: %s", name, e.message);
    return m;
}

/* text_unequal with one extra line (appended keys replace nothing: use new keys). */
static void with_line(char *buf, size_t size, const char *base, const char *line)
{
    snprintf(buf, size, "%s%s\n", base, line);
}

static void check_kevlar_file(check_state *st)
{
    wff_material m;
    wff_error e;
    int rc = wff_material_load("freefem_scripts/materials/kevlar_linear.txt", &m, &e);
    CHECK(st, rc == 0, "%s", e.message);
    if (rc)
        return;
    CHECK(st, strcmp(m.cell->name, "linear_yarns") == 0, "cell name %s", m.cell->name);
    CHECK(st, m.cell->n_amplitudes == 0, "no amplitudes");
    CHECK_CLOSE(st, m.yarn_spacing[0], 0.747e-3, 1e-15, 0, "yarn spacing 1");
    CHECK_CLOSE(st, m.areal_density, 0.181, 1e-15, 0, "rho_A");
    /* S_1 = k_1 p0_1 / (2 p0_2) of kevlar_s706.txt: 1 % warp stretch */
    double F[6] = {1.01, 0, 0, 1, 0, 0}, dA[2] = {0, 0};
    wff_point_result r;
    wff_material_evaluate(&m, F, dA, wff_rest_state, 0, &r);
    CHECK_CLOSE(st, r.stress[0], 1.03e7 * 0.3735e-3 / (2 * 0.3735e-3) * 0.01, 1e-9, 0,
                "P11 at 1 % = k p0/(2 p0) x 0.01");
}

/* F = diag(λ, 1) and diag(1, λ): P_kk = S_k (λ − 1), nothing across (no Poisson). */
static void check_uniaxial(check_state *st)
{
    wff_material m = parse(st, text_unequal, "unequal");
    const double lambda = 1.02, dA[2] = {0, 0};
    for (int k = 0; k < 2; k++) {
        double F[6] = {1, 0, 0, 1, 0, 0};
        F[k == 0 ? 0 : 3] = lambda;
        double S = k == 0 ? S1 : S2, spacing = k == 0 ? SPACING1 : SPACING2;
        wff_point_result r;
        int rc = wff_material_evaluate(&m, F, dA, wff_rest_state, 0, &r);
        CHECK(st, rc == WFF_POINT_OK, "uniaxial %d evaluates", k);
        CHECK_CLOSE(st, r.stress[k == 0 ? 0 : 3], S * (lambda - 1), 1e-12, 0, "P_kk = S_k (l - 1)");
        CHECK(st, r.stress[k == 0 ? 3 : 0] == 0, "P across = 0 (no Poisson effect): %g",
              r.stress[k == 0 ? 3 : 0]);
        CHECK(st, r.stress[1] == 0 && r.stress[2] == 0 && r.stress[4] == 0 && r.stress[5] == 0,
              "uniaxial: no shear or out-of-plane resultant");
        CHECK_CLOSE(st, r.energy, 0.5 * S * (lambda - 1) * (lambda - 1), 1e-12, 0,
                    "W = S (l - 1)^2 / 2");
        CHECK_CLOSE(st, r.diag[k == 0 ? T1 : T2], S * (lambda - 1) * spacing, 1e-12, 0,
                    "yarn tension T_k = S_k (l - 1) x spacing_k");
        CHECK(st, r.diag[k == 0 ? T2 : T1] == 0, "other family slack");
        CHECK(st, r.residual[0] == 0 && r.residual[1] == 0, "no amplitude residual");
    }
}

/* Symmetric shear F = [c s; s c], c = cos(γ/2), s = sin(γ/2): both yarns keep
 * their length, the angle closes by γ. P12 = P21 = G γ c, P11 = P22 = −G γ s. */
static void check_symmetric_shear(check_state *st)
{
    wff_material m = parse(st, text_unequal, "unequal");
    const double dA[2] = {0, 0};
    const double gammas[] = {0.05, 0.3, -0.6};
    for (size_t i = 0; i < sizeof gammas / sizeof gammas[0]; i++) {
        double g = gammas[i], c = cos(g / 2), s = sin(g / 2);
        double F[6] = {c, s, s, c, 0, 0};
        wff_point_result r;
        wff_material_evaluate(&m, F, dA, wff_rest_state, 0, &r);
        double scale = G * fabs(g);
        CHECK_CLOSE(st, r.stress[1], G * g * c, 1e-10, scale, "P12 = G g cos(g/2)");
        CHECK_CLOSE(st, r.stress[2], G * g * c, 1e-10, scale, "P21 = G g cos(g/2)");
        CHECK_CLOSE(st, r.stress[0], -G * g * s, 1e-10, scale, "P11 = -G g sin(g/2)");
        CHECK_CLOSE(st, r.stress[3], -G * g * s, 1e-10, scale, "P22 = -G g sin(g/2)");
        CHECK_CLOSE(st, r.energy, 0.5 * G * g * g, 1e-10, 0, "W = G g^2 / 2");
        CHECK_CLOSE(st, r.diag[LAMBDA1], 1, 1e-14, 0, "lambda1 = 1");
    }
}

/* Stretch and shear together: g_1 = λ1 (1, 0), g_2 = λ2 (sin γ, cos γ).
 * Q_1 = N_1 ĝ_1 + (G γ/λ_1) n̂_1 with n̂_1 ⊥ ĝ_1: P11 = S_1 (λ1 − 1) and
 * P21 = G γ/λ1; on yarn 2 the part along ĝ_2 is N_2, across it G γ/λ2. */
static void check_stretch_and_shear(check_state *st)
{
    wff_material m = parse(st, text_unequal, "unequal");
    const double l1 = 1.03, l2 = 0.99, g = 0.25, dA[2] = {0, 0};
    double F[6] = {l1, l2 * sin(g), 0, l2 * cos(g), 0, 0};
    wff_point_result r;
    wff_material_evaluate(&m, F, dA, wff_rest_state, 0, &r);
    CHECK_CLOSE(st, r.stress[0], S1 * (l1 - 1), 1e-12, 0, "P11 = N_1");
    CHECK_CLOSE(st, r.stress[2], G * g / l1, 1e-10, 0, "P21 = G g / l1");
    double along2 = r.stress[1] * sin(g) + r.stress[3] * cos(g);
    double across2 = r.stress[1] * cos(g) - r.stress[3] * sin(g);
    CHECK_CLOSE(st, along2, S2 * (l2 - 1), 1e-10, 0, "Q_2 along yarn 2 = N_2");
    CHECK_CLOSE(st, across2, G * g / l2, 1e-8, 0, "Q_2 across yarn 2 = G g / l2");
    CHECK_CLOSE(st, r.energy,
                0.5 * S1 * (l1 - 1) * (l1 - 1) + 0.5 * S2 * (l2 - 1) * (l2 - 1) + 0.5 * G * g * g,
                1e-12, 0, "W");
    double mech[WFF_MECH_MAX];
    m.cell->energy_split(m.params, F, dA, wff_rest_state, mech);
    CHECK_CLOSE(st, mech[1], 0.5 * G * g * g, 1e-10, 0, "split: shear");
    CHECK_CLOSE(st, mech[0] + mech[1], r.energy, 1e-14, 0, "split adds up");
}

/* tension_only = 1: a compressed yarn carries and stores nothing; a stretched
 * one is unchanged. */
static void check_tension_only(check_state *st)
{
    char text[512];
    with_line(text, sizeof text, text_unequal, "tension_only = 1");
    wff_material clipped = parse(st, text, "tension_only");
    wff_material plain = parse(st, text_unequal, "unequal");
    const double dA[2] = {0, 0};
    double F[6] = {0.98, 0, 0, 1.01, 0, 0};
    wff_point_result rc, rp;
    wff_material_evaluate(&clipped, F, dA, wff_rest_state, 0, &rc);
    wff_material_evaluate(&plain, F, dA, wff_rest_state, 0, &rp);
    CHECK_CLOSE(st, rp.stress[0], S1 * -0.02, 1e-12, 0, "literal: compression P11 = S_1 (l - 1)");
    CHECK(st, rc.stress[0] == 0 && rc.diag[T1] == 0, "tension_only: compressed warp carries "
          "nothing: P11 %g, T1 %g", rc.stress[0], rc.diag[T1]);
    CHECK_CLOSE(st, rc.stress[3], S2 * 0.01, 1e-12, 0, "tension_only: stretched weft as before");
    CHECK_CLOSE(st, rc.energy, 0.5 * S2 * 0.01 * 0.01, 1e-12, 0,
                "tension_only: compression stores nothing");
    /* P = dW/dF still holds with one yarn slack: central difference on F11 and F22 */
    double Fs[6] = {0.99, 0.1, 0.05, 1.02, 0.02, -0.03}, h = 1e-6;
    wff_point_result r0, rm, rpl;
    wff_material_evaluate(&clipped, Fs, dA, wff_rest_state, 0, &r0);
    for (int i = 0; i < 6; i++) {
        double x = Fs[i];
        Fs[i] = x + h;
        wff_material_evaluate(&clipped, Fs, dA, wff_rest_state, 0, &rpl);
        Fs[i] = x - h;
        wff_material_evaluate(&clipped, Fs, dA, wff_rest_state, 0, &rm);
        Fs[i] = x;
        CHECK_CLOSE(st, (rpl.energy - rm.energy) / (2 * h), r0.stress[i], 1e-6,
                    1e-3 * fabs(r0.stress[3]), "tension_only: P = dW/dF");
    }
}

/* ΔA is not used and there is no internal state (n_state 0): R = 0, nothing
 * dissipated, W the same, for any dt (the states it can carry are yarn
 * failure's, docs/model.md §20, off here). */
static void check_ignored_state(check_state *st)
{
    wff_material m = parse(st, text_unequal, "unequal");
    double F[6] = {1.01, 0.2, 0.0, 0.99, 0.1, 0}, zero[2] = {0, 0}, dA[2] = {-3e-5, 1e-5};
    wff_point_result a, b;
    wff_material_evaluate(&m, F, zero, wff_rest_state, 0, &a);
    const double junk[WFF_STATE_MAX] = {0.3, 0.3, 0.3, 0.3, 0.3, 0.3}; /* not read */
    wff_material_evaluate(&m, F, dA, junk, 1e-3, &b);
    CHECK(st, m.n_state == 0, "no internal state without yarn failure: %d", m.n_state);
    CHECK(st, b.dissipated == 0 && b.failure_dissipated == 0, "no shear flow: dissipated %g",
          b.dissipated);
    CHECK(st, b.residual[0] == 0 && b.residual[1] == 0, "no amplitude residual");
    CHECK(st, a.energy == b.energy && memcmp(a.stress, b.stress, sizeof a.stress) == 0,
          "dA and the (unread) state do not change W or P");
    double speed, omega;
    m.cell->wave_speeds(m.params, m.areal_density, F, dA, &speed, &omega);
    CHECK(st, omega == 0, "no amplitude frequency: %g", omega);
    CHECK(st, speed >= sqrt(S1 / m.areal_density), "membrane speed %g >= sqrt(S_1/rho_A) %g",
          speed, sqrt(S1 / m.areal_density));
}

/* The static uniaxial state (the strip scene's reference curve): lateral edge
 * free gives λ2 = 1 and P11 = S_1 (λ1 − 1). */
static void check_uniaxial_static(check_state *st)
{
    wff_material m = parse(st, text_unequal, "unequal");
    for (int k = 0; k < 2; k++) {
        wff_biaxial_state s = {.stretch = {1, 1}};
        wff_error e;
        int rc = wff_uniaxial_static(&m, k, 1.01, &s, &e);
        CHECK(st, rc == 0, "uniaxial static %d: %s", k, e.message);
        if (rc)
            continue;
        CHECK_CLOSE(st, s.resultant[k], (k == 0 ? S1 : S2) * 0.01, 1e-9, 0,
                    "static P_kk = S_k x strain");
        CHECK_CLOSE(st, s.stretch[1 - k], 1, 1e-9, 0, "static: no lateral contraction");
    }
}

/* Errors name the file, the line and the key. */
static void expect_error(check_state *st, const char *text, const char *what,
                         const char *want1, const char *want2)
{
    wff_material m;
    wff_error e;
    int rc = wff_material_parse_text(text, "bad.txt", &m, &e);
    CHECK(st, rc != 0, "%s: accepted", what);
    if (rc == 0)
        return;
    CHECK(st, strstr(e.message, want1) != NULL, "%s: message '%s' lacks '%s'", what, e.message,
          want1);
    CHECK(st, strstr(e.message, want2) != NULL, "%s: message '%s' lacks '%s'", what, e.message,
          want2);
}

static void check_errors(check_state *st)
{
    char text[512];
    snprintf(text, sizeof text, "%s", text_unequal);
    char *p = strstr(text, "S_1 = 5.0e6");
    memcpy(p, "S_1 = 0.0e6", 11);
    expect_error(st, text, "S_1 = 0", "bad.txt:2: key 'S_1'", "must be > 0");
    snprintf(text, sizeof text, "%s", text_unequal);
    p = strstr(text, "G = 300");
    memcpy(p, "G = -30", 7);
    expect_error(st, text, "G < 0", "bad.txt:4: key 'G'", "must be >= 0");
    snprintf(text, sizeof text, "%s", text_unequal);
    p = strstr(text, "yarn_spacing_2 = 0.8e-3\n");
    memmove(p, p + strlen("yarn_spacing_2 = 0.8e-3\n"), strlen(p + strlen("yarn_spacing_2 = 0.8e-3\n")) + 1);
    expect_error(st, text, "missing spacing", "missing key", "'yarn_spacing_2'");
    with_line(text, sizeof text, text_unequal, "tension_only = 2");
    expect_error(st, text, "tension_only = 2", "key 'tension_only'", "must be 0 or 1");
    with_line(text, sizeof text, text_unequal, "k_1 = 1.03e7");
    expect_error(st, text, "king_plain key", "bad.txt:8: unknown key 'k_1'", "linear_yarns");
}

/* Equal-force preload of a cell without amplitudes: only the stretches are
 * unknown, λ_k = 1 + T/(S_k × spacing_k). */
static void check_preload(check_state *st)
{
    wff_material m;
    wff_error e;
    int rc = wff_material_load("freefem_scripts/materials/kevlar_linear.txt", &m, &e);
    CHECK(st, rc == 0, "%s", e.message);
    wff_biaxial_state s = {.stretch = {1, 1}};
    rc = wff_preload_equal_force(&m, 1.0, &s, &e);
    CHECK(st, rc == 0, "preload without amplitudes: %s", rc ? e.message : "");
    for (int k = 0; k < 2; k++) {
        double S = m.yarn_spacing[k] > 0 ? 1.0 / (s.stretch[k] - 1) / m.yarn_spacing[k] : 0;
        CHECK_CLOSE(st, S, 5.15e6, 1e-9, 0, "S_k recovered from the preload stretch");
    }
}

int main(void)
{
    check_state st = {0, 0};
    check_kevlar_file(&st);
    check_uniaxial(&st);
    check_symmetric_shear(&st);
    check_stretch_and_shear(&st);
    check_tension_only(&st);
    check_ignored_state(&st);
    check_uniaxial_static(&st);
    check_errors(&st);
    check_preload(&st);
    return check_summary(&st, "test_linear_yarns");
}

/* The stable-step estimate bounds the true critical step, over states (issue
 * "Stable from any state", item 2). 320 states drawn from a fixed seed: yarn
 * stretch 0.98-1.06 per family and shear +-0.4 rad (the F the cell sees,
 * preload included), the warp at 0 or at a random angle, amplitudes balanced
 * at that F, with +-5 um noise, or changed from there within the cell suite's
 * range [-30, +10] um uniformly or node by node (each amplitude kept at 10 %
 * of its A0 or more), transverse bumps (slope up to 0.16), curvatures and
 * node-to-node roughness, with and without the 1 N/yarn preload, triangles and
 * quads (2-5 x 2-4 cells of 0.5-7 mm), every registered cell, some with a
 * disc zone of another cell. At each, the true critical step 2/omega_max of
 * the central-difference integrator: omega_max^2 the largest eigenvalue of
 * M^-1/2 K M^-1/2 on the free DOFs, K the whole tangent by central
 * differences of the force pass (gamma_f held), GSL's symmetric eigensolver
 * (the meshes are tiny: exact where power iteration creeps up from below).
 *
 * Then growth bisection with the built-in integrator itself on flat states
 * at rest (uniform F, yarns in tension, amplitudes balanced, edges held in
 * plane): one ply of every cell and element kind, which must agree with the
 * eigenvalue at the same state, and packs of 2 and 3 plies in contact (domed,
 * slope 0.02, the lowest ply held in u_z, the tension pressing the upper plies
 * on it: the ply contact corrects pairs every step; counted). Two runs at the
 * same fixed step (dtfactor x the estimate, dtinterval 1e6), one from the
 * state and one from it perturbed by 1e-11 m on every free DOF; unstable when
 * their difference grows 1000-fold (M-norm) within 400 steps or the run stops;
 * bisected on dtfactor to 2e-4.
 *
 * Yarn slip (docs/model.md §24): a King material that slips
 * (tests/data/king_slip.txt, T_slip = 5 F_I) through both, apart from the draws
 * above (which keep their sequence): drawn states whose points were given random
 * slips (±2 %) and then one force pass with dt > 0, so that every yarn carries at
 * most its slip tension as in a run, through the eigenvalue; and equilibrium
 * states so slipped, through the growth bisection, where the yarns slip as the
 * runs go on (counted).
 *
 * Required: critical / estimate >= 1 at every state. Printed: the number of
 * states and the worst ratio overall, per cell and per element kind; a state
 * where it fails is named with its cell, material, element kind and draw. */
#include "check.h"
#include "rng.h"
#include "test_meshes.h"
#include "wovenff/balance.h"
#include "wovenff/material.h"
#include "wovenff/pack.h"
#include "wovenff/solver.h"

#include <gsl/gsl_eigen.h>
#include <gsl/gsl_matrix.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define D WFF_DOFS_PER_NODE
#define N_STATES 320          /* drawn states measured by the eigenvalue */
#define AMPLITUDE_LOW -30e-6  /* the cell suite's amplitude range, m (cell_suite.h) */
#define AMPLITUDE_HIGH 10e-6
#define FD_STEP 1e-10         /* m: the tangent's central differences */
#define GROWTH_STEPS 400
#define GROWTH_FACTOR 1e3
#define PERTURBATION 1e-11    /* m */
#define BISECT_TOL 2e-4       /* the bisection's bracket, relative */
#define DTFACTOR_MAX 1.99     /* (dtfactor is at most 2) */
#define CELLS_MAX 16          /* registered cells tallied */

/* Materials: at least one for every registered cell (checked); the draws take the
 * first N_MATERIALS, the slip states the last. */
static const char *const materials[] = {
    "freefem_scripts/materials/kevlar_s706.txt",
    "tests/data/king_tension_only.txt",
    "freefem_scripts/materials/kevlar_basket.txt",
    "freefem_scripts/materials/kevlar_linear.txt",
    "tests/data/king_slip.txt",
};
#define N_MATERIALS ((int)(sizeof materials / sizeof materials[0]) - 1)
#define SLIP_MATERIAL N_MATERIALS
#define N_SLIP_STATES 48      /* drawn slip states measured by the eigenvalue */
#define SLIP_RANGE 0.02       /* the points' random slips before the projecting pass, - */
#define SLIP_PASS_DT 1e-9     /* s: that pass's step */
/* the amplitudes: balanced at the cell's F; that +-5 um node to node; that + a
 * change uniform over the mesh; that + a change from node to node */
enum { AMP_BALANCED, AMP_NOISY, AMP_UNIFORM, AMP_ROUGH, AMP_MODES };
static const char *const amplitude_mode_name[AMP_MODES] = {"balanced", "balanced+-5um",
                                                           "balanced+uniform", "balanced+rough"};

/* One drawn state. */
typedef struct draw {
    int index;
    int material;           /* in materials[] */
    int zone_material;      /* a disc of this material in the middle; -1: none */
    int kind;               /* TEST_MESH_TRI or TEST_MESH_QUAD */
    int preload;            /* the 1 N/yarn equal-force preload */
    int plies;              /* 1: one ply; more: a pack in contact */
    double gap_fraction;    /* a pack's gap, x the ply thickness */
    int nx, ny, alternate;
    double jitter, lx, ly;  /* m */
    double stretch[2];      /* yarn stretch seen by the cell, per family */
    double shear;           /* rad: the weft at pi/2 - shear to the warp */
    double theta;           /* warp direction to the mesh's x axis, rad */
    double bump;            /* u_z: sin(pi x/lx) sin(pi y/ly) bump, m */
    double curvature[3];    /* u_z: ½ (k11 x² + 2 k12 x y + k22 y²) about the centre, 1/m */
    double roughness;       /* u_z: per-node noise, m */
    double inplane_noise;   /* u_x, u_y: per-node noise, m */
    int amplitudes;         /* AMP_* */
    double amp_uniform[2];  /* AMP_UNIFORM: ΔA, m */
    int held_edges;         /* u_x, u_y of the edges fixed (the equilibrium states) */
    int unbalanced;         /* (set by build) the balance failed: the preload's amplitudes */
    double slip_range;      /* > 0: the points' slips drawn in ±slip_range, then one force
                               pass with dt > 0 (a slipping material) */
    uint64_t seed;
} draw;

static const char *cell_name_of(int material)
{
    wff_material mat;
    wff_error err;
    if (wff_material_load(materials[material], &mat, &err))
        return "?";
    return mat.cell->name;
}

/* The draw in words, for a failure's message and the worst states. */
static void describe(const draw *d, char *out, size_t size)
{
    char zone[160] = "";
    if (d->zone_material >= 0)
        snprintf(zone, sizeof zone, ", a disc zone of %s (%s)", cell_name_of(d->zone_material),
                 materials[d->zone_material]);
    char plies[80] = "";
    if (d->plies > 1)
        snprintf(plies, sizeof plies, ", %d plies at gap %.2f x thickness", d->plies,
                 d->gap_fraction);
    snprintf(out, size, "state %d: cell %s (%s), %s %dx%d%s%s, %.3g x %.3g mm, jitter %.2f, "
             "%s, stretch %.4f %.4f, shear %.3f rad, warp at %.3f rad, bump %.3g mm, "
             "curvatures %.3g %.3g %.3g 1/m, roughness %.3g um, amplitudes %s%s%s, seed %llu%s%s",
             d->index, cell_name_of(d->material), materials[d->material],
             d->kind == TEST_MESH_QUAD ? "quads" : "triangles", d->nx, d->ny,
             d->kind == TEST_MESH_TRI && d->alternate ? " alternating" : "", plies,
             1e3 * d->lx, 1e3 * d->ly, d->jitter, d->preload ? "1 N preload" : "no preload",
             d->stretch[0], d->stretch[1], d->shear, d->theta, 1e3 * d->bump, d->curvature[0],
             d->curvature[1], d->curvature[2], 1e6 * d->roughness,
             amplitude_mode_name[d->amplitudes],
             d->unbalanced ? " (from the preload's: no balance)" : "",
             d->held_edges ? ", edges held in-plane" : "", (unsigned long long)d->seed, zone,
             d->slip_range > 0 ? ", slips drawn then projected by a force pass" : "");
}

/* A slipping material's points given slips in ±d->slip_range (both families),
 * then one force pass with dt > 0: the tensions are brought to at most the slip
 * tension, as a run leaves them (docs/model.md §24). 0, or -1 with err set. */
static int slip_points(const draw *d, wff_model *m, wff_error *err)
{
    const int j = wff_material_state_index(&m->mat, "slip_1");
    if (j < 0)
        return wff_fail(err, "%s does not slip", materials[d->material]);
    const int ns = m->n_state;
    const size_t points = 3 * (size_t)m->el.n_tris + 4 * (size_t)m->el.n_quads;
    wff_rng g = {d->seed + 4242};
    for (size_t q = 0; q < points; q++)
        for (int k = 0; k < 2; k++)
            m->state[ns * q + j + k] = wff_rng_uniform(&g, -d->slip_range, d->slip_range);
    double *f = malloc(sizeof(double) * (size_t)m->n_dofs);
    int rc = f ? wff_model_forces(m, m->u, f, SLIP_PASS_DT, NULL, err) : -1;
    free(f);
    /* a run starts from this state: what the pass dissipated is not the run's (its
     * balance starts from the stored energy now) */
    m->dissipated_slip = m->dissipated_shear = 0;
    return rc;
}

/* A random state: every combination of material, element kind and preload
 * in turn, the rest drawn. */
static draw draw_state(wff_rng *g, int index)
{
    draw d;
    memset(&d, 0, sizeof d);
    d.index = index;
    d.material = index % N_MATERIALS;
    d.kind = (index / N_MATERIALS) % 2 ? TEST_MESH_QUAD : TEST_MESH_TRI;
    d.preload = (index / (2 * N_MATERIALS)) % 2;
    d.plies = 1;
    d.zone_material = -1;
    if (wff_rng_uniform(g, 0, 1) < 0.15) { /* a zone of another cell (one with amplitudes
                                               only where the model's cell has them) */
        int z = (int)wff_rng_uniform(g, 0, N_MATERIALS);
        z = z < N_MATERIALS ? z : N_MATERIALS - 1;
        wff_material a, b;
        wff_error err;
        if (z != d.material && wff_material_load(materials[d.material], &a, &err) == 0 &&
            wff_material_load(materials[z], &b, &err) == 0 &&
            (b.cell->n_amplitudes == 0 || a.cell->n_amplitudes > 0))
            d.zone_material = z;
    }
    d.nx = 2 + (int)wff_rng_uniform(g, 0, 4); /* 2 .. 5 */
    d.ny = 2 + (int)wff_rng_uniform(g, 0, 3); /* 2 .. 4 */
    d.alternate = wff_rng_uniform(g, 0, 1) < 0.5;
    d.jitter = wff_rng_uniform(g, 0, 0.3);
    double cell = pow(10, wff_rng_uniform(g, log10(0.5e-3), log10(7e-3))); /* element side */
    d.lx = cell * d.nx;
    d.ly = cell * d.ny * wff_rng_uniform(g, 0.7, 1.3);
    d.stretch[0] = wff_rng_uniform(g, 0.98, 1.06);
    d.stretch[1] = wff_rng_uniform(g, 0.98, 1.06);
    d.shear = wff_rng_uniform(g, -0.4, 0.4);
    d.theta = wff_rng_uniform(g, 0, 1) < 0.6 ? 0 : wff_rng_uniform(g, -M_PI / 2, M_PI / 2);
    double shape = wff_rng_uniform(g, 0, 1); /* transverse: flat, a bump, curvatures, or both */
    if (shape > 0.25 && shape < 0.75)
        d.bump = wff_rng_uniform(g, -0.05, 0.05) * fmin(d.lx, d.ly);
    if (shape > 0.5)
        for (int i = 0; i < 3; i++)
            d.curvature[i] = wff_rng_uniform(g, -0.1, 0.1) / fmax(d.lx, d.ly);
    d.roughness = wff_rng_uniform(g, 0, 1) < 0.5 ? wff_rng_uniform(g, 0, 0.01) * cell : 0;
    d.inplane_noise = wff_rng_uniform(g, 0, 0.002) * cell;
    d.amplitudes = (int)wff_rng_uniform(g, 0, AMP_MODES);
    d.amplitudes = d.amplitudes < AMP_MODES ? d.amplitudes : AMP_MODES - 1;
    for (int k = 0; k < 2; k++)
        d.amp_uniform[k] = wff_rng_uniform(g, AMPLITUDE_LOW, AMPLITUDE_HIGH);
    d.seed = 1000 + (uint64_t)index;
    return d;
}

/* The model of a draw, in its state (m->u; the caller's order is the model's:
 * test meshes are not renumbered). -1 with err set. */
static int build(draw *d, wff_model *m, wff_error *err)
{
    test_rect r = {0, d->lx, 0, d->ly, d->nx, d->ny, d->kind, d->alternate, d->jitter, d->seed};
    if (test_model_rect(m, &r, materials[d->material], err))
        return -1;
    int n_ply = m->n_nodes; /* nodes of one ply */
    double gap = 0;
    if (d->plies > 1) {
        double thickness =
            m->mat.areal_density / (WFF_PLY_FIBRE_DENSITY * WFF_PLY_FIBRE_FRACTION);
        gap = d->gap_fraction * thickness;
        if (wff_model_set_plies(m, d->plies, gap, err))
            goto fail;
    }
    if (d->theta != 0 && wff_model_set_orientation(m, d->theta, err))
        goto fail;
    double dA_pre[2] = {0, 0};
    if (d->preload) {
        wff_biaxial_state pre = {.stretch = {1, 1}};
        if (wff_preload_equal_force(&m->mat, 1.0, &pre, err))
            goto fail;
        double F[4] = {pre.stretch[0], 0, 0, pre.stretch[1]};
        if (wff_model_set_preload(m, F, pre.dA, err))
            goto fail;
        if (m->mat.cell->n_amplitudes) {
            dA_pre[0] = pre.dA[0];
            dA_pre[1] = pre.dA[1];
        }
    }
    if (d->zone_material >= 0 &&
        wff_model_zone_disc(m, 0.5 * d->lx, 0.5 * d->ly, 0.35 * fmin(d->lx, d->ly), 0,
                            materials[d->zone_material], WFF_ZONE_PRELOAD_SHARED, err) < 0)
        goto fail;
    if (d->held_edges) {
        static const char *const edges[] = {"left", "right", "bottom", "top"};
        for (int e = 0; e < 4; e++)
            for (int c = WFF_UX; c <= WFF_UY; c++)
                if (wff_model_fix_group(m, edges[e], c, err) < 0)
                    goto fail;
    }
    /* a pack's lowest ply (ply 0) held in u_z: the domed plies above press on it
     * (no group holds one ply's nodes only: its DOFs set here) */
    for (int k = 0; d->plies > 1 && k < n_ply; k++) {
        m->dof_kind[D * k + WFF_UZ] = WFF_DOF_FIXED;
        m->v[D * k + WFF_UZ] = 0;
    }
    /* the cell's in-plane F: warp stretched by stretch[0] along E1, weft by stretch[1]
     * at pi/2 - shear to it; the mesh's F = that (R F_pre)^-1 */
    const double s = sin(d->shear), c = cos(d->shear);
    const double Ft[4] = {d->stretch[0], d->stretch[1] * s, 0, d->stretch[1] * c};
    const double *P = m->em.F_pre;
    const double det = P[0] * P[3] - P[1] * P[2];
    const double Pi[4] = {P[3] / det, -P[1] / det, -P[2] / det, P[0] / det};
    const double Fm[4] = {Ft[0] * Pi[0] + Ft[1] * Pi[2], Ft[0] * Pi[1] + Ft[1] * Pi[3],
                          Ft[2] * Pi[0] + Ft[3] * Pi[2], Ft[2] * Pi[1] + Ft[3] * Pi[3]};
    /* amplitudes: balanced at the cell's F (the preload's where the balance fails:
     * a slack family), changes from there within [AMPLITUDE_LOW, AMPLITUDE_HIGH],
     * each amplitude A0 + dA kept at 10 % of A0 or more */
    double dA_bal[2] = {dA_pre[0], dA_pre[1]}, floor_dA[2] = {-INFINITY, -INFINITY};
    d->unbalanced = 0;
    if (m->mat.cell->n_amplitudes) {
        const double Fe[6] = {Ft[0], Ft[1], Ft[2], Ft[3], 0, 0};
        if (wff_balance_amplitudes(&m->mat, Fe, NULL, dA_bal, err)) {
            dA_bal[0] = dA_pre[0];
            dA_bal[1] = dA_pre[1];
            d->unbalanced = 1;
        }
        double pitch0[2], amplitude0[2];
        if (wff_cell_reference_geometry(&m->mat, pitch0, amplitude0) == 0)
            for (int a = 0; a < 2; a++)
                floor_dA[a] = -0.9 * amplitude0[a];
    }
    wff_rng g = {d->seed};
    const double cx = 0.5 * d->lx, cy = 0.5 * d->ly;
    for (int p = 0; p < d->plies; p++)
        for (int k = 0; k < n_ply; k++) {
            const int n = p * n_ply + k;
            const double x = m->mesh.xy[2 * n], y = m->mesh.xy[2 * n + 1];
            double *u = m->u + D * n;
            const int edge = x <= 0 || y <= 0 || x >= d->lx || y >= d->ly;
            const double noise = d->held_edges && edge ? 0 : 1;
            u[0] = Fm[0] * x + Fm[1] * y - x + noise * wff_rng_uniform(&g, -1, 1) *
                                                   d->inplane_noise;
            u[1] = Fm[2] * x + Fm[3] * y - y + noise * wff_rng_uniform(&g, -1, 1) *
                                                   d->inplane_noise;
            const double X = x - cx, Y = y - cy;
            u[2] = p * gap + d->bump * sin(M_PI * x / d->lx) * sin(M_PI * y / d->ly) +
                   0.5 * (d->curvature[0] * X * X + 2 * d->curvature[2] * X * Y +
                          d->curvature[1] * Y * Y) +
                   wff_rng_uniform(&g, -1, 1) * d->roughness;
            if (!m->mat.cell->n_amplitudes)
                continue;
            for (int a = 0; a < 2; a++) {
                double dA = dA_bal[a];
                if (d->amplitudes == AMP_NOISY)
                    dA += wff_rng_uniform(&g, -5e-6, 5e-6);
                else if (d->amplitudes == AMP_UNIFORM)
                    dA += d->amp_uniform[a];
                else if (d->amplitudes == AMP_ROUGH)
                    dA += wff_rng_uniform(&g, AMPLITUDE_LOW, AMPLITUDE_HIGH);
                u[3 + a] = fmax(dA, floor_dA[a]);
            }
        }
    if (d->slip_range > 0 && slip_points(d, m, err))
        goto fail;
    return 0;
fail:
    wff_model_free(m);
    return -1;
}

/* The true critical step at the model's u: 2/sqrt(lambda_max) of M^-1/2 K M^-1/2 on
 * the free DOFs, K by central differences of the force pass (gamma_f held), and the
 * largest mode's share in the amplitude DOFs (M-weighted) into *amplitude_share.
 * NAN when a force pass fails (err set). */
static double critical_step(wff_model *m, double *amplitude_share, double *asymmetry,
                            wff_error *err)
{
    const int n = m->n_dofs;
    double *buf = malloc(sizeof(double) * 6 * (size_t)n);
    int *free_dof = malloc(sizeof(int) * (size_t)n);
    double critical = NAN;
    if (!buf || !free_dof) {
        free(buf);
        free(free_dof);
        return NAN;
    }
    double *M = buf, *kind = M + n, *U = kind + n, *fp = U + n, *fm = fp + n;
    wff_model_masses(m, M);
    wff_model_dof_kinds(m, kind, NULL);
    memcpy(U, m->u, sizeof(double) * (size_t)n);
    int nf = 0;
    for (int i = 0; i < n; i++)
        if (kind[i] == WFF_DOF_FREE && M[i] > 0)
            free_dof[nf++] = i;
    gsl_matrix *A = gsl_matrix_alloc((size_t)nf, (size_t)nf);
    gsl_matrix *V = gsl_matrix_alloc((size_t)nf, (size_t)nf);
    gsl_vector *lambda = gsl_vector_alloc((size_t)nf);
    gsl_eigen_symmv_workspace *w = gsl_eigen_symmv_alloc((size_t)nf);
    int ok = A && V && lambda && w;
    for (int b = 0; ok && b < nf; b++) {
        const int j = free_dof[b];
        const double uj = U[j];
        U[j] = uj + FD_STEP;
        ok = wff_model_forces(m, U, fp, 0, NULL, err) == 0;
        U[j] = uj - FD_STEP;
        ok = ok && wff_model_forces(m, U, fm, 0, NULL, err) == 0;
        U[j] = uj;
        for (int a = 0; ok && a < nf; a++) {
            const int i = free_dof[a];
            gsl_matrix_set(A, (size_t)a, (size_t)b,
                           -(fp[i] - fm[i]) / (2 * FD_STEP) / sqrt(M[i] * M[j]));
        }
    }
    if (ok) {
        double big = 0, skew = 0;
        for (int a = 0; a < nf; a++)
            for (int b = 0; b < a; b++) {
                double x = gsl_matrix_get(A, (size_t)a, (size_t)b);
                double y = gsl_matrix_get(A, (size_t)b, (size_t)a);
                skew = fmax(skew, fabs(x - y));
                gsl_matrix_set(A, (size_t)a, (size_t)b, 0.5 * (x + y));
                gsl_matrix_set(A, (size_t)b, (size_t)a, 0.5 * (x + y));
            }
        for (int a = 0; a < nf; a++)
            big = fmax(big, fabs(gsl_matrix_get(A, (size_t)a, (size_t)a)));
        *asymmetry = skew / big;
        gsl_eigen_symmv(A, lambda, V, w);
        size_t top = gsl_vector_max_index(lambda);
        double lmax = gsl_vector_get(lambda, top), share = 0;
        for (int a = 0; a < nf; a++)
            if (free_dof[a] % D >= 3) {
                double v = gsl_matrix_get(V, (size_t)a, top);
                share += v * v;
            }
        *amplitude_share = share;
        critical = lmax > 0 ? 2 / sqrt(lmax) : INFINITY;
    }
    if (w)
        gsl_eigen_symmv_free(w);
    if (lambda)
        gsl_vector_free(lambda);
    if (V)
        gsl_matrix_free(V);
    if (A)
        gsl_matrix_free(A);
    free(free_dof);
    free(buf);
    return critical;
}

/* 1 if the built-in integrator at dtfactor `factor` (the step fixed at the start's
 * estimate) lets a 1e-11 m perturbation of the draw's state grow 1000-fold within
 * GROWTH_STEPS steps (or stops as unstable), 0 if not, -1 if a model cannot be
 * built (err set). The perturbation is the difference between two runs at the
 * same steps, one from the state and one from it perturbed (the state need not
 * be at rest: a pack's upper plies press on the lower ones). A pack's ply contact
 * corrections (node pairs, step by step, of the perturbed run) are added to
 * *contacts unless it is NULL. */
static int grows(draw *d, double factor, long *contacts, wff_error *err)
{
    wff_model base, m;
    if (build(d, &base, err))
        return -1;
    if (build(d, &m, err)) {
        wff_model_free(&base);
        return -1;
    }
    const int n = m.n_dofs;
    double *buf = malloc(sizeof(double) * 2 * (size_t)n);
    double *M = buf, *kind = buf + n;
    int grew = buf ? 0 : -1;
    if (buf) {
        wff_model_masses(&m, M);
        wff_model_dof_kinds(&m, kind, NULL);
    }
    wff_rng g = {d->seed + 77};
    double start = 0;
    for (int i = 0; i < n && grew == 0; i++)
        if (kind[i] == WFF_DOF_FREE && M[i] > 0) {
            m.u[i] += PERTURBATION * wff_rng_uniform(&g, -1, 1);
            start += M[i] * (m.u[i] - base.u[i]) * (m.u[i] - base.u[i]);
        }
    /* the same step in both: the perturbed run's factor on its own estimate */
    double dt_base = 0, dt_m = 0;
    if (grew == 0 && (wff_model_stable_step(&base, NULL, &dt_base, NULL, err) ||
                      wff_model_stable_step(&m, NULL, &dt_m, NULL, err) ||
                      wff_model_set_option(&base, "dtfactor", factor, err) ||
                      wff_model_set_option(&m, "dtfactor", factor * dt_base / dt_m, err) ||
                      wff_model_set_option(&base, "dtinterval", 1e6, err) ||
                      wff_model_set_option(&m, "dtinterval", 1e6, err)))
        grew = -1;
    for (int s = 0; s < GROWTH_STEPS && grew == 0; s++) {
        wff_error step_err;
        if (wff_model_advance(&base, 1e9, 1, &step_err)) {
            grew = 1; /* stopped as unstable (or NaN) */
            break;
        }
        if (wff_model_advance(&m, 1e9, 1, &step_err)) {
            grew = 1;
            break;
        }
        double now = 0;
        for (int i = 0; i < n; i++)
            if (kind[i] == WFF_DOF_FREE && M[i] > 0)
                now += M[i] * (m.u[i] - base.u[i]) * (m.u[i] - base.u[i]);
        grew = now > GROWTH_FACTOR * GROWTH_FACTOR * start;
        if (contacts && d->plies > 1) {
            double pairs = 0;
            if (wff_model_pack_value(&m, "ply_contacts", &pairs, err) == 0)
                *contacts += (long)pairs;
        }
    }
    free(buf);
    wff_model_free(&base);
    wff_model_free(&m);
    return grew;
}

/* The critical dtfactor by growth bisection (the largest that does not grow),
 * DTFACTOR_MAX if even that does not; NAN on failure (err set). */
static double critical_factor(draw *d, wff_error *err)
{
    double lo = 0.5, hi = DTFACTOR_MAX;
    int r = grows(d, hi, NULL, err);
    if (r < 0)
        return NAN;
    if (r == 0)
        return hi;
    r = grows(d, lo, NULL, err);
    if (r != 0)
        return r < 0 ? NAN : lo; /* grows at half the estimate: reported as 0.5 */
    while (hi - lo > BISECT_TOL * lo) {
        double mid = 0.5 * (lo + hi);
        r = grows(d, mid, NULL, err);
        if (r < 0)
            return NAN;
        if (r)
            hi = mid;
        else
            lo = mid;
    }
    return lo;
}

/* Worst ratios, by cell and element kind. */
typedef struct tally {
    int count[CELLS_MAX][2];
    double worst[CELLS_MAX][2];
    int worst_index[CELLS_MAX][2];
    double overall;
    draw overall_draw;
    int states, failures;
} tally;

static void tally_add(tally *t, const draw *d, double ratio)
{
    const wff_cell_type *cell = wff_cell_find(cell_name_of(d->material));
    int c = 0;
    for (int i = 0; i < wff_cell_count(); i++)
        if (wff_cell_at(i) == cell)
            c = i;
    if (c >= CELLS_MAX)
        c = CELLS_MAX - 1;
    int k = d->kind == TEST_MESH_QUAD;
    if (t->count[c][k] == 0 || ratio < t->worst[c][k]) {
        t->worst[c][k] = ratio;
        t->worst_index[c][k] = d->index;
    }
    t->count[c][k]++;
    if (t->states == 0 || ratio < t->overall) {
        t->overall = ratio;
        t->overall_draw = *d;
    }
    t->states++;
}

static void tally_print(const tally *t, const char *what)
{
    printf("  %s: %d states, worst critical/estimate %.4f (state %d)\n", what, t->states,
           t->overall, t->overall_draw.index);
    for (int c = 0; c < wff_cell_count() && c < CELLS_MAX; c++)
        for (int k = 0; k < 2; k++)
            if (t->count[c][k])
                printf("    %-14s %-9s %4d states, worst %.4f (state %d)\n",
                       wff_cell_at(c)->name, k ? "quads" : "triangles", t->count[c][k],
                       t->worst[c][k], t->worst_index[c][k]);
}

static double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* Every registered cell has a material here. */
static void every_cell_covered(check_state *st)
{
    for (int c = 0; c < wff_cell_count(); c++) {
        int covered = 0;
        for (int i = 0; i < N_MATERIALS; i++)
            covered |= wff_cell_find(cell_name_of(i)) == wff_cell_at(c);
        CHECK(st, covered, "registered cell '%s' has no material in test_stable_bound.c",
              wff_cell_at(c)->name);
    }
}

/* The estimate and the eigenvalue's critical step at a draw's state: the ratio
 * (NAN on failure, reported). */
static double eigen_ratio(check_state *st, draw *d, double *share_out, double *asymmetry_out)
{
    wff_model m;
    wff_error err;
    char text[1024];
    describe(d, text, sizeof text);
    if (build(d, &m, &err)) {
        CHECK(st, 0, "%s: %s", text, err.message);
        return NAN;
    }
    describe(d, text, sizeof text); /* (with what build found) */
    double estimate = 0, share = 0, asymmetry = 0;
    int worst = -1;
    int rc = wff_model_stable_step(&m, NULL, &estimate, &worst, &err);
    double critical = rc == 0 ? critical_step(&m, &share, &asymmetry, &err) : NAN;
    /* the integrator's estimate: the same */
    double step = wff_model_step_estimate(&m) / m.dt_factor;
    wff_model_free(&m);
    CHECK(st, rc != 0 || fabs(step - estimate) <= 1e-15 * estimate, "%s: the step estimate %.17g "
          "/ dtfactor is not the stable step %.17g", text, step, estimate);
    if (asymmetry_out)
        *asymmetry_out = fmax(*asymmetry_out, asymmetry);
    CHECK(st, rc == 0 && isfinite(critical) && critical > 0, "%s: %s", text,
          rc == 0 && !isfinite(critical) ? err.message : rc ? err.message : "no step");
    double ratio = critical / estimate;
    CHECK(st, ratio >= 1, "%s: the estimate %.6g s (element %d) is above the critical step "
          "%.6g s: critical/estimate %.5f, the fastest mode %.0f %% amplitudes", text, estimate,
          worst + 1, critical, ratio, 100 * share);
    if (share_out)
        *share_out = share;
    return ratio;
}

/* The drawn states, through the eigenvalue. */
static void drawn_states(check_state *st, tally *t)
{
    wff_rng g = {20260426};
    double start = seconds_now(), worst_share = 0, asymmetry = 0;
    int unbalanced = 0;
    for (int s = 0; s < N_STATES; s++) {
        draw d = draw_state(&g, s);
        double share = 0, ratio = eigen_ratio(st, &d, &share, &asymmetry);
        if (!isfinite(ratio))
            continue;
        if (t->states == 0 || ratio < t->overall)
            worst_share = share;
        unbalanced += d.unbalanced;
        tally_add(t, &d, ratio);
    }
    tally_print(t, "drawn states, critical step by the eigenvalue");
    char text[1024];
    describe(&t->overall_draw, text, sizeof text);
    printf("    worst: %s; its fastest mode %.0f %% amplitudes\n", text, 100 * worst_share);
    printf("    (%d with the preload's amplitudes where the balance failed; the tangent's "
           "largest asymmetry %.1e of its largest diagonal entry; %.1f s)\n", unbalanced,
           asymmetry, seconds_now() - start);
}

/* A flat state in equilibrium: the cell's F uniform, amplitudes balanced, the
 * edges held in-plane. */
static draw equilibrium(wff_rng *g, int index, int material, int kind, int preload, int plies)
{
    draw d;
    memset(&d, 0, sizeof d);
    d.index = index;
    d.material = material;
    d.zone_material = -1;
    d.kind = kind;
    d.preload = preload;
    d.plies = plies;
    d.gap_fraction = plies > 1 ? (index % 2 ? 0.5 : 1.0) : 0;
    d.nx = 4;
    d.ny = 3;
    d.alternate = index % 2;
    d.jitter = 0.2;
    double cell = pow(10, wff_rng_uniform(g, log10(0.5e-3), log10(3e-3)));
    d.lx = 4 * cell;
    d.ly = 3 * cell;
    /* yarns in tension: a compressed membrane buckles (grows at any step) */
    d.stretch[0] = wff_rng_uniform(g, 1.005, 1.06);
    d.stretch[1] = wff_rng_uniform(g, 1.005, 1.06);
    d.shear = wff_rng_uniform(g, -0.4, 0.4);
    d.theta = index % 3 == 2 ? wff_rng_uniform(g, -M_PI / 2, M_PI / 2) : 0;
    if (plies > 1) /* a dome: slope 0.02 at the edges, the tension presses the plies together */
        d.curvature[0] = d.curvature[1] = -0.04 / fmax(d.lx, d.ly);
    d.amplitudes = AMP_BALANCED;
    d.held_edges = 1;
    d.seed = 5000 + (uint64_t)index;
    return d;
}

/* Growth bisection with the built-in integrator: one ply (and the eigenvalue at
 * the same state: they must agree) and packs of 2 and 3 plies in contact. */
static void growth_states(check_state *st, tally *t)
{
    wff_rng g = {4262};
    double start = seconds_now(), disagree = 0;
    int index = N_STATES;
    for (int material = 0; material < N_MATERIALS; material++)
        for (int kind = 0; kind < 2; kind++) {
            draw d = equilibrium(&g, index++, material, kind, (material + kind) % 2, 1);
            char text[1024];
            wff_error err;
            describe(&d, text, sizeof text);
            double factor = critical_factor(&d, &err);
            double eigen = eigen_ratio(st, &d, NULL, NULL);
            describe(&d, text, sizeof text);
            CHECK(st, isfinite(factor), "%s: %s", text, err.message);
            if (!isfinite(factor) || !isfinite(eigen))
                continue;
            printf("    one ply, %-12s %-9s: growth bisection %.4f%s, eigenvalue %.4f\n",
                   cell_name_of(material), kind ? "quads" : "triangles", factor,
                   factor >= DTFACTOR_MAX ? " (the largest dtfactor tried)" : "", eigen);
            CHECK(st, factor >= 1, "%s: grows at dtfactor %.5f of the estimate", text, factor);
            if (eigen < DTFACTOR_MAX) { /* the integrator's threshold is the eigenvalue's */
                double e = fabs(factor - eigen) / eigen;
                disagree = fmax(disagree, e);
                CHECK(st, e <= 2e-3, "%s: growth bisection %.5f against the eigenvalue %.5f",
                      text, factor, eigen);
            }
            tally_add(t, &d, fmin(factor, eigen));
        }
    static const struct { int material, kind, preload, plies; } packs[] = {
        {0, TEST_MESH_TRI, 1, 2}, {0, TEST_MESH_QUAD, 0, 3}, {0, TEST_MESH_TRI, 0, 3},
        {2, TEST_MESH_QUAD, 1, 2}, {2, TEST_MESH_TRI, 0, 3}, {3, TEST_MESH_TRI, 1, 2},
        {3, TEST_MESH_QUAD, 0, 3}, {1, TEST_MESH_QUAD, 1, 2},
    };
    for (size_t i = 0; i < sizeof packs / sizeof packs[0]; i++) {
        draw d = equilibrium(&g, index++, packs[i].material, packs[i].kind, packs[i].preload,
                             packs[i].plies);
        char text[1024];
        wff_error err;
        describe(&d, text, sizeof text);
        double factor = critical_factor(&d, &err);
        describe(&d, text, sizeof text);
        CHECK(st, isfinite(factor), "%s: %s", text, err.message);
        if (!isfinite(factor))
            continue;
        /* at the estimate itself, the plies touching: the contact corrects pairs */
        long contacts = 0;
        int at_estimate = grows(&d, 1.0, &contacts, &err);
        CHECK(st, at_estimate == 0 && contacts > 0, "%s: at the estimate: %s, %ld ply "
              "contact corrections in %d steps", text, at_estimate ? "grows" : "stable",
              contacts, GROWTH_STEPS);
        /* the plies' own stiffness without the contact, for comparison */
        double eigen = eigen_ratio(st, &d, NULL, NULL);
        printf("    %d plies, %-11s %-9s: growth bisection %.4f%s, %ld ply contact corrections "
               "in %d steps at the estimate; eigenvalue without the contact %.4f\n", d.plies,
               cell_name_of(d.material), d.kind ? "quads" : "triangles", factor,
               factor >= DTFACTOR_MAX ? " (the largest dtfactor tried)" : "", contacts,
               GROWTH_STEPS, eigen);
        CHECK(st, factor >= 1, "%s: grows at dtfactor %.5f of the estimate", text, factor);
        tally_add(t, &d, factor);
    }
    printf("    one ply: growth bisection and eigenvalue within %.1e\n", disagree);
    tally_print(t, "equilibrium states, critical step by growth bisection");
    printf("    (%.1f s)\n", seconds_now() - start);
}

/* Yarn slip (the header comment): drawn states of the slipping material with
 * slipped points through the eigenvalue, then equilibrium states of it through
 * the growth bisection (the yarns slip as the runs go). */
static void slip_states(check_state *st, tally *t)
{
    wff_rng g = {20260711};
    double start = seconds_now(), worst_share = 0;
    for (int s = 0; s < N_SLIP_STATES; s++) {
        draw d = draw_state(&g, 10000 + s);
        d.material = SLIP_MATERIAL;
        d.zone_material = -1;
        d.slip_range = SLIP_RANGE;
        double share = 0, ratio = eigen_ratio(st, &d, &share, NULL);
        if (!isfinite(ratio))
            continue;
        if (t->states == 0 || ratio < t->overall)
            worst_share = share;
        tally_add(t, &d, ratio);
    }
    tally_print(t, "slipped states, critical step by the eigenvalue");
    char text[1024];
    describe(&t->overall_draw, text, sizeof text);
    printf("    worst: %s; its fastest mode %.0f %% amplitudes\n", text, 100 * worst_share);
    for (int kind = 0; kind < 2; kind++)
        for (int preload = 0; preload < 2; preload++) {
            draw d = equilibrium(&g, 20000 + 2 * kind + preload, SLIP_MATERIAL,
                                 kind ? TEST_MESH_QUAD : TEST_MESH_TRI, preload, 1);
            d.slip_range = SLIP_RANGE;
            wff_error err;
            describe(&d, text, sizeof text);
            double factor = critical_factor(&d, &err);
            CHECK(st, isfinite(factor), "%s: %s", text, err.message);
            if (!isfinite(factor))
                continue;
            /* the yarns do slip in these runs: the dissipation at the estimate */
            wff_model m;
            double slipped = 0;
            if (build(&d, &m, &err) == 0) {
                if (wff_model_set_option(&m, "dtinterval", 1e6, &err) == 0 &&
                    wff_model_advance(&m, 1e9, GROWTH_STEPS, &err) == 0)
                    wff_model_value(&m, "dissipated_slip", &slipped, &err);

                wff_model_free(&m);
            }
            printf("    slipping, %-9s %-10s: growth bisection %.4f%s; %.3g J dissipated by slip "
                   "in %d steps at the estimate\n", kind ? "quads" : "triangles",
                   preload ? "preload" : "no preload", factor,
                   factor >= DTFACTOR_MAX ? " (the largest dtfactor tried)" : "", slipped,
                   GROWTH_STEPS);
            CHECK(st, factor >= 1, "%s: grows at dtfactor %.5f of the estimate", text, factor);
            CHECK(st, slipped > 0, "%s: the yarns do not slip in the run (%.3g J)", text, slipped);
            tally_add(t, &d, factor);
        }
    printf("    (%.1f s)\n", seconds_now() - start);
}

int main(void)
{
    check_state st = {0, 0};
    double start = seconds_now();
    every_cell_covered(&st);
    tally drawn, grown;
    memset(&drawn, 0, sizeof drawn);
    memset(&grown, 0, sizeof grown);
    drawn_states(&st, &drawn);
    growth_states(&st, &grown);
    tally slipped;
    memset(&slipped, 0, sizeof slipped);
    slip_states(&st, &slipped);
    double worst = fmin(fmin(drawn.overall, grown.overall), slipped.overall);
    printf("  stable-step bound over %d states: worst critical/estimate %.4f (%.1f s)\n",
           drawn.states + grown.states + slipped.states, worst, seconds_now() - start);
    return check_summary(&st, "test_stable_bound");
}

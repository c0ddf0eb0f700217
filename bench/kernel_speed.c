/* Kernel speed: ns per element-step of the explicit step (forces + update +
 * contact) for the King cell on the ballistic quarter mesh, triangles or
 * quads, at a chosen size, with 1 or more threads; peak memory per element.
 * Also the same mesh through a bare linear CST membrane kernel of our own
 * (same layout, gather, scatter and update): the floor for any membrane here.
 *
 * usage: kernel_speed ELEMENT_TYPE(tri|quad) SIZE_FACTOR THREADS STEPS [static]
 *                     [orientation=DEG]
 * (static: amplitudes balanced at every point, the model option
 * static_amplitudes, with its Newton iterations per point and step;
 * orientation=DEG: the warp at DEG to x, the setting orientation, for the cost
 * of θ ≠ 0 only: the quarter mesh's symmetry planes are not the weave's then)
 * prints one JSON object on stdout. Run from the repository root. */
#include "wovenff/kernel.h"
#include "wovenff/options.h"
#include "wovenff/solver.h"

#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* Bare linear CST membrane: isotropic plane stress in the mesh plane plus a
 * transverse prestress term, 3 DOFs per node, lumped mass, central differences. */
static double linear_membrane_ns(const wff_model *m, int steps, int threads)
{
    const int nn = m->n_nodes, nt = m->el.n_tris;
    double *u = calloc((size_t)3 * nn, sizeof(double)), *v = calloc((size_t)3 * nn, sizeof(double));
    double *f = calloc((size_t)3 * nn * threads, sizeof(double)), *minv = calloc((size_t)nn, sizeof(double));
    for (int e = 0; e < nt; e++)
        for (int a = 0; a < 3; a++)
            minv[m->el.tri[3 * e + a]] += 0.181 * m->el.tri_area[e] / 3;
    for (int n = 0; n < nn; n++) {
        minv[n] = 1 / minv[n];
        v[3 * n + 2] = 1e-3 * (n % 5);
    }
    const double E = 5e6, nu = 0.1, T = 100, dt = 1e-8;
    const double c1 = E / (1 - nu * nu), c2 = c1 * nu, c3 = E / (2 * (1 + nu));
    double t0 = now();
    for (int s = 0; s < steps; s++) {
        memset(f, 0, sizeof(double) * 3 * nn * threads);
#pragma omp parallel num_threads(threads)
        {
            double *ft = f + (size_t)3 * nn * omp_get_thread_num();
#pragma omp for schedule(static)
            for (int e = 0; e < nt; e++) {
                const int *n = m->el.tri + 3 * e;
                const double *g = m->el.tri_grad + 6 * e;
                double exx = 0, eyy = 0, exy = 0, gzx = 0, gzy = 0;
                for (int a = 0; a < 3; a++) {
                    const double *ua = u + 3 * n[a];
                    exx += ua[0] * g[2 * a];
                    eyy += ua[1] * g[2 * a + 1];
                    exy += ua[0] * g[2 * a + 1] + ua[1] * g[2 * a];
                    gzx += ua[2] * g[2 * a];
                    gzy += ua[2] * g[2 * a + 1];
                }
                double sxx = c1 * exx + c2 * eyy, syy = c2 * exx + c1 * eyy, sxy = c3 * exy;
                double A = m->el.tri_area[e];
                for (int a = 0; a < 3; a++) {
                    double *fa = ft + 3 * n[a];
                    fa[0] -= A * (sxx * g[2 * a] + sxy * g[2 * a + 1]);
                    fa[1] -= A * (sxy * g[2 * a] + syy * g[2 * a + 1]);
                    fa[2] -= A * T * (gzx * g[2 * a] + gzy * g[2 * a + 1]);
                }
            }
        }
        for (int t = 1; t < threads; t++)
            for (int i = 0; i < 3 * nn; i++)
                f[i] += f[(size_t)3 * nn * t + i];
        for (int n = 0; n < nn; n++)
            for (int c = 0; c < 3; c++) {
                v[3 * n + c] += dt * f[3 * n + c] * minv[n];
                u[3 * n + c] += dt * v[3 * n + c];
            }
    }
    double ns = (now() - t0) * 1e9 / steps / nt;
    free(u);
    free(v);
    free(f);
    free(minv);
    return ns;
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: %s tri|quad SIZE_FACTOR THREADS STEPS [static] "
                "[orientation=DEG]\n", argv[0]);
        return 2;
    }
    int static_amplitudes = 0;
    double orientation = 0;
    for (int a = 5; a < argc; a++) {
        char *end = NULL;
        if (strcmp(argv[a], "static") == 0) {
            static_amplitudes = 1;
        } else if (strncmp(argv[a], "orientation=", 12) == 0) {
            orientation = strtod(argv[a] + 12, &end);
            if (end == argv[a] + 12 || *end) {
                fprintf(stderr, "%s: '%s': orientation=DEG takes a number\n", argv[0], argv[a]);
                return 2;
            }
        } else {
            fprintf(stderr, "%s: argument '%s': only 'static' and 'orientation=DEG' are known\n",
                    argv[0], argv[a]);
            return 2;
        }
    }
    int quads = strcmp(argv[1], "quad") == 0, threads = atoi(argv[3]), steps = atoi(argv[4]);
    char settings[128];
    snprintf(settings, sizeof settings, "size_factor=%s recombine=%d", argv[2], quads);
    wff_mesh_options opt;
    wff_error err;
    wff_model m;
    struct rusage r0, r1;
    getrusage(RUSAGE_SELF, &r0);
    if (wff_mesh_options_parse(settings, &opt, &err) ||
        wff_model_create(&m, "meshes/ballistic_quarter.geo", &opt,
                         "freefem_scripts/materials/kevlar_s706.txt", &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    const double F_pre[4] = {1.003963, 0, 0, 1.013476}, dA0[2] = {-9.311e-6, -23.748e-6};
    if (wff_model_set_preload(&m, F_pre, dA0, &err) || wff_model_fix_group(&m, "sym_x", 0, &err) < 0 ||
        wff_model_fix_group(&m, "sym_y", 1, &err) < 0 ||
        wff_model_fix_group(&m, "clamp", 0, &err) < 0 || wff_model_fix_group(&m, "clamp", 1, &err) < 0 ||
        wff_model_fix_group(&m, "clamp", 2, &err) < 0 ||
        wff_model_set_projectile(&m, 6.35e-3, 0.026, 22, 0.3, &err) ||
        wff_elements_set_threads(&m.el, threads, &err) ||
        (static_amplitudes && wff_model_set_option(&m, "static_amplitudes", 1, &err)) ||
        (orientation != 0 && wff_model_set_option(&m, "orientation", orientation, &err))) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    int ne = m.el.n_tris + m.el.n_quads;
    /* warm up, then time `steps` steps */
    if (wff_model_advance(&m, 1e9, 20, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    long s0 = m.step, iterations0 = m.amplitude_iterations;
    double t0 = now();
    if (wff_model_advance(&m, 1e9, steps, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    double ns = (now() - t0) * 1e9 / (double)(m.step - s0) / ne;
    double points = 3.0 * m.el.n_tris + 4.0 * m.el.n_quads;
    char newton[48] = "null";
    if (static_amplitudes)
        snprintf(newton, sizeof newton, "%.3f",
                 (double)(m.amplitude_iterations - iterations0) / points / (double)(m.step - s0));
    getrusage(RUSAGE_SELF, &r1);
    double bytes_per_element = (double)(r1.ru_maxrss - r0.ru_maxrss) * 1024.0 / ne;
    /* what the model itself holds: per node 5 DOFs × (u, v, f, mass, prescribed
     * velocity, reaction) + kind + coordinates + thread buffers; per element its
     * nodes, region, geometry, size and γᶠ per point */
    double node_bytes = m.n_nodes * (5.0 * (6 * sizeof(double) + 1) + 2 * sizeof(double) +
                                     5.0 * sizeof(double) * (m.el.max_threads - 1));
    double element_bytes = m.el.n_tris * (3 * sizeof(int) + sizeof(int) + 8 * sizeof(double) +
                                          3 * sizeof(double)) +
                           m.el.n_quads * (4 * sizeof(int) + sizeof(int) + 37 * sizeof(double) +
                                           4 * sizeof(double));
    if (m.node_user) /* the model's own order and its inverse (renumber.h) */
        node_bytes += m.n_nodes * 2.0 * sizeof(int), element_bytes += ne * 2.0 * sizeof(int);
    char linear[32] = "null";
    if (!quads)
        snprintf(linear, sizeof linear, "%.2f", linear_membrane_ns(&m, steps, threads));
    printf("{\"elements\": %d, \"element_type\": \"%s\", \"nodes\": %d, \"threads\": %d, "
           "\"steps\": %ld, \"ns_per_element_step\": %.2f, \"linear_membrane_ns\": %s, "
           "\"model_bytes_per_element\": %.0f, \"peak_rss_bytes_per_element\": %.0f, "
           "\"amplitudes\": \"%s\", \"newton_iterations_per_point_step\": %s, "
           "\"orientation_deg\": %g, \"kernel\": \"%s\"}\n",
           ne, quads ? "quad4" : "tri3", m.n_nodes, threads, m.step - s0, ns, linear,
           (node_bytes + element_bytes) / ne, bytes_per_element,
           static_amplitudes ? "static" : "dynamic", newton, orientation,
           wff_material_kernel(&m.mat));
    wff_model_free(&m);
    return 0;
}

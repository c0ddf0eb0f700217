/* mesh_labels.c: triangle meshes given by arrays (a FreeFEM mesh the binding
 * hands over, a FreeFEM-format .msh read by mesh_freefem.c) copied into a
 * wff_mesh with wff_mesh_load's checks, their labels made groups (named by
 * settings "names=1:clamp regions=0:ply"), and a label number resolved to
 * its group (include/wovenff/mesh_labels.h). Knows nothing of gmsh, FreeFEM's
 * C++ types, materials or the solver. */
#include "wovenff/mesh_labels.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define AREA_TOL 1e-12 /* x bounding-box diagonal^2, as mesh.c */
#define MAX_NAMED 64

typedef struct label_name {
    int dim;
    long label;
    char name[WFF_MESH_NAME_MAX];
} label_name;

/* Parse "names=1:a,2:b regions=0:c" into names[]; returns the count or -1. */
static int parse_names(const char *settings, label_name *names, wff_error *err)
{
    int n = 0;
    const char *p = settings ? settings : "";
    while (*p) {
        while (*p == ' ' || *p == '\t')
            p++;
        if (!*p)
            break;
        size_t len = strcspn(p, " \t");
        int dim;
        const char *value;
        if (len > 6 && strncmp(p, "names=", 6) == 0)
            dim = 1, value = p + 6;
        else if (len > 8 && strncmp(p, "regions=", 8) == 0)
            dim = 2, value = p + 8;
        else
            return wff_fail(err, "settings '%s': unknown setting '%.*s' (known: "
                            "names=LABEL:NAME,... for boundary labels, regions=LABEL:NAME,... "
                            "for region labels)", settings, (int)len, p);
        const char *end = p + len;
        while (value < end) {
            size_t item = strcspn(value, ",");
            if (value + item > end)
                item = (size_t)(end - value);
            const char *colon = memchr(value, ':', item);
            char *num_end;
            errno = 0;
            long label = strtol(value, &num_end, 10);
            size_t name_len = colon ? (size_t)(value + item - colon - 1) : 0;
            if (!colon || num_end != colon || num_end == value || errno || name_len == 0 ||
                name_len >= WFF_MESH_NAME_MAX)
                return wff_fail(err, "settings '%s': expected LABEL:NAME (a whole number, a "
                                "name of 1 to %d characters) at '%.*s'", settings,
                                WFF_MESH_NAME_MAX - 1, (int)item, value);
            if (n >= MAX_NAMED)
                return wff_fail(err, "settings '%s': more than %d label names", settings,
                                MAX_NAMED);
            label_name *ln = &names[n++];
            ln->dim = dim;
            ln->label = label;
            memcpy(ln->name, colon + 1, name_len);
            ln->name[name_len] = '\0';
            value += item + (value + item < end);
        }
        p = end;
    }
    return n;
}

static int cmp_int(const void *a, const void *b)
{
    int x = *(const int *)a, y = *(const int *)b;
    return (x > y) - (x < y);
}

/* Distinct values of v[0..n-1], sorted, into out (n entries); returns count. */
static int distinct(const int *v, int n, int *out)
{
    if (n > 0)
        memcpy(out, v, (size_t)n * sizeof *out);
    qsort(out, (size_t)n, sizeof *out, cmp_int);
    int k = 0;
    for (int i = 0; i < n; i++)
        if (k == 0 || out[k - 1] != out[i])
            out[k++] = out[i];
    return k;
}

int wff_mesh_label_groups(wff_mesh *mesh, const char *settings, wff_error *err)
{
    label_name names[MAX_NAMED];
    int n_names = parse_names(settings, names, err);
    if (n_names < 0)
        return -1;
    int cap = mesh->n_edges + mesh->n_tris + mesh->n_quads;
    int *edge_labels = malloc(((size_t)mesh->n_edges + 1) * sizeof(int));
    int *regions = malloc(((size_t)mesh->n_tris + mesh->n_quads + 1) * sizeof(int));
    int *all_regions = malloc(((size_t)mesh->n_tris + mesh->n_quads + 1) * sizeof(int));
    wff_mesh_group *groups = malloc(((size_t)cap + 1) * sizeof *groups);
    if (!edge_labels || !regions || !all_regions || !groups) {
        free(edge_labels), free(regions), free(all_regions), free(groups);
        return wff_fail(err, "out of memory for the mesh's label groups");
    }
    int n1 = distinct(mesh->edge_label, mesh->n_edges, edge_labels);
    if (mesh->n_tris)
        memcpy(all_regions, mesh->tri_region, (size_t)mesh->n_tris * sizeof(int));
    if (mesh->n_quads)
        memcpy(all_regions + mesh->n_tris, mesh->quad_region, (size_t)mesh->n_quads * sizeof(int));
    int n2 = distinct(all_regions, mesh->n_tris + mesh->n_quads, regions);
    free(all_regions);
    int rc = 0;
    /* every name must be for a label the mesh has, and unique in its dimension */
    for (int i = 0; i < n_names && !rc; i++) {
        const int *have = names[i].dim == 1 ? edge_labels : regions;
        int n_have = names[i].dim == 1 ? n1 : n2, found = 0;
        for (int k = 0; k < n_have; k++)
            found |= have[k] == names[i].label;
        if (!found) {
            char list[256] = "";
            for (int k = 0; k < n_have; k++) {
                size_t used = strlen(list);
                snprintf(list + used, sizeof list - used, "%s%d", k ? " " : "", have[k]);
            }
            rc = wff_fail(err, "settings: %s label %ld (named '%s') is not in the mesh (its %s "
                          "labels: %s)", names[i].dim == 1 ? "boundary" : "region",
                          names[i].label, names[i].name, names[i].dim == 1 ? "boundary" : "region",
                          list[0] ? list : "none");
        }
        for (int j = 0; j < i && !rc; j++)
            if (names[j].dim == names[i].dim && strcmp(names[j].name, names[i].name) == 0)
                rc = wff_fail(err, "settings: the name '%s' is given to labels %ld and %ld",
                              names[i].name, names[j].label, names[i].label);
            else if (names[j].dim == names[i].dim && names[j].label == names[i].label)
                rc = wff_fail(err, "settings: label %ld is named twice ('%s', '%s')",
                              names[i].label, names[j].name, names[i].name);
    }
    int n_groups = 0;
    for (int dim = 1; dim <= 2 && !rc; dim++) {
        const int *have = dim == 1 ? edge_labels : regions;
        int n_have = dim == 1 ? n1 : n2;
        for (int k = 0; k < n_have; k++) {
            wff_mesh_group *g = &groups[n_groups++];
            g->dim = dim;
            g->tag = have[k];
            snprintf(g->name, sizeof g->name, "%s_%d", dim == 1 ? "label" : "region", have[k]);
            for (int i = 0; i < n_names; i++)
                if (names[i].dim == dim && names[i].label == have[k])
                    snprintf(g->name, sizeof g->name, "%s", names[i].name);
        }
    }
    /* a default name may not clash with a given one (names=1:label_2 with label 2 present) */
    for (int i = 0; i < n_groups && !rc; i++)
        for (int j = 0; j < i && !rc; j++)
            if (groups[i].dim == groups[j].dim && strcmp(groups[i].name, groups[j].name) == 0)
                rc = wff_fail(err, "settings: two groups would be named '%s' (labels %d and %d)",
                              groups[i].name, groups[j].tag, groups[i].tag);
    free(edge_labels);
    free(regions);
    if (rc) {
        free(groups);
        return -1;
    }
    free(mesh->groups);
    mesh->groups = groups;
    mesh->n_groups = n_groups;
    return 0;
}

const char *wff_mesh_label_group(const wff_mesh *mesh, long label, wff_error *err)
{
    for (int dim = 1; dim <= 2; dim++)
        for (int i = 0; i < mesh->n_groups; i++)
            if (mesh->groups[i].dim == dim && mesh->groups[i].tag == label)
                return mesh->groups[i].name;
    char list[400] = "";
    for (int dim = 1; dim <= 2; dim++) {
        size_t used = strlen(list);
        snprintf(list + used, sizeof list - used, "%s%s:", dim == 1 ? "" : "; ",
                 dim == 1 ? "boundary" : "region");
        int any = 0;
        for (int i = 0; i < mesh->n_groups; i++)
            if (mesh->groups[i].dim == dim) {
                used = strlen(list);
                snprintf(list + used, sizeof list - used, " %d (%s)", mesh->groups[i].tag,
                         mesh->groups[i].name);
                any = 1;
            }
        if (!any) {
            used = strlen(list);
            snprintf(list + used, sizeof list - used, " none");
        }
    }
    wff_fail(err, "no label %ld in the mesh (labels: %s)", label, list);
    return NULL;
}

int wff_mesh_from_arrays(const wff_mesh_arrays *in, const char *settings, wff_mesh *mesh,
                         wff_error *err)
{
    memset(mesh, 0, sizeof *mesh);
    if (in->n_nodes < 3 || in->n_tris < 1 || in->n_edges < 0)
        return wff_fail(err, "mesh of %d vertices and %d triangles: needs at least 3 and 1",
                        in->n_nodes, in->n_tris);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i < in->n_nodes; i++)
        for (int d = 0; d < 2; d++) {
            double x = in->xy[2 * i + d];
            if (!isfinite(x))
                return wff_fail(err, "vertex %d (1-based): coordinate %c = %g is not finite",
                                i + 1, "xy"[d], x);
            lo[d] = fmin(lo[d], x);
            hi[d] = fmax(hi[d], x);
        }
    double diag2 = (hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]);
    double a_tol = AREA_TOL * diag2;
    size_t nv = (size_t)in->n_nodes, nt = (size_t)in->n_tris, ne = (size_t)in->n_edges;
    mesh->xy = malloc(2 * nv * sizeof(double));
    mesh->tri = malloc(3 * nt * sizeof(int));
    mesh->tri_region = malloc(nt * sizeof(int));
    mesh->quad = malloc(sizeof(int));
    mesh->quad_region = malloc(sizeof(int));
    mesh->edge = malloc((2 * ne + 1) * sizeof(int));
    mesh->edge_label = malloc((ne + 1) * sizeof(int));
    unsigned char *used = calloc(nv, 1);
    int rc = 0;
    if (!mesh->xy || !mesh->tri || !mesh->tri_region || !mesh->quad || !mesh->quad_region ||
        !mesh->edge || !mesh->edge_label || !used)
        rc = wff_fail(err, "out of memory for a mesh of %d vertices", in->n_nodes);
    for (int e = 0; e < in->n_tris && !rc; e++) {
        int v[3];
        for (int a = 0; a < 3 && !rc; a++) {
            v[a] = in->tri[3 * e + a];
            if (v[a] < 0 || v[a] >= in->n_nodes)
                rc = wff_fail(err, "triangle %d (1-based): vertex index %d is outside 1..%d",
                              e + 1, v[a] + 1, in->n_nodes);
        }
        if (rc)
            break;
        const double *x0 = &in->xy[2 * v[0]], *x1 = &in->xy[2 * v[1]], *x2 = &in->xy[2 * v[2]];
        double area = 0.5 * ((x1[0] - x0[0]) * (x2[1] - x0[1]) - (x1[1] - x0[1]) * (x2[0] - x0[0]));
        if (!(fabs(area) > a_tol)) {
            rc = wff_fail(err, "triangle %d (1-based; vertices %d %d %d): zero-area element "
                          "(area %g m^2; tolerance %g)", e + 1, v[0] + 1, v[1] + 1, v[2] + 1,
                          fabs(area), a_tol);
            break;
        }
        if (area < 0) { /* clockwise: reverse */
            int t = v[1];
            v[1] = v[2];
            v[2] = t;
        }
        for (int a = 0; a < 3; a++) {
            mesh->tri[3 * e + a] = v[a];
            used[v[a]] = 1;
        }
        mesh->tri_region[e] = in->tri_region[e];
    }
    for (int i = 0; i < in->n_nodes && !rc; i++)
        if (!used[i])
            rc = wff_fail(err, "vertex %d (1-based, at %g, %g) is in no triangle (it would "
                          "carry no mass)", i + 1, in->xy[2 * i], in->xy[2 * i + 1]);
    for (int e = 0; e < in->n_edges && !rc; e++)
        for (int a = 0; a < 2 && !rc; a++) {
            int v = in->edge[2 * e + a];
            if (v < 0 || v >= in->n_nodes)
                rc = wff_fail(err, "boundary edge %d (1-based): vertex index %d is outside 1..%d",
                              e + 1, v + 1, in->n_nodes);
            mesh->edge[2 * e + a] = v;
            mesh->edge_label[e] = in->edge_label[e];
        }
    free(used);
    if (!rc) {
        memcpy(mesh->xy, in->xy, 2 * nv * sizeof(double));
        mesh->n_nodes = in->n_nodes;
        mesh->n_tris = in->n_tris;
        mesh->n_edges = in->n_edges;
        rc = wff_mesh_label_groups(mesh, settings, err);
    }
    if (rc) {
        wff_mesh_free(mesh);
        return -1;
    }
    return 0;
}

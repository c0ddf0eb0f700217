/* mesh_freefem.c: FreeFEM's own mesh file (what savemesh writes, ".msh" like
 * gmsh's but another format): recognise it and read it into a wff_mesh, with
 * its labels as groups (mesh_labels.c does the checks and the groups).
 *
 *   nv nt nbe
 *   x y label          nv vertex lines
 *   i j k region       nt triangle lines (1-based vertex numbers)
 *   i j label          nbe boundary-edge lines
 *
 * Knows nothing of gmsh, FreeFEM's C++ types, materials or the solver. */
#include "wovenff/mesh_labels.h"
#include "wovenff/text_io.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int wff_mesh_is_freefem_msh(const char *path)
{
    FILE *f = wff_open_regular(path, "mesh file", NULL); /* a pipe: not one (refused later) */
    if (!f)
        return 0;
    char line[256];
    int yes = 0;
    if (fgets(line, sizeof line, f)) {
        long a, b, c;
        char extra;
        yes = sscanf(line, "%ld %ld %ld %c", &a, &b, &c, &extra) == 3 && a > 0 && b > 0 &&
              c >= 0;
    }
    fclose(f);
    return yes;
}

typedef struct reader {
    FILE *f;
    const char *path;
    long line;
    wff_error *err;
} reader;

/* Read n numbers of one line (doubles; `whole` marks those that must be whole
 * numbers), naming the file and line on failure. */
static int read_line(reader *r, int n, double *out, const char *what)
{
    char buf[512];
    r->line++;
    if (!fgets(buf, sizeof buf, r->f))
        return wff_fail(r->err, "%s: line %ld: the file ends where %s was expected (FreeFEM "
                        "savemesh format)", r->path, r->line, what);
    char *p = buf;
    for (int k = 0; k < n; k++) {
        char *end;
        errno = 0;
        out[k] = strtod(p, &end);
        if (end == p || errno)
            return wff_fail(r->err, "%s: line %ld: expected %s (%d numbers), got '%.60s'",
                            r->path, r->line, what, n, buf);
        p = end;
    }
    while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n')
        p++;
    if (*p)
        return wff_fail(r->err, "%s: line %ld: %s: unexpected '%.40s' after %d numbers",
                        r->path, r->line, what, p, n);
    return 0;
}

static int whole(reader *r, double x, const char *what, int *out)
{
    if (!(x == (double)(long)x) || x < INT_MIN || x > INT_MAX)
        return wff_fail(r->err, "%s: line %ld: %s %g is not a whole number", r->path, r->line,
                        what, x);
    *out = (int)x;
    return 0;
}

int wff_mesh_load_freefem(const char *path, const char *settings, wff_mesh *mesh,
                          wff_error *err)
{
    memset(mesh, 0, sizeof *mesh);
    if (access(path, R_OK) != 0)
        return wff_fail(err, "%s: cannot read: %s", path, strerror(errno));
    reader r = {wff_open_regular(path, "mesh file", err), path, 0, err};
    if (!r.f)
        return -1;
    double head[3];
    int nv = 0, nt = 0, nbe = 0;
    int rc = read_line(&r, 3, head, "\"nv nt nbe\"");
    if (!rc)
        rc = whole(&r, head[0], "nv", &nv) || whole(&r, head[1], "nt", &nt) ||
             whole(&r, head[2], "nbe", &nbe) ? -1 : 0;
    if (!rc && (nv < 3 || nt < 1 || nbe < 0))
        rc = wff_fail(err, "%s: line 1: %d vertices, %d triangles, %d edges: not a mesh", path,
                      nv, nt, nbe);
    double *xy = NULL;
    int *tri = NULL, *region = NULL, *edge = NULL, *label = NULL;
    if (!rc) {
        xy = malloc(2 * (size_t)nv * sizeof *xy);
        tri = malloc(3 * (size_t)nt * sizeof *tri);
        region = malloc((size_t)nt * sizeof *region);
        edge = malloc((2 * (size_t)nbe + 1) * sizeof *edge);
        label = malloc(((size_t)nbe + 1) * sizeof *label);
        if (!xy || !tri || !region || !edge || !label)
            rc = wff_fail(err, "%s: out of memory for %d vertices", path, nv);
    }
    for (int i = 0; i < nv && !rc; i++) {
        double v[3];
        int lab;
        rc = read_line(&r, 3, v, "a vertex \"x y label\"") || whole(&r, v[2], "label", &lab);
        xy[2 * i] = v[0];
        xy[2 * i + 1] = v[1];
    }
    for (int e = 0; e < nt && !rc; e++) {
        double v[4];
        rc = read_line(&r, 4, v, "a triangle \"i j k region\"");
        for (int a = 0; a < 3 && !rc; a++) {
            rc = whole(&r, v[a], "vertex number", &tri[3 * e + a]);
            tri[3 * e + a]--;
        }
        if (!rc)
            rc = whole(&r, v[3], "region", &region[e]);
    }
    for (int e = 0; e < nbe && !rc; e++) {
        double v[3];
        rc = read_line(&r, 3, v, "a boundary edge \"i j label\"");
        for (int a = 0; a < 2 && !rc; a++) {
            rc = whole(&r, v[a], "vertex number", &edge[2 * e + a]);
            edge[2 * e + a]--;
        }
        if (!rc)
            rc = whole(&r, v[2], "label", &label[e]);
    }
    fclose(r.f);
    if (!rc) {
        wff_mesh_arrays in = {nv, xy, nt, tri, region, nbe, edge, label};
        wff_error why;
        if (wff_mesh_from_arrays(&in, settings, mesh, &why))
            rc = wff_fail(err, "%s (FreeFEM mesh): %s", path, why.message);
    }
    free(xy);
    free(tri);
    free(region);
    free(edge);
    free(label);
    return rc ? -1 : 0;
}

/* backing_vtk.c: the backing block as a VTK unstructured grid (ParaView's
 * .vtu, ASCII): its hexahedra at their current positions, the nodes'
 * displacement and velocity, the elements' equivalent plastic strain (clay)
 * or 0 (gelatin). Written whole through wff_write_whole (never half a file). */
#include "backing.h"
#include "wovenff/backing.h"
#include "wovenff/files.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct text { char *data; size_t used, size; int failed; } text;

static void put(text *t, const char *format, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, format);
        const int n = vsnprintf(t->data + t->used, t->size - t->used, format, ap);
        va_end(ap);
        if (n < 0) {
            t->failed = 1;
            return;
        }
        if (t->used + (size_t)n < t->size) {
            t->used += (size_t)n;
            return;
        }
        const size_t grown = 2 * t->size + (size_t)n + 1;
        char *p = realloc(t->data, grown);
        if (!p) {
            t->failed = 1;
            return;
        }
        t->data = p, t->size = grown;
    }
}

int wff_model_backing_vtk(const wff_model *m, const char *path, wff_error *err)
{
    const struct wff_backing *B = m->backing;
    if (!B || B->law == WFF_BLOCK_NONE || !B->built)
        return wff_fail(err, "%s: the model has no backing block (yet: it is made at the first "
                        "step)", path);
    const wff_block *b = &B->block;
    text t = {malloc(1 << 16), 0, 1 << 16, 0};
    if (!t.data)
        return wff_fail(err, "%s: out of memory", path);
    put(&t, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
            "<UnstructuredGrid>\n<Piece NumberOfPoints=\"%d\" NumberOfCells=\"%d\">\n"
            "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n",
        b->n_nodes, b->n_elements);
    for (int k = 0; k < 3 * b->n_nodes; k++)
        put(&t, "%.9g%c", b->X[k] + b->u[k], k % 3 == 2 ? '\n' : ' ');
    put(&t, "</DataArray>\n</Points>\n<Cells>\n"
            "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n");
    for (int k = 0; k < 8 * b->n_elements; k++)
        put(&t, "%d%c", b->hex[k], k % 8 == 7 ? '\n' : ' ');
    put(&t, "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n");
    for (int e = 0; e < b->n_elements; e++)
        put(&t, "%d\n", 8 * (e + 1));
    put(&t, "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for (int e = 0; e < b->n_elements; e++)
        put(&t, "12\n"); /* (VTK_HEXAHEDRON) */
    put(&t, "</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\">\n");
    const char *const names[2] = {"displacement", "velocity"};
    for (int f = 0; f < 2; f++) {
        const double *field = f ? b->v : b->u;
        put(&t, "<DataArray type=\"Float64\" Name=\"%s\" NumberOfComponents=\"3\" "
                "format=\"ascii\">\n", names[f]);
        for (int k = 0; k < 3 * b->n_nodes; k++)
            put(&t, "%.9g%c", field[k], k % 3 == 2 ? '\n' : ' ');
        put(&t, "</DataArray>\n");
    }
    put(&t, "</PointData>\n<CellData Scalars=\"eq_plastic_strain\">\n"
            "<DataArray type=\"Float64\" Name=\"eq_plastic_strain\" format=\"ascii\">\n");
    for (int e = 0; e < b->n_elements; e++) { /* (fully integrated: its points' mean) */
        double sum = 0;
        for (int g = 0; g < b->points && b->clay_state; g++)
            sum += b->clay_state[b->points * e + g].eq_plastic;
        put(&t, "%.9g\n", sum / b->points);
    }
    put(&t, "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    int rc = t.failed ? wff_fail(err, "%s: out of memory", path)
                      : wff_write_whole(path, t.data, t.used, err);
    free(t.data);
    return rc;
}

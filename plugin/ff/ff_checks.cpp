// wovenff FreeFEM binding: checks a scene makes before its time loop (issue 11:
// a run that would take no step is refused before it starts), and before it
// takes its results folder (issue 26: slips of units).
//
//   real dt = wovenffStepEstimate(md);   // s: the step the next advance takes
//   string slip = wovenffMaterialCheck(file, changes); // "" or the unit slip of the
//                                        // material (with "key=value,..." changes):
//                                        // key, line, file, likely unit (material_scales.c)
//   int n = wovenffMeshExtent(file, settings, box); // box = [xmin xmax ymin ymax
//                                        // shortest-edge mean-edge] (m); n nodes
// and the finiteness check every model function taking reals makes
// (wff_ff_require_finite: a NaN or infinite argument is an error naming it).
//
// Knows the model handle table (ff_wovenff.hpp) and the solver's public API only.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cmath>
#include <cstdio>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/material.h"
#include "wovenff/mesh.h"
#include "wovenff/mesh_labels.h"
#include "wovenff/options.h"
#include "wovenff/text_io.h"
}

using namespace Fem2D;

namespace {

double ffStepEstimate(const long &id)
{
    const wff_model *m = wff_ff_model(id, "wovenffStepEstimate");
    double dt = wff_model_step_estimate(m);
    if (!(dt > 0) || !std::isfinite(dt))
        wff_ff_model_fail("wovenffStepEstimate", "the stable step " + std::to_string(dt)
                          + " s is not positive: degenerate elements or NaN", id);
    return dt;
}

// "" when the material file (with the changes "key=value,...", e.g. a scene's
// -set) has the scales of a woven fabric, else the slip (wff_material_scales);
// a file that is not a material fails as wovenffMaterial does.
string *ffMaterialCheck(Stack stack, string *const &file, string *const &changes)
{
    const char *fn = "wovenffMaterialCheck";
    wff_error err;
    char *text;
    if (wff_read_text_file(file->c_str(), "material file", WFF_MATERIAL_FILE_MAX, &text, &err))
        wff_ff_fail(fn, err);
    std::string source = *file;
    if (!changes->empty()) {
        char *edited;
        int rc = wff_material_text_set(text, file->c_str(), changes->c_str(), "change", &edited,
                                       &err);
        free(text);
        if (rc)
            wff_ff_fail(fn, err);
        text = edited;
        source += " with " + *changes;
    }
    int rc = wff_material_scales_text(text, source.c_str(), &err);
    free(text);
    if (rc < 0)
        wff_ff_fail(fn, err);
    return Add2StackOfPtr2Free(stack, new string(rc ? err.message : ""));
}

// A mesh file's extent (wff_mesh_extent) as the model would read it with these
// settings (gmsh's .geo/.msh; a FreeFEM .msh is read without them, its labels
// having no say in its size): box = [X min, X max, Y min,
// Y max, shortest edge, mean edge], m; returns the node count. Fails as
// wovenffModel would on a file it cannot read.
long ffMeshExtent(string *const &file, string *const &settings, KN<double> *const &box)
{
    const char *fn = "wovenffMeshExtent";
    wff_mesh mesh;
    wff_error err;
    size_t len = file->size();
    int rc;
    if (len > 4 && file->compare(len - 4, 4, ".msh") == 0 &&
        wff_mesh_is_freefem_msh(file->c_str())) {
        rc = wff_mesh_load_freefem(file->c_str(), "", &mesh, &err); /* (labels: no size) */
    } else {
        wff_mesh_options opt;
        rc = wff_mesh_options_parse(settings->c_str(), &opt, &err);
        if (!rc)
            rc = wff_mesh_load(file->c_str(), &opt, &mesh, &err);
    }
    if (rc)
        wff_ff_fail(fn, err);
    double b[4], shortest, mean;
    wff_mesh_extent(&mesh, b, &shortest, &mean);
    long n = mesh.n_nodes;
    wff_mesh_free(&mesh);
    box->resize(6);
    for (int i = 0; i < 4; i++)
        (*box)[i] = b[i];
    (*box)[4] = shortest;
    (*box)[5] = mean;
    return n;
}

} // namespace

void wff_ff_require_finite(const char *fn, const char *name, double x, long id)
{
    if (std::isfinite(x))
        return;
    char msg[160];
    snprintf(msg, sizeof msg, "%s = %g is not a finite number", name, x);
    if (id >= 0)
        wff_ff_model_fail(fn, msg, id);
    wff_ff_fail(fn, msg);
}

void wff_ff_register_checks()
{
    Global.Add("wovenffStepEstimate", "(", new OneOperator1_<double, long>(ffStepEstimate));
    Global.Add("wovenffMaterialCheck", "(",
               new OneOperator2s_<string *, string *, string *>(ffMaterialCheck));
    Global.Add("wovenffMeshExtent", "(",
               new OneOperator3_<long, string *, string *, KN<double> *>(ffMeshExtent));
}

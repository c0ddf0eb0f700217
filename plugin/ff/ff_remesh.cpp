// wovenff FreeFEM binding: a model carried onto a new mesh of the same
// specimen (wff_model_remesh, include/wovenff/solver.h).
//
//   mesh Th = wovenffMesh(md);                         // (or the mesh it was built from)
//   Th = adaptmesh(Th, uz, hmin = 1e-3, hmax = 8e-3, nbvx = 20000);   // labels kept
//   real dE = wovenffRemesh(md, Th);                   // J, whole specimen
//   real[int] e(3); wovenffRemesh(md, Th, e);          // e = [before J, after J, retraction m]
//
// The new mesh is read as wovenffModel(mesh Th, ...) reads one (its vertices,
// triangles with their region labels, boundary edges with their labels; the
// same checks, by wff_mesh_from_arrays); the model's groups are found in it by
// name or by label (tag), and its boundary conditions set again. The return
// value is the change of stored + kinetic energy, after - before, which the
// energy balance counts as a transfer term (wovenffGet(md, "transfer_energy")
// sums them), so "energy_error" measures the integration only. A projectile
// whose nose had reached between the old nodes is moved back until no new
// node is inside it (e[2]). On failure the
// model is unchanged. Only copying and argument checks here.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <string>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/solver.h"
}

using namespace Fem2D;

namespace {

double remesh(long id, const Mesh *th, double *before, double *after, double *retraction)
{
    const char *fn = "wovenffRemesh";
    wff_model *m = wff_ff_model(id, fn);
    wff_mesh mesh;
    wff_ff_mesh_from_freefem(fn, th, "", &mesh); // as wovenffModel(mesh Th, ...) reads one
    wff_error err;
    wff_remesh_report rep;
    if (wff_model_remesh(m, &mesh, &rep, &err))
        wff_ff_model_fail(fn, err.message, id);
    *before = rep.before;
    *after = rep.after;
    *retraction = rep.retraction;
    return rep.after - rep.before;
}

double ffRemesh(const long &id, const Mesh *const &th)
{
    double before, after, retraction;
    return remesh(id, th, &before, &after, &retraction);
}

double ffRemeshEnergies(const long &id, const Mesh *const &th, KN<double> *const &out)
{
    if (out->N() != 3)
        wff_ff_model_fail("wovenffRemesh", "the report array must have 3 entries "
                          "(before, after: stored + kinetic, J; the projectile's retraction, m)",
                          id);
    double before, after, retraction;
    double change = remesh(id, th, &before, &after, &retraction);
    (*out)[0] = before;
    (*out)[1] = after;
    (*out)[2] = retraction;
    return change;
}

} // namespace

void wff_ff_register_remesh()
{
    Global.Add("wovenffRemesh", "(", new OneOperator2_<double, long, const Mesh *>(ffRemesh));
    Global.Add("wovenffRemesh", "(",
               new OneOperator3_<double, long, const Mesh *, KN<double> *>(ffRemeshEnergies));
}

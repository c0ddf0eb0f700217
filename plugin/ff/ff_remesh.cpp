// wovenff FreeFEM binding: a model carried onto a new mesh of the same
// specimen (wff_model_remesh, include/wovenff/solver.h).
//
//   mesh Th = wovenffMesh(md);                         // (or the mesh it was built from)
//   Th = adaptmesh(Th, uz, hmin = 1e-3, hmax = 8e-3, nbvx = 20000);   // labels kept
//   real dE = wovenffRemesh(md, Th);                   // J, whole specimen
//   real[int] e(2); wovenffRemesh(md, Th, e);          // e = [before, after], J
//
// The new mesh is read as wovenffModel(mesh Th, ...) reads one (its vertices,
// triangles with their region labels, boundary edges with their labels; the
// same checks, by wff_mesh_from_arrays); the model's groups are found in it by
// name or by label (tag), and its boundary conditions set again. The return
// value is the change of stored + kinetic energy, after - before, which the
// energy balance counts as a transfer term (wovenffGet(md, "transfer_energy")
// sums them), so "energy_error" measures the integration only. On failure the
// model is unchanged. Only copying and argument checks here.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <string>
#include <vector>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/mesh_labels.h"
#include "wovenff/solver.h"
}

using namespace Fem2D;

namespace {

// Th's arrays as wovenffModel(mesh Th, ...) takes them (ff_femesh.cpp).
void mesh_of(const Mesh *th, wff_mesh *mesh, const char *fn, long id)
{
    if (!th)
        wff_ff_model_fail(fn, "no mesh given", id);
    const Mesh &Th = *th;
    int nv = Th.nv, nt = Th.nt, nbe = Th.neb;
    std::vector<double> xy(2 * (size_t)nv);
    std::vector<int> tri(3 * (size_t)nt), region((size_t)nt), edge(2 * (size_t)nbe),
        label((size_t)nbe);
    for (int i = 0; i < nv; i++) {
        xy[2 * i] = Th(i).x;
        xy[2 * i + 1] = Th(i).y;
    }
    for (int k = 0; k < nt; k++) {
        for (int a = 0; a < 3; a++)
            tri[3 * k + a] = Th(Th[k][a]);
        region[k] = Th[k].lab;
    }
    for (int k = 0; k < nbe; k++) {
        const Mesh::BorderElement &be = Th.be(k);
        edge[2 * k] = Th(be[0]);
        edge[2 * k + 1] = Th(be[1]);
        label[k] = be.lab;
    }
    wff_mesh_arrays in = {nv, xy.data(), nt, tri.data(), region.data(), nbe, edge.data(),
                          label.data()};
    wff_error err;
    if (wff_mesh_from_arrays(&in, "", mesh, &err))
        wff_ff_model_fail(fn, std::string("new mesh: ") + err.message, id);
}

double remesh(long id, const Mesh *th, double *before, double *after)
{
    const char *fn = "wovenffRemesh";
    wff_model *m = wff_ff_model(id, fn);
    wff_mesh mesh;
    mesh_of(th, &mesh, fn, id);
    wff_error err;
    if (wff_model_remesh(m, &mesh, before, after, &err))
        wff_ff_model_fail(fn, err.message, id);
    return *after - *before;
}

double ffRemesh(const long &id, const Mesh *const &th)
{
    double before, after;
    return remesh(id, th, &before, &after);
}

double ffRemeshEnergies(const long &id, const Mesh *const &th, KN<double> *const &out)
{
    if (out->N() != 2)
        wff_ff_model_fail("wovenffRemesh", "the energies array must have 2 entries "
                          "(before, after: stored + kinetic, J)", id);
    double before, after;
    double change = remesh(id, th, &before, &after);
    (*out)[0] = before;
    (*out)[1] = after;
    return change;
}

} // namespace

void wff_ff_register_remesh()
{
    Global.Add("wovenffRemesh", "(", new OneOperator2_<double, long, const Mesh *>(ffRemesh));
    Global.Add("wovenffRemesh", "(",
               new OneOperator3_<double, long, const Mesh *, KN<double> *>(ffRemeshEnergies));
}

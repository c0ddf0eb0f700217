// wovenff FreeFEM binding: models from FreeFEM meshes, and FreeFEM label
// numbers in place of group names (include/wovenff/mesh_labels.h).
//
//   mesh Th = square(20, 20, [0.05 * x, 0.05 * y]);
//   int md = wovenffModel(Th, materialFile);              // labels as groups
//   int md = wovenffModel(Th, materialFile, "names=1:clamp,2:sym_x regions=0:ply");
//   wovenffFix(md, 2, 0);                  // label 2 (a boundary label, else a region)
//   wovenffPrescribe(md, 3, 2, 10.0);      // label, component, velocity m/s
//   wovenffClampFriction(md, 4, 100.0, 0.3);
//   wovenffReaction(md, 4, 2, r);          // r[0] = sum of reactions, N
//
// The model has Th's vertices in Th's numbering, its triangles (region =
// triangle label) and its boundary edges (label = edge label); wovenffMesh(md)
// gives the same mesh back. Boundary label N is the group "label_N", region
// label R the group "region_R", unless the settings name them. Models read
// from gmsh files take their physical-group tags as labels. Only copying and
// argument checks here: the checks on the mesh and the label rules are the
// C core's.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cstdlib>
#include <string>
#include <vector>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/mesh_labels.h"
#include "wovenff/solver.h"
#include "wovenff/renumber.h"
}

using namespace Fem2D;

namespace {

// A model taking over mesh (emptied); its handle.
long model_of_mesh(wff_mesh *mesh, const string *mat)
{
    const char *fn = "wovenffModel";
    wff_error err;
    wff_model *m = wff_model_new();
    if (!m) {
        wff_mesh_free(mesh);
        wff_ff_fail(fn, "out of memory");
    }
    // renumbered for speed; every call keeps the FreeFEM mesh's numbering
    if (wff_model_create_ordered(m, mesh, mat->c_str(), 1, &err)) {
        free(m); /* (a failed creation leaves nothing to free inside) */
        wff_ff_fail(fn, err);
    }
    return wff_ff_model_add(m);
}

long model_from_mesh(const Mesh *th, const string *mat, const char *settings)
{
    wff_mesh mesh;
    wff_ff_mesh_from_freefem("wovenffModel", th, settings, &mesh);
    return model_of_mesh(&mesh, mat);
}

} // namespace

void wff_ff_mesh_from_freefem(const char *fn, const Mesh *th, const char *settings,
                              wff_mesh *mesh)
{
    if (!th)
        wff_ff_fail(fn, "no mesh given");
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
    if (wff_mesh_from_arrays(&in, settings, mesh, &err))
        wff_ff_fail(fn, std::string("FreeFEM mesh: ") + err.message);
}

long wff_ff_model_from_freefem_msh(const char *path, const string *mat, const string *settings)
{
    wff_mesh mesh;
    wff_error err;
    if (wff_mesh_load_freefem(path, settings->c_str(), &mesh, &err))
        wff_ff_fail("wovenffModel", err);
    return model_of_mesh(&mesh, mat);
}

namespace {

long ffModelMesh(const Mesh *const &th, string *const &mat)
{
    return model_from_mesh(th, mat, "");
}

long ffModelMeshSettings(const Mesh *const &th, string *const &mat, string *const &settings)
{
    return model_from_mesh(th, mat, settings->c_str());
}

// The group name label `label` of model id resolves to, or fail naming fn.
const char *group_of(long id, long label, const char *fn, wff_model **m)
{
    *m = wff_ff_model(id, fn);
    wff_error err;
    const char *name = wff_mesh_label_group(wff_model_mesh(*m), label, &err);
    if (!name)
        wff_ff_model_fail(fn, err.message, id);
    return name;
}

long ffFixLabel(const long &id, const long &label, const long &component)
{
    wff_model *m;
    const char *group = group_of(id, label, "wovenffFix", &m);
    wff_error err;
    int n = wff_model_fix_group(m, group, (int)component, &err);
    if (n < 0)
        wff_ff_model_fail("wovenffFix", err.message, id);
    return n;
}

long ffPrescribeLabel(const long &id, const long &label, const long &component,
                      const double &velocity)
{
    wff_model *m;
    const char *group = group_of(id, label, "wovenffPrescribe", &m);
    wff_error err;
    int n = wff_model_prescribe_group(m, group, (int)component, velocity, &err);
    if (n < 0)
        wff_ff_model_fail("wovenffPrescribe", err.message, id);
    return n;
}

long ffClampFrictionLabel(const long &id, const long &label, const double &force,
                          const double &mu)
{
    wff_model *m;
    const char *group = group_of(id, label, "wovenffClampFriction", &m);
    wff_error err;
    int n = wff_model_clamp_friction(m, group, force, mu, &err);
    if (n < 0)
        wff_ff_model_fail("wovenffClampFriction", err.message, id);
    return n;
}

long ffReactionLabel(const long &id, const long &label, const long &component,
                     KN<double> *const &out)
{
    wff_model *m;
    const char *group = group_of(id, label, "wovenffReaction", &m);
    double sum;
    wff_error err;
    int n = wff_model_group_reaction(m, group, (int)component, &sum, &err);
    if (n < 0)
        wff_ff_model_fail("wovenffReaction", err.message, id);
    out->resize(1);
    (*out)[0] = sum;
    return n;
}

} // namespace

void wff_ff_register_femesh()
{
    Global.Add("wovenffModel", "(",
               new OneOperator2_<long, const Mesh *, string *>(ffModelMesh));
    Global.Add("wovenffModel", "(",
               new OneOperator3_<long, const Mesh *, string *, string *>(ffModelMeshSettings));
    Global.Add("wovenffFix", "(", new OneOperator3_<long, long, long, long>(ffFixLabel));
    Global.Add("wovenffPrescribe", "(",
               new OneOperator4_<long, long, long, long, double>(ffPrescribeLabel));
    Global.Add("wovenffClampFriction", "(",
               new OneOperator4_<long, long, long, double, double>(ffClampFrictionLabel));
    Global.Add("wovenffReaction", "(",
               new OneOperator4_<long, long, long, long, KN<double> *>(ffReactionLabel));
}

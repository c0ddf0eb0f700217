// wovenff FreeFEM binding: the backing block behind a pack (include/wovenff/backing.h).
//
//   wovenffSet(md, "backing_depth", 0.14);  // ... backing_element, backing_growth,
//   wovenffSet(md, "backing", 1);           // backing_mu, backing_hourglass, backing_gap;
//                                           // 1 clay, 2 gelatin (before the first step)
//   real bfs = wovenffGet(md, "backface_signature");   // crater_diameter, crater_volume, ...
//   int n = wovenffBackingProfile(md, x, depth);       // the top face along x through the
//                                                      // impact point: x (m), indentation (m)
//   wovenffBackingVTK(md, dir + "/backing.vtu");       // the block for ParaView
// Failures name the function. Knows the public API only.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <vector>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/backing.h"
}

namespace {

long ffBackingProfile(const long &id, KN<double> *const &x, KN<double> *const &depth)
{
    const wff_model *m = wff_ff_model(id, "wovenffBackingProfile");
    std::vector<double> xs(4096), ds(4096);
    const int n = wff_model_backing_profile(m, 4096, xs.data(), ds.data());
    x->resize(n);
    depth->resize(n);
    for (int i = 0; i < n; i++) {
        (*x)[i] = xs[i];
        (*depth)[i] = ds[i];
    }
    return n;
}

long ffBackingVtk(const long &id, string *const &path)
{
    const char *fn = "wovenffBackingVTK";
    const wff_model *m = wff_ff_model(id, fn);
    wff_error err;
    if (wff_model_backing_vtk(m, path->c_str(), &err))
        wff_ff_fail(fn, err);
    return 0;
}

} // namespace

void wff_ff_register_backing()
{
    Global.Add("wovenffBackingProfile", "(",
               new OneOperator3_<long, long, KN<double> *, KN<double> *>(ffBackingProfile));
    Global.Add("wovenffBackingVTK", "(", new OneOperator2_<long, long, string *>(ffBackingVtk));
}

// wovenff FreeFEM binding: the projectile's shape and impact point
// (include/wovenff/solver.h, docs/model.md §16, docs/freefem_api.md).
//   wovenffProjectile(md, radius, mass, velocity, mu)  // (ff_solver.cpp) whole mass, kg
//   wovenffProjectileShape(md, "flat", edgeRadius)     // nose: hemisphere|flat|sphere; r_e, m
//   wovenffProjectileShape(md, "sphere")               // (edge radius 0)
//   wovenffImpactPoint(md, x, y)                       // projectile axis at (x, y), m
// Each may come before or after wovenffProjectile and wovenffSet(md, "symmetry", s),
// and before the first step. Knows the binding's handle table and the C API
// only; nothing of contact internals.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include "ff_wovenff.hpp"

namespace {

long ffProjectileShape2(const long &id, string *const &nose, const double &edge_radius)
{
    const char *fn = "wovenffProjectileShape";
    wff_model *m = wff_ff_model(id, fn);
    wff_error err;
    int kind = wff_nose_from_name(nose->c_str(), &err);
    if (kind < 0 || wff_model_set_projectile_shape(m, kind, edge_radius, &err))
        wff_ff_model_fail(fn, std::string(err.message), id);
    return kind;
}

long ffProjectileShape1(const long &id, string *const &nose)
{
    return ffProjectileShape2(id, nose, 0.0);
}

long ffImpactPoint(const long &id, const double &x, const double &y)
{
    const char *fn = "wovenffImpactPoint";
    wff_model *m = wff_ff_model(id, fn);
    wff_error err;
    if (wff_model_set_impact_point(m, x, y, &err))
        wff_ff_model_fail(fn, std::string(err.message), id);
    return 0;
}

} // namespace

void wff_ff_register_projectile()
{
    Global.Add("wovenffProjectileShape", "(",
               new OneOperator3_<long, long, string *, double>(ffProjectileShape2));
    Global.Add("wovenffProjectileShape", "(",
               new OneOperator2_<long, long, string *>(ffProjectileShape1));
    Global.Add("wovenffImpactPoint", "(",
               new OneOperator3_<long, long, double, double>(ffImpactPoint));
}

// wovenff FreeFEM binding: the projectile's shape and impact point
// (include/wovenff/solver.h, docs/model.md §16, docs/freefem_api.md).
//   wovenffProjectile(md, radius, mass, velocity, mu)  // (ff_solver.cpp) whole mass, kg
//   wovenffProjectileShape(md, "flat", edgeRadius)     // nose: hemisphere|flat|sphere; r_e, m
//   wovenffProjectileShape(md, "sphere")               // (edge radius 0)
//   wovenffImpactPoint(md, x, y)                       // projectile axis at (x, y), m
//   int verdict = wovenffPerforation(md);              // 1 perforated, 0 stopped, -1 undecided
//   int verdict = wovenffPerforation(md, U);           // the same at a script's own loop's U
//                                                      // (include/wovenff/perforation.h)
// Each may come before or after wovenffProjectile and wovenffSet(md, "symmetry", s),
// and before the first step. Knows the binding's handle table and the C API
// only; nothing of contact internals.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/perforation.h"
}

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

// The shot's verdict now: 1 perforated, 0 stopped, -1 undecided (the rule:
// include/wovenff/perforation.h); a model without a projectile is an error.
long ffPerforation(const long &id)
{
    const char *fn = "wovenffPerforation";
    const wff_model *m = wff_ff_model(id, fn);
    wff_perforation verdict;
    wff_error err;
    if (wff_model_perforation(m, &verdict, &err))
        wff_ff_model_fail(fn, std::string(err.message), id);
    return verdict.verdict;
}

// The same at a script's own loop's displacements U (5 per vertex, as
// wovenffForces takes them), the projectile as the last wovenffContact left it.
long ffPerforationAt(const long &id, KN<double> *const &U)
{
    const char *fn = "wovenffPerforation";
    wff_model *m = wff_ff_model(id, fn);
    if (!U || U->N() != wff_model_dof_count(m))
        wff_ff_model_fail(fn, "U must have " + std::to_string(wff_model_dof_count(m)) +
                          " entries (5 per vertex: ux uy uz dA1 dA2), got " +
                          std::to_string(U ? (long)U->N() : 0L), id);
    wff_perforation verdict;
    wff_error err;
    if (wff_model_perforation_at(m, &(*U)[0], &verdict, &err))
        wff_ff_model_fail(fn, std::string(err.message), id);
    return verdict.verdict;
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
    Global.Add("wovenffPerforation", "(", new OneOperator1_<long, long>(ffPerforation));
    Global.Add("wovenffPerforation", "(",
               new OneOperator2_<long, long, KN<double> *>(ffPerforationAt));
}

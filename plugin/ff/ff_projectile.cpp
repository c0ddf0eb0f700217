// wovenff FreeFEM binding: the projectile's shape and impact point
// (include/wovenff/solver.h, docs/model.md §16, docs/freefem_api.md).
//   wovenffProjectile(md, radius, mass, velocity, mu)  // (ff_solver.cpp) whole mass, kg
//   wovenffProjectileShape(md, "flat", edgeRadius)     // nose: hemisphere|flat|sphere; r_e, m
//   wovenffProjectileShape(md, "sphere")               // (edge radius 0)
//   wovenffProjectileShape(md, "chisel", w, beta)      // an FSP's chisel: flat width w (m),
//                                                      // bevel beta (deg from the end face)
//   real lead = wovenffObliquity(md, theta)            // path tilted theta deg toward +x; returns
//                                                      // how far (m, along z) the nose reaches
//                                                      // ahead of its tip point (0 at theta 0)
//   wovenffProjectileMomentum(md, p)                   // p(3): the whole projectile's, kg m/s
//   string nose = wovenffThreat("fsp17", t)            // a standard threat (include/wovenff/
//                                                      // threat.h): t(6) = mass kg, diameter m,
//                                                      // length m (0: none given), edge radius m,
//                                                      // chisel flat width m, bevel deg
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
#include "wovenff/threat.h"
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

long ffProjectileChisel(const long &id, string *const &nose, const double &width,
                        const double &bevel)
{
    const char *fn = "wovenffProjectileShape";
    wff_model *m = wff_ff_model(id, fn);
    wff_error err;
    if (*nose != "chisel")
        wff_ff_model_fail(fn, "a flat width and a bevel angle are the chisel's: nose '" + *nose +
                          "' takes an edge radius at most", id);
    if (wff_model_set_projectile_chisel(m, width, bevel, &err))
        wff_ff_model_fail(fn, std::string(err.message), id);
    return WFF_NOSE_CHISEL;
}

double ffObliquity(const long &id, const double &degrees)
{
    const char *fn = "wovenffObliquity";
    wff_model *m = wff_ff_model(id, fn);
    wff_error err;
    if (wff_model_set_obliquity(m, degrees, &err))
        wff_ff_model_fail(fn, std::string(err.message), id);
    return wff_model_projectile_lead(m);
}

long ffProjectileMomentum(const long &id, KN<double> *const &p)
{
    const char *fn = "wovenffProjectileMomentum";
    wff_model *m = wff_ff_model(id, fn);
    if (!p || p->N() != 3)
        wff_ff_model_fail(fn, "the momentum array must have 3 entries", id);
    double q[3];
    wff_model_projectile_momentum(m, q);
    for (int i = 0; i < 3; i++)
        (*p)[i] = q[i];
    return 0;
}

string *ffThreat(Stack stack, string *const &name, KN<double> *const &t)
{
    wff_error err;
    const wff_threat *threat = wff_threat_find(name->c_str(), &err);
    if (!threat)
        ExecError(("wovenffThreat: " + std::string(err.message)).c_str());
    if (!t || t->N() != 6)
        ExecError("wovenffThreat: the values array must have 6 entries");
    const double v[6] = {threat->mass, threat->diameter, threat->length, threat->edge_radius,
                         threat->chisel_flat, threat->chisel_bevel};
    for (int i = 0; i < 6; i++)
        (*t)[i] = v[i];
    return Add2StackOfPtr2Free(stack, new string(wff_nose_name(threat->nose)));
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
    Global.Add("wovenffProjectileShape", "(",
               new OneOperator4_<long, long, string *, double, double>(ffProjectileChisel));
    Global.Add("wovenffObliquity", "(", new OneOperator2_<double, long, double>(ffObliquity));
    Global.Add("wovenffProjectileMomentum", "(",
               new OneOperator2_<long, long, KN<double> *>(ffProjectileMomentum));
    Global.Add("wovenffThreat", "(", new OneOperator2s_<string *, string *, KN<double> *>(ffThreat));
    Global.Add("wovenffImpactPoint", "(",
               new OneOperator3_<long, long, double, double>(ffImpactPoint));
    Global.Add("wovenffPerforation", "(", new OneOperator1_<long, long>(ffPerforation));
    Global.Add("wovenffPerforation", "(",
               new OneOperator2_<long, long, KN<double> *>(ffPerforationAt));
}

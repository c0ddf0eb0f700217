// wovenff FreeFEM binding: multi-ply packs (include/wovenff/pack.h).
//
//   int md = wovenffModel(Th, materialFile);
//   wovenffPlies(md, 8, 0.3e-3);             // 8 plies, mid-planes 0.3 mm apart (right
//                                            // after wovenffModel: before the preload,
//                                            // BCs, projectile, zones, checkpoint loads)
//   wovenffPlyMaterial(md, 3, "other.txt");  // ply 3's material (a zone of its elements)
//   wovenffPlyOrientation(md, 1, 45.0);      // ply 1's warp at 45 degrees to x
//   wovenffSet(md, "ply_mu", 0.2);           // ply-on-ply friction
//   wovenffSet(md, "ply_thickness", 0.3e-3); // contact thickness, m
//   real a = wovenffPlyGet(md, p, "apex");   // apex kinetic stored dissipated absorbed
//                                            // failed eroded (J whole specimen, m)
//   wovenffGet(md, "back_face"), "plies", "ply_contact_dissipated", "ply_penetration",
//   "ply_contacts", "ply_contact_seconds" (ff_solver.cpp's state list); wovenffField(md, "ply", v).
// Failures name the function, the ply and the key. Knows the public API only.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cmath>
#include <string>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/pack.h"
}

namespace {

long ffPlies(const long &id, const long &n, const double &gap)
{
    const char *fn = "wovenffPlies";
    wff_model *m = wff_ff_model(id, fn);
    wff_ff_require_finite(fn, "gap", gap, id);
    if (n < 1 || n > WFF_PLIES_MAX)
        wff_ff_model_fail(fn, "plies = " + std::to_string(n) + ": must be 1 to " +
                          std::to_string(WFF_PLIES_MAX), id);
    wff_error err;
    if (wff_model_set_plies(m, (int)n, gap, &err))
        wff_ff_model_fail(fn, err.message, id);
    return n;
}

long ffPlyMaterial(const long &id, const long &p, string *const &file)
{
    const char *fn = "wovenffPlyMaterial";
    wff_model *m = wff_ff_model(id, fn);
    if (p < 0 || p >= wff_model_ply_count(m))
        wff_ff_model_fail(fn, "ply " + std::to_string(p) + ": the pack has plies 0 to " +
                          std::to_string(wff_model_ply_count(m) - 1), id);
    wff_error err;
    int count = wff_model_ply_material(m, (int)p, file->c_str(), &err);
    if (count < 0)
        wff_ff_model_fail(fn, err.message, id);
    return count;
}

long ffPlyOrientation(const long &id, const long &p, const double &deg)
{
    const char *fn = "wovenffPlyOrientation";
    wff_model *m = wff_ff_model(id, fn);
    wff_ff_require_finite(fn, "angle", deg, id);
    if (p < 0 || p >= wff_model_ply_count(m))
        wff_ff_model_fail(fn, "ply " + std::to_string(p) + ": the pack has plies 0 to " +
                          std::to_string(wff_model_ply_count(m) - 1), id);
    wff_error err;
    double reduced, theta; // modulo 360, exact at multiples of 90 degrees, as "orientation"
    if (wff_angle_degrees(deg, ("ply " + std::to_string(p) + " angle").c_str(), &reduced, &theta,
                          &err))
        wff_ff_model_fail(fn, err.message, id);
    if (wff_model_ply_orientation(m, (int)p, theta, &err))
        wff_ff_model_fail(fn, err.message, id);
    return 0;
}

double ffPlyGet(const long &id, const long &p, string *const &key)
{
    const char *fn = "wovenffPlyGet";
    const wff_model *m = wff_ff_model(id, fn);
    if (p < 0 || p >= wff_model_ply_count(m))
        wff_ff_model_fail(fn, "ply " + std::to_string(p) + " (key '" + *key +
                          "'): the pack has plies 0 to " +
                          std::to_string(wff_model_ply_count(m) - 1), id);
    double v;
    wff_error err;
    if (wff_model_ply_value(m, (int)p, key->c_str(), &v, &err))
        wff_ff_model_fail(fn, err.message, id);
    return v;
}

} // namespace

void wff_ff_register_pack()
{
    Global.Add("wovenffPlies", "(", new OneOperator3_<long, long, long, double>(ffPlies));
    Global.Add("wovenffPlyMaterial", "(",
               new OneOperator3_<long, long, long, string *>(ffPlyMaterial));
    Global.Add("wovenffPlyOrientation", "(",
               new OneOperator3_<long, long, long, double>(ffPlyOrientation));
    Global.Add("wovenffPlyGet", "(", new OneOperator3_<double, long, long, string *>(ffPlyGet));
}

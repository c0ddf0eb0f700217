// wovenff FreeFEM binding: zonal materials (include/wovenff/solver.h, plugin/zones.c).
//
//   int n = wovenffZoneDisc(md, [x, y, R], "far.txt", "outside matched");
//       elements whose centre is farther than R (m) from (x, y) get far.txt
//       ("inside": within R); "matched": its cell sees a preload matched to the
//       model cell's membrane forces, "shared" (default): the model's preload
//   int n = wovenffZoneRegion(md, "ply", "other.txt", "shared");
//       the elements of a physical surface by name, or of a region label
//       given as its number ("3")
//   int n = wovenffZoneElements(md, sel, "other.txt", "shared");
//       sel: one value per element of the model (triangles, then quadrilaterals, as
//       wovenffGet(md, "elements") counts them), nonzero = in the zone: a predicate
//       the script computes
//   int k = wovenffZoneCount(md);       // zones, zone 0 (the model's material) included
//   int n = wovenffZoneSize(md, k);     // elements of zone k
// Each returns the number of elements it selected; every failure names the
// function and what is wrong. Knows the solver's public API only.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cstdlib>
#include <cstring>
#include <sstream>

#include "ff_wovenff.hpp"

using namespace Fem2D;

namespace {

// "outside matched" and the like: outside (1) / inside (0), the preload mode.
void zone_words(const char *fn, const string *words, int *outside, int *preload, long id)
{
    std::istringstream in(words->c_str());
    std::string w;
    while (in >> w) {
        if (w == "outside" && outside)
            *outside = 1;
        else if (w == "inside" && outside)
            *outside = 0;
        else if (w == "matched")
            *preload = WFF_ZONE_PRELOAD_MATCHED;
        else if (w == "shared")
            *preload = WFF_ZONE_PRELOAD_SHARED;
        else
            wff_ff_model_fail(fn, "unknown word '" + w + "' (known: " +
                              (outside ? "outside inside " : "") + "matched shared)", id);
    }
}

long ffZoneDisc(const long &id, KN<double> *const &disc, string *const &material,
                string *const &words)
{
    const char *fn = "wovenffZoneDisc";
    wff_model *m = wff_ff_model(id, fn);
    if (disc->N() != 3)
        wff_ff_model_fail(fn, "the disc is [x, y, R] (m): 3 numbers, not " +
                          std::to_string(disc->N()), id);
    for (int i = 0; i < 3; i++)
        wff_ff_require_finite(fn, i == 0 ? "x" : i == 1 ? "y" : "R", (*disc)[i], id);
    int outside = 1, preload = WFF_ZONE_PRELOAD_SHARED;
    zone_words(fn, words, &outside, &preload, id);
    wff_error err;
    int n = wff_model_zone_disc(m, (*disc)[0], (*disc)[1], (*disc)[2], outside, material->c_str(),
                                preload, &err);
    if (n < 0)
        wff_ff_model_fail(fn, err.message, id);
    return n;
}

long ffZoneRegion(const long &id, string *const &region, string *const &material,
                  string *const &words)
{
    const char *fn = "wovenffZoneRegion";
    wff_model *m = wff_ff_model(id, fn);
    int preload = WFF_ZONE_PRELOAD_SHARED;
    zone_words(fn, words, nullptr, &preload, id);
    const char *text = region->c_str();
    char *end = nullptr;
    long tag = std::strtol(text, &end, 10);
    int numeric = end != text && *end == '\0';
    wff_error err;
    int n = wff_model_zone_region(m, numeric ? nullptr : text, numeric ? (int)tag : -1,
                                  material->c_str(), preload, &err);
    if (n < 0)
        wff_ff_model_fail(fn, err.message, id);
    return n;
}

long ffZoneElements(const long &id, KN<double> *const &selected, string *const &material,
                    string *const &words)
{
    const char *fn = "wovenffZoneElements";
    wff_model *m = wff_ff_model(id, fn);
    long n_el = wff_model_triangle_count(m) + wff_model_quad_count(m);
    if (selected->N() != n_el)
        wff_ff_model_fail(fn, "the selection has " + std::to_string(selected->N()) +
                          " values: one per element of the model, " + std::to_string(n_el), id);
    int preload = WFF_ZONE_PRELOAD_SHARED;
    zone_words(fn, words, nullptr, &preload, id);
    // in the script's element order (wff_model_zone_elements maps it to the model's)
    std::string flags((size_t)n_el, '\0');
    for (long e = 0; e < n_el; e++) {
        wff_ff_require_finite(fn, "selection", (*selected)[e], id);
        flags[(size_t)e] = (*selected)[e] != 0;
    }
    wff_error err;
    int n = wff_model_zone_elements(m, (const unsigned char *)flags.data(), material->c_str(),
                                    preload, &err);
    if (n < 0)
        wff_ff_model_fail(fn, err.message, id);
    return n;
}

long ffZoneCount(const long &id)
{
    return wff_model_zone_count(wff_ff_model(id, "wovenffZoneCount"));
}

long ffZoneSize(const long &id, const long &zone)
{
    const wff_model *m = wff_ff_model(id, "wovenffZoneSize");
    if (zone < 0 || zone >= wff_model_zone_count(m))
        wff_ff_model_fail("wovenffZoneSize", "zone " + std::to_string(zone) + ": the model has " +
                          std::to_string(wff_model_zone_count(m)) + " (0 .. " +
                          std::to_string(wff_model_zone_count(m) - 1) + ")", id);
    return wff_model_zone_size(m, (int)zone);
}

} // namespace

void wff_ff_register_zones()
{
    Global.Add("wovenffZoneDisc", "(",
               new OneOperator4_<long, long, KN<double> *, string *, string *>(ffZoneDisc));
    Global.Add("wovenffZoneRegion", "(",
               new OneOperator4_<long, long, string *, string *, string *>(ffZoneRegion));
    Global.Add("wovenffZoneElements", "(",
               new OneOperator4_<long, long, KN<double> *, string *, string *>(ffZoneElements));
    Global.Add("wovenffZoneCount", "(", new OneOperator1_<long, long>(ffZoneCount));
    Global.Add("wovenffZoneSize", "(", new OneOperator2_<long, long, long>(ffZoneSize));
}

// wovenff FreeFEM binding: parameter identification (include/wovenff/fit.h,
// docs/fit.md). Thin: option strings in, the C core's fit out.
//
//   real r = wovenffFit(matFile, dataCsv, "K_I,a", "1e-3:1e-1,1e4:1e6", result);
//   real r = wovenffFit(matFile, dataCsv, "K_I,a", "1e-3:1e-1,1e4:1e6",
//                       "start=0.012,7e4 weights=relative maxiter=200 out=DIR", result);
//   int n = wovenffFitSynth(matFile, csvOut, "tests=strip_warp,shear n=10 strain=0.03 "
//                                            "shear=0.6 noise=0.01 seed=1 set=K_I=0.0104");
//       (defaults: all five tests, 10 points each, 0.03, 0.6 rad, 1 %, seed 1; set=
//       changes material keys before the curves are made)
//   wovenffFitPredict(matFile, "strip_warp", x, y);   // y resized to x's size
//
// wovenffFit returns the residual norm √SSR and fills result (p parameters):
//   [0, p)        estimates                [p, 2p)   standard errors
//   [2p, 3p)      starting values
//   3p   residual norm   3p+1 start residual norm   3p+2 s² = SSR/(n − p)
//   3p+3 iterations      3p+4 converged (0 no; 1 step, 2 gradient, 3 cost)
//   3p+5 points          3p+6 reciprocal condition number (relative sensitivities)
//   3p+7 .. 3p+11   points per test (strip_warp strip_weft equibiaxial_warp
//                   equibiaxial_weft shear)
//   3p+12 .. 3p+16  RMS residual per test, N/m
//   3p+17 wall seconds   3p+18 .. 4p+17  at-bound flags
// With out=DIR it also writes DIR/fit.json, fitted_material.txt,
// fit_curves.csv and fit_points.csv (gnuplot blocks, one per test present, in
// the order above). Options are name=value words separated by blanks (so no
// blanks inside a value).
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/fit.h"
#include "wovenff/text_io.h"
}

using namespace Fem2D;

namespace {

// name=value words; unknown names and words without '=' stop the script.
// out=DIR comes last: DIR is the rest of the text (a folder name may hold blanks).
struct Options {
    std::string start, weights, out, tests, set;
    double maxiter = NAN, n = NAN, strain = NAN, shear = NAN, noise = NAN, seed = NAN;
};

double number(const char *fn, const std::string &name, const std::string &value)
{
    double v = 0;
    if (wff_parse_decimal(value.c_str(), value.c_str() + value.size(), &v)) {
        std::string msg = "option " + name + "=" + value + ": not a finite decimal number";
        wff_ff_fail(fn, msg.c_str());
    }
    return v;
}

Options parse_options(const char *fn, const string *text, const char *const *allowed)
{
    Options o;
    if (!text)
        return o;
    std::istringstream in(*text);
    std::string word;
    while (in >> word) {
        if (word.compare(0, 4, "out=") == 0) {   // the rest of the text: a folder may hold blanks
            std::string rest;
            std::getline(in, rest, '\0');
            word += rest;
        }
        size_t eq = word.find('=');
        std::string name = word.substr(0, eq);
        std::string value = eq == std::string::npos ? "" : word.substr(eq + 1);
        bool known = false;
        for (const char *const *a = allowed; eq != std::string::npos && *a; a++)
            known = known || name == *a;
        if (!known) {
            std::string list;
            for (const char *const *a = allowed; *a; a++)
                list += std::string(list.empty() ? "" : " ") + *a;
            std::string msg =
                "option '" + word + "': expected name=value with name one of: " + list;
            wff_ff_fail(fn, msg.c_str());
        }
        if (name == "start") o.start = value;
        else if (name == "weights") o.weights = value;
        else if (name == "out") o.out = value;
        else if (name == "tests") o.tests = value;
        else if (name == "set") o.set = value;
        else if (name == "maxiter") o.maxiter = number(fn, name, value);
        else if (name == "n") o.n = number(fn, name, value);
        else if (name == "strain") o.strain = number(fn, name, value);
        else if (name == "shear") o.shear = number(fn, name, value);
        else if (name == "noise") o.noise = number(fn, name, value);
        else if (name == "seed") o.seed = number(fn, name, value);
    }
    return o;
}

const char *str(const string *s) { return s ? s->c_str() : ""; }

double fit(const char *fn, string *material, string *data, string *params, string *bounds,
           const string *options, KN<double> *result)
{
    static const char *const allowed[] = {"start", "weights", "maxiter", "out", nullptr};
    Options o = parse_options(fn, options, allowed);
    if (!result)
        wff_ff_fail(fn, "no result array");
    if (!material || !data)
        wff_ff_fail(fn, "no material or data file name given");
    wff_fit_options opt;
    wff_fit_options_default(&opt);
    if (!o.weights.empty()) {
        opt.weighting = wff_fit_weighting_find(o.weights.c_str());
        if (opt.weighting < 0) {
            std::string msg = "option weights=" + o.weights + ": want test or relative";
            wff_ff_fail(fn, msg.c_str());
        }
    }
    if (!std::isnan(o.maxiter)) {
        if (!(o.maxiter >= 1 && o.maxiter <= 100000))
            wff_ff_fail(fn, "option maxiter: want 1 to 100000");
        opt.max_iterations = (int)o.maxiter;
    }
    wff_fit_result res;
    wff_error err;
    if (wff_fit_files(material->c_str(), data->c_str(), str(params), str(bounds),
                      o.start.c_str(), &opt, o.out.empty() ? nullptr : o.out.c_str(), &res, &err))
        wff_ff_fail(fn, err);
    const int p = res.n_params;
    result->resize(4 * p + 18);
    KN<double> &r = *result;
    for (int j = 0; j < p; j++) {
        r[j] = res.value[j];
        r[p + j] = res.std_error[j];
        r[2 * p + j] = res.start[j];
        r[3 * p + 18 + j] = res.at_bound[j];
    }
    r[3 * p] = res.residual_norm;
    r[3 * p + 1] = res.start_residual_norm;
    r[3 * p + 2] = res.s2;
    r[3 * p + 3] = res.iterations;
    r[3 * p + 4] = res.converged;
    r[3 * p + 5] = res.n_points;
    r[3 * p + 6] = res.condition;
    for (int t = 0; t < WFF_FIT_TESTS; t++) {
        r[3 * p + 7 + t] = res.test_points[t];
        r[3 * p + 12 + t] = res.test_rms[t];
    }
    r[3 * p + 17] = res.wall_seconds;
    return res.residual_norm;
}

double ffFit(string *const &material, string *const &data, string *const &params,
             string *const &bounds, KN<double> *const &result)
{
    return fit("wovenffFit", material, data, params, bounds, nullptr, result);
}

double ffFitOptions(string *const &material, string *const &data, string *const &params,
                    string *const &bounds, string *const &options, KN<double> *const &result)
{
    return fit("wovenffFit", material, data, params, bounds, options, result);
}

long ffFitSynth(string *const &material, string *const &csv, string *const &options)
{
    const char *fn = "wovenffFitSynth";
    static const char *const allowed[] = {"tests", "n", "strain", "shear", "noise", "seed",
                                          "set", nullptr};
    Options o = parse_options(fn, options, allowed);
    if (!material || !csv)
        wff_ff_fail(fn, "no material or output file name given");
    wff_fit_synth spec;
    spec.test_mask = 0;
    std::string tests = o.tests.empty()
                            ? "strip_warp,strip_weft,equibiaxial_warp,equibiaxial_weft,shear"
                            : o.tests;
    std::istringstream in(tests);
    std::string name;
    while (std::getline(in, name, ',')) {
        int t = wff_fit_test_find(name.c_str());
        if (t < 0) {
            std::string msg = "option tests: unknown test '" + name + "' (known: strip_warp, "
                              "strip_weft, equibiaxial_warp, equibiaxial_weft, shear)";
            wff_ff_fail(fn, msg.c_str());
        }
        spec.test_mask |= 1u << t;
    }
    spec.n_per_test = std::isnan(o.n) ? 10 : (int)o.n;
    spec.strain_max = std::isnan(o.strain) ? 0.03 : o.strain;
    spec.shear_max = std::isnan(o.shear) ? 0.6 : o.shear;
    spec.noise = std::isnan(o.noise) ? 0.01 : o.noise;
    if (!std::isnan(o.seed) && !(o.seed >= 0 && o.seed < 9e15 && o.seed == std::floor(o.seed)))
        wff_ff_fail(fn, "option seed: want a whole number >= 0");
    spec.seed = std::isnan(o.seed) ? 1 : (unsigned long long)o.seed;
    int n = 0;
    wff_error err;
    if (o.set.empty()) {
        if (wff_fit_synthesize_file(material->c_str(), &spec, csv->c_str(), &n, &err))
            wff_ff_fail(fn, err);
        return n;
    }
    // set=K_I=0.0104,a=85000: the material with these values changed (the C
    // core's material editor; its messages name the item and the file)
    char *text = nullptr, *edited = nullptr;
    if (wff_read_text_file(material->c_str(), "material file", WFF_MATERIAL_FILE_MAX, &text,
                           &err))
        wff_ff_fail(fn, err);
    int edit_rc = wff_material_text_set(text, material->c_str(), o.set.c_str(), "option set",
                                        &edited, &err);
    std::free(text);
    if (edit_rc)
        wff_ff_fail(fn, err);
    std::string source = *material + " with set=" + o.set;
    wff_material mat;
    wff_fit_data data;
    int parse_rc = wff_material_parse_text(edited, source.c_str(), &mat, &err);
    std::free(edited);
    if (parse_rc || wff_fit_synthesize(&mat, &spec, &data, &err))
        wff_ff_fail(fn, err);
    int rc = wff_fit_data_write(&data, csv->c_str(), &err);
    n = data.n;
    wff_fit_data_free(&data);
    if (rc)
        wff_ff_fail(fn, err);
    return n;
}

long ffFitPredict(string *const &material, string *const &test, KN<double> *const &x,
                  KN<double> *const &y)
{
    const char *fn = "wovenffFitPredict";
    if (!x || !y)
        wff_ff_fail(fn, "no x or y array");
    int t = wff_fit_test_find(str(test));
    if (t < 0) {
        std::string msg = std::string("unknown test '") + str(test) +
                          "' (known: strip_warp, strip_weft, equibiaxial_warp, "
                          "equibiaxial_weft, shear)";
        wff_ff_fail(fn, msg.c_str());
    }
    wff_material mat;
    wff_ff_material(fn, material, &mat);
    const long n = x->N();
    std::vector<double> xs(n), ys(n);
    for (long i = 0; i < n; i++)
        xs[i] = (*x)[i];
    wff_error err;
    if (wff_fit_predict(&mat, t, (int)n, xs.data(), ys.data(), &err))
        wff_ff_fail(fn, err);
    y->resize(n);
    for (long i = 0; i < n; i++)
        (*y)[i] = ys[i];
    return n;
}

} // namespace

void wff_ff_register_fit()
{
    Global.Add("wovenffFit", "(",
               new OneOperator5_<double, string *, string *, string *, string *, KN<double> *>(
                   ffFit));
    Global.Add("wovenffFit", "(",
               new OneOperator6_<double, string *, string *, string *, string *, string *,
                                 KN<double> *>(ffFitOptions));
    Global.Add("wovenffFitSynth", "(",
               new OneOperator3_<long, string *, string *, string *>(ffFitSynth));
    Global.Add("wovenffFitPredict", "(",
               new OneOperator4_<long, string *, string *, KN<double> *, KN<double> *>(
                   ffFitPredict));
}

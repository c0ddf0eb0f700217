// wovenff FreeFEM binding: the ballistic limit from a set of impacts
// (include/wovenff/limit.h). Thin: arrays in, the C core's fit out.
//
//   real vbl = wovenffLambertJonas(Vs, Vr, result);  // Vs, Vr: striking and residual
//                                                   // speeds, m/s (Vr = 0: stopped)
//   real vr = wovenffLambertJonasLaw(vs, vbl, a, p); // the law at one speed
//
// wovenffLambertJonas returns V_bl and resizes result to 25 entries:
//   0 V_bl (m/s)  1 a  2 p          3 .. 5  their standard errors (NaN: no residual variance)
//   6 residual sd s (m/s)  7 RMS residual (m/s)
//   8 V50 from the fit (= V_bl)  9 its error    10 V50 from the bracket  11 half the gap
//   12, 13 the bound kept on V_bl (low, high), m/s
//   14 runs  15 perforating  16 stopped  17 stopped above the lowest perforating speed
//   18 iterations  19 converged (GSL's reason, 0 not)  20 .. 22 at-bound flags (V_bl, a, p)
//   23 highest stopped speed  24 lowest perforating speed (NaN: none)
// A refused input (fewer than 3 perforating runs, a non-finite or negative value)
// stops the script with the core's message (a try/catch gets it).
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <vector>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/limit.h"
}

namespace {

const long kResultSize = 25;

double ffLambertJonas(KN<double> *const &vs, KN<double> *const &vr, KN<double> *const &result)
{
    const char *fn = "wovenffLambertJonas";
    if (!vs || !vr || !result)
        wff_ff_fail(fn, "expected (striking speeds, residual speeds, result)");
    long n = vs->N();
    if (vr->N() != n)
        wff_ff_fail(fn, "the striking and residual speed arrays differ in size (" +
                            std::to_string(n) + " and " + std::to_string(vr->N()) + ")");
    std::vector<double> s(n), r(n);
    for (long i = 0; i < n; i++) {
        s[i] = (*vs)[i];
        r[i] = (*vr)[i];
    }
    wff_limit_fit f;
    wff_error err;
    if (wff_limit_fit_run(s.data(), r.data(), (int)n, &f, &err))
        wff_ff_fail(fn, err);
    result->resize(kResultSize);
    double *o = &(*result)[0];
    for (int j = 0; j < WFF_LIMIT_NP; j++) {
        o[j] = f.value[j];
        o[3 + j] = f.std_error[j];
        o[20 + j] = f.at_bound[j];
    }
    o[6] = f.residual_sd;
    o[7] = f.rms_residual;
    o[8] = f.v50_fit;
    o[9] = f.v50_fit_error;
    o[10] = f.v50_bracket;
    o[11] = f.v50_bracket_half_gap;
    o[12] = f.bracket_low;
    o[13] = f.bracket_high;
    o[14] = f.n_points;
    o[15] = f.n_perforated;
    o[16] = f.n_stopped;
    o[17] = f.n_mixed;
    o[18] = f.iterations;
    o[19] = f.converged;
    o[23] = f.highest_stopped;
    o[24] = f.lowest_perforated;
    return f.value[WFF_LIMIT_VBL];
}

double ffLambertJonasLaw(const double &vs, const double &vbl, const double &a, const double &p)
{
    return wff_lambert_jonas(vs, vbl, a, p);
}

} // namespace

void wff_ff_register_limit()
{
    Global.Add("wovenffLambertJonas", "(",
               new OneOperator3_<double, KN<double> *, KN<double> *, KN<double> *>(
                   ffLambertJonas));
    Global.Add("wovenffLambertJonasLaw", "(",
               new OneOperator4_<double, double, double, double, double>(ffLambertJonasLaw));
}

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
//
// The MIL-STD-662F sequence (include/wovenff/mil662.h); outcomes 1 complete,
// 0 partial, -1 neither (undecided, failed):
//   real m = wovenffMil662Next(V, O, params, next);  // params [first speed, step,
//            // step after the first reversal, jobs] (m/s, m/s, m/s, -); next resized
//            // to m, the next round's speeds (m/s); m = 0: no new speed
//   real v50 = wovenffMil662V50(V, O, spread, result);  // NaN unless met; result (14):
//   0 V50 (NaN unless met)  1 spread  2 sample sd  3 status (0 met, 1 too few, 2 too wide)
//   4 partial  5 complete  6 neither  7 .. 12 the six's shot indices (-1 none)
//   13 the six's mean (NaN without six)
//
// The Phoenix-Porwal membrane estimate (include/wovenff/membrane_limit.h), a first
// shot for the sequence:
//   real v = wovenffV50Estimate(material, plies, mass, radius, opening);  // m/s;
//            // material file, plies (a whole number >= 1), projectile mass (kg) and
//            // face radius (m), clamp opening radius (m; 0: no clamp). The infinite
//            // membrane's V50
//   real v = wovenffV50Estimate(material, plies, mass, radius, opening, result);
//            // the same; result (8): 0 V50 (m/s)  1 K_max  2 x* (cone radius / r_p at
//            // the peak)  3 K at the clamp  4 the speed above which the fabric fails
//            // before the cone reaches the clamp (m/s; 3, 4: 0 unless the clamp is
//            // inside the peak)  5 c (m/s)  6 eps_max  7 Gamma
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/limit.h"
#include "wovenff/membrane_limit.h"
#include "wovenff/mil662.h"
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

// The history's outcomes as the core's (each -1, 0 or 1, else an error naming it).
std::vector<int> mil662Outcomes(const char *fn, KN<double> *const &v, KN<double> *const &o)
{
    if (!v || !o || v->N() != o->N())
        wff_ff_fail(fn, "the speed and outcome arrays differ in size");
    std::vector<int> out(o->N());
    for (long i = 0; i < o->N(); i++) {
        double x = (*o)[i];
        if (!(x == -1 || x == 0 || x == 1))
            wff_ff_fail(fn, "shot " + std::to_string(i + 1) + ": outcome " + std::to_string(x) +
                                " (1 complete, 0 partial, -1 neither)");
        out[i] = (int)x;
    }
    return out;
}

double ffMil662Next(KN<double> *const &v, KN<double> *const &o, KN<double> *const &params,
                    KN<double> *const &next)
{
    const char *fn = "wovenffMil662Next";
    std::vector<int> oc = mil662Outcomes(fn, v, o);
    if (!params || params->N() != 4 || !next)
        wff_ff_fail(fn, "expected params [first speed, step, step after the first reversal, jobs]");
    wff_mil662_params p = wff_mil662_defaults((*params)[0]);
    p.step = (*params)[1];
    p.step_after = (*params)[2];
    double jobs = (*params)[3];
    if (!(jobs >= 1 && jobs <= WFF_MIL662_JOBS_MAX))
        wff_ff_fail(fn, "jobs " + std::to_string(jobs) + " (1 to " + std::to_string(WFF_MIL662_JOBS_MAX) + ")");
    std::vector<double> s(v->N()), out((size_t)jobs);
    for (long i = 0; i < v->N(); i++)
        s[i] = (*v)[i];
    wff_error err;
    int m = wff_mil662_next(s.data(), oc.data(), (int)s.size(), &p, (int)jobs, out.data(), NULL, &err);
    if (m < 0)
        wff_ff_fail(fn, err);
    next->resize(m > 0 ? m : 1);
    (*next)[0] = 0;
    for (int k = 0; k < m; k++)
        (*next)[k] = out[k];
    return m;
}

double ffMil662V50(KN<double> *const &v, KN<double> *const &o, const double &spread,
                   KN<double> *const &result)
{
    const char *fn = "wovenffMil662V50";
    std::vector<int> oc = mil662Outcomes(fn, v, o);
    if (!result)
        wff_ff_fail(fn, "expected (speeds, outcomes, largest spread, result)");
    std::vector<double> s(v->N());
    for (long i = 0; i < v->N(); i++)
        s[i] = (*v)[i];
    wff_mil662_result r;
    wff_error err;
    if (wff_mil662_v50(s.data(), oc.data(), (int)s.size(), spread, &r, &err))
        wff_ff_fail(fn, err);
    result->resize(14);
    double *x = &(*result)[0];
    x[0] = r.v50;
    x[1] = r.spread;
    x[2] = r.std_dev;
    x[3] = r.status;
    x[4] = r.n_partial;
    x[5] = r.n_complete;
    x[6] = r.n_none;
    for (int k = 0; k < 6; k++)
        x[7 + k] = r.chosen[k];
    x[13] = r.mean;
    return r.v50;
}

double ffV50EstimateAll(string *const &material, const double &plies, const double &mass,
                        const double &radius, const double &opening, KN<double> *const &result)
{
    const char *fn = "wovenffV50Estimate";
    if (!(plies >= 1 && plies <= 1e6 && plies == std::floor(plies))) {
        std::ostringstream what;
        what << "plies = " << plies << ": must be a whole number >= 1 (at most 1e6)";
        wff_ff_fail(fn, what.str());
    }
    wff_pp_result r;
    wff_pp_input used;
    wff_error err;
    if (wff_membrane_limit_estimate(material->c_str(), (int)plies, mass, radius, opening, &r,
                                    &used, &err))
        wff_ff_fail(fn, err);
    if (result) {
        result->resize(8);
        const double v[8] = {r.v50, r.k_max, r.x_peak, r.k_clamp, r.v50_clamp,
                             used.wave_speed, used.failure_strain, used.gamma};
        for (int i = 0; i < 8; i++)
            (*result)[i] = v[i];
    }
    return r.v50;
}

double ffV50Estimate(string *const &material, const double &plies, const double &mass,
                     const double &radius, const double &opening)
{
    return ffV50EstimateAll(material, plies, mass, radius, opening, nullptr);
}

} // namespace

void wff_ff_register_limit()
{
    Global.Add("wovenffLambertJonas", "(",
               new OneOperator3_<double, KN<double> *, KN<double> *, KN<double> *>(
                   ffLambertJonas));
    Global.Add("wovenffLambertJonasLaw", "(",
               new OneOperator4_<double, double, double, double, double>(ffLambertJonasLaw));
    Global.Add("wovenffMil662Next", "(",
               new OneOperator4_<double, KN<double> *, KN<double> *, KN<double> *, KN<double> *>(
                   ffMil662Next));
    Global.Add("wovenffMil662V50", "(",
               new OneOperator4_<double, KN<double> *, KN<double> *, double, KN<double> *>(ffMil662V50));
    Global.Add("wovenffV50Estimate", "(",
               new OneOperator5_<double, string *, double, double, double, double>(ffV50Estimate));
    Global.Add("wovenffV50Estimate", "(",
               new OneOperator6_<double, string *, double, double, double, double, KN<double> *>(
                   ffV50EstimateAll));
}

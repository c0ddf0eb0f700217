// wovenff FreeFEM binding: checks a scene makes before its time loop (issue 11:
// a run that would take no step is refused before it starts).
//
//   real dt = wovenffStepEstimate(md);   // s: the step the next advance takes
// and the finiteness check every model function taking reals makes
// (wff_ff_require_finite: a NaN or infinite argument is an error naming it).
//
// Knows the model handle table (ff_wovenff.hpp) and the solver's public API only.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cmath>
#include <cstdio>

#include "ff_wovenff.hpp"

using namespace Fem2D;

namespace {

double ffStepEstimate(const long &id)
{
    const wff_model *m = wff_ff_model(id, "wovenffStepEstimate");
    double dt = wff_model_step_estimate(m);
    if (!(dt > 0) || !std::isfinite(dt))
        wff_ff_model_fail("wovenffStepEstimate", "the stable step " + std::to_string(dt)
                          + " s is not positive: degenerate elements or NaN", id);
    return dt;
}

} // namespace

void wff_ff_require_finite(const char *fn, const char *name, double x, long id)
{
    if (std::isfinite(x))
        return;
    char msg[160];
    snprintf(msg, sizeof msg, "%s = %g is not a finite number", name, x);
    if (id >= 0)
        wff_ff_model_fail(fn, msg, id);
    wff_ff_fail(fn, msg);
}

void wff_ff_register_checks()
{
    Global.Add("wovenffStepEstimate", "(", new OneOperator1_<double, long>(ffStepEstimate));
}

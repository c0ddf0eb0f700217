// wovenff FreeFEM binding: whether a model as configured takes the run-level
// features a scene asks of it (include/wovenff/combine.h, plugin/combine.c).
//
//   string why = wovenffRefuses(md, "remesh checkpoint");   // "" if they combine
//
// The answer is "FEATURE: reason" or "FEATURE with OTHER: reason" (the first
// rule of combine.c's table that applies); a feature name it does not know is
// an error (naming the known ones). A scene asks once, before its run
// (freefem_scripts/lib/wff_combine.idp: wffCombineCheck), and names its
// options in the message. Knows the model handle table (ff_wovenff.hpp) and
// combine.h only.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/combine.h"
}

using namespace Fem2D;

namespace {

string *ffRefuses(Stack stack, const long &id, string *const &features)
{
    const wff_model *m = wff_ff_model(id, "wovenffRefuses");
    char why[512];
    if (wff_model_refuses(m, features->c_str(), why, sizeof why) < 0)
        wff_ff_model_fail("wovenffRefuses", why, id);
    return Add2StackOfPtr2Free(stack, new string(why));
}

} // namespace

void wff_ff_register_combine()
{
    Global.Add("wovenffRefuses", "(", new OneOperator2s_<string *, long, string *>(ffRefuses));
}

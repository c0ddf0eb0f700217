// wovenff FreeFEM binding: a model's state in and out as FreeFEM arrays, and
// element (P0) fields (include/wovenff/state.h).
//
//   fespace Vh5(Th, [P1, P1, P1, P1, P1]);     // node-major: ux uy uz dA1 dA2
//   Vh5 [ux, uy, uz, a1, a2];
//   wovenffGetVector(md, "u", ux[]);            // u (m) into the 5 x nodes array
//   wovenffSetVector(md, "v", ux[]);            // v (m/s): checked, energies follow
//   fespace Ph(Th, P0); Ph s;
//   wovenffElementField(md, "T1", s[]);         // one value per triangle of wovenffMesh(md)
//   string h = wovenffStateHash(md);            // 16 hex digits: the state's bits hashed
//
// Sizes are checked (5 x nodes for a vector); the C core checks the values
// and recomputes what follows a set state. Thin: no physics here.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cstdio>
#include <string>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/state.h"
}

using namespace Fem2D;

namespace {

long ffGetVector(const long &id, string *const &which, KN<double> *const &out)
{
    const char *fn = "wovenffGetVector";
    const wff_model *m = wff_ff_model(id, fn);
    wff_error err;
    if (*which != "u" && *which != "v")
        wff_ff_model_fail(fn, "unknown state vector '" + *which + "' (known: u, v)", id);
    out->resize(wff_model_dof_count(m));
    if (wff_model_get_vector(m, which->c_str(), &(*out)[0], &err))
        wff_ff_model_fail(fn, err.message, id);
    return wff_model_dof_count(m);
}

long ffSetVector(const long &id, string *const &which, KN<double> *const &in)
{
    const char *fn = "wovenffSetVector";
    wff_model *m = wff_ff_model(id, fn);
    if (*which != "u" && *which != "v")
        wff_ff_model_fail(fn, "unknown state vector '" + *which + "' (known: u, v)", id);
    if (!in || in->N() != wff_model_dof_count(m))
        wff_ff_model_fail(fn, *which + " must have " + std::to_string(wff_model_dof_count(m)) +
                                  " entries (5 per node: ux uy uz dA1 dA2, node-major, as "
                                  "fespace [P1,P1,P1,P1,P1]), got " +
                                  std::to_string(in ? (long)in->N() : 0L), id);
    wff_error err;
    if (wff_model_set_vector(m, which->c_str(), &(*in)[0], &err))
        wff_ff_model_fail(fn, err.message, id);
    return wff_model_dof_count(m);
}

long ffElementField(const long &id, string *const &name, KN<double> *const &out)
{
    const char *fn = "wovenffElementField";
    const wff_model *m = wff_ff_model(id, fn);
    long n = wff_model_triangle_count(m) + 2L * wff_model_quad_count(m);
    out->resize(n);
    wff_error err;
    if (wff_model_element_field(m, name->c_str(), &(*out)[0], &err))
        wff_ff_model_fail(fn, err.message, id);
    return n;
}

string *ffStateHash(Stack stack, const long &id)
{
    char hex[32];
    snprintf(hex, sizeof hex, "%016llx", wff_model_state_hash(wff_ff_model(id, "wovenffStateHash")));
    return Add2StackOfPtr2Free(stack, new string(hex));
}

} // namespace

void wff_ff_register_state()
{
    Global.Add("wovenffStateHash", "(", new OneOperator1s_<string *, long>(ffStateHash));
    Global.Add("wovenffGetVector", "(",
               new OneOperator3_<long, long, string *, KN<double> *>(ffGetVector));
    Global.Add("wovenffSetVector", "(",
               new OneOperator3_<long, long, string *, KN<double> *>(ffSetVector));
    Global.Add("wovenffElementField", "(",
               new OneOperator3_<long, long, string *, KN<double> *>(ffElementField));
}

// wovenff FreeFEM binding: which kernel variant a model runs (the per-element
// kernels built for several instruction sets, include/wovenff/kernel.h).
//
//   string k = wovenffKernel(md);   // "baseline", "avx2" or "avx512"
//
// A model chooses its variant when it is created, from the environment
// variable WOVENFF_KERNEL (auto when unset: the widest this CPU runs).
// Knows the model handle table (ff_wovenff.hpp) and kernel.h only.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/kernel.h"
}

using namespace Fem2D;

namespace {

string *ffKernel(Stack stack, const long &id)
{
    const wff_model *m = wff_ff_model(id, "wovenffKernel");
    return Add2StackOfPtr2Free(stack, new string(wff_material_kernel(wff_model_material(m))));
}

} // namespace

void wff_ff_register_kernel()
{
    Global.Add("wovenffKernel", "(", new OneOperator1s_<string *, long>(ffKernel));
}

// wovenff FreeFEM binding: what the module's .cpp files share.
//
// Each binding file defines one wff_ff_register_*() that adds its functions
// to FreeFEM; wovenff.cpp calls them all from the module's init(). The helpers
// below turn C-core failures into FreeFEM ExecError (the script stops with
// exit code 8 and the message). The binding is thin: no physics here.
#ifndef WOVENFF_FF_WOVENFF_HPP
#define WOVENFF_FF_WOVENFF_HPP

#include "ff++.hpp"

extern "C" {
#include "wovenff/cell.h"
#include "wovenff/error.h"
}

// Registration, one per binding file (wovenff.cpp lists them).
void wff_ff_register_point();  // ff_point.cpp: pointwise material API
void wff_ff_register_solver(); // ff_solver.cpp: models, meshes, explicit solver
void wff_ff_register_fit();    // ff_fit.cpp: parameter identification
void wff_ff_register_explore(); // ff_explore.cpp: one point along a load path (explorer)

// ExecError("fn: message"). Never returns.
[[noreturn]] void wff_ff_fail(const char *fn, const char *message);
// ExecError("fn: err.message"). Never returns.
[[noreturn]] void wff_ff_fail(const char *fn, const wff_error &err);

// Load a material file (read afresh on every call: no cache). On failure
// ExecError with the loader's message, which names the file, line and key.
void wff_ff_material(const char *fn, const string *path, wff_material *mat);

// ExecError unless v has exactly n entries; `layout` says what they are,
// e.g. "F11 F12 F21 F22 F31 F32".
void wff_ff_require_size(const char *fn, const char *name, const KN<double> *v, long n,
                         const char *layout);

#endif

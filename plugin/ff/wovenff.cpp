// wovenff FreeFEM load module: entry point and the helpers the binding files
// share (ff_wovenff.hpp). `load "wovenff"` in a script runs init(), which
// registers every binding file's functions.
//
// To add a binding file: define `void wff_ff_register_NAME()` in it, declare it
// in ff_wovenff.hpp and add it to kRegister below.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/material.h"
}

using namespace Fem2D;

namespace {

// A module error. Code NONE: FreeFEM's Error constructor prints nothing (an
// ExecError prints its message when raised, so a caught one was printed twice:
// there and by the script's handler). Exit code 8 like ExecError.
class ModuleError : public Error {
public:
    explicit ModuleError(const std::string &message) : Error(NONE, message.c_str(), nullptr) {}
    int errcode() const override { return UNKNOWN; }
};

std::string &last_error()
{
    static std::string message; // binding-level: FreeFEM passes no user data
    return message;
}

} // namespace

const std::string &wff_ff_last_error()
{
    return last_error();
}

void wff_ff_fail(const char *fn, const std::string &message)
{
    last_error() = std::string(fn) + ": " + message;
    throw ModuleError(last_error());
}

void wff_ff_fail(const char *fn, const char *message)
{
    wff_ff_fail(fn, std::string(message));
}

void wff_ff_fail(const char *fn, const wff_error &err)
{
    wff_ff_fail(fn, std::string(err.message));
}

void wff_ff_material(const char *fn, const string *path, wff_material *mat)
{
    wff_error err;
    if (!path || wff_material_load(path->c_str(), mat, &err))
        wff_ff_fail(fn, path ? err.message : "no material file name given");
}

void wff_ff_require_size(const char *fn, const char *name, const KN<double> *v, long n,
                         const char *layout)
{
    if (!v || v->N() != n) {
        char msg[300];
        snprintf(msg, sizeof msg, "%s must have %ld entries (%s), got %ld", name, n, layout,
                 v ? (long)v->N() : 0L);
        wff_ff_fail(fn, msg);
    }
}

static void (*const kRegister[])() = {
    wff_ff_register_point,
    wff_ff_register_solver,
    wff_ff_register_fit,
    wff_ff_register_explore,
    wff_ff_register_projectile,
    wff_ff_register_loop,
    wff_ff_register_femesh,
    wff_ff_register_state,
    wff_ff_register_remesh,
    wff_ff_register_materials,
    wff_ff_register_files,
    wff_ff_register_checks,
    wff_ff_register_background,
    wff_ff_register_zones,
    wff_ff_register_threads,
    wff_ff_register_kernel,
    wff_ff_register_limit,
    wff_ff_register_pack,
    wff_ff_register_backing,
    wff_ff_register_combine,
};

static void init()
{
    for (void (*reg)() : kRegister)
        reg();
}

LOADFUNC(init)

// wovenff FreeFEM binding: what the module's .cpp files share.
//
// Each binding file defines one wff_ff_register_*() that adds its functions
// to FreeFEM; wovenff.cpp calls them all from the module's init(). Every
// failure of every function goes through wff_ff_fail: the message
// ("function: what went wrong") is recorded as the last error
// (wovenffLastError) and thrown as an error FreeFEM does not print when it is
// raised: a script's try/catch prints it once (the scenes: "error: ..."),
// uncaught FreeFEM prints it once and exits with code 8. The binding is thin:
// no physics here.
#ifndef WOVENFF_FF_WOVENFF_HPP
#define WOVENFF_FF_WOVENFF_HPP

#include "ff++.hpp"

#include <string>

extern "C" {
#include "wovenff/cell.h"
#include "wovenff/error.h"
#include "wovenff/solver.h"
}

// Registration, one per binding file (wovenff.cpp lists them).
void wff_ff_register_point();  // ff_point.cpp: pointwise material API
void wff_ff_register_solver(); // ff_solver.cpp: models, meshes, explicit solver
void wff_ff_register_fit();    // ff_fit.cpp: parameter identification
void wff_ff_register_explore(); // ff_explore.cpp: one point along a load path (explorer)
void wff_ff_register_projectile(); // ff_projectile.cpp: nose shape, impact point
void wff_ff_register_loop();   // ff_loop.cpp: element operators for a script's own loop
void wff_ff_register_femesh(); // ff_femesh.cpp: models from FreeFEM meshes, labels as groups
void wff_ff_register_remesh(); // ff_remesh.cpp: a model's state carried onto a new mesh
void wff_ff_register_state();  // ff_state.cpp: state vectors in and out, element fields
void wff_ff_register_materials(); // ff_materials.cpp: the material handle table
void wff_ff_register_files();   // ff_files.cpp: checked writes, folders, locks, no shell
void wff_ff_register_checks(); // ff_checks.cpp: checks a scene makes before it runs
void wff_ff_register_background(); // ff_background.cpp: programs started without waiting
void wff_ff_register_zones();  // ff_zones.cpp: zonal materials
void wff_ff_register_threads(); // ff_threads.cpp: the default thread count, a model's
void wff_ff_register_kernel(); // ff_kernel.cpp: the kernel variant a model runs
void wff_ff_register_limit();  // ff_limit.cpp: the Lambert-Jonas fit of a ballistic-limit study
void wff_ff_register_pack();   // ff_pack.cpp: multi-ply packs
void wff_ff_register_backing(); // ff_backing.cpp: the backing block behind a pack
void wff_ff_register_combine(); // ff_combine.cpp: which run-level features a model takes

// Record "fn: message" as the last error and stop the script (exit code 8
// unless it catches the error). Never returns.
[[noreturn]] void wff_ff_fail(const char *fn, const char *message);
[[noreturn]] void wff_ff_fail(const char *fn, const wff_error &err);
[[noreturn]] void wff_ff_fail(const char *fn, const std::string &message);

// The message of the last failure of any function of the module ("" if none).
const std::string &wff_ff_last_error();

// The model handle table (ff_models.cpp). A script holds an integer handle;
// FreeFEM passes no user data to functions, so the table is the binding's
// (the C core keeps no global state).
// Take ownership of a created model (calloc'd, wff_model_create'd); returns its handle.
long wff_ff_model_add(wff_model *m);
// The live model of handle id, or wff_ff_fail naming fn.
wff_model *wff_ff_model(long id, const char *fn);
// wff_model_free and release the handle (a later use of it is an error).
void wff_ff_model_free(long id, const char *fn);
// wff_ff_fail, the message also kept as model id's last error (id < 0: none).
[[noreturn]] void wff_ff_model_fail(const char *fn, const std::string &message, long id);
// Model id's last error; for id < 0 (or not a model) the module's last error.
std::string wff_ff_model_last_error(long id);

// A model from a FreeFEM-format .msh file, its labels named by settings
// ("names=1:clamp regions=0:ply"); its handle (ff_femesh.cpp).
long wff_ff_model_from_freefem_msh(const char *path, const string *mat, const string *settings);

// Copy FreeFEM mesh th into *mesh (same vertex numbering, triangle regions and
// boundary-edge labels as groups named by settings, checked by the C core;
// caller frees with wff_mesh_free), or wff_ff_fail naming fn (ff_femesh.cpp).
void wff_ff_mesh_from_freefem(const char *fn, const Fem2D::Mesh *th, const char *settings,
                              wff_mesh *mesh);
// wff_ff_model_fail unless x is finite: "NAME = inf is not a finite number"
// (ff_checks.cpp; id < 0: no model).
void wff_ff_require_finite(const char *fn, const char *name, double x, long id);

// Load a material file (read afresh on every call: no cache). On failure
// wff_ff_fail with the loader's message, which names the file, line and key.
void wff_ff_material(const char *fn, const string *path, wff_material *mat);

// The material handle table (ff_materials.cpp): wovenffMaterial(file) loads
// a material once. The material of handle id, or wff_ff_fail naming fn and id.
const wff_material *wff_ff_material(long id, const char *fn);
// A pointwise function's material argument, a file name or a handle: the file
// is loaded into *scratch (as wff_ff_material above), the handle looked up.
const wff_material *wff_ff_material_arg(const char *fn, string *const &path,
                                        wff_material *scratch);
const wff_material *wff_ff_material_arg(const char *fn, const long &id, wff_material *scratch);

// wff_ff_fail unless v has exactly n entries; `layout` says what they are,
// e.g. "F11 F12 F21 F22 F31 F32".
void wff_ff_require_size(const char *fn, const char *name, const KN<double> *v, long n,
                         const char *layout);

#endif

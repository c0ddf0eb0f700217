/* wovenff — mesh options from a one-line text, for scripts:
 *   "h_min=0.002 h_max=0.01 size_factor=0.5 recombine=1"
 * size_factor and recombine are wff_mesh_options fields; every other
 * name=value pair is a number handed to the .geo (DefineConstant). */
#ifndef WOVENFF_OPTIONS_H
#define WOVENFF_OPTIONS_H

#include "wovenff/mesh.h"

#ifdef __cplusplus
extern "C" {
#endif

int wff_mesh_options_parse(const char *text, wff_mesh_options *opt, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

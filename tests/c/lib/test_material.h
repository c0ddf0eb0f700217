/* A material file's text with assignments applied, for the C tests that edit
 * a material on the fly (slip, cutting). */
#ifndef WFF_TEST_MATERIAL_H
#define WFF_TEST_MATERIAL_H

#include "check.h"

/* The text of material file `path` with `assignments` ("key=value,...", or ""
 * for none) applied, as the scenes' -set applies them; the caller frees it.
 * NULL on failure (reported through st). */
char *test_material_text(check_state *st, const char *path, const char *assignments);

#endif

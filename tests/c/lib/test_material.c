/* test_material.h: a material file's text with assignments applied. */
#include "test_material.h"
#include "wovenff/material.h"
#include "wovenff/text_io.h"

#include <stdlib.h>

char *test_material_text(check_state *st, const char *path, const char *assignments)
{
    char *text = NULL, *out = NULL;
    wff_error e;
    if (wff_read_text_file(path, "material", 1 << 20, &text, &e)) {
        CHECK(st, 0, "%s", e.message);
        return NULL;
    }
    if (!assignments[0])
        return text;
    int rc = wff_material_text_set(text, path, assignments, "test", &out, &e);
    CHECK(st, rc == 0, "%s: %s", assignments, e.message);
    free(text);
    return rc ? NULL : out;
}

/* options.c: mesh options from a script's one-line text ("h_min=0.002
 * recombine=1 ..."): size_factor and recombine into wff_mesh_options, every
 * other name=value into the .geo's numbers (include/wovenff/options.h).
 * Knows nothing of gmsh, materials or the solver. */
#include "wovenff/options.h"
#include "wovenff/text_io.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

int wff_mesh_options_parse(const char *text, wff_mesh_options *opt, wff_error *err)
{
    memset(opt, 0, sizeof *opt);
    const char *p = text;
    while (*p) {
        while (*p == ' ' || *p == '\t' || *p == ',' || *p == ';')
            p++;
        if (!*p)
            break;
        const char *eq = strchr(p, '=');
        size_t len = strcspn(p, " \t,;");
        if (!eq || (size_t)(eq - p) >= len)
            return wff_fail(err, "mesh settings '%s': expected name=value at '%.*s'", text,
                            (int)len, p);
        char name[WFF_MESH_NAME_MAX];
        size_t nlen = (size_t)(eq - p);
        if (nlen == 0 || nlen >= sizeof name)
            return wff_fail(err, "mesh settings '%s': bad name at '%.*s'", text, (int)len, p);
        memcpy(name, p, nlen);
        name[nlen] = '\0';
        double value = 0;
        if (wff_parse_decimal(eq + 1, p + len, &value))
            return wff_fail(err, "mesh settings: '%s' needs a number, got '%.*s'", name,
                            (int)(len - nlen - 1), eq + 1);
        if (strcmp(name, "size_factor") == 0) {
            if (!(value > 0))
                return wff_fail(err, "mesh settings: size_factor = %g must be > 0", value);
            opt->size_factor = value;
        } else if (strcmp(name, "recombine") == 0) {
            opt->recombine = value != 0;
        } else if (strcmp(name, "vertex_only") == 0) { /* elements meeting at a vertex */
            opt->allow_vertex_only = value != 0;
        } else {
            if (opt->n_settings >= WFF_MESH_SETTINGS_MAX)
                return wff_fail(err, "mesh settings: more than %d numbers", WFF_MESH_SETTINGS_MAX);
            wff_mesh_setting *s = &opt->settings[opt->n_settings++];
            memcpy(s->name, name, nlen + 1);
            s->value = value;
        }
        p += len;
    }
    return 0;
}

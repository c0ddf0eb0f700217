/* Material files: `key = value` lines, `#` comments, SI units.
 * The reader keeps each key with its line so that every error can name the
 * file, the line and the key. */
#include "wovenff/material.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Largest material file read, with the reason: a material is a page of text;
 * anything larger is not a material file. */
#define WFF_MATERIAL_FILE_MAX (64 * 1024)

static char *trim(char *s)
{
    while (isspace((unsigned char)*s))
        s++;
    char *end = s + strlen(s);
    while (end > s && isspace((unsigned char)end[-1]))
        *--end = '\0';
    return s;
}

static wff_kv_entry *kv_lookup(wff_kv *kv, const char *key)
{
    for (int i = 0; i < kv->n; i++)
        if (strcmp(kv->entry[i].key, key) == 0)
            return &kv->entry[i];
    return NULL;
}

/* Split text into entries; rejects syntax errors and duplicates. */
static int kv_read(const char *text, wff_kv *kv, wff_error *err)
{
    kv->n = 0;
    int line_no = 0;
    const char *p = text;
    while (*p) {
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        line_no++;
        char line[256];
        if (len >= sizeof line)
            return wff_fail(err, "%s:%d: line too long (%zu characters; at most %zu)",
                            kv->source, line_no, len, sizeof line - 1);
        memcpy(line, p, len);
        line[len] = '\0';
        p += len + (eol ? 1 : 0);

        char *hash = strchr(line, '#');
        if (hash)
            *hash = '\0';
        char *body = trim(line);
        if (*body == '\0')
            continue;
        char *eq = strchr(body, '=');
        if (!eq)
            return wff_fail(err, "%s:%d: expected 'key = value', got '%s'", kv->source,
                            line_no, body);
        *eq = '\0';
        char *key = trim(body), *value = trim(eq + 1);
        if (*key == '\0')
            return wff_fail(err, "%s:%d: missing key before '='", kv->source, line_no);
        for (const char *c = key; *c; c++)
            if (!(isalnum((unsigned char)*c) || *c == '_'))
                return wff_fail(err, "%s:%d: key '%s' has a character other than letters, "
                                "digits and '_'", kv->source, line_no, key);
        if (*value == '\0')
            return wff_fail(err, "%s:%d: key '%s' has no value", kv->source, line_no, key);
        if (strlen(key) >= WFF_KV_KEY_MAX || strlen(value) >= WFF_KV_VALUE_MAX)
            return wff_fail(err, "%s:%d: key '%s': key or value too long", kv->source,
                            line_no, key);
        wff_kv_entry *prev = kv_lookup(kv, key);
        if (prev)
            return wff_fail(err, "%s:%d: duplicate key '%s' (first given on line %d)",
                            kv->source, line_no, key, prev->line);
        if (kv->n >= WFF_KV_MAX)
            return wff_fail(err, "%s:%d: more than %d keys", kv->source, line_no, WFF_KV_MAX);
        wff_kv_entry *e = &kv->entry[kv->n++];
        snprintf(e->key, sizeof e->key, "%s", key);
        snprintf(e->value, sizeof e->value, "%s", value);
        e->line = line_no;
        e->used = 0;
    }
    return 0;
}

static int parse_number(const wff_kv *kv, const wff_kv_entry *e, double *value, wff_error *err)
{
    char *end;
    errno = 0;
    double v = strtod(e->value, &end);
    if (end == e->value || *trim(end) != '\0')
        return wff_fail(err, "%s:%d: key '%s': '%s' is not a number", kv->source, e->line,
                        e->key, e->value);
    if (errno == ERANGE || !isfinite(v))
        return wff_fail(err, "%s:%d: key '%s': '%s' is not a finite number", kv->source,
                        e->line, e->key, e->value);
    *value = v;
    return 0;
}

int wff_kv_number(wff_kv *kv, const char *key, double *value, wff_error *err)
{
    wff_kv_entry *e = kv_lookup(kv, key);
    if (!e)
        return wff_fail(err, "%s: missing key '%s'", kv->source, key);
    e->used = 1;
    return parse_number(kv, e, value, err);
}

int wff_kv_number_or(wff_kv *kv, const char *key, double fallback, double *value,
                     wff_error *err)
{
    wff_kv_entry *e = kv_lookup(kv, key);
    if (!e) {
        *value = fallback;
        return 0;
    }
    e->used = 1;
    return parse_number(kv, e, value, err);
}

int wff_kv_reject(const wff_kv *kv, const char *key, wff_error *err, const char *format, ...)
{
    char why[WFF_ERROR_MAX];
    va_list args;
    va_start(args, format);
    vsnprintf(why, sizeof why, format, args);
    va_end(args);
    for (int i = 0; i < kv->n; i++)
        if (strcmp(kv->entry[i].key, key) == 0)
            return wff_fail(err, "%s:%d: key '%s' = %s: %s", kv->source, kv->entry[i].line,
                            key, kv->entry[i].value, why);
    return wff_fail(err, "%s: key '%s': %s", kv->source, key, why);
}

int wff_material_parse_text(const char *text, const char *source_name, wff_material *mat,
                            wff_error *err)
{
    wff_kv kv;
    kv.source = source_name;
    memset(mat, 0, sizeof *mat);
    snprintf(mat->source, sizeof mat->source, "%s", source_name);
    if (kv_read(text, &kv, err))
        return -1;

    wff_kv_entry *cell = kv_lookup(&kv, "cell");
    if (!cell)
        return wff_fail(err, "%s: missing key 'cell' (the unit-cell name, e.g. cell = %s)",
                        source_name, wff_cell_count() ? wff_cell_at(0)->name : "?");
    cell->used = 1;
    mat->cell = wff_cell_find(cell->value);
    if (!mat->cell) {
        char known[256] = "";
        for (int i = 0; i < wff_cell_count(); i++) {
            size_t used = strlen(known);
            snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "",
                     wff_cell_at(i)->name);
        }
        return wff_fail(err, "%s:%d: key 'cell': unknown unit cell '%s' (known: %s)",
                        source_name, cell->line, cell->value, known);
    }
    if (wff_kv_number(&kv, "rho_A", &mat->areal_density, err))
        return -1;
    if (!(mat->areal_density > 0))
        return wff_kv_reject(&kv, "rho_A", err, "areal density must be > 0 kg/m^2");
    if (mat->cell->parse(&kv, mat, err))
        return -1;
    for (int i = 0; i < kv.n; i++)
        if (!kv.entry[i].used)
            return wff_fail(err, "%s:%d: unknown key '%s' for cell '%s'", source_name,
                            kv.entry[i].line, kv.entry[i].key, mat->cell->name);
    return 0;
}

int wff_material_load(const char *path, wff_material *mat, wff_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return wff_fail(err, "%s: cannot open material file: %s", path, strerror(errno));
    char *text = malloc(WFF_MATERIAL_FILE_MAX + 1);
    if (!text) {
        fclose(f);
        return wff_fail(err, "%s: out of memory", path);
    }
    size_t n = fread(text, 1, WFF_MATERIAL_FILE_MAX + 1, f);
    int read_error = ferror(f);
    fclose(f);
    int rc;
    if (read_error)
        rc = wff_fail(err, "%s: read error", path);
    else if (n > WFF_MATERIAL_FILE_MAX)
        rc = wff_fail(err, "%s: larger than %d bytes: not a material file", path,
                      WFF_MATERIAL_FILE_MAX);
    else if (memchr(text, '\0', n))
        rc = wff_fail(err, "%s: contains a NUL byte: not a text file", path);
    else {
        text[n] = '\0';
        rc = wff_material_parse_text(text, path, mat, err);
    }
    free(text);
    return rc;
}

/* Replace the value on the line of `key` (keeping its comment); -1 if absent. */
static int replace_value(char *text, size_t size, const char *key, const char *value)
{
    size_t klen = strlen(key);
    for (char *line = text; line && *line; line = strchr(line, '\n') ? strchr(line, '\n') + 1 : NULL) {
        char *p = line;
        while (*p == ' ' || *p == '\t')
            p++;
        if (strncmp(p, key, klen) != 0)
            continue;
        char *q = p + klen;
        while (*q == ' ' || *q == '\t')
            q++;
        if (*q != '=')
            continue;
        char *v = q + 1;
        char *end = v + strcspn(v, "#\n");
        char *rest = end; /* the comment and the line end stay */
        char replacement[WFF_KV_VALUE_MAX + 4];
        snprintf(replacement, sizeof replacement, " %s ", value);
        size_t old_len = (size_t)(rest - v), new_len = strlen(replacement);
        size_t tail = strlen(rest) + 1;
        if (strlen(text) + new_len - old_len + 1 > size)
            return -2;
        memmove(v + new_len, rest, tail);
        memcpy(v, replacement, new_len);
        return 0;
    }
    return -1;
}

int wff_material_override(const char *path, const char *overrides, const char *out_path,
                          wff_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return wff_fail(err, "%s: cannot open material file: %s", path, strerror(errno));
    size_t size = WFF_MATERIAL_FILE_MAX + 4096;
    char *text = calloc(1, size);
    if (!text) {
        fclose(f);
        return wff_fail(err, "%s: out of memory", path);
    }
    size_t n = fread(text, 1, WFF_MATERIAL_FILE_MAX, f);
    fclose(f);
    text[n] = '\0';
    int rc = 0;
    const char *p = overrides;
    while (rc == 0 && *p) {
        while (*p == ',' || *p == ' ' || *p == ';')
            p++;
        if (!*p)
            break;
        size_t len = strcspn(p, ",; ");
        char item[WFF_KV_KEY_MAX + WFF_KV_VALUE_MAX + 2];
        if (len >= sizeof item) {
            rc = wff_fail(err, "override '%.*s' is too long", (int)len, p);
            break;
        }
        memcpy(item, p, len);
        item[len] = '\0';
        p += len;
        char *eq = strchr(item, '=');
        if (!eq || eq == item || !eq[1]) {
            rc = wff_fail(err, "override '%s': expected key=value", item);
            break;
        }
        *eq = '\0';
        int r = replace_value(text, size, item, eq + 1);
        if (r == -1)
            rc = wff_fail(err, "override '%s=%s': %s has no key '%s'", item, eq + 1, path, item);
        else if (r == -2)
            rc = wff_fail(err, "override '%s': material text too long", item);
    }
    wff_material check;
    if (rc == 0) {
        char source[600];
        snprintf(source, sizeof source, "%s with %s", path, overrides);
        rc = wff_material_parse_text(text, source, &check, err);
    }
    if (rc == 0) {
        char tmp[1100];
        snprintf(tmp, sizeof tmp, "%s.tmp", out_path);
        FILE *o = fopen(tmp, "wb");
        if (!o)
            rc = wff_fail(err, "%s: cannot write: %s", tmp, strerror(errno));
        else {
            fprintf(o, "# %s with %s\n%s", path, overrides, text);
            if (fclose(o) != 0 || rename(tmp, out_path) != 0)
                rc = wff_fail(err, "%s: cannot write: %s", out_path, strerror(errno));
        }
    }
    free(text);
    return rc;
}

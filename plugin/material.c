/* material.c: material files (`key = value` lines, `#` comments, SI units):
 * the reader, which keeps each key with its line so that every error can name
 * the file, the line and the key, and the one editor of material text (find
 * a key's value, replace values, list keys) that overrides, the fit and the
 * FreeFEM binding use. Knows the cell registry and the cells' parse(), nothing
 * of meshes, elements or the solver. */
#include "wovenff/material.h"
#include "wovenff/text_io.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    int why = wff_parse_decimal(e->value, e->value + strlen(e->value), value);
    if (why == WFF_NUMBER_SYNTAX)
        return wff_fail(err, "%s:%d: key '%s': '%s' is not a number (decimal: digits, one "
                        "point, an optional exponent, e.g. 1.25e-3)", kv->source, e->line,
                        e->key, e->value);
    if (why)
        return wff_fail(err, "%s:%d: key '%s': '%s' is not a finite number (beyond the range "
                        "of a double)", kv->source, e->line, e->key, e->value);
    return 0;
}

/* Remember that the cell asked for key (a key it knows). */
static void kv_asked(wff_kv *kv, const char *key)
{
    for (int i = 0; i < kv->n_asked; i++)
        if (strcmp(kv->asked[i], key) == 0)
            return;
    if (kv->n_asked < WFF_KV_MAX)
        snprintf(kv->asked[kv->n_asked++], WFF_KV_KEY_MAX, "%s", key);
}

static int kv_was_asked(const wff_kv *kv, const char *key)
{
    for (int i = 0; i < kv->n_asked; i++)
        if (strcmp(kv->asked[i], key) == 0)
            return 1;
    return 0;
}

int wff_kv_number(wff_kv *kv, const char *key, double *value, wff_error *err)
{
    kv_asked(kv, key);
    wff_kv_entry *e = kv_lookup(kv, key);
    if (!e) {
        if (!kv->missing[0])
            snprintf(kv->missing, sizeof kv->missing, "%s", key);
        return wff_fail(err, "%s: missing key '%s'", kv->source, key);
    }
    e->used = 1;
    return parse_number(kv, e, value, err);
}

int wff_kv_number_or(wff_kv *kv, const char *key, double fallback, double *value,
                     wff_error *err)
{
    kv_asked(kv, key);
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

/* ---- unknown keys named with the known key nearest to them ---------------- */

/* Edit distance between two keys in half-edits (optimal string alignment): an
 * insertion, deletion, substitution or swap of neighbours costs 2, a change of
 * case only 1 (k_i for K_I). */
static int key_distance(const char *a, const char *b)
{
    int n = (int)strlen(a), m = (int)strlen(b);
    int d[WFF_KV_KEY_MAX + 1][WFF_KV_KEY_MAX + 1];
    if (n > WFF_KV_KEY_MAX || m > WFF_KV_KEY_MAX)
        return 1000;
    for (int i = 0; i <= n; i++)
        d[i][0] = 2 * i;
    for (int j = 0; j <= m; j++)
        d[0][j] = 2 * j;
    for (int i = 1; i <= n; i++)
        for (int j = 1; j <= m; j++) {
            int cost = a[i - 1] == b[j - 1] ? 0
                       : tolower((unsigned char)a[i - 1]) == tolower((unsigned char)b[j - 1])
                           ? 1
                           : 2;
            int best = d[i - 1][j - 1] + cost;
            if (d[i - 1][j] + 2 < best)
                best = d[i - 1][j] + 2;
            if (d[i][j - 1] + 2 < best)
                best = d[i][j - 1] + 2;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 2 < best)
                best = d[i - 2][j - 2] + 2;
            d[i][j] = best;
        }
    return d[n][m];
}

/* Close enough to be a slip of the keyboard: one edit for keys of up to three
 * characters, two for longer ones (never all of a key). */
static int keys_near(const char *a, const char *b, int distance)
{
    int longer = (int)(strlen(a) > strlen(b) ? strlen(a) : strlen(b));
    return distance < 2 * longer && distance <= (longer <= 3 ? 2 : 4);
}

/* The key the cell asked for that is nearest to `key` and not in the file, or NULL. */
static const char *nearest_known_key(const wff_kv *kv, const char *key)
{
    const char *best = NULL;
    int best_distance = 0;
    for (int i = 0; i < kv->n_asked; i++) {
        const char *known = kv->asked[i];
        if (kv_lookup((wff_kv *)kv, known))
            continue;
        int d = key_distance(key, known);
        if (keys_near(key, known, d) && (!best || d < best_distance)) {
            best = known;
            best_distance = d;
        }
    }
    return best;
}

/* The checks after kv_read: the cell, rho_A, the cell's own keys, unknown keys. */
static int parse_kv(wff_kv *kv, wff_material *mat, wff_error *err)
{
    const char *source_name = kv->source;
    kv_asked(kv, "cell");
    wff_kv_entry *cell_key = kv_lookup(kv, "cell");
    if (!cell_key) {
        snprintf(kv->missing, sizeof kv->missing, "cell");
        return wff_fail(err, "%s: missing key 'cell' (the unit-cell name, e.g. cell = %s)",
                        source_name, wff_cell_count() ? wff_cell_name(wff_cell_at(0)) : "?");
    }
    cell_key->used = 1;
    mat->cell = wff_cell_find(cell_key->value);
    if (!mat->cell) {
        char known[256] = "";
        for (int i = 0; i < wff_cell_count(); i++) {
            size_t used = strlen(known);
            snprintf(known + used, sizeof known - used, "%s%s", i ? ", " : "",
                     wff_cell_name(wff_cell_at(i)));
        }
        return wff_fail(err, "%s:%d: key 'cell': unknown unit cell '%s' (known: %s)",
                        source_name, cell_key->line, cell_key->value, known);
    }
    if (wff_kv_number(kv, "rho_A", &mat->areal_density, err))
        return -1;
    if (!(mat->areal_density > 0))
        return wff_kv_reject(kv, "rho_A", err, "areal density must be > 0 kg/m^2");
    mat->n_state = wff_cell_n_state_max(mat->cell); /* parse may carry fewer (a prefix) */
    if (wff_cell_parse(kv, mat, err))
        return -1;
    if (mat->n_state < 0 || mat->n_state > wff_cell_n_state_max(mat->cell) ||
        wff_cell_n_state_max(mat->cell) > WFF_STATE_MAX)
        return wff_fail(err, "%s: cell '%s' set %d internal states per point (at most "
                        "n_state_max %d <= WFF_STATE_MAX %d): a bug in the cell",
                        source_name, wff_cell_name(mat->cell), mat->n_state, wff_cell_n_state_max(mat->cell),
                        WFF_STATE_MAX);
    for (int i = 0; i < kv->n; i++) {
        const wff_kv_entry *e = &kv->entry[i];
        if (e->used)
            continue;
        const char *near = nearest_known_key(kv, e->key);
        if (near)
            return wff_fail(err, "%s:%d: unknown key '%s' (line %d) for cell '%s': did you "
                            "mean '%s'?", source_name, e->line, e->key, e->line,
                            wff_cell_name(mat->cell), near);
        return wff_fail(err, "%s:%d: unknown key '%s' for cell '%s'", source_name, e->line,
                        e->key, wff_cell_name(mat->cell));
    }
    return 0;
}

/* After a parse that missed the required key kv->missing: if a key of the file
 * the cell did not ask for is near it, and the file parses past it with that
 * key renamed (the renamed key is not one the cell asks for either), that key
 * is the slip: err names it, its line and the key meant, in place of "missing
 * key". Candidates are tried nearest first. */
static void name_slipped_key(const wff_kv *kv, const wff_material *failed, wff_error *err)
{
    int order[WFF_KV_MAX], distance[WFF_KV_MAX], n = 0;
    for (int i = 0; i < kv->n; i++) {
        const char *key = kv->entry[i].key;
        if (kv_was_asked(kv, key))
            continue;
        int d = key_distance(key, kv->missing);
        if (!keys_near(key, kv->missing, d))
            continue;
        int at = n++;
        for (; at > 0 && distance[at - 1] > d; at--) {
            order[at] = order[at - 1];
            distance[at] = distance[at - 1];
        }
        order[at] = i;
        distance[at] = d;
    }
    if (n == 0)
        return;
    wff_kv *trial = malloc(sizeof *trial);
    wff_material *scratch = malloc(sizeof *scratch);
    for (int c = 0; trial && scratch && c < n; c++) {
        const wff_kv_entry *slip = &kv->entry[order[c]];
        memcpy(trial->entry, kv->entry, sizeof kv->entry);
        trial->source = kv->source;
        trial->n = kv->n;
        trial->n_asked = 0;
        trial->missing[0] = '\0';
        for (int i = 0; i < trial->n; i++)
            trial->entry[i].used = 0;
        snprintf(trial->entry[order[c]].key, WFF_KV_KEY_MAX, "%s", kv->missing);
        memset(scratch, 0, sizeof *scratch);
        wff_error ignored;
        parse_kv(trial, scratch, &ignored);
        if (strcmp(trial->missing, kv->missing) == 0 || kv_was_asked(trial, slip->key))
            continue; /* still missing, or a key the cell takes: not the slip */
        const wff_cell_type *cell = failed->cell ? failed->cell : scratch->cell;
        char needs[120] = "which every material needs";
        if (cell && strcmp(kv->missing, "cell") != 0 && strcmp(kv->missing, "rho_A") != 0)
            snprintf(needs, sizeof needs, "which cell '%s' needs", wff_cell_name(cell));
        wff_fail(err, "%s:%d: unknown key '%s' (line %d): did you mean '%s'? (the file has "
                 "no key '%s', %s)", kv->source, slip->line, slip->key, slip->line,
                 kv->missing, kv->missing, needs);
        break;
    }
    free(trial);
    free(scratch);
}

int wff_material_parse_text(const char *text, const char *source_name, wff_material *mat,
                            wff_error *err)
{
    wff_kv kv;
    kv.source = source_name;
    kv.n_asked = 0;
    kv.missing[0] = '\0';
    memset(mat, 0, sizeof *mat);
    snprintf(mat->source, sizeof mat->source, "%s", source_name);
    if (kv_read(text, &kv, err))
        return -1;
    if (parse_kv(&kv, mat, err) == 0)
        return 0;
    if (kv.missing[0])
        name_slipped_key(&kv, mat, err);
    return -1;
}

int wff_material_load(const char *path, wff_material *mat, wff_error *err)
{
    char *text;
    if (wff_read_text_file(path, "material file", WFF_MATERIAL_FILE_MAX, &text, err))
        return -1;
    int rc = wff_material_parse_text(text, path, mat, err);
    free(text);
    return rc;
}

/* ---- editing material text ------------------------------------------------ */

/* Calls visit for every `key = value` line of text with the key's and the
 * value's spans (blanks and comment excluded) and the 1-based line; stops
 * when visit returns nonzero and returns that. */
typedef int (*key_visitor)(const char *kb, const char *ke, const char *vb, const char *ve,
                           int line, void *data);

static int for_each_key(const char *text, key_visitor visit, void *data)
{
    const char *p = text;
    int line_no = 0;
    while (*p) {
        const char *eol = strchr(p, '\n');
        const char *end = eol ? eol : p + strlen(p);
        line_no++;
        const char *hash = memchr(p, '#', (size_t)(end - p));
        const char *content_end = hash ? hash : end;
        const char *eq = memchr(p, '=', (size_t)(content_end - p));
        if (eq) {
            const char *kb = wff_skip_space(p, eq), *ke = wff_trim_end(kb, eq);
            const char *vb = wff_skip_space(eq + 1, content_end);
            const char *ve = wff_trim_end(vb, content_end);
            int stop = visit(kb, ke, vb, ve, line_no, data);
            if (stop)
                return stop;
        }
        p = eol ? eol + 1 : end;
    }
    return 0;
}

typedef struct key_search {
    const char *key;
    const char *vb, *ve;
    int line;
} key_search;

static int match_key(const char *kb, const char *ke, const char *vb, const char *ve, int line,
                     void *data)
{
    key_search *s = data;
    size_t klen = strlen(s->key);
    if ((size_t)(ke - kb) != klen || memcmp(kb, s->key, klen) != 0)
        return 0;
    s->vb = vb;
    s->ve = ve;
    s->line = line;
    return 1;
}

int wff_material_text_find(const char *text, const char *key, const char **value_begin,
                           const char **value_end, int *line)
{
    key_search s = {key, NULL, NULL, 0};
    if (!for_each_key(text, match_key, &s))
        return 0;
    *value_begin = s.vb;
    *value_end = s.ve;
    *line = s.line;
    return 1;
}

typedef struct key_list { char *buf; size_t cap; } key_list;

static int add_key(const char *kb, const char *ke, const char *vb, const char *ve, int line,
                   void *data)
{
    (void)vb, (void)ve, (void)line;
    key_list *l = data;
    size_t used = strlen(l->buf);
    if (ke > kb && used + 8 < l->cap)
        snprintf(l->buf + used, l->cap - used, "%s%.*s", used ? ", " : "", (int)(ke - kb), kb);
    return 0;
}

void wff_material_text_keys(const char *text, char *buf, size_t cap)
{
    buf[0] = '\0';
    key_list l = {buf, cap};
    for_each_key(text, add_key, &l);
}

int wff_material_text_replace(const char *text, const char *source, int n,
                              const char *const *keys, const char *const *values, char **out,
                              wff_error *err)
{
    *out = NULL;
    /* the spans of the values to replace, in text order */
    typedef struct span { const char *b, *e, *value; } span;
    span sp[WFF_KV_MAX];
    if (n < 0 || n > WFF_KV_MAX)
        return wff_fail(err, "%s: %d values to replace (at most %d)", source, n, WFF_KV_MAX);
    size_t size = strlen(text) + 1;
    for (int i = 0; i < n; i++) {
        int line;
        if (!wff_material_text_find(text, keys[i], &sp[i].b, &sp[i].e, &line)) {
            char known[400];
            wff_material_text_keys(text, known, sizeof known);
            return wff_fail(err, "%s has no key '%s' (its keys: %s)", source, keys[i], known);
        }
        sp[i].value = values[i];
        size += strlen(values[i]);
        for (int j = 0; j < i; j++)
            if (sp[j].b == sp[i].b)
                return wff_fail(err, "%s: key '%s' given twice", source, keys[i]);
    }
    for (int i = 1; i < n; i++) /* insertion sort by position */
        for (int j = i; j > 0 && sp[j].b < sp[j - 1].b; j--) {
            span t = sp[j];
            sp[j] = sp[j - 1];
            sp[j - 1] = t;
        }
    char *edited = malloc(size);
    if (!edited)
        return wff_fail(err, "%s: out of memory", source);
    size_t len = 0;
    const char *p = text;
    for (int i = 0; i <= n; i++) {
        const char *stop = i < n ? sp[i].b : p + strlen(p);
        memcpy(edited + len, p, (size_t)(stop - p));
        len += (size_t)(stop - p);
        if (i < n) {
            size_t vlen = strlen(sp[i].value);
            memcpy(edited + len, sp[i].value, vlen);
            len += vlen;
            p = sp[i].e;
        }
    }
    edited[len] = '\0';
    *out = edited;
    return 0;
}

int wff_material_text_set(const char *text, const char *source, const char *assignments,
                          const char *what, char **out, wff_error *err)
{
    char *current = strdup(text);
    if (!current)
        return wff_fail(err, "%s: out of memory", source);
    const char *p = assignments;
    while (*p) {
        while (*p == ',' || *p == ' ' || *p == ';')
            p++;
        if (!*p)
            break;
        size_t len = strcspn(p, ",; ");
        char item[WFF_KV_KEY_MAX + WFF_KV_VALUE_MAX + 2];
        if (len >= sizeof item) {
            free(current);
            return wff_fail(err, "%s '%.*s' is too long", what, (int)len, p);
        }
        memcpy(item, p, len);
        item[len] = '\0';
        p += len;
        char *eq = strchr(item, '=');
        if (!eq || eq == item || !eq[1]) {
            free(current);
            return wff_fail(err, "%s '%s': expected key=value", what, item);
        }
        *eq = '\0';
        const char *key = item, *value = eq + 1;
        char *edited;
        if (wff_material_text_replace(current, source, 1, &key, &value, &edited, err)) {
            char why[WFF_ERROR_MAX];
            snprintf(why, sizeof why, "%s", err ? err->message : "");
            free(current);
            return wff_fail(err, "%s '%s=%s': %s", what, key, value, why);
        }
        free(current);
        current = edited;
    }
    *out = current;
    return 0;
}

int wff_material_override(const char *path, const char *overrides, const char *out_path,
                          wff_error *err)
{
    char *text, *edited = NULL;
    if (wff_read_text_file(path, "material file", WFF_MATERIAL_FILE_MAX, &text, err))
        return -1;
    int rc = wff_material_text_set(text, path, overrides, "override", &edited, err);
    free(text);
    wff_material check;
    char source[600];
    snprintf(source, sizeof source, "%s with %s", path, overrides);
    if (rc == 0)
        rc = wff_material_parse_text(edited, source, &check, err);
    if (rc == 0) {
        wff_text b = {0};
        wff_text_printf(&b, "# %s\n%s", source, edited);
        rc = wff_text_write(&b, out_path, "material file", err);
        free(b.s);
    }
    free(edited);
    return rc;
}

int wff_material_state_index(const wff_material *mat, const char *name)
{
    for (int i = 0; i < mat->n_state; i++)
        if (strcmp(wff_cell_state_name(mat->cell, i), name) == 0)
            return i;
    return -1;
}

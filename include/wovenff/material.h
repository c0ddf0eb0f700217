/* wovenff — material files.
 *
 * Format: plain text, one `key = value` per line, `#` starts a comment (put
 * the unit there), SI units. `cell = NAME` picks the unit cell and
 * `rho_A = ...` (kg/m^2) is common to every cell; all other keys belong to the
 * cell. Unknown, missing, duplicate and non-numeric keys are errors that name
 * the file, the line and the key; so are values the cell finds physically
 * impossible. An unknown key is named with its line and the known key nearest
 * to it (edit distance), before any complaint of a missing key it may stand
 * for: "kevlar.txt:10: unknown key 'k2' (line 10): did you mean 'k_2'?". */
#ifndef WOVENFF_MATERIAL_H
#define WOVENFF_MATERIAL_H

#include <stddef.h>

#include "wovenff/cell.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Limits of the key-value reader, with the reason: a material has a few
 * dozen keys; longer keys or values are a sign of a wrong file. */
#define WFF_KV_MAX 64
#define WFF_KV_KEY_MAX 48
#define WFF_KV_VALUE_MAX 96
/* Largest material file read, with the reason: a material is a page of text;
 * anything larger is not a material file. */
#define WFF_MATERIAL_FILE_MAX (64 * 1024)

typedef struct wff_kv_entry {
    char key[WFF_KV_KEY_MAX];
    char value[WFF_KV_VALUE_MAX];
    int line;   /* 1-based line in the source */
    int used;   /* set when a cell takes the key */
} wff_kv_entry;

struct wff_kv {
    const char *source;  /* file name for messages */
    int n;
    wff_kv_entry entry[WFF_KV_MAX];
    /* What the cell asked for (wff_kv_number, wff_kv_number_or): the keys it
     * knows, and the first required key it did not find; for the messages
     * that name an unknown key with the known key nearest to it. Start them
     * zeroed. */
    int n_asked;
    char asked[WFF_KV_MAX][WFF_KV_KEY_MAX];
    char missing[WFF_KV_KEY_MAX];
};

/* Load and validate a material file. On failure mat is left unusable and err
 * names file, line and key. */
int wff_material_load(const char *path, wff_material *mat, wff_error *err);

/* The same from text in memory; source_name is used in messages. */
int wff_material_parse_text(const char *text, const char *source_name,
                            wff_material *mat, wff_error *err);

/* A material's scales against woven fabrics (plugin/material_scales.c,
 * docs/limits.md "Input checks"), to catch slips of units before a run: the
 * areal density, each family's yarn spacing and each family's stiffness (the
 * stress per width at 1 % stretch over 1 % x rho_A, a wave speed squared)
 * against wide bands of Kevlar-like fabrics and their kin (aramid, UHMWPE,
 * glass, nylon weaves). Returns 0 when each is inside its band or a factor of
 * a few outside; 1 when one is orders of magnitude off: err then says which
 * key, its line and file, the value, how far off and the likely unit
 * ("rho_A = 181 kg/m^2 (line 21 of F) is ~1000x the areal density of
 * Kevlar-like fabrics (0.03-1.5 kg/m^2; ...): given in g/m^2?"); −1 when the
 * file or text is not a valid material (err as wff_material_load's). The
 * reader itself (wff_material_load) does not apply these bands: a model may
 * be any fabric, or none (the tests' light and stiff variants). */
int wff_material_scales(const char *path, wff_error *err);
/* The stiffness the scale check measures, family (0 warp, 1 weft): the cell's
 * stress per width P_kk (N/m) at 1 % stretch of that family alone (amplitudes
 * and state at the reference), over (1 % x rho_A): m^2/s^2, the square of the
 * membrane's tensile wave speed. NaN when the cell cannot evaluate there. Used
 * by the check above and by the Phoenix-Porwal estimate (membrane_limit.h). */
double wff_material_specific_stiffness(const wff_material *mat, int family);
int wff_material_scales_text(const char *text, const char *source, wff_error *err);

/* Write a copy of the material file `path` to `out_path` with some values
 * replaced: overrides is "key=value,key=value" (a key must already be in the
 * file). The copy is validated by loading it, then written atomically (a
 * temporary file, then rename). For switching mechanisms off in a scene
 * ("K_d=0" removes locking) and for fitting. */
int wff_material_override(const char *path, const char *overrides, const char *out_path,
                          wff_error *err);

/* ---- editing material text: the one editor, used by wff_material_override,
 * the fit (fit.h) and the FreeFEM binding. A key is found on a line
 * `key = value`, before any `#` comment. */

/* Where the value of `key` is: [*value_begin, *value_end) without the blanks
 * and the comment around it, on 1-based *line. Returns 1 if found, 0 if not. */
int wff_material_text_find(const char *text, const char *key, const char **value_begin,
                           const char **value_end, int *line);
/* The text's keys, "cell, rho_A, ...", into buf (capacity cap), for messages. */
void wff_material_text_keys(const char *text, char *buf, size_t cap);
/* *out (malloc'ed; the caller frees it) = text with the value of keys[i]
 * replaced by the string values[i], i < n (at most WFF_KV_MAX): each key once
 * and already in the text; blanks and the comment around a value are kept.
 * source names the text in messages. */
int wff_material_text_replace(const char *text, const char *source, int n,
                              const char *const *keys, const char *const *values, char **out,
                              wff_error *err);
/* The same from a list "key=value,key=value" (items separated by ',', ';' or
 * blanks; applied in order, so a key given twice takes the last value).
 * Messages start with `what` and the item, e.g. "override 'K_x=1': ...". */
int wff_material_text_set(const char *text, const char *source, const char *assignments,
                          const char *what, char **out, wff_error *err);

/* For cells' parse(): take a required number. Missing or non-numeric is an error. */
int wff_kv_number(wff_kv *kv, const char *key, double *value, wff_error *err);
/* Take an optional number; absent means fallback. */
int wff_kv_number_or(wff_kv *kv, const char *key, double fallback, double *value,
                     wff_error *err);
/* Report a bad value of key: "FILE:LINE: key 'KEY' = VALUE: <message>". Returns -1. */
int wff_kv_reject(const wff_kv *kv, const char *key, wff_error *err, const char *format, ...)
    __attribute__((format(printf, 4, 5)));

#ifdef __cplusplus
}
#endif
#endif

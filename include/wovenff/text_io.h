/* wovenff — whole files in and out, and JSON text, for every part of the C
 * core that reads or writes a file (materials, fit data and reports,
 * checkpoints) and for the FreeFEM binding.
 *
 * Reading takes a whole file into memory with a size limit (a file larger
 * than the limit is the wrong file). Writing is atomic: the data go to
 * PATH.tmp, every write and the close are checked, the file is fsync'ed and
 * then renamed over PATH, so PATH holds either the old or the new contents,
 * never a part. Errors name the file, say what it was for ("material file",
 * "checkpoint", ...) and give strerror. Knows nothing of materials, meshes or
 * the solver. */
#ifndef WOVENFF_TEXT_IO_H
#define WOVENFF_TEXT_IO_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "wovenff/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Every input is a regular file: a named pipe (or a shell's <(...), or a
 * folder, a device) is refused, naming the path and what it is, before it is
 * read (a pipe would wait for ever for a writer, and what it gives can be read
 * only once: a second read of the same path would find it empty).
 * wff_open_regular opens path for reading ("rb") so, without waiting on a pipe
 * (NULL and err on failure); wff_regular_file_check only looks (stat), for a
 * path another library opens (gmsh). */
FILE *wff_open_regular(const char *path, const char *what, wff_error *err);
int wff_regular_file_check(const char *path, const char *what, wff_error *err);

/* The whole file at path into *data (malloc'ed, with a terminating '\0' after
 * the *size bytes; the caller frees it). `what` names the file in messages,
 * e.g. "checkpoint". Fails for a file larger than max bytes, and for what is
 * not a regular file (wff_open_regular). */
int wff_read_file(const char *path, const char *what, size_t max, char **data, size_t *size,
                  wff_error *err);
/* The same for a text file: also fails if it contains a NUL byte. */
int wff_read_text_file(const char *path, const char *what, size_t max, char **text,
                       wff_error *err);

/* An atomic write in pieces: open, write (any number of times), commit. A
 * failed write is remembered and reported by commit; commit removes the
 * temporary file on any failure. */
typedef struct wff_atomic_file {
    FILE *file;
    const char *what;
    char path[4096], tmp[4100];
    int failed, saved_errno;
} wff_atomic_file;

int wff_atomic_open(wff_atomic_file *af, const char *path, const char *what, wff_error *err);
void wff_atomic_write(wff_atomic_file *af, const void *data, size_t size);
int wff_atomic_commit(wff_atomic_file *af, wff_error *err);
/* Open, write size bytes, commit. */
int wff_write_file(const char *path, const char *what, const void *data, size_t size,
                   wff_error *err);

/* A growable text buffer for writers that build a file in memory: appends
 * stop (failed = 1) when memory runs out. Start it as {0}; free(b.s). */
typedef struct wff_text {
    char *s;
    size_t len, cap;
    int failed;
} wff_text;

void wff_text_printf(wff_text *b, const char *format, ...) __attribute__((format(printf, 2, 3)));
/* A JSON string: quotes, \" and \\ escaped, control characters as \u00XX. */
void wff_text_json_string(wff_text *b, const char *s);
/* A JSON number with 10 significant digits; null for NaN and infinities. */
void wff_text_json_number(wff_text *b, double v);
/* `lead` as it is (e.g. ", \"ssr\": "), then v as a JSON number. */
void wff_text_json_member(wff_text *b, const char *lead, double v);
/* Write the buffer's text to path atomically; an out-of-memory buffer is an
 * error naming path. */
int wff_text_write(const wff_text *b, const char *path, const char *what, wff_error *err);

/* The one number grammar of every text input (material files, mesh settings,
 * fit data; the scenes' options follow the same rule in wff_args.idp):
 * decimal only, no blanks: an optional sign, digits with at most one point
 * (at least one digit), an optional exponent e|E[sign]digits. "0x10", "inf",
 * "nan", "1,5" are not numbers. wff_number_grammar is 1 if [begin, end) is one.
 * wff_parse_decimal also rejects a value that overflows or underflows a double
 * (strtod's ERANGE: "1e400", "1e-400"): 0, WFF_NUMBER_SYNTAX or WFF_NUMBER_RANGE. */
enum { WFF_NUMBER_SYNTAX = -1, WFF_NUMBER_RANGE = -2 };
int wff_number_grammar(const char *begin, const char *end);
int wff_parse_decimal(const char *begin, const char *end, double *value);

/* Text spans [begin, end) of a line being read: the first non-blank from p,
 * the end with trailing blanks dropped, and a number spanning exactly the
 * span (wff_parse_decimal; -1 if it is not one or is out of range). */
const char *wff_skip_space(const char *p, const char *end);
const char *wff_trim_end(const char *begin, const char *end);
int wff_parse_number_span(const char *begin, const char *end, double *value);

/* 64-bit FNV-1a of `size` bytes, continuing from hash h (start with
 * WFF_FNV_START): the checksums and fingerprints of checkpoints and results
 * files. */
#define WFF_FNV_START 0xcbf29ce484222325ULL
static inline uint64_t wff_fnv1a(uint64_t h, const void *data, size_t size)
{
    const unsigned char *b = (const unsigned char *)data;
    for (size_t i = 0; i < size; i++) {
        h ^= b[i];
        h *= 0x100000001b3ULL;
    }
    return h;
}

#ifdef __cplusplus
}
#endif
#endif

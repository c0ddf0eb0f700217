/* A fresh folder for a C test's files: under $WFF_TEST_TMP (make test sets
 * it and removes it afterwards), else under /tmp. */
#ifndef WFF_TEST_TMP_H
#define WFF_TEST_TMP_H

#include <stddef.h>

/* Make dir = $WFF_TEST_TMP/NAME_XXXXXX (or /tmp/wff_NAME_XXXXXX) with
 * mkdtemp. Returns 0, or prints why and returns -1. */
int test_tmp_dir(const char *name, char *dir, size_t size);
/* out = dir/name; returns out. */
char *test_tmp_path(const char *dir, const char *name, char *out, size_t size);
/* Copy text file src to dst with every line that starts with `prefix` replaced
 * by `line` (which ends with its newline). Returns the lines replaced (0: none,
 * the copy made all the same), -1 if a file cannot be read or written. */
int test_tmp_copy_replacing(const char *src, const char *dst, const char *prefix,
                            const char *line);
/* Remove dir and everything in it. */
void test_tmp_remove(const char *dir);
#endif

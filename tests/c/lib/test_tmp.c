/* Temporary folders for the C tests (see test_tmp.h). */
#define _GNU_SOURCE /* nftw, mkdtemp */
#include "test_tmp.h"

#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int test_tmp_dir(const char *name, char *dir, size_t size)
{
    const char *base = getenv("WFF_TEST_TMP");
    int n = base && *base ? snprintf(dir, size, "%s/%s_XXXXXX", base, name)
                          : snprintf(dir, size, "/tmp/wff_%s_XXXXXX", name);
    if (n < 0 || (size_t)n >= size) {
        fprintf(stderr, "temporary folder name for %s too long\n", name);
        return -1;
    }
    if (!mkdtemp(dir)) {
        perror(dir);
        return -1;
    }
    return 0;
}

char *test_tmp_path(const char *dir, const char *name, char *out, size_t size)
{
    snprintf(out, size, "%s/%s", dir, name);
    return out;
}

static int remove_entry(const char *path, const struct stat *sb, int flag, struct FTW *ftw)
{
    (void)sb, (void)flag, (void)ftw;
    return remove(path);
}

void test_tmp_remove(const char *dir)
{
    nftw(dir, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

int test_tmp_copy_replacing(const char *src, const char *dst, const char *prefix,
                            const char *line)
{
    FILE *in = fopen(src, "r"), *out = in ? fopen(dst, "w") : NULL;
    if (!in || !out) {
        if (in)
            fclose(in);
        return -1;
    }
    char text[4096];
    int replaced = 0;
    const size_t n = strlen(prefix);
    while (fgets(text, sizeof text, in)) {
        if (strncmp(text, prefix, n) == 0) {
            fputs(line, out);
            replaced++;
        } else
            fputs(text, out);
    }
    int bad = ferror(in);
    fclose(in);
    if (fclose(out) || bad)
        return -1;
    return replaced;
}

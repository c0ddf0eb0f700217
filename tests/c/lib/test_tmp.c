/* Temporary folders for the C tests (see test_tmp.h). */
#define _GNU_SOURCE /* nftw, mkdtemp */
#include "test_tmp.h"

#include <ftw.h>
#include <stdio.h>
#include <stdlib.h>
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

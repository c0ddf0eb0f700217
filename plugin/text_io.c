/* text_io.c: read a whole file with a size limit, write a file atomically
 * (PATH.tmp, checked writes and close, fsync, rename), and a growable text
 * buffer with JSON strings and numbers. See include/wovenff/text_io.h.
 * Knows nothing of what the files hold. */
#include "wovenff/text_io.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

/* What a file of mode `mode` is, for the refusal of what is not a regular file. */
static const char *file_kind(mode_t mode)
{
    if (S_ISDIR(mode))
        return "a folder";
    if (S_ISFIFO(mode))
        return "a pipe (a named pipe, or a shell's <(...))";
    if (S_ISCHR(mode) || S_ISBLK(mode))
        return "a device";
    if (S_ISSOCK(mode))
        return "a socket";
    return "not a regular file";
}

static int refuse_kind(const char *path, const char *what, mode_t mode, wff_error *err)
{
    return wff_fail(err, "%s %s is %s, not a regular file: give a file%s", what, path,
                    file_kind(mode),
                    S_ISFIFO(mode) ? " (a pipe waits for a writer, and what it gives can be "
                                     "read only once)" : "");
}

int wff_regular_file_check(const char *path, const char *what, wff_error *err)
{
    struct stat st;
    if (stat(path, &st) != 0)
        return wff_fail(err, "cannot open %s %s: %s", what, path, strerror(errno));
    if (!S_ISREG(st.st_mode))
        return refuse_kind(path, what, st.st_mode, err);
    return 0;
}

FILE *wff_open_regular(const char *path, const char *what, wff_error *err)
{
    /* O_NONBLOCK: opening a named pipe does not wait for a writer; the mode is
     * checked on the descriptor opened (no window between a stat and the open) */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        wff_fail(err, "cannot open %s %s: %s", what, path, strerror(errno));
        return NULL;
    }
    struct stat st;
    if (fstat(fd, &st) != 0) {
        wff_fail(err, "cannot open %s %s: %s", what, path, strerror(errno));
        close(fd);
        return NULL;
    }
    if (!S_ISREG(st.st_mode)) {
        refuse_kind(path, what, st.st_mode, err);
        close(fd);
        return NULL;
    }
    int flags = fcntl(fd, F_GETFL);
    FILE *in = flags < 0 || fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) != 0 ? NULL
                                                                        : fdopen(fd, "rb");
    if (!in) {
        wff_fail(err, "cannot open %s %s: %s", what, path, strerror(errno));
        close(fd);
    }
    return in;
}

int wff_read_file(const char *path, const char *what, size_t max, char **data, size_t *size,
                  wff_error *err)
{
    *data = NULL;
    *size = 0;
    FILE *in = wff_open_regular(path, what, err);
    if (!in)
        return -1;
    char *buf = NULL;
    size_t used = 0, cap = 0;
    int too_large = 0;
    for (;;) {
        if (used == cap) {
            if (cap > max) {
                too_large = 1;
                break;
            }
            size_t grown_cap = cap ? 2 * cap : 1 << 16;
            if (grown_cap > max + 2)
                grown_cap = max + 2; /* room for max + 1 bytes and the '\0' */
            char *grown = realloc(buf, grown_cap);
            if (!grown) {
                free(buf);
                fclose(in);
                return wff_fail(err, "%s %s: out of memory", what, path);
            }
            buf = grown;
            cap = grown_cap - 1;
        }
        size_t got = fread(buf + used, 1, cap - used, in);
        used += got;
        if (got == 0)
            break;
    }
    int read_error = ferror(in);
    int saved_errno = errno;
    fclose(in);
    if (read_error || too_large || used > max) {
        free(buf);
        if (read_error)
            return wff_fail(err, "cannot read %s %s: %s", what, path, strerror(saved_errno));
        return wff_fail(err, "%s %s is larger than %zu bytes: not a %s", what, path, max, what);
    }
    buf[used] = '\0';
    *data = buf;
    *size = used;
    return 0;
}

int wff_read_text_file(const char *path, const char *what, size_t max, char **text,
                       wff_error *err)
{
    size_t size;
    if (wff_read_file(path, what, max, text, &size, err))
        return -1;
    if (memchr(*text, '\0', size)) {
        free(*text);
        *text = NULL;
        return wff_fail(err, "%s %s contains a NUL byte: not a text file", what, path);
    }
    return 0;
}

int wff_atomic_open(wff_atomic_file *af, const char *path, const char *what, wff_error *err)
{
    memset(af, 0, sizeof *af);
    af->what = what;
    if (snprintf(af->path, sizeof af->path, "%s", path) >= (int)sizeof af->path)
        return wff_fail(err, "%s path too long: %s", what, path);
    snprintf(af->tmp, sizeof af->tmp, "%s.tmp", path);
    af->file = fopen(af->tmp, "wb");
    if (!af->file)
        return wff_fail(err, "cannot write %s %s: %s", what, af->tmp, strerror(errno));
    return 0;
}

void wff_atomic_write(wff_atomic_file *af, const void *data, size_t size)
{
    if (af->failed || size == 0)
        return;
    if (fwrite(data, 1, size, af->file) != size) {
        af->failed = 1;
        af->saved_errno = errno;
    }
}

int wff_atomic_commit(wff_atomic_file *af, wff_error *err)
{
    if (!af->failed && (fflush(af->file) != 0 || fsync(fileno(af->file)) != 0)) {
        af->failed = 1;
        af->saved_errno = errno;
    }
    if (fclose(af->file) != 0 && !af->failed) {
        af->failed = 1;
        af->saved_errno = errno;
    }
    af->file = NULL;
    if (af->failed) {
        remove(af->tmp);
        return wff_fail(err, "cannot write %s %s: %s", af->what, af->tmp,
                        strerror(af->saved_errno));
    }
    if (rename(af->tmp, af->path) != 0) {
        int saved_errno = errno;
        remove(af->tmp);
        return wff_fail(err, "cannot rename %s %s to %s: %s", af->what, af->tmp, af->path,
                        strerror(saved_errno));
    }
    return 0;
}

int wff_write_file(const char *path, const char *what, const void *data, size_t size,
                   wff_error *err)
{
    wff_atomic_file af;
    if (wff_atomic_open(&af, path, what, err))
        return -1;
    wff_atomic_write(&af, data, size);
    return wff_atomic_commit(&af, err);
}

void wff_text_printf(wff_text *b, const char *format, ...)
{
    if (b->failed)
        return;
    for (;;) {
        va_list args;
        va_start(args, format);
        size_t room = b->cap - b->len;
        int n = vsnprintf(b->s ? b->s + b->len : NULL, b->s ? room : 0, format, args);
        va_end(args);
        if (n < 0) {
            b->failed = 1;
            return;
        }
        if (b->s && (size_t)n < room) {
            b->len += (size_t)n;
            return;
        }
        size_t cap = b->cap ? b->cap : 4096;
        while (cap <= b->len + (size_t)n)
            cap *= 2;
        char *s = realloc(b->s, cap);
        if (!s) {
            b->failed = 1;
            return;
        }
        b->s = s;
        b->cap = cap;
    }
}

void wff_text_json_string(wff_text *b, const char *s)
{
    wff_text_printf(b, "\"");
    for (; s && *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            wff_text_printf(b, "\\%c", ch);
        else if (ch < 0x20)
            wff_text_printf(b, "\\u%04x", ch);
        else
            wff_text_printf(b, "%c", ch);
    }
    wff_text_printf(b, "\"");
}

void wff_text_json_number(wff_text *b, double v)
{
    if (isfinite(v))
        wff_text_printf(b, "%.10g", v);
    else
        wff_text_printf(b, "null");
}

void wff_text_json_member(wff_text *b, const char *lead, double v)
{
    wff_text_printf(b, "%s", lead);
    wff_text_json_number(b, v);
}

int wff_text_write(const wff_text *b, const char *path, const char *what, wff_error *err)
{
    if (b->failed)
        return wff_fail(err, "%s %s: out of memory", what, path);
    return wff_write_file(path, what, b->s ? b->s : "", b->len, err);
}

const char *wff_skip_space(const char *p, const char *end)
{
    while (p < end && isspace((unsigned char)*p))
        p++;
    return p;
}

const char *wff_trim_end(const char *begin, const char *end)
{
    while (end > begin && isspace((unsigned char)end[-1]))
        end--;
    return end;
}

int wff_number_grammar(const char *begin, const char *end)
{
    const char *p = begin;
    int digits = 0, points = 0;
    if (p < end && (*p == '+' || *p == '-'))
        p++;
    for (; p < end && (isdigit((unsigned char)*p) || *p == '.'); p++) {
        if (*p == '.')
            points++;
        else
            digits++;
    }
    if (digits == 0 || points > 1)
        return 0;
    if (p < end && (*p == 'e' || *p == 'E')) {
        p++;
        if (p < end && (*p == '+' || *p == '-'))
            p++;
        int exp_digits = 0;
        for (; p < end && isdigit((unsigned char)*p); p++)
            exp_digits++;
        if (exp_digits == 0)
            return 0;
    }
    return p == end;
}

int wff_parse_decimal(const char *begin, const char *end, double *value)
{
    char buf[96];
    size_t len = (size_t)(end - begin);
    if (len == 0 || len >= sizeof buf || !wff_number_grammar(begin, end))
        return WFF_NUMBER_SYNTAX;
    memcpy(buf, begin, len);
    buf[len] = '\0';
    char *stop;
    errno = 0;
    double v = strtod(buf, &stop);
    if (stop != buf + len)
        return WFF_NUMBER_SYNTAX;
    if (errno == ERANGE || !isfinite(v))
        return WFF_NUMBER_RANGE;
    *value = v;
    return 0;
}

int wff_parse_number_span(const char *begin, const char *end, double *value)
{
    return wff_parse_decimal(begin, end, value) ? -1 : 0;
}

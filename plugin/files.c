/* files.c: results files and folders without a shell (include/wovenff/files.h):
 * checked whole-row appends, commits of tool-written files, mkdir -p, rename,
 * copy and removal of trees, line counts and hashes, the run lock, fork/exec.
 * Knows nothing of what the files hold (beyond newlines and the tails of .vtu
 * and .png files), nothing of models or scenes. */
#define _GNU_SOURCE
#include "wovenff/files.h"
#include "wall_clock.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "wovenff/text_io.h"

#define PATH_MAXLEN 4096


uint64_t wff_hash_bytes(const void *data, size_t size) { return wff_fnv1a(WFF_FNV_START, data, size); }

size_t wff_arg_escape(const char *in, int backslash, char *out, size_t size)
{
    size_t n = 0;
    for (const unsigned char *p = (const unsigned char *)in; *p; p++) {
        char esc[5] = {0};
        if (*p == '\\' && backslash)
            memcpy(esc, "\\\\", 2);
        else if (*p == '\t')
            memcpy(esc, "\\t", 2);
        else if (*p == '\n')
            memcpy(esc, "\\n", 2);
        else if (*p == '\r')
            memcpy(esc, "\\r", 2);
        else if (*p < 0x20 || *p == 0x7f)
            snprintf(esc, sizeof esc, "\\x%02x", *p);
        else
            esc[0] = (char)*p;
        for (const char *e = esc; *e; e++, n++)
            if (size > 0 && n < size - 1)
                out[n] = *e;
    }
    if (size > 0)
        out[n < size ? n : size - 1] = '\0';
    return n;
}

static int hex_digit(char c)
{
    return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
                                          : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
}

void wff_arg_unescape(char *s)
{
    char *w = s;
    for (const char *r = s; *r; r++) {
        if (*r != '\\' || !r[1]) {
            *w++ = *r;
            continue;
        }
        char c = r[1];
        if (c == '\\' || c == 't' || c == 'n' || c == 'r') {
            *w++ = c == 't' ? '\t' : c == 'n' ? '\n' : c == 'r' ? '\r' : '\\';
            r++;
        } else if (c == 'x' && hex_digit(r[2]) >= 0 && hex_digit(r[3]) >= 0) {
            *w++ = (char)(hex_digit(r[2]) * 16 + hex_digit(r[3]));
            r += 3;
        } else
            *w++ = *r;
    }
    *w = '\0';
}

int wff_path_check(const char *path, const char *what, wff_error *err)
{
    if (!path[0])
        return wff_fail(err, "%s: an empty path", what);
    for (const unsigned char *p = (const unsigned char *)path; *p; p++)
        if (*p < 0x20 || *p == 0x7f)
            return wff_fail(err, "%s '%s': a path with a control character (newline, tab, ...) "
                            "is refused", what, path);
    if (strlen(path) >= PATH_MAXLEN - 64)
        return wff_fail(err, "%s: path longer than %d characters", what, PATH_MAXLEN - 64);
    return 0;
}

/* write(2) all of it; 0 or -1 with errno (a short write with no errno: EIO... */
static int write_all(int fd, const void *data, size_t size)
{
    const char *p = data;
    while (size > 0) {
        ssize_t n = write(fd, p, size);
        if (n < 0) {
            if (errno == EINTR)
                continue;
            return -1;
        }
        if (n == 0) {
            errno = ENOSPC;
            return -1;
        }
        p += n;
        size -= (size_t)n;
    }
    return 0;
}

int wff_write_whole(const char *path, const void *data, size_t size, wff_error *err)
{
    wff_atomic_file af;
    if (wff_atomic_open(&af, path, "file", err))
        return -1;
    wff_atomic_write(&af, data, size);
    return wff_atomic_commit(&af, err);
}

int wff_append_whole(const char *path, const void *data, size_t size, wff_error *err)
{
    int fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
        return wff_fail(err, "cannot append to %s: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0) {
        int e = errno;
        close(fd);
        return wff_fail(err, "cannot append to %s: %s", path, strerror(e));
    }
    if (write_all(fd, data, size) != 0) {
        int e = errno;
        int cut = ftruncate(fd, st.st_size); /* the row whole or not at all */
        close(fd);
        return wff_fail(err, "cannot write %s: %s%s", path, strerror(e),
                        cut ? " (and the partial row could not be removed)" : "");
    }
    if (close(fd) != 0)
        return wff_fail(err, "cannot write %s: %s", path, strerror(errno));
    return 0;
}

static int ends_with(const char *s, const char *tail)
{
    size_t a = strlen(s), b = strlen(tail);
    return a >= b && strcmp(s + a - b, tail) == 0;
}

/* The last up to 64 bytes of fd (size bytes long) into tail, trailing blanks dropped. */
static size_t read_tail(int fd, off_t size, char *tail)
{
    size_t want = size < 64 ? (size_t)size : 64;
    ssize_t got = pread(fd, tail, want, size - (off_t)want);
    if (got < 0)
        got = 0;
    return (size_t)got;
}

int wff_commit_file(const char *tmp, const char *final, wff_error *err)
{
    int fd = open(tmp, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return wff_fail(err, "cannot write %s: %s was not written (%s)", final, tmp,
                        strerror(errno));
    struct stat st;
    const char *why = NULL;
    int e = 0;
    if (fstat(fd, &st) != 0) {
        e = errno;
        why = "cannot be examined";
    } else if (st.st_size == 0) {
        why = "is empty (the tool that wrote it failed)";
    } else {
        char tail[64];
        size_t n = read_tail(fd, st.st_size, tail);
        while (n > 0 && (tail[n - 1] == '\n' || tail[n - 1] == ' ' || tail[n - 1] == '\r'))
            n--;
        static const char vtk_end[] = "</VTKFile>";
        static const unsigned char png_end[] = {'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};
        if (ends_with(final, ".vtu") || ends_with(final, ".pvd")) {
            if (n < sizeof vtk_end - 1 || memcmp(tail + n - (sizeof vtk_end - 1), vtk_end,
                                                 sizeof vtk_end - 1))
                why = "is incomplete (it does not end with </VTKFile>)";
        } else if (ends_with(final, ".json")) {
            if (n == 0 || tail[n - 1] != '}')
                why = "is incomplete (a JSON file that does not end with })";
        } else if (ends_with(final, ".csv")) {
            n = read_tail(fd, st.st_size, tail);
            if (n == 0 || tail[n - 1] != '\n')
                why = "is incomplete (a CSV file that ends mid-row)";
        } else if (ends_with(final, ".png")) {
            n = read_tail(fd, st.st_size, tail);
            if (n < sizeof png_end || memcmp(tail + n - sizeof png_end, png_end, sizeof png_end))
                why = "is incomplete (no PNG end chunk)";
        }
    }
    if (!why && fsync(fd) != 0) {
        e = errno;
        why = "cannot be synced";
    }
    /* the tool does not say why: a file at the file-size limit, or a full file system */
    char cause[160] = "";
    struct rlimit lim;
    struct statvfs fs;
    if (why && !e) {
        if (getrlimit(RLIMIT_FSIZE, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY &&
            (rlim_t)st.st_size >= lim.rlim_cur / 2)
            snprintf(cause, sizeof cause, " (%s: the file-size limit is %llu bytes)",
                     strerror(EFBIG), (unsigned long long)lim.rlim_cur);
        else if (fstatvfs(fd, &fs) == 0 && fs.f_bavail == 0)
            snprintf(cause, sizeof cause, " (%s)", strerror(ENOSPC));
    }
    close(fd);
    if (why) {
        unlink(tmp);
        return wff_fail(err, "cannot write %s: %s %s%s%s%s", final, tmp, why, e ? ": " : "",
                        e ? strerror(e) : "", cause);
    }
    if (rename(tmp, final) != 0) {
        e = errno;
        unlink(tmp);
        return wff_fail(err, "cannot rename %s to %s: %s", tmp, final, strerror(e));
    }
    return 0;
}

int wff_make_dirs(const char *path, wff_error *err)
{
    char buf[PATH_MAXLEN];
    if (snprintf(buf, sizeof buf, "%s", path) >= (int)sizeof buf)
        return wff_fail(err, "folder path too long: %s", path);
    for (char *p = buf + 1;; p++) {
        if (*p == '/' || *p == '\0') {
            char c = *p;
            *p = '\0';
            if (mkdir(buf, 0755) != 0 && errno != EEXIST)
                return wff_fail(err, "cannot create folder %s: %s", buf, strerror(errno));
            *p = c;
            if (c == '\0')
                break;
        }
    }
    struct stat st;
    if (stat(path, &st) != 0 || !S_ISDIR(st.st_mode))
        return wff_fail(err, "%s is not a folder", path);
    if (access(path, W_OK | X_OK) != 0)
        return wff_fail(err, "folder %s cannot be written: %s", path, strerror(errno));
    return 0;
}

int wff_rename(const char *from, const char *to, wff_error *err)
{
    if (rename(from, to) != 0)
        return wff_fail(err, "cannot rename %s to %s: %s", from, to, strerror(errno));
    return 0;
}

static int remove_one(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st; (void)ftw;
    return (flag == FTW_DP ? rmdir(path) : unlink(path)) != 0 ? -1 : 0;
}

int wff_remove_tree(const char *path, wff_error *err)
{
    struct stat st;
    if (lstat(path, &st) != 0)
        return errno == ENOENT ? 0 : wff_fail(err, "cannot remove %s: %s", path, strerror(errno));
    int rc = S_ISDIR(st.st_mode) ? nftw(path, remove_one, 16, FTW_DEPTH | FTW_PHYS) : unlink(path);
    if (rc != 0)
        return wff_fail(err, "cannot remove %s: %s", path, strerror(errno));
    return 0;
}

/* The next entry of the open folder d (named dir) other than ".", ".." and
 * skip: its path dir/NAME into path; 1, or 0 at the end, -1 (err set) if the
 * path is too long. */
static int next_entry(DIR *d, const char *dir, const char *skip, char path[PATH_MAXLEN],
                      wff_error *err)
{
    struct dirent *e;
    while ((e = readdir(d))) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, "..") ||
            (skip && !strcmp(e->d_name, skip)))
            continue;
        if (snprintf(path, PATH_MAXLEN, "%s/%s", dir, e->d_name) >= PATH_MAXLEN)
            return wff_fail(err, "path too long under %s", dir);
        return 1;
    }
    return 0;
}

int wff_copy_tree(const char *from, const char *to, const char *skip, wff_error *err)
{
    if (wff_make_dirs(to, err))
        return -1;
    DIR *d = opendir(from);
    if (!d)
        return wff_fail(err, "cannot read folder %s: %s", from, strerror(errno));
    int rc = 0, more;
    char src[PATH_MAXLEN], dst[PATH_MAXLEN];
    while (rc == 0 && (more = next_entry(d, from, skip, src, err)) != 0) {
        if (more < 0 ||
            snprintf(dst, sizeof dst, "%s/%s", to, src + strlen(from) + 1) >= (int)sizeof dst) {
            rc = more < 0 ? -1 : wff_fail(err, "path too long under %s", to);
            break;
        }
        struct stat st;
        if (lstat(src, &st) != 0) {
            rc = wff_fail(err, "cannot read %s: %s", src, strerror(errno));
        } else if (S_ISDIR(st.st_mode)) {
            rc = wff_copy_tree(src, dst, NULL, err);
        } else if (S_ISREG(st.st_mode)) {
            char *data;
            size_t size;
            rc = wff_read_file(src, "file", (size_t)1 << 40, &data, &size, err);
            if (rc == 0) {
                rc = wff_write_whole(dst, data, size, err);
                free(data);
            }
        }
    }
    closedir(d);
    return rc;
}

int wff_clear_dir(const char *dir, const char *skip, wff_error *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return wff_fail(err, "cannot read folder %s: %s", dir, strerror(errno));
    int rc = 0, more;
    char path[PATH_MAXLEN];
    while (rc == 0 && (more = next_entry(d, dir, skip, path, err)) != 0)
        rc = more < 0 ? -1 : wff_remove_tree(path, err);
    closedir(d);
    return rc;
}

/* 1 if name is what an atomic write leaves while it writes: NAME.tmp
 * (text_io.c, the commits of tool-written files, gnuplot's pictures) or
 * NAME.tmp.vtu (a VTK frame: FreeFEM's savevtk wants the extension). */
static int is_write_temporary(const char *name)
{
    return ends_with(name, ".tmp") || ends_with(name, ".tmp.vtu");
}

int wff_remove_temporaries(const char *dir, long *removed, wff_error *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return wff_fail(err, "cannot read folder %s: %s", dir, strerror(errno));
    int rc = 0, more;
    char path[PATH_MAXLEN];
    while (rc == 0 && (more = next_entry(d, dir, NULL, path, err)) != 0) {
        struct stat st;
        if (more < 0) {
            rc = -1;
        } else if (lstat(path, &st) != 0) {
            if (errno != ENOENT)
                rc = wff_fail(err, "cannot read %s: %s", path, strerror(errno));
        } else if (S_ISDIR(st.st_mode)) {
            rc = wff_remove_temporaries(path, removed, err);
        } else if (S_ISREG(st.st_mode) && is_write_temporary(strrchr(path, '/') + 1)) {
            if (unlink(path) != 0 && errno != ENOENT)
                rc = wff_fail(err, "cannot remove %s: %s", path, strerror(errno));
            else
                (*removed)++;
        }
    }
    closedir(d);
    return rc;
}

int wff_same_file(const char *a, const char *b)
{
    struct stat sa, sb;
    return stat(a, &sa) == 0 && stat(b, &sb) == 0 && sa.st_dev == sb.st_dev &&
           sa.st_ino == sb.st_ino;
}

int wff_exists(const char *path)
{
    struct stat st;
    return lstat(path, &st) == 0;
}

int wff_dir_entries(const char *dir, const char *skip, long *count, wff_error *err)
{
    *count = 0;
    DIR *d = opendir(dir);
    if (!d)
        return wff_fail(err, "cannot read folder %s: %s", dir, strerror(errno));
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..") && !(skip && !strcmp(e->d_name, skip)))
            (*count)++;
    closedir(d);
    return 0;
}

int wff_file_lines(const char *path, long n, long *lines, uint64_t *hash, char *last,
                   size_t last_size, wff_error *err)
{
    *lines = 0;
    *hash = WFF_FNV_START;
    if (last && last_size)
        last[0] = '\0';
    char *data;
    size_t size;
    if (wff_read_file(path, "file", (size_t)1 << 40, &data, &size, err))
        return -1;
    size_t end = 0, line_start = 0, prev_start = 0;
    for (size_t i = 0; i < size && (n < 0 || *lines < n); i++)
        if (data[i] == '\n') {
            (*lines)++;
            prev_start = line_start;
            line_start = end = i + 1;
        }
    *hash = wff_fnv1a(WFF_FNV_START, data, end);
    if (last && last_size && *lines > 0) {
        size_t len = end - 1 - prev_start;
        if (len >= last_size)
            len = last_size - 1;
        memcpy(last, data + prev_start, len);
        last[len] = '\0';
    }
    free(data);
    return 0;
}

int wff_file_hash(const char *path, uint64_t *hash, wff_error *err)
{
    char *data;
    size_t size;
    if (wff_read_file(path, "file", (size_t)1 << 40, &data, &size, err))
        return -1;
    *hash = wff_fnv1a(WFF_FNV_START, data, size);
    free(data);
    return 0;
}

int wff_cut_lines(const char *path, long n, wff_error *err)
{
    char *data;
    size_t size;
    if (wff_read_file(path, "file", (size_t)1 << 40, &data, &size, err))
        return -1;
    size_t end = 0;
    long lines = 0;
    for (size_t i = 0; i < size && lines < n; i++)
        if (data[i] == '\n') {
            lines++;
            end = i + 1;
        }
    int rc = 0;
    if (lines < n)
        rc = wff_fail(err, "%s has %ld lines, fewer than %ld", path, lines, n);
    else if (end != size)
        rc = wff_write_whole(path, data, end, err);
    free(data);
    return rc;
}

static int lock_path(const char *dir, char *path, size_t size)
{
    return snprintf(path, size, "%s/.wovenff.lock", dir) >= (int)size ? -1 : 0;
}

int wff_lock_take(const char *dir, char *note, size_t note_size, wff_error *err)
{
    char path[PATH_MAXLEN];
    if (note_size)
        note[0] = '\0';
    if (lock_path(dir, path, sizeof path))
        return wff_fail(err, "folder path too long: %s", dir);
    for (int attempt = 0; attempt < 2; attempt++) {
        int fd = open(path, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
        if (fd >= 0) {
            char text[32];
            int len = snprintf(text, sizeof text, "%ld\n", (long)getpid());
            int bad = write_all(fd, text, (size_t)len) != 0;
            int e = errno;
            if (close(fd) != 0 && !bad) {
                bad = 1;
                e = errno;
            }
            if (bad) {
                unlink(path);
                return wff_fail(err, "cannot write the lock %s: %s", path, strerror(e));
            }
            return 0;
        }
        if (errno != EEXIST)
            return wff_fail(err, "cannot create the lock %s: %s", path, strerror(errno));
        char *text = NULL;
        size_t size;
        long pid = 0;
        if (wff_read_file(path, "lock", 64, &text, &size, NULL) == 0) {
            pid = strtol(text, NULL, 10);
            free(text);
        }
        if (pid == (long)getpid())
            return 0; /* ours already */
        if (pid > 0 && (kill((pid_t)pid, 0) == 0 || errno == EPERM))
            return wff_fail(err, "folder %s is in use by another run (process %ld holds %s); "
                            "wait for it, or choose another folder", dir, pid, path);
        /* the holder is gone (killed): take the lock over */
        if (note_size)
            snprintf(note, note_size, "note: %s was left by process %ld, which no longer runs "
                     "(a killed run); taking it over", path, pid);
        if (unlink(path) != 0 && errno != ENOENT)
            return wff_fail(err, "cannot remove the stale lock %s: %s", path, strerror(errno));
    }
    return wff_fail(err, "cannot take the lock of %s (another run took it at the same time)", dir);
}

void wff_lock_release(const char *dir)
{
    char path[PATH_MAXLEN];
    if (lock_path(dir, path, sizeof path))
        return;
    char *text = NULL;
    size_t size;
    if (wff_read_file(path, "lock", 64, &text, &size, NULL) == 0) {
        long pid = strtol(text, NULL, 10);
        free(text);
        if (pid == (long)getpid())
            unlink(path);
    }
}

static int is_executable_file(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode) && access(path, X_OK) == 0;
}

int wff_find_program(const char *name, char *path, size_t size)
{
    if (size > 0)
        path[0] = '\0';
    if (!name[0] || size == 0)
        return 0;
    if (strchr(name, '/')) {
        if (!is_executable_file(name) || strlen(name) >= size)
            return 0;
        memcpy(path, name, strlen(name) + 1);
        return 1;
    }
    const char *dirs = getenv("PATH");
    if (!dirs)
        dirs = "/usr/local/bin:/usr/bin:/bin";
    for (const char *p = dirs;; ) {
        const char *end = strchr(p, ':');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        int n = len == 0 ? snprintf(path, size, "%s", name)
                         : snprintf(path, size, "%.*s/%s", (int)len, p, name);
        if (n > 0 && (size_t)n < size && is_executable_file(path))
            return 1;
        if (!end)
            break;
        p = end + 1;
    }
    path[0] = '\0';
    return 0;
}

int wff_run_program(char *const argv[], int *status, wff_error *err)
{
    long pid;
    *status = -1;
    if (wff_start_program(argv, &pid, err))
        return -1;
    return wff_wait_program(pid, status, err);
}

/* In a child just forked from parent: killed when the parent dies, even by
 * SIGKILL (a picture drawn in the background does not outlive a killed scene
 * to leave its half-written .tmp after a restart has cleared the folder). */
static void die_with_parent(pid_t parent)
{
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) /* it died before the request */
        _exit(127);
}

int wff_start_program(char *const argv[], long *pid, wff_error *err)
{
    *pid = -1;
    fflush(NULL);
    pid_t parent = getpid(), child = fork();
    if (child < 0)
        return wff_fail(err, "cannot start %s: %s", argv[0], strerror(errno));
    if (child == 0) {
        die_with_parent(parent);
        execvp(argv[0], argv);
        fprintf(stderr, "cannot run %s: %s\n", argv[0], strerror(errno));
        _exit(127);
    }
    *pid = (long)child;
    return 0;
}

int wff_wait_program(long pid, int *status, wff_error *err)
{
    *status = -1;
    int ws;
    while (waitpid((pid_t)pid, &ws, 0) < 0)
        if (errno != EINTR)
            return wff_fail(err, "waiting for process %ld: %s", pid, strerror(errno));
    *status = WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + WTERMSIG(ws);
    return 0;
}

/* The child's side of wff_run_logged: stdin /dev/null, stdout and stderr log. */
static void exec_logged(char *const argv[], const char *log)
{
    int in = open("/dev/null", O_RDONLY);
    int out = open(log, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0) {
        fprintf(stderr, "cannot write %s: %s\n", log, strerror(errno));
        _exit(127);
    }
    if (in >= 0) {
        dup2(in, 0);
        close(in);
    }
    dup2(out, 1);
    dup2(out, 2);
    close(out);
    execvp(argv[0], argv);
    fprintf(stderr, "cannot run %s: %s\n", argv[0], strerror(errno));
    _exit(127);
}

static int wait_status(int ws) { return WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + WTERMSIG(ws); }

int wff_run_logged(char *const argv[], const char *log, int *status, wff_error *err)
{
    *status = -1;
    if (!argv[0])
        return wff_fail(err, "no program to run");
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0)
        return wff_fail(err, "cannot start %s: %s", argv[0], strerror(errno));
    if (pid == 0)
        exec_logged(argv, log);
    int ws;
    while (waitpid(pid, &ws, 0) < 0)
        if (errno != EINTR)
            return wff_fail(err, "waiting for %s: %s", argv[0], strerror(errno));
    *status = wait_status(ws);
    return 0;
}

int wff_run_jobs(const char *list, int jobs, int *status, long max, long *count, wff_error *err)
{
    *count = 0;
    char *text;
    if (wff_read_text_file(list, "job list", (size_t)1 << 26, &text, err))
        return -1;
    /* fields in place: tabs and newlines become NULs */
    long n = 0, nfields = 0;
    for (char *p = text; *p; p++)
        if (*p == '\n')
            n++;
    size_t len = strlen(text);
    if (len > 0 && text[len - 1] != '\n')
        n++;
    for (char *p = text; *p; p++)
        if (*p == '\t' || *p == '\n')
            nfields++;
    if (n > max) {
        free(text);
        return wff_fail(err, "%s: %ld jobs, more than the %ld expected", list, n, max);
    }
    char **fields = calloc((size_t)(nfields + 2 * n + 2), sizeof *fields);
    long *start = calloc((size_t)n + 1, sizeof *start);
    pid_t *pids = calloc((size_t)n + 1, sizeof *pids);
    double *t0 = calloc((size_t)n + 1, sizeof *t0);
    if (!fields || !start || !pids || !t0) {
        free(text); free(fields); free(start); free(pids); free(t0);
        return wff_fail(err, "out of memory for %ld jobs", n);
    }
    long f = 0, job = 0;
    char *p = text;
    while (job < n) {
        start[job] = f;
        for (;;) {
            fields[f++] = p;
            while (*p && *p != '\t' && *p != '\n')
                p++;
            char c = *p;
            if (c)
                *p++ = '\0';
            if (c != '\t')
                break;
        }
        fields[f++] = NULL;
        for (long k = start[job]; k < f - 1; k++) /* (each field escaped: wff_arg_escape) */
            wff_arg_unescape(fields[k]);
        if (f - start[job] < 4) {
            int rc = wff_fail(err, "%s line %ld: expected label, log, program and arguments "
                              "separated by tabs", list, job + 1);
            free(text); free(fields); free(start); free(pids); free(t0);
            return rc;
        }
        job++;
    }
    if (jobs < 1)
        jobs = 1;
    long next = 0, running = 0, done = 0;
    int rc = 0;
    for (long j = 0; j < n; j++)
        status[j] = -1;
    fflush(NULL);
    while (done < n) {
        while (running < jobs && next < n) {
            char **job_fields = fields + start[next];
            t0[next] = wff_wall_seconds();
            pid_t pid = fork();
            if (pid < 0) {
                status[next] = 127;
                printf("  [%ld/%ld] %s: failed (cannot start: %s)\n", ++done, n, job_fields[0],
                       strerror(errno));
                fflush(stdout);
                next++;
                continue;
            }
            if (pid == 0)
                exec_logged(job_fields + 2, job_fields[1]);
            pids[next++] = pid;
            running++;
        }
        if (running == 0)
            continue;
        int ws;
        pid_t pid = waitpid(-1, &ws, 0);
        if (pid < 0) {
            if (errno == EINTR)
                continue;
            rc = wff_fail(err, "waiting for the jobs of %s: %s", list, strerror(errno));
            break;
        }
        for (long j = 0; j < next; j++)
            if (pids[j] == pid) {
                pids[j] = 0;
                status[j] = wait_status(ws);
                running--;
                printf("  [%ld/%ld] %s: %s (exit %d), %.1f s\n", ++done, n, fields[start[j]],
                       status[j] == 0 ? "ok" : "failed", status[j], wff_wall_seconds() - t0[j]);
                fflush(stdout);
            }
    }
    *count = n;
    free(text); free(fields); free(start); free(pids); free(t0);
    return rc;
}

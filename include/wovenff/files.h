/* wovenff — results files and folders without a shell: checked appends of
 * whole rows, commits of files a tool wrote, folders, renames, copies and
 * removals of trees, line counts and prefix hashes (for restarts), a run's
 * lock file, and running a program with an argument vector (no shell).
 *
 * Every function returns 0 on success, -1 on failure with a message naming
 * the path and strerror in err. Knows nothing of what the files hold beyond
 * "a line ends with a newline" and the tails of .vtu and .png files. */
#ifndef WOVENFF_FILES_H
#define WOVENFF_FILES_H

#include <stddef.h>
#include <stdint.h>

#include "wovenff/error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A path a user typed: refused (-1) if empty or holding a control character
 * (a newline, tab, ...); `what` names it in the message ("-out"). */
int wff_path_check(const char *path, const char *what, wff_error *err);

/* The whole of data (size bytes) as path: PATH.tmp, checked writes and close,
 * fsync, rename. */
int wff_write_whole(const char *path, const void *data, size_t size, wff_error *err);

/* Append size bytes to path (created if absent) with one checked write; on a
 * short or failed write the file is cut back to its former length, so a row
 * is in the file whole or not at all. */
int wff_append_whole(const char *path, const void *data, size_t size, wff_error *err);

/* A file a tool wrote at tmp: checked to exist, be non-empty and complete
 * (a .vtu/.pvd ends with </VTKFile>, a .png with its IEND chunk, a .json
 * with }, a .csv with a newline), fsync'ed and
 * renamed to final. The tmp file is removed on failure. */
int wff_commit_file(const char *tmp, const char *final, wff_error *err);

/* mkdir -p path, then checks that the folder is writable. */
int wff_make_dirs(const char *path, wff_error *err);
/* rename(2), with the message. */
int wff_rename(const char *from, const char *to, wff_error *err);
/* Remove path: a file, or a folder and everything in it (no symlink is
 * followed). Absent: success. */
int wff_remove_tree(const char *path, wff_error *err);
/* Copy folder from's contents into folder to (made if absent), recursively;
 * every file through wff_write_whole. Entries named skip (NULL: none) at the
 * top level are left out. */
int wff_copy_tree(const char *from, const char *to, const char *skip, wff_error *err);

/* Remove every entry of folder dir but skip (NULL: none). */
int wff_clear_dir(const char *dir, const char *skip, wff_error *err);
/* Remove, in folder dir and its subfolders, every file an interrupted atomic
 * write left (NAME.tmp, NAME.tmp.vtu: a killed or failed run's); *removed
 * counts them (added to). Symbolic links are not followed. */
int wff_remove_temporaries(const char *dir, long *removed, wff_error *err);
/* 1 if a and b are the same file or folder (same device and inode), else 0. */
int wff_same_file(const char *a, const char *b);

/* 1 if path exists (any kind), 0 if not. */
int wff_exists(const char *path);
/* Folder dir's entries other than "." ".." and skip (NULL: none), counted. */
int wff_dir_entries(const char *dir, const char *skip, long *count, wff_error *err);

/* The first n complete lines of path (n < 0: all complete lines): their
 * number in *lines, the FNV-1a hash of their bytes in *hash, and line number
 * *lines (1-based; the last counted) in last (up to last_size - 1 bytes, no
 * newline; last may be NULL). Fails if the file cannot be read; fewer than n
 * lines is not an error (*lines says so). */
int wff_file_lines(const char *path, long n, long *lines, uint64_t *hash, char *last,
                   size_t last_size, wff_error *err);
/* Cut path back to its first n lines (atomically); no-op if it is exactly
 * those already. Fails if it has fewer. */
int wff_cut_lines(const char *path, long n, wff_error *err);
/* FNV-1a hash of a file's bytes. */
int wff_file_hash(const char *path, uint64_t *hash, wff_error *err);
/* FNV-1a hash of size bytes. */
uint64_t wff_hash_bytes(const void *data, size_t size);

/* Take folder dir's lock (dir/.wovenff.lock holding our pid, made with
 * O_EXCL). A lock of a process that no longer exists is taken over (note
 * says so, else note is ""); a live one: -1 naming its pid. */
int wff_lock_take(const char *dir, char *note, size_t note_size, wff_error *err);
/* Remove dir's lock if it holds our pid. */
void wff_lock_release(const char *dir);

/* Run argv[0] (searched in PATH) with argv, no shell, and wait: its exit code
 * in *status (128 + signal if killed). -1 if it could not be started. */
int wff_run_program(char *const argv[], int *status, wff_error *err);

/* Start argv[0] (searched in PATH) with argv, no shell, without waiting: its
 * process id in *pid; wff_wait_program(pid) waits for it and gives its exit
 * code as wff_run_program does. -1 if it could not be started / waited for. */
int wff_start_program(char *const argv[], long *pid, wff_error *err);
int wff_wait_program(long pid, int *status, wff_error *err);

/* The same with its stdin from /dev/null and its stdout and stderr into log
 * (created or truncated; opened by the child: a log that cannot be opened
 * gives status 127). */
int wff_run_logged(char *const argv[], const char *log, int *status, wff_error *err);

/* The program `name` as execvp would find it: name itself if it holds a '/'
 * and is an executable file, else the first executable regular file
 * DIR/name of the PATH environment variable's folders (an empty entry: the
 * working folder). Its path into path (size bytes with the NUL); 1 found, 0
 * not (path ""). */
int wff_find_program(const char *name, char *path, size_t size);

/* A value as one field of a job list or an argument line (wff_run_jobs,
 * wovenffRun): a backslash, a tab, a newline, a carriage return and any other
 * control character escaped (\\ \t \n \r \xHH), so no value splits into
 * fields or lines nobody gave; with backslash 0 only the control characters
 * (a value shown in a message). Writes at most size bytes with its NUL;
 * returns the length the whole escaped text needs (as snprintf). */
size_t wff_arg_escape(const char *in, int backslash, char *out, size_t size);

/* Undo wff_arg_escape(…, 1, …) in place (an unknown escape is kept as is). */
void wff_arg_unescape(char *s);

/* Run the jobs of the text file list, at most `jobs` at once, no shell. One
 * job a line: label, log file, then the program and its arguments, fields
 * separated by tabs, each field escaped by wff_arg_escape (its tabs, newlines
 * and backslashes: a value is data, never split again) and unescaped here. Each
 * job runs as wff_run_logged; as each ends a progress line
 * "  [done/total] label: ok|failed (exit N), S s" goes to stdout. The exit
 * codes in status[0..] (max entries at most; 128 + signal if killed, 127 not
 * started) in the list's order; *count the number of jobs. -1 on a list that
 * cannot be read, a line without a program, more than max jobs. */
int wff_run_jobs(const char *list, int jobs, int *status, long max, long *count, wff_error *err);

#ifdef __cplusplus
}
#endif
#endif

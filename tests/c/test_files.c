/* test_files: plugin/files.c — a row appended whole or not at all under a
 * file-size limit, commits of incomplete tool files refused, prefix hashes and
 * cut-back of line files, the run lock (ours, a live holder, a stale one), a
 * path with a control character refused, a tree copied and removed, a program
 * run without a shell. */
#define _GNU_SOURCE
#include "check.h"
#include "test_tmp.h"
#include "wovenff/files.h"
#include "wovenff/text_io.h"

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static long file_size(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 ? (long)st.st_size : -1;
}

static void put(const char *path, const char *text)
{
    FILE *f = fopen(path, "wb");
    fputs(text, f);
    fclose(f);
}

int main(void)
{
    check_state st = {0, 0};
    char dir[512], a[600], b[600], c[600];
    wff_error err;
    if (test_tmp_dir("files", dir, sizeof dir))
        return 1;

    /* rows under a file-size limit: whole or not at all, the error says why */
    test_tmp_path(dir, "rows.csv", a, sizeof a);
    pid_t pid = fork();
    if (pid == 0) {
        signal(SIGXFSZ, SIG_IGN);
        struct rlimit lim = {1000, 1000};
        setrlimit(RLIMIT_FSIZE, &lim);
        char row[64];
        memset(row, 'x', 29);
        row[29] = '\n';
        int i = 0;
        while (wff_append_whole(a, row, 30, &err) == 0 && i < 100)
            i++;
        /* 33 rows of 30 bytes fit in 1000; the 34th fails and is cut back */
        _exit(i == 33 && strstr(err.message, "File too large") ? 0 : 1);
    }
    int ws;
    waitpid(pid, &ws, 0);
    CHECK(&st, WIFEXITED(ws) && WEXITSTATUS(ws) == 0, "append under a limit: child status %d", ws);
    CHECK(&st, file_size(a) == 990, "rows file is %ld bytes, want 990 (33 whole rows)", file_size(a));

    /* line counts, prefix hashes, cut back */
    long lines;
    uint64_t h1, h2;
    char last[64];
    CHECK(&st, wff_file_lines(a, 10, &lines, &h1, last, sizeof last, &err) == 0 && lines == 10,
          "10 lines: %ld", lines);
    CHECK(&st, strlen(last) == 29, "line 10 is %zu characters", strlen(last));
    CHECK(&st, wff_cut_lines(a, 10, &err) == 0 && file_size(a) == 300, "cut to 10 lines: %ld bytes",
          file_size(a));
    CHECK(&st, wff_file_lines(a, -1, &lines, &h2, NULL, 0, &err) == 0 && lines == 10 && h1 == h2,
          "the cut file hashes as its prefix did");
    CHECK(&st, wff_cut_lines(a, 11, &err) != 0 && strstr(err.message, "fewer than 11"),
          "cutting to more lines than there are: %s", err.message);

    /* commits of files a tool wrote */
    test_tmp_path(dir, "f.vtu.tmp", a, sizeof a);
    test_tmp_path(dir, "f.vtu", b, sizeof b);
    put(a, "<VTKFile>\n<Piece>");
    CHECK(&st, wff_commit_file(a, b, &err) != 0 && strstr(err.message, "does not end with </VTKFile>"),
          "incomplete vtu: %s", err.message);
    CHECK(&st, !wff_exists(a) && !wff_exists(b), "incomplete vtu: tmp removed, nothing renamed");
    put(a, "<VTKFile>\n</VTKFile>\n");
    CHECK(&st, wff_commit_file(a, b, &err) == 0 && wff_exists(b) && !wff_exists(a), "whole vtu: %s",
          err.message);
    test_tmp_path(dir, "p.png.tmp", a, sizeof a);
    test_tmp_path(dir, "p.png", b, sizeof b);
    put(a, "");
    CHECK(&st, wff_commit_file(a, b, &err) != 0 && strstr(err.message, "is empty"), "empty png: %s",
          err.message);
    put(a, "\x89PNG\r\n truncated");
    CHECK(&st, wff_commit_file(a, b, &err) != 0 && strstr(err.message, "no PNG end chunk"),
          "truncated png: %s", err.message);
    test_tmp_path(dir, "s.json.tmp", a, sizeof a);
    test_tmp_path(dir, "s.json", b, sizeof b);
    put(a, "{\n  \"status\": \"ok\",\n  \"ste");
    CHECK(&st, wff_commit_file(a, b, &err) != 0 && strstr(err.message, "does not end with }"),
          "truncated json: %s", err.message);

    /* the lock: ours twice, a live holder, a stale one */
    char note[256];
    CHECK(&st, wff_lock_take(dir, note, sizeof note, &err) == 0 && !note[0], "take: %s", err.message);
    CHECK(&st, wff_lock_take(dir, note, sizeof note, &err) == 0, "ours again: %s", err.message);
    wff_lock_release(dir);
    test_tmp_path(dir, ".wovenff.lock", a, sizeof a);
    CHECK(&st, !wff_exists(a), "released");
    snprintf(c, sizeof c, "%ld\n", (long)getppid());
    put(a, c);
    CHECK(&st, wff_lock_take(dir, note, sizeof note, &err) != 0 &&
                   strstr(err.message, "is in use by another run"), "live holder: %s", err.message);
    pid = fork();
    if (pid == 0)
        _exit(0);
    waitpid(pid, &ws, 0); /* a pid that no longer runs */
    snprintf(c, sizeof c, "%ld\n", (long)pid);
    put(a, c);
    CHECK(&st, wff_lock_take(dir, note, sizeof note, &err) == 0 && strstr(note, "taking it over"),
          "stale lock: %s / %s", err.message, note);
    wff_lock_release(dir);

    /* paths a user can type */
    CHECK(&st, wff_path_check("it's a \"folder\" ünï", "-out", &err) == 0, "quotes and unicode");
    CHECK(&st, wff_path_check("a\nb", "-out", &err) != 0 && strstr(err.message, "control character"),
          "newline: %s", err.message);

    /* a tree copied (the skipped name left out) and removed; a folder made */
    test_tmp_path(dir, "tree/sub/deep", a, sizeof a);
    CHECK(&st, wff_make_dirs(a, &err) == 0, "make dirs: %s", err.message);
    test_tmp_path(dir, "tree/sub/deep/x.txt", b, sizeof b);
    put(b, "x\n");
    test_tmp_path(dir, "tree/skip.me", b, sizeof b);
    put(b, "s\n");
    test_tmp_path(dir, "tree", a, sizeof a);
    test_tmp_path(dir, "copy 'of' tree", b, sizeof b);
    CHECK(&st, wff_copy_tree(a, b, "skip.me", &err) == 0, "copy: %s", err.message);
    test_tmp_path(dir, "copy 'of' tree/sub/deep/x.txt", c, sizeof c);
    CHECK(&st, file_size(c) == 2, "copied file: %ld bytes", file_size(c));
    test_tmp_path(dir, "copy 'of' tree/skip.me", c, sizeof c);
    CHECK(&st, !wff_exists(c), "the skipped entry was copied");
    CHECK(&st, wff_remove_tree(b, &err) == 0 && !wff_exists(b), "remove: %s", err.message);

    /* a program with an argument vector: the ';' is an argument, not a command */
    char p0[] = "printf", p1[] = "%s", p2[] = "a'; exit 7; '";
    char *argv[] = {p0, p1, p2, NULL};
    int status;
    CHECK(&st, wff_run_program(argv, &status, &err) == 0 && status == 0, "printf: status %d", status);
    char q0[] = "no-such-program-wovenff";
    char *argv2[] = {q0, NULL};
    CHECK(&st, wff_run_program(argv2, &status, &err) == 0 && status == 127, "missing: status %d",
          status);

    /* wff_run_logged: the program's output into its log, an argument with quotes verbatim */
    test_tmp_path(dir, "it's a log.txt", a, sizeof a);
    CHECK(&st, wff_run_logged(argv, a, &status, &err) == 0 && status == 0, "logged: status %d",
          status);
    char *text = NULL;
    CHECK(&st, wff_read_text_file(a, "log", 1024, &text, &err) == 0 && text &&
                   strcmp(text, "a'; exit 7; '") == 0, "logged output: '%s'", text ? text : "");
    free(text);

    /* wff_run_jobs: four jobs, two at once, exit codes in list order, each log its own */
    char list[600], log[4][600], line[4][4096];
    test_tmp_path(dir, "jobs.txt", list, sizeof list);
    const char *progs[4] = {"true", "false", "printf\tjob %s\tthree", "no-such-program-wovenff"};
    size_t used = 0;
    char body[4 * 4096];
    for (int j = 0; j < 4; j++) {
        char name[32];
        snprintf(name, sizeof name, "job %d.log", j);
        test_tmp_path(dir, name, log[j], sizeof log[j]);
        snprintf(line[j], sizeof line[j], "label%d\t%s\t%s\n", j, log[j], progs[j]);
        used += (size_t)snprintf(body + used, sizeof body - used, "%s", line[j]);
    }
    CHECK(&st, wff_write_whole(list, body, used, &err) == 0, "job list: %s", err.message);
    int codes[4] = {-9, -9, -9, -9};
    long count = 0;
    CHECK(&st, wff_run_jobs(list, 2, codes, 4, &count, &err) == 0 && count == 4, "jobs: %s",
          err.message);
    CHECK(&st, codes[0] == 0 && codes[1] == 1 && codes[2] == 0 && codes[3] == 127,
          "job exit codes %d %d %d %d, want 0 1 0 127", codes[0], codes[1], codes[2], codes[3]);
    text = NULL;
    CHECK(&st, wff_read_text_file(log[2], "log", 1024, &text, &err) == 0 && text &&
                   strcmp(text, "job three") == 0, "job 2's log: '%s'", text ? text : "");
    free(text);
    CHECK(&st, wff_run_jobs(list, 2, codes, 3, &count, &err) != 0, "4 jobs accepted into 3 codes");
    /* a value with a tab, a newline, a backslash and a control character stays one
     * argument (escaped in the list, unescaped for the program): data, not fields */
    {
        const char *value = "a\tb\nc\\d\x01" "e";
        char esc[128], job[1200];
        size_t need = wff_arg_escape(value, 1, esc, sizeof esc);
        CHECK(&st, need == strlen(esc) && strcmp(esc, "a\\tb\\nc\\\\d\\x01e") == 0 &&
                       !strchr(esc, '\t') && !strchr(esc, '\n'),
              "escaped '%s' (%zu)", esc, need);
        char back[128];
        snprintf(back, sizeof back, "%s", esc);
        wff_arg_unescape(back);
        CHECK(&st, strcmp(back, value) == 0, "unescaped differs");
        char shown[128];
        wff_arg_escape(value, 0, shown, sizeof shown);
        CHECK(&st, strcmp(shown, "a\\tb\\nc\\d\\x01e") == 0, "visible '%s'", shown);
        char small[4];
        CHECK(&st, wff_arg_escape(value, 1, small, sizeof small) == need && strlen(small) == 3,
              "truncated");
        int len = snprintf(job, sizeof job, "one\t%s\tprintf\t%%s|\t%s\n", log[0], esc);
        CHECK(&st, wff_write_whole(list, job, (size_t)len, &err) == 0 &&
                       wff_run_jobs(list, 1, codes, 4, &count, &err) == 0 && count == 1 &&
                       codes[0] == 0, "escaped job: %s", err.message);
        text = NULL;
        CHECK(&st, wff_read_text_file(log[0], "log", 1024, &text, &err) == 0 && text &&
                       strcmp(text, "a\tb\nc\\d\x01" "e|") == 0,
              "the value as the program got it: '%s'", text ? text : "");
        free(text);
    }
    CHECK(&st, wff_write_whole(list, "label\tlog only\n", 14, &err) == 0 &&
                   wff_run_jobs(list, 1, codes, 4, &count, &err) != 0,
          "a job without a program accepted");

    test_tmp_remove(dir);
    return check_summary(&st, "test_files");
}

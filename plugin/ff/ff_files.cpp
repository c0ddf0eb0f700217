// wovenff FreeFEM binding: results files and folders without a shell, every
// write checked (include/wovenff/files.h, text_io.h).
//   wovenffWriteText(file, text)        // whole file, atomic (tmp, checked writes, fsync, rename)
//   wovenffAppendRow(file, row)         // one checked write: the row is in the file whole or not
//   wovenffAppendCsv(file, a, b)        // a row: the values of a then b, %.10g, comma-separated
//   wovenffWriteTable(file, header, v, ncols, digits) // CSV: header, then v row-major, atomic
//   wovenffCommit(tmp, final)           // a file a tool wrote: non-empty, complete (.vtu/.pvd:
//                                       // </VTKFile>, .png: IEND), fsync, rename
//   wovenffCommitAll(finals)            // the same for each FINAL.tmp of a newline-separated
//                                       // list; a failure removes the later ones' .tmp first
//   (the cost estimate uses wovenffStableStep(md) of ff_loop.cpp)
//   wovenffSaveCheckpoint(md, file)     // wovenffSave, a failure is a write failure
//   wovenffMakeDir(dir) wovenffRename(from, to) wovenffCopyTree(from, to) wovenffRemove(path)
//   wovenffCutLines(file, n)            // keep the first n lines (atomic)
//   wovenffClearDir(dir)                // remove everything in dir but its lock
//   wovenffRemoveTemporaries(dir)       // the .tmp files interrupted writes left: their count
//   wovenffWriteFailed(file, reason)    // a write a tool reported failed: exit 3 as below
//   int wovenffSameFile(a, b)           // same file or folder (device and inode)
// A failed write stops the script at once with exit code 3 and "error: <file>: <strerror>",
// writes a failed summary.json into the locked run folder (if it can), waits for the
// pictures still drawn in the background and removes every .tmp left in that folder,
// releases the lock.
//   wovenffRunLock(dir)                 // take dir/.wovenff.lock (released at any exit; a lock of
//                                       // a dead process taken over); in use: exit 2
//   int wovenffExists(path), int wovenffDirEntries(dir) (the lock not counted)
//   int wovenffLineCount(file)          // complete lines (-1: unreadable)
//   string wovenffLinesHash(file, n)    // "lines hash" of the first n lines (n < 0: all)
//   string wovenffLine(file, n)         // line n (1-based)
//   string wovenffFileHash(file), wovenffTextHash(text), wovenffReadText(file)
//   string wovenffTextProblem(file)     // "" if wovenffReadText would read it, else why not
//   string wovenffFormat(x, digits)     // %.<digits>g
//   string wovenffPathProblem(path, what) // "" or why a typed path is refused (control chars)
//   string wovenffInputProblem(path, what) // "" or why an input file is refused: not a
//                                       // regular file (a pipe, <(...), a folder); "" if absent
//   int wovenffGnuplot(vars, script)    // gnuplot -e vars script, no shell; its exit code
//   int wovenffRun(argv, log)           // argv: the program and its arguments separated by
//                                       // tabs, each a wovenffArg; no shell, stdout and stderr
//                                       // into log; exit code
//   int wovenffRunJobs(list, jobs, status) // the jobs of list (a line: label, log, program,
//                                       // arguments, tab-separated, each a wovenffArg), jobs at
//                                       // once, a progress line as each ends; exit codes; count
//   string wovenffProgram(name)         // the program's path as execvp finds it on PATH ("": none)
//   string wovenffEnv(name)             // the environment variable's value ("": unset)
//   string wovenffArg(text)             // text as one such field: \\ \t \n \r \xHH escaped
//   string wovenffVisible(text)         // text with its control characters shown (\t ...)
// Knows nothing of scenes or models beyond the checkpoint call.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <sys/wait.h>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/files.h"
#include "wovenff/membrane.h"
#include "wovenff/text_io.h"
}

namespace {

// The run folder whose lock this process holds ("" none): binding-level, as
// FreeFEM passes no user data (the C core keeps no state).
std::string &locked_dir()
{
    static std::string dir;
    return dir;
}

void release_lock()
{
    if (!locked_dir().empty())
        wff_lock_release(locked_dir().c_str());
}

std::string json_string(const std::string &s)
{
    std::string out = "\"";
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += (char)c;
        } else if (c < 0x20)
            out += ' ';
        else
            out += (char)c;
    }
    return out + "\"";
}

// A write failed: say so, a failed summary if it can be written, exit 3.
[[noreturn]] void write_fail(const char *fn, const std::string &message)
{
    std::cout << "error: " << fn << ": " << message << std::endl;
    if (!locked_dir().empty()) {
        std::string text = "{\n  \"status\": \"failed\",\n  \"error\": " +
                           json_string(std::string(fn) + ": " + message) +
                           ",\n  \"exit_code\": 3\n}\n";
        wff_error err2;
        std::string path = locked_dir() + "/summary.json";
        if (wff_write_whole(path.c_str(), text.data(), text.size(), &err2))
            std::cout << "(the failed summary could not be written either: " << err2.message
                      << ")" << std::endl;
        else
            std::cout << "the run failed: " << path << " says why (exit code 3)" << std::endl;
        // the pictures drawn in the background end (they die with this process
        // anyway), then no half-written file of this run stays
        while (waitpid(-1, nullptr, 0) > 0 || errno == EINTR) {
        }
        long removed = 0;
        wff_remove_temporaries(locked_dir().c_str(), &removed, &err2);
    }
    std::cout.flush();
    release_lock();
    std::_Exit(3);
}

void check(const char *fn, int rc, const wff_error &err)
{
    if (rc)
        write_fail(fn, err.message);
}

std::string hex(uint64_t h)
{
    char buf[24];
    std::snprintf(buf, sizeof buf, "%016llx", (unsigned long long)h);
    return buf;
}

std::string format(double x, long digits)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.*g", (int)digits, x);
    return buf;
}

string *ret(Stack stack, const std::string &s) { return Add2StackOfPtr2Free(stack, new string(s)); }

long ffWriteText(string *const &file, string *const &text)
{
    wff_error err;
    check("wovenffWriteText", wff_write_whole(file->c_str(), text->data(), text->size(), &err), err);
    return 0;
}

long ffAppendRow(string *const &file, string *const &row)
{
    std::string r = *row;
    if (r.empty() || r.back() != '\n')
        r += '\n';
    wff_error err;
    check("wovenffAppendRow", wff_append_whole(file->c_str(), r.data(), r.size(), &err), err);
    return 0;
}

long ffAppendCsv(string *const &file, KN<double> *const &a, KN<double> *const &b)
{
    std::string r;
    r.reserve(24 * (a->N() + b->N()));
    for (long i = 0; i < a->N(); i++)
        r += (i ? "," : "") + format((*a)[i], 10);
    for (long i = 0; i < b->N(); i++)
        r += "," + format((*b)[i], 10);
    r += '\n';
    wff_error err;
    check("wovenffAppendCsv", wff_append_whole(file->c_str(), r.data(), r.size(), &err), err);
    return 0;
}

long ffWriteTable(string *const &file, string *const &header, KN<double> *const &v,
                  const long &ncols, const long &digits)
{
    if (ncols <= 0 || v->N() % ncols != 0)
        wff_ff_fail("wovenffWriteTable", "values: " + std::to_string(v->N()) +
                                             " entries, not a whole number of rows of " +
                                             std::to_string(ncols) + " columns");
    std::string t = *header + "\n";
    for (long i = 0; i < v->N(); i++)
        t += format((*v)[i], digits) + ((i + 1) % ncols ? "," : "\n");
    wff_error err;
    check("wovenffWriteTable", wff_write_whole(file->c_str(), t.data(), t.size(), &err), err);
    return 0;
}

long ffCommit(string *const &tmp, string *const &final)
{
    wff_error err;
    check("wovenffCommit", wff_commit_file(tmp->c_str(), final->c_str(), &err), err);
    return 0;
}

// finals: newline-separated; each FINAL.tmp committed in turn; on the first that fails,
// the later ones' .tmp removed before the write failure (nothing half-done is left)
long ffCommitAll(string *const &finals)
{
    std::vector<std::string> names;
    std::string all = *finals;
    for (size_t from = 0; from < all.size();) {
        size_t nl = all.find('\n', from);
        if (nl == std::string::npos)
            nl = all.size();
        if (nl > from)
            names.push_back(all.substr(from, nl - from));
        from = nl + 1;
    }
    for (size_t i = 0; i < names.size(); i++) {
        wff_error err;
        if (wff_commit_file((names[i] + ".tmp").c_str(), names[i].c_str(), &err)) {
            for (size_t j = i + 1; j < names.size(); j++)
                std::remove((names[j] + ".tmp").c_str());
            write_fail("wovenffCommitAll", err.message);
        }
    }
    return 0;
}

long ffSaveCheckpoint(const long &id, string *const &file)
{
    wff_error err;
    check("wovenffSaveCheckpoint",
          wff_model_save(wff_ff_model(id, "wovenffSaveCheckpoint"), file->c_str(), &err), err);
    return 0;
}

long ffMakeDir(string *const &dir)
{
    wff_error err;
    if (wff_make_dirs(dir->c_str(), &err))
        write_fail("wovenffMakeDir", "output folder '" + *dir + "' cannot be created or written (" +
                                         err.message + ")");
    return 0;
}

long ffRename(string *const &from, string *const &to)
{
    wff_error err;
    check("wovenffRename", wff_rename(from->c_str(), to->c_str(), &err), err);
    return 0;
}

long ffCopyTree(string *const &from, string *const &to)
{
    wff_error err;
    check("wovenffCopyTree", wff_copy_tree(from->c_str(), to->c_str(), ".wovenff.lock", &err), err);
    return 0;
}

long ffRemove(string *const &path)
{
    wff_error err;
    check("wovenffRemove", wff_remove_tree(path->c_str(), &err), err);
    return 0;
}

long ffClearDir(string *const &dir)
{
    wff_error err;
    check("wovenffClearDir", wff_clear_dir(dir->c_str(), ".wovenff.lock", &err), err);
    return 0;
}

// The files interrupted atomic writes left in dir (NAME.tmp, NAME.tmp.vtu) removed: their count.
long ffRemoveTemporaries(string *const &dir)
{
    wff_error err;
    long removed = 0;
    check("wovenffRemoveTemporaries", wff_remove_temporaries(dir->c_str(), &removed, &err), err);
    return removed;
}

long ffSameFile(string *const &a, string *const &b) { return wff_same_file(a->c_str(), b->c_str()); }

long ffWriteFailed(string *const &file, string *const &reason)
{
    write_fail("wovenffWriteFailed", "cannot write " + *file + ": " + *reason);
}

long ffCutLines(string *const &file, const long &n)
{
    wff_error err;
    check("wovenffCutLines", wff_cut_lines(file->c_str(), n, &err), err);
    return 0;
}

long ffRunLock(string *const &dir)
{
    char note[600];
    wff_error err;
    if (wff_lock_take(dir->c_str(), note, sizeof note, &err)) {
        std::cout << "error: " << err.message << " (exit code 2)" << std::endl;
        std::cout.flush();
        std::_Exit(2);   // (not exit(): that would run the atexit release of our own lock)
    }
    if (note[0])
        std::cout << note << std::endl;
    if (locked_dir().empty()) {
        locked_dir() = *dir;
        std::atexit(release_lock);
    }
    return 0;
}

long ffExists(string *const &path) { return wff_exists(path->c_str()); }

long ffDirEntries(string *const &dir)
{
    long n;
    wff_error err;
    if (wff_dir_entries(dir->c_str(), ".wovenff.lock", &n, &err))
        return -1;
    return n;
}

long ffLineCount(string *const &file)
{
    long lines;
    uint64_t h;
    wff_error err;
    if (wff_file_lines(file->c_str(), -1, &lines, &h, NULL, 0, &err))
        return -1;
    return lines;
}

string *ffLinesHash(Stack stack, string *const &file, const long &n)
{
    long lines;
    uint64_t h;
    wff_error err;
    if (wff_file_lines(file->c_str(), n, &lines, &h, NULL, 0, &err))
        return ret(stack, "");
    return ret(stack, std::to_string(lines) + " " + hex(h));
}

string *ffLine(Stack stack, string *const &file, const long &n)
{
    long lines;
    uint64_t h;
    char last[4096];
    wff_error err;
    if (n <= 0 || wff_file_lines(file->c_str(), n, &lines, &h, last, sizeof last, &err) ||
        lines < n)
        return ret(stack, "");
    return ret(stack, last);
}

string *ffFileHash(Stack stack, string *const &file)
{
    uint64_t h;
    wff_error err;
    if (wff_file_hash(file->c_str(), &h, &err))
        return ret(stack, "");
    return ret(stack, hex(h));
}

string *ffTextHash(Stack stack, string *const &text)
{
    return ret(stack, hex(wff_hash_bytes(text->data(), text->size())));
}

string *ffReadText(Stack stack, string *const &file)
{
    char *text;
    wff_error err;
    if (wff_read_text_file(file->c_str(), "file", (size_t)1 << 30, &text, &err))
        wff_ff_fail("wovenffReadText", err);
    std::string s(text);
    free(text);
    return ret(stack, s);
}

// "" if wovenffReadText would read file (a text file of at most 1 GiB, no NUL byte), else why not.
string *ffTextProblem(Stack stack, string *const &file)
{
    char *text;
    wff_error err;
    if (wff_read_text_file(file->c_str(), "file", (size_t)1 << 30, &text, &err))
        return ret(stack, err.message);
    free(text);
    return ret(stack, "");
}

string *ffFormat(Stack stack, const double &x, const long &digits)
{
    return ret(stack, format(x, digits < 1 ? 1 : digits > 17 ? 17 : digits));
}

std::string escaped(const std::string &text, int backslash)
{
    std::string out(wff_arg_escape(text.c_str(), backslash, nullptr, 0) + 1, '\0');
    wff_arg_escape(text.c_str(), backslash, &out[0], out.size());
    out.resize(out.size() - 1);
    return out;
}

string *ffArg(Stack stack, string *const &text) { return ret(stack, escaped(*text, 1)); }

string *ffVisible(Stack stack, string *const &text) { return ret(stack, escaped(*text, 0)); }

string *ffProgram(Stack stack, string *const &name)
{
    char path[4096];
    wff_find_program(name->c_str(), path, sizeof path);
    return ret(stack, path);
}

string *ffEnv(Stack stack, string *const &name)
{
    const char *v = std::getenv(name->c_str());
    return ret(stack, v ? v : "");
}

string *ffPathProblem(Stack stack, string *const &path, string *const &what)
{
    wff_error err;
    if (wff_path_check(path->c_str(), what->c_str(), &err))
        return ret(stack, err.message);
    return ret(stack, "");
}

string *ffInputProblem(Stack stack, string *const &path, string *const &what)
{
    wff_error err;
    if (!wff_exists(path->c_str()) || wff_regular_file_check(path->c_str(), what->c_str(), &err) == 0)
        return ret(stack, "");
    return ret(stack, err.message);
}

long ffGnuplot(string *const &vars, string *const &script)
{
    char prog[] = "gnuplot", e[] = "-e";
    char *argv[] = {prog, e, const_cast<char *>(vars->c_str()), const_cast<char *>(script->c_str()),
                    nullptr};
    int status;
    wff_error err;
    if (wff_run_program(argv, &status, &err))
        return -1;
    return status;
}

long ffRun(string *const &args, string *const &log)
{
    std::vector<std::string> words;
    std::string a = *args;
    size_t from = 0;
    for (;;) {
        size_t tab = a.find('\t', from);
        words.push_back(a.substr(from, tab == std::string::npos ? std::string::npos : tab - from));
        if (tab == std::string::npos)
            break;
        from = tab + 1;
    }
    if (words.empty() || words[0].empty())
        wff_ff_fail("wovenffRun", "no program to run");
    std::vector<char *> argv;
    for (std::string &w : words) {
        wff_arg_unescape(&w[0]); // (each word escaped: wovenffArg)
        w.resize(std::char_traits<char>::length(w.c_str()));
        argv.push_back(&w[0]);
    }
    argv.push_back(nullptr);
    int status;
    wff_error err;
    if (wff_run_logged(argv.data(), log->c_str(), &status, &err))
        return -1;
    return status;
}

long ffRunJobs(string *const &list, const long &jobs, KN<double> *const &status)
{
    std::vector<int> codes(status->N() + 1);
    long count = 0;
    wff_error err;
    if (wff_run_jobs(list->c_str(), (int)jobs, codes.data(), status->N(), &count, &err))
        wff_ff_fail("wovenffRunJobs", err);
    for (long j = 0; j < count; j++)
        (*status)[j] = codes[j];
    return count;
}

} // namespace

void wff_ff_register_files()
{
    // A write beyond a file-size limit (ulimit -f) fails with EFBIG, checked
    // like any other write, instead of killing the run mid-row.
    std::signal(SIGXFSZ, SIG_IGN);
    Global.Add("wovenffWriteText", "(", new OneOperator2_<long, string *, string *>(ffWriteText));
    Global.Add("wovenffAppendRow", "(", new OneOperator2_<long, string *, string *>(ffAppendRow));
    Global.Add("wovenffAppendCsv", "(",
               new OneOperator3_<long, string *, KN<double> *, KN<double> *>(ffAppendCsv));
    Global.Add("wovenffWriteTable", "(",
               new OneOperator5_<long, string *, string *, KN<double> *, long, long>(ffWriteTable));
    Global.Add("wovenffCommit", "(", new OneOperator2_<long, string *, string *>(ffCommit));
    Global.Add("wovenffCommitAll", "(", new OneOperator1_<long, string *>(ffCommitAll));
    Global.Add("wovenffSaveCheckpoint", "(",
               new OneOperator2_<long, long, string *>(ffSaveCheckpoint));
    Global.Add("wovenffMakeDir", "(", new OneOperator1_<long, string *>(ffMakeDir));
    Global.Add("wovenffRename", "(", new OneOperator2_<long, string *, string *>(ffRename));
    Global.Add("wovenffCopyTree", "(", new OneOperator2_<long, string *, string *>(ffCopyTree));
    Global.Add("wovenffRemove", "(", new OneOperator1_<long, string *>(ffRemove));
    Global.Add("wovenffClearDir", "(", new OneOperator1_<long, string *>(ffClearDir));
    Global.Add("wovenffRemoveTemporaries", "(", new OneOperator1_<long, string *>(ffRemoveTemporaries));
    Global.Add("wovenffSameFile", "(", new OneOperator2_<long, string *, string *>(ffSameFile));
    Global.Add("wovenffWriteFailed", "(", new OneOperator2_<long, string *, string *>(ffWriteFailed));
    Global.Add("wovenffCutLines", "(", new OneOperator2_<long, string *, long>(ffCutLines));
    Global.Add("wovenffRunLock", "(", new OneOperator1_<long, string *>(ffRunLock));
    Global.Add("wovenffExists", "(", new OneOperator1_<long, string *>(ffExists));
    Global.Add("wovenffDirEntries", "(", new OneOperator1_<long, string *>(ffDirEntries));
    Global.Add("wovenffLineCount", "(", new OneOperator1_<long, string *>(ffLineCount));
    Global.Add("wovenffLinesHash", "(", new OneOperator2s_<string *, string *, long>(ffLinesHash));
    Global.Add("wovenffLine", "(", new OneOperator2s_<string *, string *, long>(ffLine));
    Global.Add("wovenffFileHash", "(", new OneOperator1s_<string *, string *>(ffFileHash));
    Global.Add("wovenffTextHash", "(", new OneOperator1s_<string *, string *>(ffTextHash));
    Global.Add("wovenffReadText", "(", new OneOperator1s_<string *, string *>(ffReadText));
    Global.Add("wovenffTextProblem", "(", new OneOperator1s_<string *, string *>(ffTextProblem));
    Global.Add("wovenffFormat", "(", new OneOperator2s_<string *, double, long>(ffFormat));
    Global.Add("wovenffInputProblem", "(",
               new OneOperator2s_<string *, string *, string *>(ffInputProblem));
    Global.Add("wovenffPathProblem", "(",
               new OneOperator2s_<string *, string *, string *>(ffPathProblem));
    Global.Add("wovenffGnuplot", "(", new OneOperator2_<long, string *, string *>(ffGnuplot));
    Global.Add("wovenffRun", "(", new OneOperator2_<long, string *, string *>(ffRun));
    Global.Add("wovenffProgram", "(", new OneOperator1s_<string *, string *>(ffProgram));
    Global.Add("wovenffEnv", "(", new OneOperator1s_<string *, string *>(ffEnv));
    Global.Add("wovenffArg", "(", new OneOperator1s_<string *, string *>(ffArg));
    Global.Add("wovenffVisible", "(", new OneOperator1s_<string *, string *>(ffVisible));
    Global.Add("wovenffRunJobs", "(",
               new OneOperator3_<long, string *, long, KN<double> *>(ffRunJobs));
}

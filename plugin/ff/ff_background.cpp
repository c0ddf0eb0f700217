// wovenff FreeFEM binding: programs started without waiting, waited for later
// (include/wovenff/files.h), so that a scene's pictures are drawn while it
// computes and side by side at its end (freefem_scripts/lib/wff_background.idp).
//   long wovenffGnuplotStart(vars, script) // gnuplot -e vars script, no shell, not waited
//                                          // for: its process id, -1 if it could not start
//   long wovenffWait(pid)                  // wait for that process: its exit code (128 +
//                                          // signal if killed), -1 if it is not ours to wait
// Knows nothing of scenes, models or pictures: the script keeps the list of what it
// started (no state here).
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <string>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/files.h"
}

namespace {

long ffGnuplotStart(string *const &vars, string *const &script)
{
    char prog[] = "gnuplot", e[] = "-e";
    char *argv[] = {prog, e, const_cast<char *>(vars->c_str()), const_cast<char *>(script->c_str()),
                    nullptr};
    long pid;
    wff_error err;
    if (wff_start_program(argv, &pid, &err))
        return -1;
    return pid;
}

long ffWait(const long &pid)
{
    if (pid <= 0)
        return -1;
    int status;
    wff_error err;
    if (wff_wait_program(pid, &status, &err))
        return -1;
    return status;
}

} // namespace

void wff_ff_register_background()
{
    Global.Add("wovenffGnuplotStart", "(",
               new OneOperator2_<long, string *, string *>(ffGnuplotStart));
    Global.Add("wovenffWait", "(", new OneOperator1_<long, long>(ffWait));
}

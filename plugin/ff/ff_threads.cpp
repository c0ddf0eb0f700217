// wovenff FreeFEM binding: thread counts (issue 12).
//
//   int n = wovenffDefaultThreads();   // OMP_NUM_THREADS, else the cores this process may use
//   int t = wovenffThreads(md);        // the count model md runs every per-step pass with
//   real s = wovenffWallClock();       // a monotonic wall clock, s (FreeFEM's clock() is
//                                      // CPU time: with 2 threads it counts both)
//
// A scene's -threads default is wovenffDefaultThreads(), and its summary.json
// "threads" is wovenffThreads(md). Knows the model handle table
// (ff_wovenff.hpp) and the solver's public API only.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include "ff_wovenff.hpp"

#include <time.h>

using namespace Fem2D;

namespace {

long ffDefaultThreads() { return wff_default_threads(); }

long ffThreads(const long &id)
{
    return wff_model_thread_count(wff_ff_model(id, "wovenffThreads"));
}

double ffWallClock()
{
    struct timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return (double)now.tv_sec + 1e-9 * (double)now.tv_nsec;
}

} // namespace

void wff_ff_register_threads()
{
    Global.Add("wovenffDefaultThreads", "(", new OneOperator0<long>(ffDefaultThreads));
    Global.Add("wovenffThreads", "(", new OneOperator1_<long, long>(ffThreads));
    Global.Add("wovenffWallClock", "(", new OneOperator0<double>(ffWallClock));
}

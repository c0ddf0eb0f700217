// wovenff FreeFEM binding: thread counts (issue 12) and MPI ranks (docs/distributed.md).
//
//   int n = wovenffDefaultThreads();   // OMP_NUM_THREADS, else the cores this process may use
//   int t = wovenffThreads(md);        // the count model md runs every per-step pass with
//   real s = wovenffWallClock();       // a monotonic wall clock, s (FreeFEM's clock() is
//                                      // CPU time: with 2 threads it counts both); over
//                                      // MPI ranks rank 0's (every rank calls it alike)
//   int r = wovenffRank();             // this process's MPI rank (0 outside mpirun, or with
//   int n = wovenffRanks();            //  the serial module) and the rank count (1)
//   string d = wovenffRankDir(dir);    // rank 0: dir; another rank: a new private folder
//                                      // under $TMPDIR (/tmp) for what it would write (its
//                                      // results are rank 0's); wovenffRemove it at the end
//
// A scene's -threads default is wovenffDefaultThreads(), and its summary.json
// "threads" is wovenffThreads(md). Knows the model handle table
// (ff_wovenff.hpp) and the solver's public API only.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include "ff_wovenff.hpp"

#include "wovenff/comm.h"
#include "wovenff/files.h"

#include <stdio.h>
#include <stdlib.h>
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
    /* (over MPI ranks: rank 0's, so that what a script decides by the clock is
     * decided alike on every rank) */
    return wff_comm_world_agreed((double)now.tv_sec + 1e-9 * (double)now.tv_nsec);
}

long ffRank() { return wff_comm_world_rank(); }
long ffRanks() { return wff_comm_world_size(); }

string *ffRankDir(Stack stack, string *const &dir)
{
    const int rank = wff_comm_world_rank();
    if (rank == 0)
        return Add2StackOfPtr2Free(stack, new string(*dir));
    const char *tmp = getenv("TMPDIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/wovenff-rank%d-XXXXXX", tmp && *tmp ? tmp : "/tmp", rank);
    if (!mkdtemp(path)) {
        char what[4200];
        snprintf(what, sizeof what, "wovenffRankDir: cannot make a folder %s for rank %d", path,
                 rank);
        ExecError(what);
    }
    return Add2StackOfPtr2Free(stack, new string(path));
}

} // namespace

void wff_ff_register_threads()
{
    Global.Add("wovenffDefaultThreads", "(", new OneOperator0<long>(ffDefaultThreads));
    Global.Add("wovenffThreads", "(", new OneOperator1_<long, long>(ffThreads));
    Global.Add("wovenffWallClock", "(", new OneOperator0<double>(ffWallClock));
    Global.Add("wovenffRank", "(", new OneOperator0<long>(ffRank));
    Global.Add("wovenffRanks", "(", new OneOperator0<long>(ffRanks));
    Global.Add("wovenffRankDir", "(", new OneOperator1s_<string *, string *>(ffRankDir));
}

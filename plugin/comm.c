/* comm.c: include/wovenff/comm.h. Without MPI (the default build) one rank:
 * sums and minima are the rank's own, broadcasts no-ops, an exchange copies
 * rank 0's own part. With MPI (WFF_MPI, make MPI=1) the calls run over the
 * model's duplicate of the communicator the binding passed. Nothing of
 * models, elements or FreeFEM. */
#include "wovenff/comm.h"

#include <stdlib.h>
#include <string.h>

#ifdef WFF_MPI
#define OMPI_SKIP_MPICXX 1
#include <mpi.h>

int wff_comm_has_mpi(void)
{
    return 1;
}

/* What the handle holds: the duplicate communicator and the 128-bit sums'
 * type and operation (made once per communicator). */
typedef struct comm_state {
    MPI_Comm comm;
    MPI_Datatype fixed_type;
    MPI_Op fixed_op;
} comm_state;

static MPI_Comm comm_of(const wff_comm *c)
{
    return ((const comm_state *)c->handle)->comm;
}

/* MPI has no 128-bit integer: the sums travel as bytes, added by this op. */
static void fixed_add_op(void *in, void *inout, int *len, MPI_Datatype *type)
{
    (void)type;
    wff_fixed *a = in, *b = inout;
    for (int i = 0; i < *len; i++)
        wff_fixed_merge(&b[i], &a[i]);
}

int wff_comm_from_mpi(wff_comm *c, const void *mpi_comm, wff_error *err)
{
    comm_state *s = malloc(sizeof *s);
    if (!s)
        return wff_fail(err, "out of memory for the communicator");
    if (MPI_Comm_dup(*(const MPI_Comm *)mpi_comm, &s->comm) != MPI_SUCCESS) {
        free(s);
        return wff_fail(err, "MPI_Comm_dup failed");
    }
    MPI_Type_contiguous((int)sizeof(wff_fixed), MPI_BYTE, &s->fixed_type);
    MPI_Type_commit(&s->fixed_type);
    MPI_Op_create(fixed_add_op, 1, &s->fixed_op);
    MPI_Comm_rank(s->comm, &c->rank);
    MPI_Comm_size(s->comm, &c->size);
    c->handle = s;
    return 0;
}

int wff_comm_world(wff_comm *c, wff_error *err)
{
    int ready = 0;
    MPI_Initialized(&ready);
    if (!ready && MPI_Init(NULL, NULL) != MPI_SUCCESS)
        return wff_fail(err, "MPI_Init failed");
    MPI_Comm world = MPI_COMM_WORLD;
    return wff_comm_from_mpi(c, &world, err);
}

void wff_comm_free(wff_comm *c)
{
    if (c->handle) {
        comm_state *s = c->handle;
        int finalized = 0;
        MPI_Finalized(&finalized);
        if (!finalized) {
            MPI_Op_free(&s->fixed_op);
            MPI_Type_free(&s->fixed_type);
            MPI_Comm_free(&s->comm);
        }
        free(s);
    }
    *c = wff_comm_self();
}

void wff_comm_sum_fixed(const wff_comm *c, wff_fixed *v, int n)
{
    if (c->size <= 1 || n <= 0)
        return;
    const comm_state *s = c->handle;
    MPI_Allreduce(MPI_IN_PLACE, v, n, s->fixed_type, s->fixed_op, s->comm);
}

void wff_comm_min_index(const wff_comm *c, double *value, int *index)
{
    if (c->size <= 1)
        return;
    /* (value, index) pairs: MPI_MINLOC takes the lowest index among equal values */
    struct { double v; int i; } in = {*value, *index}, out;
    MPI_Allreduce(&in, &out, 1, MPI_DOUBLE_INT, MPI_MINLOC, comm_of(c));
    *value = out.v;
    *index = out.i;
}

void wff_comm_max(const wff_comm *c, double *v, int n)
{
    if (c->size <= 1 || n <= 0)
        return;
    MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_DOUBLE, MPI_MAX, comm_of(c));
}

void wff_comm_sum_long(const wff_comm *c, long *v, int n)
{
    if (c->size <= 1 || n <= 0)
        return;
    MPI_Allreduce(MPI_IN_PLACE, v, n, MPI_LONG, MPI_SUM, comm_of(c));
}

void wff_comm_broadcast(const wff_comm *c, int root, void *bytes, long n)
{
    if (c->size <= 1 || n <= 0)
        return;
    MPI_Bcast(bytes, (int)n, MPI_BYTE, root, comm_of(c));
}

void wff_comm_exchange(const wff_comm *c, const void *send, const long *send_counts,
                       const long *send_offsets, void *recv, const long *recv_counts,
                       const long *recv_offsets)
{
    if (c->size <= 1) {
        memcpy((char *)recv + recv_offsets[0], (const char *)send + send_offsets[0],
               (size_t)send_counts[0]);
        return;
    }
    int *sc = malloc(sizeof(int) * 4 * (size_t)c->size), *so = sc + c->size,
        *rc = so + c->size, *ro = rc + c->size;
    for (int r = 0; r < c->size; r++)
        sc[r] = (int)send_counts[r], so[r] = (int)send_offsets[r],
        rc[r] = (int)recv_counts[r], ro[r] = (int)recv_offsets[r];
    MPI_Alltoallv(send, sc, so, MPI_BYTE, recv, rc, ro, MPI_BYTE, comm_of(c));
    free(sc);
}

void wff_comm_gather(const wff_comm *c, int root, const void *bytes, long n, void *all,
                     const long *counts)
{
    if (c->size <= 1) {
        if (all != bytes)
            memcpy(all, bytes, (size_t)n);
        return;
    }
    int *rc = malloc(sizeof(int) * 2 * (size_t)c->size), *ro = rc + c->size;
    long offset = 0;
    for (int r = 0; r < c->size; r++) {
        rc[r] = (int)counts[r];
        ro[r] = (int)offset;
        offset += counts[r];
    }
    MPI_Gatherv(bytes, (int)n, MPI_BYTE, all, rc, ro, MPI_BYTE, root, comm_of(c));
    free(rc);
}

void wff_comm_barrier(const wff_comm *c)
{
    if (c->size > 1)
        MPI_Barrier(comm_of(c));
}

void wff_comm_allgather(const wff_comm *c, void *all, const long *counts, const long *offsets)
{
    if (c->size <= 1)
        return;
    int *rc = malloc(sizeof(int) * 2 * (size_t)c->size), *ro = rc + c->size;
    for (int r = 0; r < c->size; r++) {
        rc[r] = (int)counts[r];
        ro[r] = (int)offsets[r];
    }
    MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_BYTE, all, rc, ro, MPI_BYTE, comm_of(c));
    free(rc);
}

int wff_comm_world_rank(void)
{
    int ready = 0, finalized = 0, rank = 0;
    MPI_Initialized(&ready);
    MPI_Finalized(&finalized);
    if (ready && !finalized)
        MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    return rank;
}

int wff_comm_world_size(void)
{
    int ready = 0, finalized = 0, size = 1;
    MPI_Initialized(&ready);
    MPI_Finalized(&finalized);
    if (ready && !finalized)
        MPI_Comm_size(MPI_COMM_WORLD, &size);
    return size;
}

double wff_comm_world_agreed(double value)
{
    if (wff_comm_world_size() > 1)
        MPI_Bcast(&value, 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    return value;
}

int wff_comm_default(wff_comm *c, wff_error *err)
{
    *c = wff_comm_self();
    if (wff_comm_world_size() <= 1)
        return 0;
    MPI_Comm world = MPI_COMM_WORLD;
    return wff_comm_from_mpi(c, &world, err);
}

#else /* one rank */

void wff_comm_allgather(const wff_comm *c, void *all, const long *counts, const long *offsets)
{
    (void)c, (void)all, (void)counts, (void)offsets;
}

int wff_comm_world_rank(void)
{
    return 0;
}

int wff_comm_world_size(void)
{
    return 1;
}

double wff_comm_world_agreed(double value)
{
    return value;
}

int wff_comm_default(wff_comm *c, wff_error *err)
{
    (void)err;
    *c = wff_comm_self();
    return 0;
}

int wff_comm_has_mpi(void)
{
    return 0;
}

int wff_comm_from_mpi(wff_comm *c, const void *mpi_comm, wff_error *err)
{
    (void)mpi_comm;
    *c = wff_comm_self();
    return wff_fail(err, "this build of wovenff has no MPI (make MPI=1): one rank only");
}

int wff_comm_world(wff_comm *c, wff_error *err)
{
    *c = wff_comm_self();
    (void)err;
    return 0;
}

void wff_comm_free(wff_comm *c)
{
    *c = wff_comm_self();
}

void wff_comm_sum_fixed(const wff_comm *c, wff_fixed *v, int n)
{
    (void)c, (void)v, (void)n;
}

void wff_comm_min_index(const wff_comm *c, double *value, int *index)
{
    (void)c, (void)value, (void)index;
}

void wff_comm_max(const wff_comm *c, double *v, int n)
{
    (void)c, (void)v, (void)n;
}

void wff_comm_sum_long(const wff_comm *c, long *v, int n)
{
    (void)c, (void)v, (void)n;
}

void wff_comm_broadcast(const wff_comm *c, int root, void *bytes, long n)
{
    (void)c, (void)root, (void)bytes, (void)n;
}

void wff_comm_exchange(const wff_comm *c, const void *send, const long *send_counts,
                       const long *send_offsets, void *recv, const long *recv_counts,
                       const long *recv_offsets)
{
    (void)c, (void)recv_counts;
    memcpy((char *)recv + recv_offsets[0], (const char *)send + send_offsets[0],
           (size_t)send_counts[0]);
}

void wff_comm_gather(const wff_comm *c, int root, const void *bytes, long n, void *all,
                     const long *counts)
{
    (void)c, (void)root, (void)counts;
    if (all != bytes)
        memcpy(all, bytes, (size_t)n);
}

void wff_comm_barrier(const wff_comm *c)
{
    (void)c;
}

#endif

/* comm.h: the ranks one model runs over (issue "Distributed runs"). A build
 * without MPI (the default: `make`) has one rank, and every call below is a
 * no-op or a copy; a build with it (`make MPI=1`) keeps the MPI communicator
 * the binding passed (FreeFEM's) and runs them over it. The C core calls these
 * and nothing of MPI itself: what a rank computes and what it exchanges is the
 * decomposition's (plugin/decomp.c). */
#ifndef WOVENFF_COMM_H
#define WOVENFF_COMM_H

#include "wovenff/error.h"
#include "wovenff/fixed_sum.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wff_comm {
    int rank, size;   /* this rank and how many (1 without MPI) */
    void *handle;     /* the MPI communicator (a duplicate the model owns), or NULL */
} wff_comm;

/* One rank (rank 0 of 1): the default of every model. */
static inline wff_comm wff_comm_self(void)
{
    wff_comm c = {0, 1, 0};
    return c;
}

/* 1 if this build has MPI (make MPI=1). */
int wff_comm_has_mpi(void);
/* c over the MPI communicator *mpi_comm (an MPI_Comm, passed as a pointer to keep
 * MPI out of this header): a duplicate, freed by wff_comm_free. -1 (err set)
 * without MPI or on failure. */
int wff_comm_from_mpi(wff_comm *c, const void *mpi_comm, wff_error *err);
/* c as every rank of MPI_COMM_WORLD (MPI initialised here if it is not). */
int wff_comm_world(wff_comm *c, wff_error *err);
void wff_comm_free(wff_comm *c);

/* Every rank's v[0..n) added, in place on every rank (order-free: the same bits
 * at any rank count). */
void wff_comm_sum_fixed(const wff_comm *c, wff_fixed *v, int n);
/* The smallest value over the ranks, and its index (the lowest index among
 * equal values), on every rank. */
void wff_comm_min_index(const wff_comm *c, double *value, int *index);
/* The largest of v[0..n) over the ranks, in place. */
void wff_comm_max(const wff_comm *c, double *v, int n);
/* Integers summed over the ranks, in place. */
void wff_comm_sum_long(const wff_comm *c, long *v, int n);
/* bytes[0..n) of rank root to every rank. */
void wff_comm_broadcast(const wff_comm *c, int root, void *bytes, long n);
/* Each rank's send[0..n_send) to the ranks named: rank r sends send_counts[r]
 * bytes from send + send_offsets[r] and receives recv_counts[r] bytes into recv
 * + recv_offsets[r] (every rank's plan matches: the halo exchange). */
void wff_comm_exchange(const wff_comm *c, const void *send, const long *send_counts,
                       const long *send_offsets, void *recv, const long *recv_counts,
                       const long *recv_offsets);
/* Gather: every rank's bytes[0..n) to rank root, in rank order, into all
 * (root only: sum of the counts). counts[r] bytes from rank r (every rank passes
 * the same counts). */
void wff_comm_gather(const wff_comm *c, int root, const void *bytes, long n, void *all,
                     const long *counts);
void wff_comm_barrier(const wff_comm *c);
/* Every rank's part of all (rank r's counts[r] bytes at offsets[r], in place)
 * to every rank: all whole on every rank. */
void wff_comm_allgather(const wff_comm *c, void *all, const long *counts, const long *offsets);
/* The communicator a new model runs over: every rank of MPI_COMM_WORLD when
 * this build has MPI and the process runs under it with more than one rank
 * (FreeFem++-mpi under mpirun), else one rank. -1 (err set) on failure. */
int wff_comm_default(wff_comm *c, wff_error *err);
/* This process's rank in MPI_COMM_WORLD and how many there are (0 and 1
 * without MPI or outside mpirun): which rank writes the results. */
int wff_comm_world_rank(void);
int wff_comm_world_size(void);
/* Rank 0's value of `value` on every rank of MPI_COMM_WORLD (collective: every
 * rank calls it at the same point; the value itself without MPI): a wall time
 * every rank decides by alike (how many passes a timing takes, when a
 * progress line or a re-estimate comes), so that the ranks' calls stay in
 * step. */
double wff_comm_world_agreed(double value);

#ifdef __cplusplus
}
#endif

#endif

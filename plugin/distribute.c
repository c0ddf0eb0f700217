/* distribute.c: one model over the ranks of its communicator (comm.h), the
 * same bits as one rank (docs/distributed.md). Every rank holds the whole
 * model: its positions, velocities, the projectile and the contacts are
 * advanced on every rank from the same forces, in the same order, by the
 * serial code. What is split is the force pass, nearly all of a step's work:
 *
 *  - elements: contiguous ranges of the model's order (Hilbert-sorted, each
 *    ply of a pack after the one before), balanced by quadrature points; a
 *    rank owns its range's points' states and erosion;
 *  - nodes: a node is its lowest element's rank's; the ranks' nodes are
 *    contiguous ranges too (nodes are numbered in the order elements first use
 *    them);
 *  - a rank computes the blocks of elements it owns and those touching a node
 *    it owns (the ghosts: redundant, the same inputs so the same bits), gathers
 *    its own nodes' forces from their slots in element order (membrane_forces.c)
 *    and sends them to every rank: one exchange a force pass, 5 doubles a
 *    node;
 *  - a block's energies are added by one rank (the rank of its first element)
 *    into the order-free sums (fixed_sum.h), reduced over the ranks;
 *  - static amplitudes: the points' own balanced amplitudes (el->point_dA,
 *    what each pass's Newton starts from) are read by the replicated stable
 *    step at every element; a rank's own elements' ride along in the pass's
 *    exchange, so they are whole on every rank after every pass;
 *  - erosion: each rank judges its own elements, the lists are gathered in
 *    rank order (element order), every rank erodes them all;
 *  - the points' states of other ranks' elements go stale on a rank; they are
 *    gathered whole (wff_dist_states_whole) when a run's advance returns, so
 *    that fields, values and checkpoints read the whole state on every rank.
 *
 * Nothing here runs for a model on one rank (m->dist stays NULL). */
#include "distribute.h"
#include "part.h"
#include "wall_clock.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct wff_dist {
    int rank, size;
    int n_elements;
    int *element_lo;   /* size + 1: rank r's elements are [element_lo[r], element_lo[r+1]) */
    int *node_lo;      /* size + 1: rank r's nodes [node_lo[r], node_lo[r+1]) */
    int *owner;        /* per element (model order): its rank */
    long *counts, *offsets; /* scratch for an exchange, size each */
    long *taken, *taken_at; /* scratch: a pass's eroded elements per rank, where each goes */
    char *scratch;              /* a pass's exchange: every rank's message */
    size_t scratch_size;
    wff_fixed *fixed;           /* a zone's sums for the exchange (wff_dist_fixed_scratch) */
    size_t fixed_size;
    double exchange_seconds;    /* wall time in the exchanges and reductions so far, s */
    double gather_seconds;      /* of it, the states gathered whole (at each advance's end), s */
};

void wff_dist_free(wff_model *m)
{
    struct wff_dist *d = m->dist;
    if (!d)
        return;
    free(d->element_lo);
    free(d->node_lo);
    free(d->owner);
    free(d->counts);
    free(d->scratch);
    free(d->fixed);
    free(d);
    m->dist = NULL;
}

/* Element e's nodes (model order: triangles, then quads): their count, into n. */
static int element_nodes(const wff_model *m, int e, int n[4])
{
    const int nt = m->mesh.n_tris;
    if (e < nt) {
        for (int a = 0; a < 3; a++)
            n[a] = m->mesh.tri[3 * e + a];
        return 3;
    }
    for (int a = 0; a < 4; a++)
        n[a] = m->mesh.quad[4 * (e - nt) + a];
    return 4;
}

static int dist_setup(wff_model *m, wff_error *err)
{
    if (m->comm.size <= 1 || m->dist)
        return 0;
    const int size = m->comm.size, nt = m->mesh.n_tris, n_el = nt + m->mesh.n_quads;
    struct wff_dist *d = calloc(1, sizeof *d);
    if (!d)
        return wff_fail(err, "out of memory for the model's ranks");
    d->rank = m->comm.rank;
    d->size = size;
    d->n_elements = n_el;
    d->element_lo = malloc(sizeof(int) * (size_t)(size + 1));
    d->node_lo = malloc(sizeof(int) * (size_t)(size + 1));
    d->owner = malloc(sizeof(int) * (size_t)(n_el ? n_el : 1));
    d->counts = malloc(sizeof(long) * 4 * (size_t)size);
    int *node_owner = malloc(sizeof(int) * (size_t)(m->n_nodes ? m->n_nodes : 1));
    if (!d->element_lo || !d->node_lo || !d->owner || !d->counts || !node_owner) {
        free(node_owner);
        m->dist = d;
        wff_dist_free(m);
        return wff_fail(err, "out of memory for the model's ranks");
    }
    d->offsets = d->counts + size;
    d->taken = d->counts + 2 * size;
    d->taken_at = d->counts + 3 * size;
    /* elements: contiguous ranges of equal quadrature points (a point is the
     * cost: a triangle 3, a quad 4) */
    const long points = 3L * nt + 4L * (n_el - nt);
    long acc = 0;
    int r = 0;
    d->element_lo[0] = 0;
    for (int e = 0; e < n_el; e++) {
        while (r + 1 < size && acc >= points * (r + 1) / size)
            d->element_lo[++r] = e;
        d->owner[e] = r;
        acc += e < nt ? 3 : 4;
    }
    while (r + 1 <= size)
        d->element_lo[++r] = n_el;
    /* nodes: the rank of the lowest element using them, made monotone (a
     * contiguous range per rank; any split is right, this one has few ghosts) */
    for (int i = 0; i < m->n_nodes; i++)
        node_owner[i] = -1;
    for (int e = 0; e < n_el; e++) {
        int n[4], k = element_nodes(m, e, n);
        for (int a = 0; a < k; a++)
            if (node_owner[n[a]] < 0)
                node_owner[n[a]] = d->owner[e];
    }
    int running = 0;
    r = 0;
    d->node_lo[0] = 0;
    for (int i = 0; i < m->n_nodes; i++) {
        if (node_owner[i] > running)
            running = node_owner[i];
        while (r < running)
            d->node_lo[++r] = i;
    }
    while (r + 1 <= size)
        d->node_lo[++r] = m->n_nodes;
    free(node_owner);
    m->dist = d;
    return 0;
}

/* el's blocks this rank computes and counts, its own nodes' range of the
 * gather; `global` maps el's elements to the model's (NULL: the same). */
static int elements_masks(const wff_model *m, wff_elements *el, const int *global,
                          wff_error *err)
{
    const struct wff_dist *d = m->dist;
    const int nt = el->n_tris, n_el = nt + el->n_quads;
    const int tri_blocks = (nt + WFF_BLOCK - 1) / WFF_BLOCK;
    const int n_blocks = tri_blocks + (el->n_quads + WFF_BLOCK - 1) / WFF_BLOCK;
    el->block_run = calloc((size_t)(n_blocks ? n_blocks : 1), 1);
    el->block_count = calloc((size_t)(n_blocks ? n_blocks : 1), 1);
    if (!el->block_run || !el->block_count)
        return wff_fail(err, "out of memory for the model's ranks");
    const int lo = d->node_lo[d->rank], hi = d->node_lo[d->rank + 1];
    for (int i = 0; i < n_el; i++) {
        const int block = i < nt ? i / WFF_BLOCK : tri_blocks + (i - nt) / WFF_BLOCK;
        const int first = i < nt ? i % WFF_BLOCK == 0 : (i - nt) % WFF_BLOCK == 0;
        const int g = global ? global[i] : i;
        const int mine = d->owner[g] == d->rank;
        if (first && mine)
            el->block_count[block] = 1;
        int run = mine;
        const int *n = i < nt ? el->tri + 3 * (size_t)i : el->quad + 4 * (size_t)(i - nt);
        for (int a = 0; a < (i < nt ? 3 : 4); a++)
            run |= n[a] >= lo && n[a] < hi;
        el->block_run[block] |= (unsigned char)run;
    }
    for (int b = 0; b < n_blocks; b++)
        el->block_run[b] |= el->block_count[b];
    int begin = 0, end = el->n_gather;
    while (begin < el->n_gather && el->node_list[begin] < lo)
        begin++;
    end = begin;
    while (end < el->n_gather && el->node_list[end] < hi)
        end++;
    el->gather_begin = begin;
    el->gather_end = end;
    return 0;
}

static int dist_elements(const wff_model *m, wff_elements *el, const int *global, wff_error *err)
{
    if (!m->dist || el->block_run)
        return 0;
    return elements_masks(m, el, global, err);
}

void wff_dist_prepare(wff_model *m, wff_elements *el, const int *global)
{
    if (m->comm.size <= 1 || (m->dist && el->block_run))
        return;
    wff_error err = {0};
    if (dist_setup(m, &err) || dist_elements(m, el, global, &err)) {
        /* (a few bytes an element: a machine out of memory here cannot step) */
        fprintf(stderr, "wovenff: rank %d: %s\n", m->comm.rank, err.message);
        abort();
    }
}

/* The scratch buffer of at least `bytes` (grown, never shrunk: one
 * allocation at a run's first pass); out of memory stops the run. */
static void *scratch(struct wff_dist *d, size_t bytes)
{
    if (bytes > d->scratch_size) {
        void *p = realloc(d->scratch, bytes);
        if (!p) {
            fprintf(stderr, "wovenff: rank %d: out of memory for a force exchange of %zu bytes\n",
                    d->rank, bytes);
            abort();
        }
        d->scratch = p;
        d->scratch_size = bytes;
    }
    return d->scratch;
}

wff_fixed *wff_dist_fixed_scratch(wff_model *m, int n)
{
    struct wff_dist *d = m->dist;
    if (!d)
        return NULL;
    if ((size_t)n > d->fixed_size) {
        wff_fixed *p = realloc(d->fixed, sizeof(wff_fixed) * (size_t)n);
        if (!p) {
            fprintf(stderr, "wovenff: rank %d: out of memory for %d sums\n", d->rank, n);
            abort();
        }
        d->fixed = p;
        d->fixed_size = (size_t)n;
    }
    return d->fixed;
}

/* What a rank adds to its forces in the one exchange of a pass: its sums (the
 * pass's three and `n_more` others), its Newton count and whether it met a bad
 * point. */
typedef struct pass_extras {
    long amplitude_iterations, bad;
} pass_extras;

/* The points' static amplitudes the pass updates (m->el.point_dA: 2 a point),
 * NULL with dynamic amplitudes (zones keep them dynamic: model.c). The
 * replicated stable step reads them at every element (membrane_centre.c), and
 * outputs, snapshots and checkpoints do: each rank's own elements' go with its
 * forces. */
static double *pass_amplitudes(const wff_model *m)
{
    return m->em.static_amplitudes && !m->zones ? m->el.point_dA : NULL;
}

/* Bytes of rank r's elements' static amplitudes (0 without), from double
 * *first (into dA). */
static size_t amplitude_bytes(const wff_model *m, const struct wff_dist *d, int r, size_t *first)
{
    const size_t a = wff_element_first_point(m->el.n_tris, d->element_lo[r]);
    const size_t b = wff_element_first_point(m->el.n_tris, d->element_lo[r + 1]);
    *first = 2 * a;
    return pass_amplitudes(m) ? sizeof(double) * 2 * (b - a) : 0;
}

int wff_dist_forces(wff_model *m, double *f, wff_force_totals *t, wff_fixed *more, int n_more)
{
    struct wff_dist *d = m->dist;
    if (!d)
        return 0;
    const double start = wff_wall_seconds();
    /* one exchange a pass: each rank's message its nodes' forces (then its
     * elements' static amplitudes, if any), then its sums and counts; every
     * rank gets every rank's */
    const size_t extra = sizeof(wff_fixed) * (size_t)(WFF_BLOCK_SUMS + n_more) + sizeof(pass_extras);
    double *dA = pass_amplitudes(m);
    size_t total = 0, first;
    for (int r = 0; r < d->size; r++) {
        d->offsets[r] = (long)total;
        d->counts[r] = (long)(sizeof(double) * D * (size_t)(d->node_lo[r + 1] - d->node_lo[r]) +
                              amplitude_bytes(m, d, r, &first) + extra);
        total += (size_t)d->counts[r];
    }
    char *all = scratch(d, total);
    {   /* this rank's message */
        char *mine = all + d->offsets[d->rank];
        size_t forces = sizeof(double) * D * (size_t)(d->node_lo[d->rank + 1] - d->node_lo[d->rank]);
        memcpy(mine, f + D * (size_t)d->node_lo[d->rank], forces);
        const size_t amplitudes = amplitude_bytes(m, d, d->rank, &first);
        if (amplitudes)
            memcpy(mine + forces, dA + first, amplitudes);
        forces += amplitudes; /* (what comes before the sums) */
        memcpy(mine + forces, t->sums, sizeof(wff_fixed) * WFF_BLOCK_SUMS);
        if (n_more > 0)
            memcpy(mine + forces + sizeof(wff_fixed) * WFF_BLOCK_SUMS, more, sizeof(wff_fixed) * (size_t)n_more);
        pass_extras e = {t->amplitude_iterations, t->bad_element >= 0};
        memcpy(mine + forces + sizeof(wff_fixed) * (size_t)(WFF_BLOCK_SUMS + n_more), &e, sizeof e);
    }
    wff_comm_allgather(&m->comm, all, d->counts, d->offsets);
    /* every rank's forces into f; the sums added (order-free), the counts too */
    wff_fixed sums[WFF_BLOCK_SUMS];
    for (int k = 0; k < WFF_BLOCK_SUMS; k++)
        sums[k] = wff_fixed_zero();
    for (int k = 0; k < n_more; k++)
        more[k] = wff_fixed_zero();
    long iterations = 0, bad = 0;
    for (int r = 0; r < d->size; r++) {
        const char *msg = all + d->offsets[r];
        size_t forces = sizeof(double) * D * (size_t)(d->node_lo[r + 1] - d->node_lo[r]);
        const size_t amplitudes = amplitude_bytes(m, d, r, &first);
        if (r != d->rank) {
            memcpy(f + D * (size_t)d->node_lo[r], msg, forces);
            if (amplitudes)
                memcpy(dA + first, msg + forces, amplitudes);
        }
        forces += amplitudes;
        for (int k = 0; k < WFF_BLOCK_SUMS + n_more; k++) {
            wff_fixed x;
            memcpy(&x, msg + forces + sizeof(wff_fixed) * (size_t)k, sizeof x);
            wff_fixed_merge(k < WFF_BLOCK_SUMS ? &sums[k] : &more[k - WFF_BLOCK_SUMS], &x);
        }
        pass_extras e;
        memcpy(&e, msg + forces + sizeof(wff_fixed) * (size_t)(WFF_BLOCK_SUMS + n_more), sizeof e);
        iterations += e.amplitude_iterations;
        bad += e.bad;
    }
    for (int k = 0; k < WFF_BLOCK_SUMS; k++)
        t->sums[k] = sums[k];
    t->internal_energy = wff_fixed_value(&t->sums[0]);
    t->dissipated = wff_fixed_value(&t->sums[1]);
    t->failure_dissipated = wff_fixed_value(&t->sums[2]);
    t->slip_dissipated = wff_fixed_value(&t->sums[3]);
    t->amplitude_iterations = iterations;
    if (bad > 0) { /* a bad point somewhere (rare: the run stops): the lowest element's */
        double lowest = t->bad_element >= 0 ? t->bad_element : (double)d->n_elements;
        int from = d->rank;
        wff_comm_min_index(&m->comm, &lowest, &from);
        struct { int element, point, status, iterations; double residual; } worst = {
            t->bad_element, t->bad_point, t->bad_status, t->bad_iterations, t->bad_residual};
        wff_comm_broadcast(&m->comm, from, &worst, (long)sizeof worst);
        t->bad_element = worst.element;
        t->bad_point = worst.point;
        t->bad_status = worst.status;
        t->bad_iterations = worst.iterations;
        t->bad_residual = worst.residual;
    }
    d->exchange_seconds += wff_wall_seconds() - start;
    return 0;
}

int wff_dist_owns_element(const wff_model *m, int e)
{
    return !m->dist || m->dist->owner[e] == m->dist->rank;
}

int wff_dist_eroded_gather(wff_model *m, int n_mine)
{
    struct wff_dist *d = m->dist;
    if (!d)
        return n_mine;
    /* how many each rank took, then the lists in rank order (element order) */
    const double start = wff_wall_seconds();
    long *n = d->taken, *at = d->taken_at;
    for (int r = 0; r < d->size; r++)
        n[r] = 0;
    n[d->rank] = n_mine;
    wff_comm_sum_long(&m->comm, n, d->size);
    long total = 0;
    for (int r = 0; r < d->size; r++) {
        at[r] = total;
        total += n[r];
    }
    if (total == 0) {
        m->dist->exchange_seconds += wff_wall_seconds() - start;
        return 0;
    }
    memmove(m->eroded_now + at[d->rank], m->eroded_now, sizeof(int) * (size_t)n_mine);
    memmove(m->eroded_now_energy + at[d->rank], m->eroded_now_energy,
            sizeof(double) * (size_t)n_mine);
    for (int r = 0; r < d->size; r++)
        d->counts[r] = (long)sizeof(int) * n[r], d->offsets[r] = (long)sizeof(int) * at[r];
    wff_comm_allgather(&m->comm, m->eroded_now, d->counts, d->offsets);
    for (int r = 0; r < d->size; r++)
        d->counts[r] = (long)sizeof(double) * n[r], d->offsets[r] = (long)sizeof(double) * at[r];
    wff_comm_allgather(&m->comm, m->eroded_now_energy, d->counts, d->offsets);
    m->dist->exchange_seconds += wff_wall_seconds() - start;
    return (int)total;
}

void wff_dist_states_whole(wff_model *m)
{
    struct wff_dist *d = m->dist;
    if (!d || !m->state)
        return;
    const double start = wff_wall_seconds();
    const int nt = m->mesh.n_tris;
    for (int r = 0; r < d->size; r++) {
        const size_t a = wff_element_first_point(nt, d->element_lo[r]);
        const size_t b = wff_element_first_point(nt, d->element_lo[r + 1]);
        d->counts[r] = (long)(sizeof(double) * (size_t)m->n_state * (b - a));
        d->offsets[r] = (long)(sizeof(double) * (size_t)m->n_state * a);
    }
    wff_comm_allgather(&m->comm, m->state, d->counts, d->offsets);
    const double spent = wff_wall_seconds() - start;
    m->dist->exchange_seconds += spent;
    m->dist->gather_seconds += spent;
}

/* The part (part.h): the model's ranks and the timers of the pass it splits
 * (force_seconds: the steps' force passes with their exchange; exchange_seconds:
 * the exchanges alone) in its values; a mesh transfer over
 * ranks refused (not built: the states would have to be gathered first). */
static const char *const distributed_value_names[] = {"mpi_ranks", "force_seconds",
                                                      "exchange_seconds", NULL};

static void distributed_value(const wff_model *m, const char *key, double *value)
{
    const struct wff_dist *d = m->dist;
    if (strcmp(key, "mpi_ranks") == 0)
        *value = m->comm.size;
    else if (strcmp(key, "force_seconds") == 0) /* (the model's timer: the split's share) */
        *value = m->force_seconds;
    else
        *value = d ? d->exchange_seconds : 0;
}

static int distributed_refuses_remesh(const wff_model *m, char *why, size_t size)
{
    if (m->comm.size <= 1)
        return 0;
    snprintf(why, size, "the model runs over %d MPI ranks: a mesh transfer over ranks is not "
             "built (run -adapt on one rank)", m->comm.size);
    return 1;
}

const wff_part_ops wff_distributed_part = {
    .name = "distributed",
    .value_names = distributed_value_names,
    .value = distributed_value,
    .refuses_remesh = distributed_refuses_remesh,
};

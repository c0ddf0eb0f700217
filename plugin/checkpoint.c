/* checkpoint.c: a model's evolving state saved to and loaded from a binary
 * file (the format is in include/wovenff/solver.h): 64-bit FNV-1a
 * fingerprints of what must match, the state fields in file order, an
 * atomic save (text_io.c) and a load that says which input differs. Knows the
 * model's arrays; nothing of how they evolve, of cells by name or of FreeFEM. */
#include "part.h"
#include "state_fields.h"
#include "zones.h"
#include "wovenff/text_io.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Largest checkpoint read: far above any model this code runs (a 50k-element
 * model's state is a few megabytes). */
#define CHECKPOINT_FILE_MAX ((size_t)1 << 40)

static const char checkpoint_magic[8] = {'W', 'F', 'F', 'S', 'T', 'A', 'T', 'E'};
#define BYTE_ORDER_MARK 0x0102030405060708ULL


static size_t n_points(const wff_model *m)
{
    return wff_elements_point_count(&m->el);
}

#define STATE_LAYOUT_MAX 128

/* What a checkpoint must match: sizes, fingerprints, settings. */
typedef struct checkpoint_header {
    char magic[8];
    uint32_t version, header_size;
    uint64_t byte_order;
    int32_t n_nodes, n_tris, n_quads, n_points, n_candidates, projectile_active, clamp_nodes,
        dt_interval, reference_path, n_state, erosion;
    char state_names[STATE_LAYOUT_MAX]; /* the points' states, space-separated ("gamma_f") */
    uint64_t mesh_hash, material_hash, mass_hash, bc_hash, settings_hash;
    double dt_factor, symmetry_factor, projectile_radius, projectile_mass, projectile_mu;
    double orientation;               /* the warp's angle to the mesh's x axis, rad */
    uint64_t payload_size;
} checkpoint_header;

static void fingerprint(const wff_model *m, checkpoint_header *h)
{
    memset(h, 0, sizeof *h);
    memcpy(h->magic, checkpoint_magic, sizeof h->magic);
    h->version = WFF_CHECKPOINT_VERSION;
    h->header_size = sizeof *h;
    h->byte_order = BYTE_ORDER_MARK;
    h->n_nodes = m->n_nodes;
    h->n_tris = m->el.n_tris;
    h->n_quads = m->el.n_quads;
    h->n_points = (int32_t)n_points(m);
    h->n_candidates = m->projectile.active ? m->projectile.n_candidates : 0;
    h->projectile_active = m->projectile.active;
    h->clamp_nodes = m->clamp.n;
    h->dt_interval = m->dt_interval;
    h->reference_path = m->em.reference_path;
    h->n_state = m->n_state;
    h->erosion = m->el.eroded ? m->el.erosion : 0;
    for (int i = 0; i < m->n_state; i++) {
        size_t used = strlen(h->state_names);
        snprintf(h->state_names + used, sizeof h->state_names - used, "%s%s", i ? " " : "",
                 wff_model_state_name(m, i));
    }
    uint64_t g = WFF_FNV_START;
    g = wff_fnv1a(g, m->mesh.xy, sizeof(double) * 2 * (size_t)m->n_nodes);
    g = wff_fnv1a(g, m->el.tri, sizeof(int) * 3 * (size_t)m->el.n_tris);
    g = wff_fnv1a(g, m->el.quad, sizeof(int) * 4 * (size_t)m->el.n_quads);
    h->mesh_hash = g;
    const char *cell = m->mat.cell ? wff_cell_name(m->mat.cell) : "";
    g = wff_fnv1a(WFF_FNV_START, cell, strlen(cell));
    g = wff_fnv1a(g, &m->mat.areal_density, sizeof(double));
    g = wff_fnv1a(g, m->mat.params, sizeof m->mat.params);
    g = wff_zones_fingerprint(m, g); /* the zones' materials (unchanged without zones) */
    h->material_hash = g;
    h->mass_hash = wff_fnv1a(WFF_FNV_START, m->mass, sizeof(double) * (size_t)m->n_dofs);
    g = wff_fnv1a(WFF_FNV_START, m->dof_kind, (size_t)m->n_dofs);
    g = wff_fnv1a(g, m->clamp.node, sizeof(int) * (size_t)m->clamp.n);
    g = wff_fnv1a(g, m->clamp.normal_force, sizeof(double) * (size_t)m->clamp.n);
    g = wff_fnv1a(g, &m->clamp.mu, sizeof(double));
    g = wff_fnv1a(g, &m->clamp.edge_reaction, sizeof(int));
    h->bc_hash = g;
    /* settings that change the numbers: preload, amplitude treatment, contact search,
     * threads (the force sums' order) */
    g = wff_fnv1a(WFF_FNV_START, m->em.F_pre, sizeof m->em.F_pre);
    g = wff_fnv1a(g, &m->em.amplitude_mass_factor, sizeof(double));
    g = wff_fnv1a(g, &m->em.static_amplitudes, sizeof(int));
    if (m->travel_off) /* (the default leaves the hash as it was) */
        g = wff_fnv1a(g, &m->travel_off, sizeof(int));
    if (m->travel_fraction != WFF_TRAVEL)
        g = wff_fnv1a(g, &m->travel_fraction, sizeof(double));
    g = wff_fnv1a(g, &m->projectile.search_all, sizeof(int));
    g = wff_fnv1a(g, &m->el.n_threads, sizeof(int));
    /* the projectile's nose and axis, when not the default (older checkpoints of a
     * hemisphere at the origin still load) */
    const wff_projectile *p = &m->projectile;
    if (p->nose != WFF_NOSE_HEMISPHERE || p->axis[0] != 0 || p->axis[1] != 0) {
        g = wff_fnv1a(g, &p->nose, sizeof(int));
        g = wff_fnv1a(g, &p->edge_radius, sizeof(double));
        g = wff_fnv1a(g, p->axis, sizeof p->axis);
    }
    if (p->nose == WFF_NOSE_CHISEL) { /* (new shapes: older checkpoints have none) */
        g = wff_fnv1a(g, &p->chisel_flat, sizeof(double));
        g = wff_fnv1a(g, &p->chisel_bevel, sizeof(double));
    }
    if (p->oblique)
        g = wff_fnv1a(g, p->path, sizeof p->path);
    g = wff_parts_fingerprint(m, g); /* the parts' (a pack's; unchanged without) */
    h->settings_hash = g;
    h->dt_factor = m->dt_factor;
    h->symmetry_factor = m->symmetry_factor;
    h->orientation = m->em.orientation;
    if (m->projectile.active) {
        h->projectile_radius = m->projectile.radius;
        h->projectile_mass = m->projectile.mass;
        h->projectile_mu = m->projectile.mu;
    }
}



int wff_model_save(const wff_model *m, const char *path, wff_error *err)
{
    char why[WFF_ERROR_MAX - 64];
    if (wff_parts_refuse_checkpoint(m, why, sizeof why)) /* (part.h) */
        return wff_fail(err, "checkpoint '%s': cannot be written: %s: refused", path, why);
    checkpoint_header h;
    fingerprint(m, &h);
    wff_state_field fields[WFF_STATE_FIELDS_MAX];
    int nf = wff_state_fields((wff_model *)m, h.n_candidates, fields);
    size_t payload = 0;
    for (int i = 0; i < nf; i++)
        payload += fields[i].size * fields[i].count;
    h.payload_size = payload;
    wff_atomic_file out;
    if (wff_atomic_open(&out, path, "checkpoint", err))
        return -1;
    uint64_t sum = wff_fnv1a(WFF_FNV_START, &h, sizeof h);
    wff_atomic_write(&out, &h, sizeof h);
    for (int i = 0; i < nf; i++) {
        size_t bytes = fields[i].size * fields[i].count;
        if (bytes == 0)
            continue;
        sum = wff_fnv1a(sum, fields[i].data, bytes);
        wff_atomic_write(&out, fields[i].data, bytes);
    }
    wff_atomic_write(&out, &sum, sizeof sum);
    return wff_atomic_commit(&out, err);
}

static const char *hash_mismatch(const checkpoint_header *a, const checkpoint_header *b)
{
    if (a->mesh_hash != b->mesh_hash)
        return "the mesh differs (same sizes, other node coordinates or connectivity)";
    if (a->material_hash != b->material_hash)
        return "the material differs (cell or parameters)";
    if (a->mass_hash != b->mass_hash)
        return "the lumped masses differ (another preload or areal density)";
    if (a->bc_hash != b->bc_hash)
        return "the boundary conditions differ (fixed or prescribed DOFs, friction clamp)";
    if (a->settings_hash != b->settings_hash)
        return "the solver settings differ (preload F_pre, amplitude mass factor, static "
               "amplitudes, contact search, threads, the projectile's nose, chisel, obliquity or "
               "impact point, or a pack's gap, layup, ply_mu or ply_thickness)";
    return NULL;
}

int wff_model_load_state(wff_model *m, const char *path, wff_error *err)
{
    char refusal[WFF_ERROR_MAX - 64];
    if (wff_parts_refuse_checkpoint(m, refusal, sizeof refusal)) /* (part.h) */
        return wff_fail(err, "checkpoint '%s': cannot be restarted from: %s: refused", path,
                        refusal);
    char *buf;
    size_t size;
    if (wff_read_file(path, "checkpoint", CHECKPOINT_FILE_MAX, &buf, &size, err))
        return -1;
    int rc = -1;
    checkpoint_header h, want;
    if (size < sizeof checkpoint_magic || memcmp(buf, checkpoint_magic, sizeof checkpoint_magic)) {
        wff_fail(err, "%s is not a wovenff checkpoint (no WFFSTATE magic)", path);
        goto done;
    }
    if (size < sizeof h + sizeof(uint64_t)) {
        wff_fail(err, "checkpoint %s is truncated (%zu bytes)", path, size);
        goto done;
    }
    memcpy(&h, buf, sizeof h);
    if (h.byte_order != BYTE_ORDER_MARK) {
        wff_fail(err, "checkpoint %s was written on a machine with another byte order", path);
        goto done;
    }
    if (h.version != WFF_CHECKPOINT_VERSION || h.header_size != sizeof h) {
        wff_fail(err, "checkpoint %s has format version %u (header %u bytes); this build reads "
                 "version %d (header %zu bytes)", path, h.version, h.header_size,
                 WFF_CHECKPOINT_VERSION, sizeof h);
        goto done;
    }
    if (h.payload_size != size - sizeof h - sizeof(uint64_t)) {
        wff_fail(err, "checkpoint %s is truncated or has trailing data (%zu bytes, header says "
                 "%llu)", path, size, (unsigned long long)(sizeof h + h.payload_size + 8));
        goto done;
    }
    uint64_t stored;
    memcpy(&stored, buf + size - sizeof stored, sizeof stored);
    if (wff_fnv1a(WFF_FNV_START, buf, size - sizeof stored) != stored) {
        wff_fail(err, "checkpoint %s is corrupt (checksum mismatch)", path);
        goto done;
    }
    fingerprint(m, &want);
    if (h.n_nodes != want.n_nodes || h.n_tris != want.n_tris || h.n_quads != want.n_quads ||
        h.n_points != want.n_points) {
        wff_fail(err, "checkpoint %s was written for a model of %d nodes, %d triangles, %d "
                 "quadrilaterals; this model has %d nodes, %d triangles, %d quadrilaterals "
                 "(another mesh)", path, h.n_nodes, h.n_tris, h.n_quads, want.n_nodes,
                 want.n_tris, want.n_quads);
        goto done;
    }
    h.state_names[sizeof h.state_names - 1] = 0;
    if (h.n_state != want.n_state || strcmp(h.state_names, want.state_names) != 0) {
        wff_fail(err, "checkpoint %s carries %d internal states per point (%s); this model's "
                 "points carry %d (%s): another cell or failure setting", path, h.n_state,
                 h.n_state ? h.state_names : "none", want.n_state,
                 want.n_state ? want.state_names : "none");
        goto done;
    }
    if (h.erosion != want.erosion) {
        wff_fail(err, "checkpoint %s was written with erosion %d; this model has erosion %d "
                 "(0 off, 1 both yarn families, 2 either: set it as the run was)", path,
                 h.erosion, want.erosion);
        goto done;
    }
    if (h.orientation != want.orientation) { /* (before the settings' hash, which holds it) */
        wff_fail(err, "checkpoint %s was written with orientation %.15g deg; this model has %.15g "
                 "deg (the warp's angle to the mesh's x axis: set it as the run was)", path,
                 h.orientation * 180 / M_PI, want.orientation * 180 / M_PI);
        goto done;
    }
    const char *why = hash_mismatch(&h, &want);
    if (why) {
        wff_fail(err, "checkpoint %s does not match this model: %s", path, why);
        goto done;
    }
    if (h.dt_factor != want.dt_factor || h.dt_interval != want.dt_interval ||
        h.symmetry_factor != want.symmetry_factor || h.reference_path != want.reference_path) {
        wff_fail(err, "checkpoint %s has solver settings dtfactor %g, dtinterval %d, symmetry "
                 "%g, reference_path %d; this model has %g, %d, %g, %d", path, h.dt_factor,
                 h.dt_interval, h.symmetry_factor, h.reference_path, want.dt_factor,
                 want.dt_interval, want.symmetry_factor, want.reference_path);
        goto done;
    }
    if (h.projectile_active != want.projectile_active ||
        h.projectile_radius != want.projectile_radius ||
        h.projectile_mass != want.projectile_mass || h.projectile_mu != want.projectile_mu) {
        if (h.projectile_active && want.projectile_active)
            wff_fail(err, "checkpoint %s has a projectile of radius %g m, mass %g kg, mu %g; "
                     "this model's has %g m, %g kg, %g", path, h.projectile_radius,
                     h.projectile_mass, h.projectile_mu, want.projectile_radius,
                     want.projectile_mass, want.projectile_mu);
        else
            wff_fail(err, "checkpoint %s was written %s a projectile, this model has %s", path,
                     h.projectile_active ? "with" : "without",
                     want.projectile_active ? "one" : "none");
        goto done;
    }
    if (h.n_candidates < 0 || h.n_candidates > h.n_nodes) {
        wff_fail(err, "checkpoint %s is corrupt (%d contact candidates)", path, h.n_candidates);
        goto done;
    }
    wff_state_field fields[WFF_STATE_FIELDS_MAX];
    int nf = wff_state_fields(m, h.n_candidates, fields);
    size_t payload = 0;
    for (int i = 0; i < nf; i++)
        payload += fields[i].size * fields[i].count;
    if (payload != h.payload_size) {
        wff_fail(err, "checkpoint %s: state of %llu bytes, this model's is %zu", path,
                 (unsigned long long)h.payload_size, payload);
        goto done;
    }
    const char *at = buf + sizeof h;
    for (int i = 0; i < nf; i++) {
        size_t bytes = fields[i].size * fields[i].count;
        if (bytes)
            memcpy(fields[i].data, at, bytes);
        at += bytes;
    }
    rc = 0;
done:
    free(buf);
    return rc;
}


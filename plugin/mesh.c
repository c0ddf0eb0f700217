/* mesh.c: planar meshes through gmsh's C API (gmsh 4.8.4): open a .geo (and
 * mesh it in 2-D) or a .msh, copy nodes, triangles, quadrilaterals and the
 * line elements of physical curves into plain arrays, and check them. The
 * only file that knows gmsh (mesh_arrays.c has what is done with the arrays
 * afterwards); knows nothing of materials, elements or the solver.
 *
 * gmsh is one global session per process: each load initialises it, and
 * finalises it on every path, so nothing of gmsh outlives the call. */
#include "wovenff/mesh.h"
#include "wovenff/mesh_labels.h"
#include "wovenff/text_io.h"

#include <errno.h>
#include <limits.h>
#include <locale.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

#include <gmshc.h>
#ifdef _OPENMP
#include <omp.h>
#endif

/* gmsh element types kept (see gmsh's MSH format documentation). */
#define GMSH_LINE2 1
#define GMSH_TRI3 2
#define GMSH_QUAD4 3

/* Tolerances relative to the bounding-box diagonal d of the kept nodes:
 * |z| <= Z_TOL d, element area > AREA_TOL d^2 (and each quad corner's cross
 * product beyond AREA_TOL d^2, so a 180-degree corner counts as non-convex). */
#define Z_TOL 1e-9
#define AREA_TOL 1e-12

typedef struct node_key {
    size_t tag; /* gmsh node tag */
    int pos;    /* position in the arrays gmsh returned */
} node_key;

/* One kept 2-D element, in the order read (its 1-based ordinal is index+1). */
typedef struct elem_rec {
    size_t tag;  /* gmsh element tag */
    int n;       /* 3 or 4 */
    int region;
    int node[4]; /* positions in the gmsh node arrays */
} elem_rec;

/* Everything a load holds; released by build_release() on every path. */
typedef struct build {
    const char *path;
    wff_error *err;
    /* from gmsh (gmshFree) */
    size_t *gtag;
    double *gxyz;
    size_t n_gnodes;
    /* ours (free) */
    node_key *keys;  /* gtag sorted */
    int *new_index;  /* per gmsh node position: -1 unused, else output index */
    elem_rec *elems;
    int n_elems, cap_elems;
    int *edge_pos;   /* 2 per edge: gmsh node positions */
    int *edge_label;
    int n_edges, cap_edges;
    wff_mesh_group *groups;
    int n_groups;
} build;

static void build_release(build *b)
{
    gmshFree(b->gtag);
    gmshFree(b->gxyz);
    free(b->keys);
    free(b->new_index);
    free(b->elems);
    free(b->edge_pos);
    free(b->edge_label);
    free(b->groups);
}

/* Frees what gmshModelMeshGetElements() returns. */
static void free_elements(int *types, size_t n_types, size_t **etags, size_t **ntags)
{
    for (size_t i = 0; i < n_types; i++) {
        if (etags)
            gmshFree(etags[i]);
        if (ntags)
            gmshFree(ntags[i]);
    }
    gmshFree(types);
    gmshFree(etags);
    gmshFree(ntags);
}

/* gmsh's first "Error: " line since the logger started into buf (size 0: only
 * asked); 1 if there is one. */
static int logged_error(char *buf, size_t size)
{
    int ierr = 0, found = 0;
    char **log = NULL;
    size_t n_log = 0;
    gmshLoggerGet(&log, &n_log, &ierr);
    for (size_t i = 0; i < n_log; i++) {
        if (!found && !ierr && strncmp(log[i], "Error: ", 7) == 0) {
            found = 1;
            if (size)
                snprintf(buf, size, "%s", log[i] + 7);
        }
        gmshFree(log[i]);
    }
    gmshFree(log);
    return found;
}

/* gmsh's first error since the logger started (else its last error) into buf,
 * with control and non-ASCII bytes replaced: gmsh quotes file contents. */
static void gmsh_message(char *buf, size_t size)
{
    buf[0] = '\0';
    if (!logged_error(buf, size)) {
        int ierr = 0;
        char *last = NULL;
        gmshLoggerGetLastError(&last, &ierr);
        if (!ierr && last)
            snprintf(buf, size, "%s", last);
        gmshFree(last);
    }
    if (!buf[0])
        snprintf(buf, size, "unknown gmsh error");
    for (char *p = buf; *p; p++)
        if ((unsigned char)*p < 0x20 || (unsigned char)*p > 0x7e)
            *p = '?';
}

/* Fails with gmsh's own words about what went wrong while doing `what`. */
static int gmsh_fail(build *b, const char *what)
{
    char msg[WFF_ERROR_MAX];
    gmsh_message(msg, sizeof msg);
    return wff_fail(b->err, "%s: gmsh could not %s: %s", b->path, what, msg);
}

/* True when the logger recorded an error (gmsh reports some, e.g. while
 * meshing, without setting ierr). */
static int gmsh_logged_error(void)
{
    return logged_error(NULL, 0);
}

static int has_suffix(const char *s, const char *suffix)
{
    size_t n = strlen(s), m = strlen(suffix);
    return n > m && strcasecmp(s + n - m, suffix) == 0;
}

static int check_options(const char *path, const wff_mesh_options *o, wff_error *err)
{
    if (o->n_settings < 0 || o->n_settings > WFF_MESH_SETTINGS_MAX)
        return wff_fail(err, "%s: %d mesh settings (0 to %d allowed)", path, o->n_settings,
                        WFF_MESH_SETTINGS_MAX);
    for (int i = 0; i < o->n_settings; i++) {
        const wff_mesh_setting *s = &o->settings[i];
        if (!memchr(s->name, '\0', sizeof s->name) || !s->name[0])
            return wff_fail(err, "%s: mesh setting %d has an empty or unterminated name", path,
                            i + 1);
        if (!isfinite(s->value))
            return wff_fail(err, "%s: mesh setting '%s' is not a finite number", path, s->name);
    }
    if (!isfinite(o->size_factor) || o->size_factor < 0)
        return wff_fail(err, "%s: size_factor %g must be positive (or 0 for 1)", path,
                        o->size_factor);
    return 0;
}

/* Each setting must have reached a DefineConstant of the .geo: gmsh marks
 * the ONELAB parameters a file read with its client ("clients" in the JSON),
 * while one set by us and never read has none. Catches misspelt names. */
static int check_settings_used(build *b, const wff_mesh_options *o)
{
    for (int i = 0; i < o->n_settings; i++) {
        const char *name = o->settings[i].name;
        char *json = NULL;
        int ierr = 0;
        gmshOnelabGet(&json, name, "json", &ierr);
        int used = !ierr && json && strstr(json, "\"clients\"");
        gmshFree(json);
        if (!used)
            return wff_fail(b->err,
                            "%s: setting '%s' is not a parameter of this file (it needs "
                            "DefineConstant[ %s = {default, Name \"%s\"} ])",
                            b->path, name, name, name);
    }
    return 0;
}

/* Open (and for a .geo, mesh) the file in the current gmsh session. */
static int gmsh_load(build *b, const wff_mesh_options *o, int is_geo)
{
    int ierr = 0;
    if (is_geo) {
        gmshOnelabClear("", &ierr); /* ONELAB outlives gmshFinalize: drop old settings */
        if (ierr)
            return gmsh_fail(b, "clear its parameters");
        for (int i = 0; i < o->n_settings; i++) {
            double v = o->settings[i].value;
            gmshOnelabSetNumber(o->settings[i].name, &v, 1, &ierr);
            if (ierr)
                return gmsh_fail(b, "set a parameter");
        }
    }
    /* Quads by "simple full-quad" recombination unless the file chooses: the
     * default (Blossom) writes to stdout and takes minutes from ~100k quads. */
    gmshOptionSetNumber("Mesh.RecombinationAlgorithm", 2, &ierr);
    if (ierr)
        return gmsh_fail(b, "set its mesh options");
    gmshOpen(b->path, &ierr);
    if (ierr || gmsh_logged_error())
        return gmsh_fail(b, "read it");
    if (!is_geo)
        return 0;
    if (check_settings_used(b, o))
        return -1;
    /* After gmshOpen, so these win over the file's own Mesh options. */
    if (o->recombine)
        gmshOptionSetNumber("Mesh.RecombineAll", 1, &ierr);
    if (!ierr && o->size_factor > 0)
        gmshOptionSetNumber("Mesh.MeshSizeFactor", o->size_factor, &ierr);
    if (!ierr) /* again, in case the file changed them (see wff_mesh_load) */
        gmshOptionSetNumber("General.AbortOnError", 0, &ierr);
    if (!ierr)
        gmshOptionSetNumber("General.Verbosity", 1, &ierr);
    if (ierr)
        return gmsh_fail(b, "set its mesh options");
    gmshModelMeshGenerate(2, &ierr);
    if (ierr || gmsh_logged_error())
        return gmsh_fail(b, "mesh it");
    return 0;
}

static int read_groups(build *b)
{
    int ierr = 0;
    for (int dim = 1; dim <= 2; dim++) {
        int *dt = NULL;
        size_t n_dt = 0;
        gmshModelGetPhysicalGroups(&dt, &n_dt, dim, &ierr);
        if (ierr) {
            gmshFree(dt);
            return gmsh_fail(b, "list its physical groups");
        }
        size_t n = n_dt / 2;
        wff_mesh_group *g = n ? realloc(b->groups, (b->n_groups + n) * sizeof *g) : b->groups;
        if (n && !g) {
            gmshFree(dt);
            return wff_fail(b->err, "%s: out of memory for %zu physical groups", b->path, n);
        }
        b->groups = g;
        for (size_t i = 0; i < n; i++) {
            wff_mesh_group *gi = &b->groups[b->n_groups];
            gi->dim = dt[2 * i];
            gi->tag = dt[2 * i + 1];
            char *name = NULL;
            gmshModelGetPhysicalName(gi->dim, gi->tag, &name, &ierr);
            int too_long = !ierr && name && strlen(name) >= sizeof gi->name;
            if (!ierr && !too_long)
                snprintf(gi->name, sizeof gi->name, "%s", name ? name : "");
            gmshFree(name);
            if (ierr) {
                gmshFree(dt);
                return gmsh_fail(b, "read a physical group name");
            }
            if (too_long) {
                gmshFree(dt);
                return wff_fail(b->err, "%s: physical group %d (dimension %d) has a name longer "
                                "than %d characters", b->path, gi->tag, gi->dim,
                                WFF_MESH_NAME_MAX - 1);
            }
            b->n_groups++;
        }
        gmshFree(dt);
    }
    return 0;
}

static int cmp_node_key(const void *a, const void *b)
{
    size_t x = ((const node_key *)a)->tag, y = ((const node_key *)b)->tag;
    return (x > y) - (x < y);
}

/* All nodes of the model, with a tag -> position lookup (tags may be sparse). */
static int read_nodes(build *b)
{
    int ierr = 0;
    size_t n_coord = 0, n_param = 0;
    double *param = NULL;
    gmshModelMeshGetNodes(&b->gtag, &b->n_gnodes, &b->gxyz, &n_coord, &param, &n_param, -1, -1,
                          0, 0, &ierr);
    gmshFree(param);
    if (ierr)
        return gmsh_fail(b, "return its nodes");
    if (n_coord != 3 * b->n_gnodes)
        return wff_fail(b->err, "%s: gmsh returned %zu coordinates for %zu nodes", b->path,
                        n_coord, b->n_gnodes);
    if (b->n_gnodes > INT_MAX / 4)
        return wff_fail(b->err, "%s: %zu nodes (at most %d)", b->path, b->n_gnodes, INT_MAX / 4);
    size_t n = b->n_gnodes ? b->n_gnodes : 1;
    b->keys = malloc(n * sizeof *b->keys);
    b->new_index = malloc(n * sizeof *b->new_index);
    if (!b->keys || !b->new_index)
        return wff_fail(b->err, "%s: out of memory for %zu nodes", b->path, b->n_gnodes);
    for (size_t i = 0; i < b->n_gnodes; i++) {
        b->keys[i].tag = b->gtag[i];
        b->keys[i].pos = (int)i;
        b->new_index[i] = -1;
    }
    qsort(b->keys, b->n_gnodes, sizeof *b->keys, cmp_node_key);
    for (size_t i = 1; i < b->n_gnodes; i++)
        if (b->keys[i].tag == b->keys[i - 1].tag)
            return wff_fail(b->err, "%s: node tag %zu appears twice", b->path, b->keys[i].tag);
    return 0;
}

static int node_pos(const build *b, size_t tag)
{
    node_key key = {tag, 0};
    const node_key *k = bsearch(&key, b->keys, b->n_gnodes, sizeof key, cmp_node_key);
    return k ? k->pos : -1;
}

/* The single physical group of an entity: 1 and *tag set, 0 if none, -1 on a
 * gmsh error; *count says how many groups it has. */
static int entity_group(int dim, int entity, int *tag, size_t *count)
{
    int ierr = 0, *phys = NULL;
    size_t n = 0;
    gmshModelGetPhysicalGroupsForEntity(dim, entity, &phys, &n, &ierr);
    if (!ierr && n >= 1)
        *tag = phys[0];
    gmshFree(phys);
    *count = n;
    return ierr ? -1 : n > 0;
}

/* The name gmsh gives an element type, e.g. "Triangle 6". */
static void element_type_name(int type, char *buf, size_t size)
{
    int ierr = 0, dim = 0, order = 0, n_nodes = 0, n_primary = 0;
    char *name = NULL;
    double *local = NULL;
    size_t n_local = 0;
    gmshModelMeshGetElementProperties(type, &name, &dim, &order, &n_nodes, &local, &n_local,
                                      &n_primary, &ierr);
    snprintf(buf, size, "%s", !ierr && name ? name : "unknown element");
    gmshFree(name);
    gmshFree(local);
}

static int push_elem(build *b, const elem_rec *e)
{
    if (b->n_elems == b->cap_elems) {
        if (b->cap_elems > INT_MAX / 8)
            return wff_fail(b->err, "%s: too many 2-D elements", b->path);
        int cap = b->cap_elems ? 2 * b->cap_elems : 1024;
        elem_rec *p = realloc(b->elems, (size_t)cap * sizeof *p);
        if (!p)
            return wff_fail(b->err, "%s: out of memory for %d 2-D elements", b->path, cap);
        b->elems = p;
        b->cap_elems = cap;
    }
    b->elems[b->n_elems++] = *e;
    return 0;
}

/* The 2-D elements that count: those of physical surfaces if the model has
 * any (what gmsh saves), else all; region = physical surface tag or 0. */
static int read_elements(build *b)
{
    int ierr = 0, has_physical = 0;
    for (int i = 0; i < b->n_groups; i++)
        has_physical |= b->groups[i].dim == 2;
    int *ents = NULL;
    size_t n_ents = 0;
    gmshModelGetEntities(&ents, &n_ents, 2, &ierr);
    if (ierr) {
        gmshFree(ents);
        return gmsh_fail(b, "list its surfaces");
    }
    int rc = 0;
    for (size_t s = 0; s < n_ents / 2 && !rc; s++) {
        int entity = ents[2 * s + 1], region = 0;
        size_t n_phys = 0;
        int g = entity_group(2, entity, &region, &n_phys);
        if (g < 0) {
            rc = gmsh_fail(b, "list the physical groups of a surface");
            break;
        }
        if (n_phys > 1) {
            rc = wff_fail(b->err, "%s: surface %d belongs to %zu physical surfaces; an element "
                          "can have only one region", b->path, entity, n_phys);
            break;
        }
        if (has_physical && g == 0)
            continue;
        int *types = NULL;
        size_t n_types = 0, **etags = NULL, *n_etags = NULL, n_etn = 0;
        size_t **ntags = NULL, *n_ntags = NULL, n_ntn = 0;
        gmshModelMeshGetElements(&types, &n_types, &etags, &n_etags, &n_etn, &ntags, &n_ntags,
                                 &n_ntn, 2, entity, &ierr);
        if (ierr) {
            rc = gmsh_fail(b, "return the elements of a surface");
        }
        for (size_t t = 0; t < n_types && !rc; t++) {
            int nv = types[t] == GMSH_TRI3 ? 3 : types[t] == GMSH_QUAD4 ? 4 : 0;
            if (!nv) {
                char name[64];
                element_type_name(types[t], name, sizeof name);
                rc = wff_fail(b->err, "%s: 2-D element %d (gmsh tag %zu) is a %s (gmsh type %d); "
                              "only 3-node triangles and 4-node quadrilaterals are supported",
                              b->path, b->n_elems + 1, n_etags[t] ? etags[t][0] : 0, name,
                              types[t]);
                break;
            }
            if (n_ntags[t] != (size_t)nv * n_etags[t]) {
                rc = wff_fail(b->err, "%s: gmsh returned %zu node tags for %zu elements of "
                              "type %d", b->path, n_ntags[t], n_etags[t], types[t]);
                break;
            }
            for (size_t e = 0; e < n_etags[t] && !rc; e++) {
                elem_rec r = {etags[t][e], nv, region, {-1, -1, -1, -1}};
                for (int k = 0; k < nv; k++) {
                    size_t nt = ntags[t][(size_t)nv * e + k];
                    r.node[k] = node_pos(b, nt);
                    if (r.node[k] < 0) {
                        rc = wff_fail(b->err, "%s: 2-D element %d (gmsh tag %zu) uses node %zu, "
                                      "which gmsh does not list", b->path, b->n_elems + 1,
                                      r.tag, nt);
                        break;
                    }
                }
                if (!rc)
                    rc = push_elem(b, &r);
            }
        }
        free_elements(types, n_types, etags, ntags);
        gmshFree(n_etags);
        gmshFree(n_ntags);
    }
    gmshFree(ents);
    if (!rc && b->n_elems == 0)
        rc = wff_fail(b->err, has_physical
                                  ? "%s: no 2-D elements in its physical surfaces"
                                  : "%s: no 2-D elements (triangles or quadrilaterals)",
                      b->path);
    return rc;
}

static int push_edge(build *b, int p0, int p1, int label)
{
    if (b->n_edges == b->cap_edges) {
        if (b->cap_edges > INT_MAX / 8)
            return wff_fail(b->err, "%s: too many edges", b->path);
        int cap = b->cap_edges ? 2 * b->cap_edges : 256;
        int *pos = realloc(b->edge_pos, 2 * (size_t)cap * sizeof *pos);
        if (pos)
            b->edge_pos = pos;
        int *lab = realloc(b->edge_label, (size_t)cap * sizeof *lab);
        if (lab)
            b->edge_label = lab;
        if (!pos || !lab)
            return wff_fail(b->err, "%s: out of memory for %d edges", b->path, cap);
        b->cap_edges = cap;
    }
    b->edge_pos[2 * b->n_edges] = p0;
    b->edge_pos[2 * b->n_edges + 1] = p1;
    b->edge_label[b->n_edges++] = label;
    return 0;
}

/* Sort key of an edge: label, then its two nodes in increasing order, then
 * its position (so that the first of equal edges sorts first). */
typedef struct edge_key {
    int label, lo, hi, index;
} edge_key;

static int cmp_edge_key(const void *a, const void *b)
{
    const edge_key *x = a, *y = b;
    if (x->label != y->label)
        return (x->label > y->label) - (x->label < y->label);
    if (x->lo != y->lo)
        return (x->lo > y->lo) - (x->lo < y->lo);
    if (x->hi != y->hi)
        return (x->hi > y->hi) - (x->hi < y->hi);
    return (x->index > y->index) - (x->index < y->index);
}

/* Drops repeated edges of one label, keeping the order of first occurrence:
 * an MSH2 file stores a line element once per physical curve it belongs to,
 * and gmsh reads back every copy into the curve. */
static int dedupe_edges(build *b)
{
    if (b->n_edges < 2)
        return 0;
    edge_key *k = malloc((size_t)b->n_edges * sizeof *k);
    char *drop = calloc((size_t)b->n_edges, 1);
    if (!k || !drop) {
        free(k);
        free(drop);
        return wff_fail(b->err, "%s: out of memory for %d edges", b->path, b->n_edges);
    }
    for (int i = 0; i < b->n_edges; i++) {
        int p0 = b->edge_pos[2 * i], p1 = b->edge_pos[2 * i + 1];
        k[i] = (edge_key){b->edge_label[i], p0 < p1 ? p0 : p1, p0 < p1 ? p1 : p0, i};
    }
    qsort(k, (size_t)b->n_edges, sizeof *k, cmp_edge_key);
    for (int i = 1; i < b->n_edges; i++)
        if (k[i].label == k[i - 1].label && k[i].lo == k[i - 1].lo && k[i].hi == k[i - 1].hi)
            drop[k[i].index] = 1;
    int n = 0;
    for (int i = 0; i < b->n_edges; i++)
        if (!drop[i]) {
            b->edge_pos[2 * n] = b->edge_pos[2 * i];
            b->edge_pos[2 * n + 1] = b->edge_pos[2 * i + 1];
            b->edge_label[n++] = b->edge_label[i];
        }
    b->n_edges = n;
    free(k);
    free(drop);
    return 0;
}

/* Line elements of each physical curve, labelled with its tag (an element in
 * two physical curves appears once per curve, as gmsh saves it). Their nodes
 * must belong to the kept 2-D elements: a node outside them would carry no
 * mass in the physics. */
static int read_edges(build *b)
{
    int rc = 0;
    for (int gi = 0; gi < b->n_groups && !rc; gi++) {
        if (b->groups[gi].dim != 1)
            continue;
        int label = b->groups[gi].tag, ierr = 0;
        int *ents = NULL;
        size_t n_ents = 0;
        gmshModelGetEntitiesForPhysicalGroup(1, label, &ents, &n_ents, &ierr);
        if (ierr)
            rc = gmsh_fail(b, "list the curves of a physical group");
        for (size_t c = 0; c < n_ents && !rc; c++) {
            int *types = NULL;
            size_t n_types = 0, **etags = NULL, *n_etags = NULL, n_etn = 0;
            size_t **ntags = NULL, *n_ntags = NULL, n_ntn = 0;
            gmshModelMeshGetElements(&types, &n_types, &etags, &n_etags, &n_etn, &ntags,
                                     &n_ntags, &n_ntn, 1, ents[c], &ierr);
            if (ierr)
                rc = gmsh_fail(b, "return the elements of a curve");
            for (size_t t = 0; t < n_types && !rc; t++) {
                if (types[t] != GMSH_LINE2) {
                    char name[64];
                    element_type_name(types[t], name, sizeof name);
                    rc = wff_fail(b->err, "%s: physical curve '%s' (tag %d) has a %s (gmsh type "
                                  "%d, element %zu); only 2-node lines are supported", b->path,
                                  b->groups[gi].name, label, name, types[t],
                                  n_etags[t] ? etags[t][0] : 0);
                    break;
                }
                for (size_t e = 0; e < n_etags[t] && !rc; e++) {
                    int p[2];
                    for (int k = 0; k < 2 && !rc; k++) {
                        size_t nt = ntags[t][2 * e + k];
                        p[k] = node_pos(b, nt);
                        if (p[k] < 0 || b->new_index[p[k]] < 0)
                            rc = wff_fail(b->err, "%s: line element %zu of physical curve '%s' "
                                          "(tag %d) uses node %zu, which is in no 2-D element "
                                          "of the mesh", b->path, etags[t][e],
                                          b->groups[gi].name, label, nt);
                    }
                    if (!rc)
                        rc = push_edge(b, p[0], p[1], label);
                }
            }
            free_elements(types, n_types, etags, ntags);
            gmshFree(n_etags);
            gmshFree(n_ntags);
        }
        gmshFree(ents);
    }
    return rc ? rc : dedupe_edges(b);
}

static double cross(const double *o, const double *a, const double *c)
{
    return (a[0] - o[0]) * (c[1] - o[1]) - (a[1] - o[1]) * (c[0] - o[0]);
}

/* z = 0 plane, positive area, convex quads; makes every element
 * counter-clockwise (quads keep node 0 first, so the 0-2 diagonal stays). */
static int check_elements(build *b)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int e = 0; e < b->n_elems; e++)
        for (int k = 0; k < b->elems[e].n; k++) {
            const double *x = &b->gxyz[3 * (size_t)b->elems[e].node[k]];
            for (int d = 0; d < 3; d++) {
                lo[d] = fmin(lo[d], x[d]);
                hi[d] = fmax(hi[d], x[d]);
            }
        }
    double diag = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                       (hi[2] - lo[2]) * (hi[2] - lo[2]));
    double z_tol = Z_TOL * diag, a_tol = AREA_TOL * diag * diag;
    for (int e = 0; e < b->n_elems; e++) {
        elem_rec *r = &b->elems[e];
        const double *x[4];
        for (int k = 0; k < r->n; k++) {
            x[k] = &b->gxyz[3 * (size_t)r->node[k]];
            if (!(fabs(x[k][2]) <= z_tol))
                return wff_fail(b->err, "%s: 2-D element %d (gmsh tag %zu): mesh not in the "
                                "z = 0 plane (node %zu has z = %g; tolerance %g)", b->path,
                                e + 1, r->tag, b->gtag[r->node[k]], x[k][2], z_tol);
        }
        double area = 0.5 * cross(x[0], x[1], x[2]);
        if (r->n == 4) {
            area += 0.5 * cross(x[0], x[2], x[3]);
            int pos = 0, neg = 0;
            for (int k = 0; k < 4; k++) {
                double c = cross(x[k], x[(k + 1) % 4], x[(k + 3) % 4]);
                pos += c > a_tol;
                neg += c < -a_tol;
            }
            /* mixed signs (bow-tie, re-entrant corner) before the area test:
             * a symmetric bow-tie has zero signed area */
            if ((pos && neg) || (fabs(area) > a_tol && pos + neg < 4))
                return wff_fail(b->err, "%s: 2-D element %d (gmsh tag %zu): non-convex or "
                                "inverted quadrilateral (nodes %zu %zu %zu %zu; corner cross "
                                "products differ in sign)", b->path, e + 1, r->tag,
                                b->gtag[r->node[0]], b->gtag[r->node[1]], b->gtag[r->node[2]],
                                b->gtag[r->node[3]]);
        }
        if (!(fabs(area) > a_tol))
            return wff_fail(b->err, "%s: 2-D element %d (gmsh tag %zu): zero-area element "
                            "(area %g m^2; tolerance %g)", b->path, e + 1, r->tag, fabs(area),
                            a_tol);
        if (area < 0) { /* clockwise: reverse, keeping node 0 */
            int t = r->node[1];
            r->node[1] = r->node[r->n - 1];
            r->node[r->n - 1] = t;
        }
    }
    return 0;
}

/* Output arrays: nodes numbered 0.. in increasing gmsh tag order. */
static int assemble(build *b, wff_mesh *m)
{
    int n_nodes = 0, n_tris = 0, n_quads = 0;
    for (int e = 0; e < b->n_elems; e++)
        if (b->elems[e].n == 3)
            n_tris++;
        else
            n_quads++;
    for (size_t i = 0; i < b->n_gnodes; i++) {
        int pos = b->keys[i].pos;
        if (b->new_index[pos] >= 0)
            b->new_index[pos] = n_nodes++;
    }
    m->xy = malloc(2 * (size_t)n_nodes * sizeof *m->xy);
    m->tri = malloc((3 * (size_t)n_tris + 1) * sizeof *m->tri);
    m->tri_region = malloc(((size_t)n_tris + 1) * sizeof *m->tri_region);
    m->quad = malloc((4 * (size_t)n_quads + 1) * sizeof *m->quad);
    m->quad_region = malloc(((size_t)n_quads + 1) * sizeof *m->quad_region);
    m->edge = malloc((2 * (size_t)b->n_edges + 1) * sizeof *m->edge);
    m->edge_label = malloc(((size_t)b->n_edges + 1) * sizeof *m->edge_label);
    m->groups = malloc(((size_t)b->n_groups + 1) * sizeof *m->groups);
    if (!m->xy || !m->tri || !m->tri_region || !m->quad || !m->quad_region || !m->edge ||
        !m->edge_label || !m->groups)
        return wff_fail(b->err, "%s: out of memory for the mesh arrays", b->path);
    for (size_t i = 0; i < b->n_gnodes; i++) {
        int j = b->new_index[i];
        if (j >= 0) {
            m->xy[2 * j] = b->gxyz[3 * i];
            m->xy[2 * j + 1] = b->gxyz[3 * i + 1];
        }
    }
    for (int e = 0; e < b->n_elems; e++) {
        const elem_rec *r = &b->elems[e];
        int *out = r->n == 3 ? &m->tri[3 * m->n_tris] : &m->quad[4 * m->n_quads];
        for (int k = 0; k < r->n; k++)
            out[k] = b->new_index[r->node[k]];
        if (r->n == 3)
            m->tri_region[m->n_tris++] = r->region;
        else
            m->quad_region[m->n_quads++] = r->region;
    }
    for (int i = 0; i < b->n_edges; i++) {
        m->edge[2 * i] = b->new_index[b->edge_pos[2 * i]];
        m->edge[2 * i + 1] = b->new_index[b->edge_pos[2 * i + 1]];
        m->edge_label[i] = b->edge_label[i];
    }
    if (b->n_groups)
        memcpy(m->groups, b->groups, (size_t)b->n_groups * sizeof *m->groups);
    m->n_nodes = n_nodes;
    m->n_edges = b->n_edges;
    m->n_groups = b->n_groups;
    return 0;
}

/* Everything done inside one gmsh session. */
static int load_in_session(build *b, const wff_mesh_options *o, int is_geo, wff_mesh *m)
{
    if (gmsh_load(b, o, is_geo) || read_groups(b) || read_nodes(b) || read_elements(b))
        return -1;
    for (int e = 0; e < b->n_elems; e++) /* mark the nodes of 2-D elements */
        for (int k = 0; k < b->elems[e].n; k++)
            b->new_index[b->elems[e].node[k]] = 0;
    if (read_edges(b) || check_elements(b))
        return -1;
    return assemble(b, m);
}

int wff_mesh_load(const char *path, const wff_mesh_options *options, wff_mesh *mesh,
                  wff_error *err)
{
    if (!mesh)
        return wff_fail(err, "wff_mesh_load: no mesh to fill");
    memset(mesh, 0, sizeof *mesh);
    if (!path || !*path)
        return wff_fail(err, "wff_mesh_load: no file name");
    wff_mesh_options defaults = {0};
    const wff_mesh_options *o = options ? options : &defaults;
    if (check_options(path, o, err))
        return -1;
    int is_geo = has_suffix(path, ".geo");
    if (!is_geo && !has_suffix(path, ".msh"))
        return wff_fail(err, "%s: unknown mesh file type (expected .geo or .msh)", path);
    /* gmsh opens a missing file without any error: check first. */
    if (access(path, R_OK) != 0)
        return wff_fail(err, "%s: cannot read: %s", path, strerror(errno));
    if (wff_regular_file_check(path, "mesh file", err)) /* gmsh would wait on a pipe */
        return -1;
    /* FreeFEM's savemesh format, also named .msh (gmsh's starts "$MeshFormat") */
    if (!is_geo && wff_mesh_is_freefem_msh(path))
        return wff_mesh_load_freefem(path, NULL, mesh, err);

    /* gmshInitialize() switches the process locale (LC_CTYPE etc.): restore it. */
    const char *cur = setlocale(LC_ALL, NULL);
    char *saved_locale = cur ? strdup(cur) : NULL;
    if (cur && !saved_locale)
        return wff_fail(err, "%s: out of memory", path);

    build b = {0};
    b.path = path;
    b.err = err;
    wff_mesh m = {0};
    int ierr = 0, rc;
#ifdef _OPENMP
    /* gmsh sets OpenMP's thread count to its own General.NumThreads (1): restore it */
    int saved_threads = omp_get_max_threads();
#endif
    gmshInitialize(0, NULL, 0, &ierr);
    if (!ierr)
        gmshOptionSetNumber("General.Terminal", 0, &ierr);
    /* The API default (2) makes every gmsh error a C++ exception. Thrown from
     * the .geo parser it leaves the parser's input buffer and file behind, so
     * the next file read in this process is parsed wrongly; thrown while
     * meshing, inside an OpenMP region, it terminates the process. With 0 gmsh
     * only logs errors: the logger tells us. (Never 1: that calls exit().) */
    if (!ierr)
        gmshOptionSetNumber("General.AbortOnError", 0, &ierr);
    if (!ierr) /* errors only: all the logger needs to hold */
        gmshOptionSetNumber("General.Verbosity", 1, &ierr);
    if (!ierr)
        gmshLoggerStart(&ierr);
    if (ierr)
        rc = wff_fail(err, "%s: gmsh failed to start", path);
    else
        rc = load_in_session(&b, o, is_geo, &m);
    build_release(&b);
    gmshLoggerStop(&ierr);
    gmshOnelabClear("", &ierr); /* our settings would outlive gmshFinalize */
    gmshFinalize(&ierr);
#ifdef _OPENMP
    omp_set_num_threads(saved_threads);
#endif
    if (saved_locale) {
        setlocale(LC_ALL, saved_locale);
        free(saved_locale);
    }
    if (!rc)
        rc = wff_mesh_check(&m, o->allow_vertex_only, path, err);
    if (rc) {
        wff_mesh_free(&m);
        return -1;
    }
    *mesh = m;
    return 0;
}

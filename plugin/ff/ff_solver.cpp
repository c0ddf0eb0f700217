// wovenff FreeFEM binding: the explicit solver (include/wovenff/solver.h).
//
// A script creates a model and gets an integer handle:
//   int md = wovenffModel(meshFile, materialFile, meshSettings);
//   mesh Th = wovenffMesh(md);            // triangles (quads split), same vertex numbering
//   wovenffFix(md, "sym_x", 0);           // fix a DOF (0 ux, 1 uy, 2 uz, 3 dA1, 4 dA2)
//   wovenffAdvance(md, tEnd);             // explicit steps until tEnd
//   real t = wovenffGet(md, "time");      // one state quantity by name (plugin/values.c)
//   wovenffState(md, st);                 // all of them, in wovenffStateNames' order
//   wovenffField(md, "uz", values);       // nodal values, P1 DOF order
//   wovenffFree(md);
//
// Added for runs that must survive (docs/limits.md):
//   wovenffProjectileTip(md, z)        // nose tip at z (m, <= 0: a stand-off); refused,
//                                      // naming the node, if the fabric would be inside
//   int n = wovenffEnergySplit(md, e)  // stored energy per mechanism, J, whole specimen
//   string names = wovenffMechNames(md) // their names, space-separated ("yarn_stretch ...")
//   wovenffSave(md, file)              // checkpoint (binary, versioned, checksummed, atomic)
//   int step = wovenffLoadState(md, file) // continue it in a model built the same way
//                                      // (mesh, material, preload, BCs, settings, projectile;
//                                      // refused, saying what differs); bitwise continuation
//   string bad = wovenffInvariants(md) // the physical invariants violated now ("" none)
//   string msg = wovenffLastError(md)  // after try { } catch (...) { }: that model's last
//                                      // error; md = -1: the last error of any function here
//                                      // (e.g. wovenffModel, which has no handle yet)
// Failures stop the script (exit 8) with "function: message" unless the script
// catches them (wff_ff_fail; FreeFEM's try/catch also takes exit(): never exit
// inside a try block).
// Models live in the binding's handle table (ff_models.cpp).
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/solver.h"
#include "wovenff/renumber.h"
#include "wovenff/options.h"
#include "wovenff/mesh_labels.h"
#include "wovenff/pack.h"
}

using namespace Fem2D;

namespace {

// wff_ff_fail, remembered also as model id's last error (if id is a model).
[[noreturn]] void fail(const char *fn, const std::string &message, long id = -1)
{
    wff_ff_model_fail(fn, message, id);
}

[[noreturn]] void fail(const char *fn, const wff_error &err, long id = -1)
{
    wff_ff_model_fail(fn, std::string(err.message), id);
}

wff_model *model_of(long id, const char *fn)
{
    return wff_ff_model(id, fn);
}

// The model's state quantities by name (plugin/values.c: the model's own and
// its parts'): wovenffGet(md, name) reads one, wovenffState(md, v) all of them
// in their order, wovenffStateNames lists them.
std::string state_names()
{
    std::string names;
    for (int i = 0; i < wff_model_value_count(); i++)
        names += std::string(i ? " " : "") + wff_model_value_name(i);
    return names;
}

long ffModel(string *const &meshFile, string *const &materialFile, string *const &settings)
{
    wff_mesh_options opt;
    wff_error err;
    // a FreeFEM-format .msh: settings name its labels (ff_femesh.cpp)
    size_t len = meshFile->size();
    if (len > 4 && meshFile->compare(len - 4, 4, ".msh") == 0 &&
        wff_mesh_is_freefem_msh(meshFile->c_str()))
        return wff_ff_model_from_freefem_msh(meshFile->c_str(), materialFile, settings);
    if (wff_mesh_options_parse(settings->c_str(), &opt, &err))
        fail("wovenffModel", err);
    wff_model *m = wff_model_new();
    if (!m)
        fail("wovenffModel", "out of memory");
    if (wff_model_create(m, meshFile->c_str(), &opt, materialFile->c_str(), &err)) {
        free(m);
        fail("wovenffModel", err);
    }
    return wff_ff_model_add(m);
}

long ffFree(const long &id)
{
    wff_ff_model_free(id, "wovenffFree");
    return 0;
}

pmesh ffMesh(Stack stack, const long &id)
{
    const wff_model *m = model_of(id, "wovenffMesh");
    const wff_mesh &g = *wff_model_mesh(m);
    int nt = g.n_tris + 2 * g.n_quads;
    std::vector<int> tri(3 * (size_t)nt), region((size_t)nt);
    wff_mesh_triangulate(&g, tri.data(), region.data());
    // the model's order (renumber.h) back to the numbering the mesh was given in
    auto node = [m](int n) { return wff_model_user_node(m, n); };
    std::vector<int> twin((size_t)nt); // model twin triangle -> the user's
    for (int e = 0; e < g.n_tris; e++)
        twin[e] = wff_model_user_element(m, e);
    for (int q = 0; q < g.n_quads; q++)
        for (int h = 0; h < 2; h++)
            twin[g.n_tris + 2 * q + h] =
                g.n_tris + 2 * (wff_model_user_element(m, g.n_tris + q) - g.n_tris) + h;
    Mesh::Vertex *v = new Mesh::Vertex[g.n_nodes];
    for (int i = 0; i < g.n_nodes; i++) {
        v[node(i)].x = g.xy[2 * i];
        v[node(i)].y = g.xy[2 * i + 1];
        v[node(i)].lab = 0;
    }
    for (int e = 0; e < g.n_edges; e++)
        for (int a = 0; a < 2; a++)
            v[node(g.edge[2 * e + a])].lab = g.edge_label[e];
    Mesh::Triangle *t = new Mesh::Triangle[nt];
    for (int e = 0; e < nt; e++)
        t[twin[e]].set(v, node(tri[3 * e]), node(tri[3 * e + 1]), node(tri[3 * e + 2]),
                       region[e]);
    Mesh::BorderElement *b = new Mesh::BorderElement[g.n_edges > 0 ? g.n_edges : 1];
    for (int e = 0; e < g.n_edges; e++)
        b[e].set(v, node(g.edge[2 * e]), node(g.edge[2 * e + 1]), g.edge_label[e]);
    Mesh *th = new Mesh(g.n_nodes, nt, g.n_edges, v, t, b);
    R2 pmin, pmax;
    th->BoundingBox(pmin, pmax);
    // A pack's N plies lie on one another in the plane: FreeFEM's quadtree splits a
    // box of more than 4 vertices at one point without end (5 plies and more: out of
    // memory). It holds ply 0's vertices only (the strike face: the user's nodes
    // 0 .. n/N - 1), so that a point search finds ply 0's triangles.
    int plies = wff_model_ply_count(m) > 1 ? wff_model_ply_count(m) : 1;
    if (!th->quadtree)
        th->quadtree = new FQuadTree(th, pmin, pmax, th->nv / plies);
    return Add2StackOfPtr2FreeRC(stack, th);
}

long ffSetPreload(const long &id, KN<double> *const &F, KN<double> *const &dA)
{
    wff_model *m = model_of(id, "wovenffSetPreload");
    if (F->N() != 4 || dA->N() != 2)
        fail("wovenffSetPreload", "F_pre must have 4 entries (F11 F12 F21 F22) and dA0 2", id);
    double Fp[4] = {(*F)[0], (*F)[1], (*F)[2], (*F)[3]}, d[2] = {(*dA)[0], (*dA)[1]};
    for (int i = 0; i < 4; i++)
        wff_ff_require_finite("wovenffSetPreload", i < 2 ? (i ? "F_pre[1]" : "F_pre[0]")
                              : (i == 2 ? "F_pre[2]" : "F_pre[3]"), Fp[i], id);
    wff_ff_require_finite("wovenffSetPreload", "dA0[0]", d[0], id);
    wff_ff_require_finite("wovenffSetPreload", "dA0[1]", d[1], id);
    wff_error err;
    if (wff_model_set_preload(m, Fp, d, &err))
        fail("wovenffSetPreload", err, id);
    return 0;
}

long ffFix(const long &id, string *const &group, const long &component)
{
    wff_error err;
    int n = wff_model_fix_group(model_of(id, "wovenffFix"), group->c_str(), (int)component, &err);
    if (n < 0)
        fail("wovenffFix", err, id);
    return n;
}

long ffPrescribe(const long &id, string *const &group, const long &component,
                 const double &velocity)
{
    wff_ff_require_finite("wovenffPrescribe", "velocity", velocity, id);
    wff_error err;
    int n = wff_model_prescribe_group(model_of(id, "wovenffPrescribe"), group->c_str(),
                                      (int)component, velocity, &err);
    if (n < 0)
        fail("wovenffPrescribe", err, id);
    return n;
}

long ffClampFriction(const long &id, string *const &group, const double &force, const double &mu)
{
    wff_ff_require_finite("wovenffClampFriction", "force", force, id);
    wff_ff_require_finite("wovenffClampFriction", "mu", mu, id);
    wff_error err;
    int n = wff_model_clamp_friction(model_of(id, "wovenffClampFriction"), group->c_str(), force,
                                     mu, &err);
    if (n < 0)
        fail("wovenffClampFriction", err, id);
    return n;
}

long ffProjectile(const long &id, const double &radius, const double &mass,
                  const double &velocity, const double &mu)
{
    const char *fn = "wovenffProjectile";
    wff_ff_require_finite(fn, "radius", radius, id);
    wff_ff_require_finite(fn, "mass", mass, id);
    wff_ff_require_finite(fn, "velocity", velocity, id);
    wff_ff_require_finite(fn, "mu", mu, id);
    wff_error err;
    if (wff_model_set_projectile(model_of(id, "wovenffProjectile"), radius, mass, velocity, mu,
                                 &err))
        fail("wovenffProjectile", err, id);
    return 0;
}

long ffSet(const long &id, string *const &key, const double &value)
{
    wff_model *m = model_of(id, "wovenffSet");
    wff_ff_require_finite("wovenffSet", key->c_str(), value, id);
    wff_error err;
    if (wff_model_set_option(m, key->c_str(), value, &err))
        fail("wovenffSet", err, id);
    return 0;
}

long ffAdvance(const long &id, const double &t_end)
{
    wff_model *m = model_of(id, "wovenffAdvance");
    wff_ff_require_finite("wovenffAdvance", "t_end", t_end, id);
    wff_error err;
    if (wff_model_advance(m, t_end, 2000000000L, &err))
        fail("wovenffAdvance", err, id);
    return wff_model_step_count(m);
}

long ffState(const long &id, KN<double> *const &out)
{
    const wff_model *m = model_of(id, "wovenffState");
    std::vector<double> values((size_t)wff_model_value_count());
    wff_model_values(m, 1, 1, values.data());
    out->resize((long)values.size());
    for (size_t i = 0; i < values.size(); i++)
        (*out)[(long)i] = values[i];
    return 0;
}

double ffGet(const long &id, string *const &name)
{
    const wff_model *m = model_of(id, "wovenffGet");
    double value;
    wff_error err;
    if (wff_model_value(m, name->c_str(), &value, &err) == 0)
        return value;
    fail("wovenffGet", "unknown state quantity '" + *name + "' (known: " + state_names() + ")",
         id);
}

string *ffStateNames(Stack stack, const long &id)
{
    (void)id;
    return Add2StackOfPtr2Free(stack, new string(state_names()));
}

long ffField(const long &id, string *const &name, KN<double> *const &out)
{
    const wff_model *m = model_of(id, "wovenffField");
    out->resize(wff_model_node_count(m));
    wff_error err;
    if (wff_model_nodal_field(m, name->c_str(), &(*out)[0], &err))
        fail("wovenffField", err, id);
    return wff_model_node_count(m);
}

long ffNearestNode(const long &id, const double &x, const double &y)
{
    const wff_model *m = model_of(id, "wovenffNearestNode");
    wff_ff_require_finite("wovenffNearestNode", "x", x, id);
    wff_ff_require_finite("wovenffNearestNode", "y", y, id);
    return wff_model_nearest_node(m, x, y);
}

long ffReaction(const long &id, string *const &group, const long &component, KN<double> *const &out)
{
    wff_model *m = model_of(id, "wovenffReaction");
    double sum;
    wff_error err;
    int n = wff_model_group_reaction(m, group->c_str(), (int)component, &sum, &err);
    if (n < 0)
        fail("wovenffReaction", err, id);
    out->resize(1);
    (*out)[0] = sum;
    return n;
}

long ffProjectileTip(const long &id, const double &tip)
{
    wff_model *m = model_of(id, "wovenffProjectileTip");
    wff_ff_require_finite("wovenffProjectileTip", "tip", tip, id);
    wff_error err;
    if (wff_model_place_projectile(m, tip, &err))
        fail("wovenffProjectileTip", err, id);
    return 0;
}

long ffSave(const long &id, string *const &path)
{
    wff_error err;
    if (wff_model_save(model_of(id, "wovenffSave"), path->c_str(), &err))
        fail("wovenffSave", err, id);
    return 0;
}

long ffLoadState(const long &id, string *const &path)
{
    wff_model *m = model_of(id, "wovenffLoadState");
    wff_error err;
    if (wff_model_load_state(m, path->c_str(), &err))
        fail("wovenffLoadState", err, id);
    return wff_model_step_count(m);
}

long ffEnergySplit(const long &id, KN<double> *const &out)
{
    const wff_model *m = model_of(id, "wovenffEnergySplit");
    double mech[WFF_MECH_MAX];
    int n = wff_model_energy_split(m, mech);
    out->resize(n > 0 ? n : 0);
    for (int k = 0; k < n; k++)
        (*out)[k] = mech[k];
    return n;
}

string *ffMechNames(Stack stack, const long &id)
{
    const wff_model *m = model_of(id, "wovenffMechNames");
    const wff_cell_type *cell = wff_model_material(m)->cell;
    std::string names;
    for (int k = 0; k < wff_cell_n_mech(cell) && k < WFF_MECH_MAX; k++)
        names += std::string(k ? " " : "") + wff_cell_mech_name(cell, k);
    return Add2StackOfPtr2Free(stack, new string(names));
}

string *ffInvariants(Stack stack, const long &id)
{
    const wff_model *m = model_of(id, "wovenffInvariants");
    char text[WFF_ERROR_MAX];
    wff_model_invariants(m, text, sizeof text);
    return Add2StackOfPtr2Free(stack, new string(text));
}

string *ffLastError(Stack stack, const long &id)
{
    return Add2StackOfPtr2Free(stack, new string(wff_ff_model_last_error(id)));
}

} // namespace

void wff_ff_register_solver()
{
    Global.Add("wovenffModel", "(",
               new OneOperator3_<long, string *, string *, string *>(ffModel));
    Global.Add("wovenffFree", "(", new OneOperator1_<long, long>(ffFree));
    Global.Add("wovenffMesh", "(", new OneOperator1s_<pmesh, long>(ffMesh));
    Global.Add("wovenffSetPreload", "(",
               new OneOperator3_<long, long, KN<double> *, KN<double> *>(ffSetPreload));
    Global.Add("wovenffFix", "(", new OneOperator3_<long, long, string *, long>(ffFix));
    Global.Add("wovenffPrescribe", "(",
               new OneOperator4_<long, long, string *, long, double>(ffPrescribe));
    Global.Add("wovenffClampFriction", "(",
               new OneOperator4_<long, long, string *, double, double>(ffClampFriction));
    Global.Add("wovenffProjectile", "(",
               new OneOperator5_<long, long, double, double, double, double>(ffProjectile));
    Global.Add("wovenffSet", "(", new OneOperator3_<long, long, string *, double>(ffSet));
    Global.Add("wovenffAdvance", "(", new OneOperator2_<long, long, double>(ffAdvance));
    Global.Add("wovenffState", "(", new OneOperator2_<long, long, KN<double> *>(ffState));
    Global.Add("wovenffGet", "(", new OneOperator2_<double, long, string *>(ffGet));
    Global.Add("wovenffStateNames", "(", new OneOperator1s_<string *, long>(ffStateNames));
    Global.Add("wovenffField", "(",
               new OneOperator3_<long, long, string *, KN<double> *>(ffField));
    Global.Add("wovenffNearestNode", "(",
               new OneOperator3_<long, long, double, double>(ffNearestNode));
    Global.Add("wovenffReaction", "(",
               new OneOperator4_<long, long, string *, long, KN<double> *>(ffReaction));
    Global.Add("wovenffProjectileTip", "(",
               new OneOperator2_<long, long, double>(ffProjectileTip));
    Global.Add("wovenffSave", "(", new OneOperator2_<long, long, string *>(ffSave));
    Global.Add("wovenffLoadState", "(", new OneOperator2_<long, long, string *>(ffLoadState));
    Global.Add("wovenffEnergySplit", "(",
               new OneOperator2_<long, long, KN<double> *>(ffEnergySplit));
    Global.Add("wovenffMechNames", "(", new OneOperator1s_<string *, long>(ffMechNames));
    Global.Add("wovenffInvariants", "(", new OneOperator1s_<string *, long>(ffInvariants));
    Global.Add("wovenffLastError", "(", new OneOperator1s_<string *, long>(ffLastError));
}

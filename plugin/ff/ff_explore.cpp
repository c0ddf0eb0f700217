// wovenff FreeFEM binding: one material point along a load path, for the
// unit-cell explorer (C core: plugin/point_path.c). Works with every cell: the
// record's columns come from the cell's own diagnostic and mechanism names.
// Every function takes its material as a file name (read afresh on every
// call) or as a wovenffMaterial handle (loaded once; ff_materials.cpp) and
// reports failures with wff_ff_fail. No physics here.
//
//   int n = wovenffPathSegment(mat, Fa, Fb, duration, dynamicAmplitudes, shearFlow, state);
//       F linear in time from Fa to Fb over duration (s): dynamic amplitudes
//       (0|1) and/or shear flow (0|1); state = [dA1, dA2, vA1, vA2, gamma_f,
//       previous step] in and out (m, m/s, rad, s), then optionally the cell's
//       other internal states in order (absent: 0); n: steps taken. gamma_f is
//       the cell's state of that name (ignored by a cell without one)
//   int n = wovenffPathSegment(mat, Fa, Fb, duration, dynamicAmplitudes, shearFlow, state,
//                              dissipated);
//       the same, and what the segment dissipated added to dissipated = [shear flow, yarn
//       failure, yarn slip] (J/m^2, 3 entries)
//   int r = wovenffPathStatic(mat, F, duration, shearFlow, state, dissipated);
//       a static level at F: the amplitudes in balance and the internal states (slip,
//       damage; gamma_f by the flow rule when shearFlow, else held) advanced over duration
//       from those in state, solved in turn until they agree (C: wff_point_path_static_level);
//       r: the rounds taken; dissipated as above
//   wovenffPathPull(mat, stretch1, tension2, duration, state, dissipated, F);
//       the pull-out level: family 1 at stretch1, family 2 carrying the yarn tension
//       tension2 (N), unsheared, the static level there (F in: the last level's, its
//       lambda2 the guess; out: this level's; C: wff_point_path_pull_level)
//   string cols = wovenffExploreColumns(mat);   // "lambda1,lambda2,...,E_shear"
//   string units = wovenffExploreUnits(mat);    // their units, space-separated
//   int i = wovenffExploreColumn(mat, "F_L1");  // index of a column, -1 if none
//   int n = wovenffExploreRow(mat, F, state, dAstatic, out);   // the values
//   int na = wovenffCellAmplitudes(mat);        // amplitude DOFs: 0 or 2
//   int has = wovenffReferenceGeometry(mat, out);   // 1: out = [p0_1, p0_2, A0_1, A0_2] (m)
//
// F is row-major 3x2 (F11 F12 F21 F22 F31 F32); SI units.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/point_path.h"
}

using namespace Fem2D;

namespace {

const char *const kStateLayout = "dA1 dA2 vA1 vA2 gamma_f previous_step";
const long kStateSize = 6;

// ExecError unless v has n entries (layout says which), all finite numbers.
void require_finite(const char *fn, const char *name, const KN<double> *v, long n,
                    const char *layout)
{
    wff_ff_require_size(fn, name, v, n, layout);
    for (long i = 0; i < n; i++)
        if (!std::isfinite((*v)[i])) {
            char msg[200];
            snprintf(msg, sizeof msg, "%s[%ld] = %g is not a finite number (%s)", name, i,
                     (*v)[i], layout);
            wff_ff_fail(fn, msg);
        }
}

void take_F(const char *fn, const char *name, const KN<double> *v, double F[6])
{
    require_finite(fn, name, v, 6, "F11 F12 F21 F22 F31 F32");
    for (int i = 0; i < 6; i++)
        F[i] = (*v)[i];
}

// Where the explorer's state array keeps the cell's internal state i: slot 4
// for the state named gamma_f, then the others from slot kStateSize on.
long state_slot(const wff_material &mat, int i)
{
    int g = wff_material_state_index(&mat, "gamma_f");
    if (i == g)
        return 4;
    return kStateSize + i - (g >= 0 && i > g ? 1 : 0);
}

wff_point_state take_state(const char *fn, const KN<double> *v, const wff_material &mat)
{
    if (v && v->N() > kStateSize) // the optional further states, checked whole
        require_finite(fn, "state", v, v->N(), kStateLayout);
    else
        require_finite(fn, "state", v, kStateSize, kStateLayout);
    wff_point_state s = {{(*v)[0], (*v)[1]}, {(*v)[2], (*v)[3]}, {0}, (*v)[5], 0, {0, 0, 0}};
    for (int i = 0; i < mat.n_state; i++) {
        long slot = state_slot(mat, i);
        s.state[i] = slot < v->N() ? (*v)[slot] : 0;
    }
    return s;
}

void give_state(const wff_point_state &s, const wff_material &mat, KN<double> *v)
{
    const double back[kStateSize] = {s.dA[0], s.dA[1], s.velocity[0], s.velocity[1],
                                     (*v)[4], s.previous_step};
    for (long i = 0; i < kStateSize; i++)
        (*v)[i] = back[i];
    for (int i = 0; i < mat.n_state; i++) {
        long slot = state_slot(mat, i);
        if (slot < v->N())
            (*v)[slot] = s.state[i];
    }
}

struct Column {
    std::string name;
    const char *unit;
    double value;
};

// The explorer's record at one level, column by column: kinematics, stress,
// the amplitudes (cells with amplitudes only), the cell's diagnostics (a name
// already listed is not repeated: linear_yarns reports lambda1, lambda2),
// energy, the amplitudes' kinetic energy, energy per mechanism.
std::vector<Column> columns(const wff_material &mat, const wff_point_record &rec,
                            const wff_point_state &s, const double dA_static[2])
{
    const wff_cell_type *c = mat.cell;
    // gamma_f always (0 for a cell without it: the shear path's plot reads it), then
    // the cell's other internal states by name
    int g = wff_material_state_index(&mat, "gamma_f");
    std::vector<Column> out = {{"lambda1", "-", rec.stretch[0]},
                               {"lambda2", "-", rec.stretch[1]},
                               {"gamma", "rad", rec.shear_angle},
                               {"gamma_f", "rad", g >= 0 ? s.state[g] : 0.0}};
    for (int i = 0; i < mat.n_state; i++)
        if (i != g)
            out.push_back({wff_cell_state_name(c, i), wff_cell_state_unit(c, i), s.state[i]});
    out.insert(out.end(), {{"P11", "N/m", rec.point.stress[0]},
                           {"P22", "N/m", rec.point.stress[3]},
                           {"P12", "N/m", rec.point.stress[1]}});
    if (wff_cell_amplitudes(c) > 0)
        out.insert(out.end(), {{"R1", "N/m^2", rec.point.residual[0]},
                               {"R2", "N/m^2", rec.point.residual[1]},
                               {"dA1", "m", s.dA[0]},
                               {"dA2", "m", s.dA[1]},
                               {"dA1_static", "m", dA_static[0]},
                               {"dA2_static", "m", dA_static[1]}});
    for (int i = 0; i < wff_cell_n_diag(c); i++) {
        bool listed = false;
        for (const Column &col : out)
            listed = listed || col.name == wff_cell_diag_name(c, i);
        if (!listed)
            out.push_back({wff_cell_diag_name(c, i), wff_cell_diag_unit(c, i), rec.point.diag[i]});
    }
    out.push_back({"W", "J/m^2", rec.point.energy});
    if (wff_cell_amplitudes(c) > 0)
        out.push_back({"K_amp", "J/m^2", rec.amplitude_kinetic});
    for (int i = 0; i < rec.n_mech; i++)
        out.push_back({std::string("E_") + wff_cell_mech_name(c, i), "J/m^2", rec.mech_energy[i]});
    return out;
}

// The columns without values (names and units).
template <class M>
std::vector<Column> column_names(const char *fn, const M &material)
{
    wff_material scratch;
    const wff_material &mat = *wff_ff_material_arg(fn, material, &scratch);
    wff_point_record rec = {};
    rec.n_mech = wff_cell_has_energy_split(mat.cell) ? wff_cell_n_mech(mat.cell) : 0;
    const wff_point_state s = {};
    const double none[2] = {0, 0};
    return columns(mat, rec, s, none);
}

std::string joined(const std::vector<Column> &cols, bool units, const char *sep)
{
    std::string text;
    for (size_t i = 0; i < cols.size(); i++)
        text += (i ? sep : "") + (units ? std::string(cols[i].unit) : cols[i].name);
    return text;
}

// dissipated: 3 finite entries the path's dissipation is added to (J/m^2).
void take_dissipated(const char *fn, KN<double> *v, wff_point_state *s)
{
    require_finite(fn, "dissipated", v, 3, "shear flow, yarn failure, yarn slip (J/m^2)");
    for (int i = 0; i < 3; i++)
        s->dissipated[i] = (*v)[i];
}
void give_dissipated(const wff_point_state &s, KN<double> *v)
{
    for (int i = 0; i < 3; i++)
        (*v)[i] = s.dissipated[i];
}

// One segment of a path (both forms of wovenffPathSegment); dissipated NULL:
// the form without it.
template <class M>
long path_segment(const M &material, KN<double> *Fa, KN<double> *Fb, double duration,
                  long dynamic_amplitudes, long shear_flow, KN<double> *state,
                  KN<double> *dissipated)
{
    const char *fn = "wovenffPathSegment";
    double F_a[6], F_b[6];
    take_F(fn, "Fa", Fa, F_a);
    take_F(fn, "Fb", Fb, F_b);
    wff_ff_require_finite(fn, "duration", duration, -1);
    wff_material scratch;
    const wff_material *mat = wff_ff_material_arg(fn, material, &scratch);
    wff_point_state s = take_state(fn, state, *mat);
    if (dissipated)
        take_dissipated(fn, dissipated, &s);
    wff_path_mode mode = {dynamic_amplitudes != 0, shear_flow != 0, WFF_PATH_STEP_SAFETY,
                          WFF_PATH_FLOW_SUBSTEPS};
    wff_error err;
    if (wff_point_path_segment(mat, F_a, F_b, duration, &mode, &s, &err))
        wff_ff_fail(fn, err);
    give_state(s, *mat, state);
    if (dissipated)
        give_dissipated(s, dissipated);
    return s.substeps;
}

template <class M>
long ffPathSegment(const M &material, KN<double> *const &Fa, KN<double> *const &Fb,
                   const double &duration, const long &dynamic_amplitudes,
                   const long &shear_flow, KN<double> *const &state)
{
    return path_segment(material, Fa, Fb, duration, dynamic_amplitudes, shear_flow, state, NULL);
}

template <class M>
long ffPathSegmentDissipated(const M &material, KN<double> *const &Fa, KN<double> *const &Fb,
                             const double &duration, const long &dynamic_amplitudes,
                             const long &shear_flow, KN<double> *const &state,
                             KN<double> *const &dissipated)
{
    return path_segment(material, Fa, Fb, duration, dynamic_amplitudes, shear_flow, state,
                        dissipated);
}

template <class M>
long ffPathStatic(const M &material, KN<double> *const &Fv, const double &duration,
                  const long &shear_flow, KN<double> *const &state,
                  KN<double> *const &dissipated)
{
    const char *fn = "wovenffPathStatic";
    double F[6];
    take_F(fn, "F", Fv, F);
    wff_ff_require_finite(fn, "duration", duration, -1);
    wff_material scratch;
    const wff_material *mat = wff_ff_material_arg(fn, material, &scratch);
    wff_point_state s = take_state(fn, state, *mat);
    take_dissipated(fn, dissipated, &s);
    wff_error err;
    int rounds = wff_point_path_static_level(mat, F, duration, shear_flow != 0, &s, &err);
    if (rounds < 0)
        wff_ff_fail(fn, err);
    give_state(s, *mat, state);
    give_dissipated(s, dissipated);
    return rounds;
}

template <class M>
long ffPathPull(const M &material, const double &stretch1, const double &tension2,
                const double &duration, KN<double> *const &state,
                KN<double> *const &dissipated, KN<double> *const &Fv)
{
    const char *fn = "wovenffPathPull";
    wff_ff_require_finite(fn, "stretch1", stretch1, -1);
    wff_ff_require_finite(fn, "tension2", tension2, -1);
    wff_ff_require_finite(fn, "duration", duration, -1);
    double F[6];
    take_F(fn, "F", Fv, F);
    wff_material scratch;
    const wff_material *mat = wff_ff_material_arg(fn, material, &scratch);
    wff_point_state s = take_state(fn, state, *mat);
    take_dissipated(fn, dissipated, &s);
    wff_error err;
    if (wff_point_path_pull_level(mat, stretch1, tension2, duration, &s, F, &err))
        wff_ff_fail(fn, err);
    give_state(s, *mat, state);
    give_dissipated(s, dissipated);
    for (int i = 0; i < 6; i++)
        (*Fv)[i] = F[i];
    return 0;
}

template <class M>
string *ffExploreColumns(Stack stack, const M &material)
{
    std::vector<Column> cols = column_names("wovenffExploreColumns", material);
    return Add2StackOfPtr2Free(stack, new string(joined(cols, false, ",")));
}

template <class M>
string *ffExploreUnits(Stack stack, const M &material)
{
    std::vector<Column> cols = column_names("wovenffExploreUnits", material);
    return Add2StackOfPtr2Free(stack, new string(joined(cols, true, " ")));
}

template <class M>
long ffExploreColumn(const M &material, string *const &name)
{
    std::vector<Column> cols = column_names("wovenffExploreColumn", material);
    for (size_t i = 0; i < cols.size(); i++)
        if (cols[i].name == *name)
            return (long)i;
    return -1;
}

template <class M>
long ffExploreRow(const M &material, KN<double> *const &Fv, KN<double> *const &state,
                  KN<double> *const &dA_static, KN<double> *const &out)
{
    const char *fn = "wovenffExploreRow";
    double F[6];
    take_F(fn, "F", Fv, F);
    wff_material scratch;
    const wff_material &mat = *wff_ff_material_arg(fn, material, &scratch);
    wff_point_state s = take_state(fn, state, mat);
    require_finite(fn, "dAstatic", dA_static, 2, "dA1 dA2");
    const double dAst[2] = {(*dA_static)[0], (*dA_static)[1]};
    if (!out)
        wff_ff_fail(fn, "no output array");
    wff_point_record rec;
    wff_error err;
    if (wff_point_path_record(&mat, F, &s, &rec, &err))
        wff_ff_fail(fn, err);
    std::vector<Column> cols = columns(mat, rec, s, dAst);
    out->resize((long)cols.size());
    for (size_t i = 0; i < cols.size(); i++)
        (*out)[(long)i] = cols[i].value;
    return (long)cols.size();
}

template <class M>
long ffCellAmplitudes(const M &material)
{
    wff_material scratch;
    return wff_cell_amplitudes(wff_ff_material_arg("wovenffCellAmplitudes", material, &scratch)->cell);
}

template <class M>
long ffReferenceGeometry(const M &material, KN<double> *const &out)
{
    const char *fn = "wovenffReferenceGeometry";
    if (!out)
        wff_ff_fail(fn, "no output array");
    wff_material scratch;
    const wff_material &mat = *wff_ff_material_arg(fn, material, &scratch);
    if (!wff_cell_has_reference_geometry(mat.cell)) {
        out->resize(0);
        return 0;
    }
    double pitch0[2], amplitude0[2];
    wff_cell_reference_geometry(&mat, pitch0, amplitude0);
    out->resize(4);
    (*out)[0] = pitch0[0];
    (*out)[1] = pitch0[1];
    (*out)[2] = amplitude0[0];
    (*out)[3] = amplitude0[1];
    return 1;
}

// Every function twice: the material as a file name (M = string *) or as a
// wovenffMaterial handle (M = long).
template <class M>
void register_explore()
{
    Global.Add("wovenffPathSegment", "(",
               new OneOperator7_<long, M, KN<double> *, KN<double> *, double, long, long,
                                 KN<double> *>(ffPathSegment<M>));
    Global.Add("wovenffPathSegment", "(",
               new OneOperator8_<long, M, KN<double> *, KN<double> *, double, long, long,
                                 KN<double> *, KN<double> *>(ffPathSegmentDissipated<M>));
    Global.Add("wovenffPathStatic", "(",
               new OneOperator6_<long, M, KN<double> *, double, long, KN<double> *,
                                 KN<double> *>(ffPathStatic<M>));
    Global.Add("wovenffPathPull", "(",
               new OneOperator7_<long, M, double, double, double, KN<double> *, KN<double> *,
                                 KN<double> *>(ffPathPull<M>));
    Global.Add("wovenffExploreColumns", "(",
               new OneOperator1s_<string *, M>(ffExploreColumns<M>));
    Global.Add("wovenffExploreUnits", "(", new OneOperator1s_<string *, M>(ffExploreUnits<M>));
    Global.Add("wovenffExploreColumn", "(",
               new OneOperator2_<long, M, string *>(ffExploreColumn<M>));
    Global.Add("wovenffExploreRow", "(",
               new OneOperator5_<long, M, KN<double> *, KN<double> *, KN<double> *,
                                 KN<double> *>(ffExploreRow<M>));
    Global.Add("wovenffCellAmplitudes", "(", new OneOperator1_<long, M>(ffCellAmplitudes<M>));
    Global.Add("wovenffReferenceGeometry", "(",
               new OneOperator2_<long, M, KN<double> *>(ffReferenceGeometry<M>));
}

} // namespace

void wff_ff_register_explore()
{
    register_explore<string *>();
    register_explore<long>();
}

// wovenff FreeFEM binding: the pointwise material API (material points, no
// mesh). Every function takes its material as a file name (read afresh on
// every call) or as a handle from wovenffMaterial (ff_materials.cpp: loaded
// once; use it in loops), and reports failures with wff_ff_fail.
//
//   real r = wovenffPoint(matFile, F, dA, gammaf, out);   // P, R, W, diagnostics
//   wovenffBalance(matFile, F, dA);                        // dA: guess in, balance out
//   wovenffBalance(matFile, F, dA, gammaf);                //   the same with gamma_f held
//   wovenffPreload(matFile, yarnTension, out);             // out = [l1, l2, dA1, dA2]
//   wovenffUniaxial(matFile, family, stretch, out);        // [l1, l2, dA1, dA2, P11, P22]
//   cout << wovenffCellInfo(matFile);                      // cell and out layout
//   wovenffPointStep(matFile, F, dA, gammaf, dt, out);     // wovenffPoint's out + new gamma_f
//   wovenffPointEnergySplit(matFile, F, dA, gammaf, out);  // energy per mechanism, J/m^2
//   string names = wovenffPointMechNames(matFile);         // "yarn_stretch yarn_bending ..."
//   wovenffPoints(mat, F, dA, gammaf, out);   // n points: F 6n, dA 2n, gammaf n; out n rows
// (wovenffEnergySplit / wovenffMechNames are a model's: ff_solver.cpp)
//
// F is row-major 3x2 (F11 F12 F21 F22 F31 F32), dA = [dA1, dA2] in m; SI units.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "ff_wovenff.hpp"

extern "C" {
#include "wovenff/balance.h"
#include "wovenff/material.h"
}

using namespace Fem2D;

namespace {

const char *const kFLayout = "F11 F12 F21 F22 F31 F32";
const char *const kDALayout = "dA1 dA2";

// wovenffPoint's out: P (6), R (2), W, then the cell's diagnostics.
const int kOutFixed = 9;
const char *const kOutNames[kOutFixed] = {"P11", "P12", "P21", "P22", "P31", "P32",
                                          "R1",  "R2",  "W"};
const char *const kOutUnits[kOutFixed] = {"N/m", "N/m",   "N/m",   "N/m", "N/m",
                                          "N/m", "N/m^2", "N/m^2", "J/m^2"};

// Copy a real[int] of known size, rejecting NaN and infinities.
void take(const char *fn, const char *name, const KN<double> *v, long n, const char *layout,
          double *dst)
{
    wff_ff_require_size(fn, name, v, n, layout);
    for (long i = 0; i < n; i++) {
        dst[i] = (*v)[i];
        if (!std::isfinite(dst[i])) {
            char msg[200];
            snprintf(msg, sizeof msg, "%s[%ld] = %g is not a finite number", name, i, dst[i]);
            wff_ff_fail(fn, msg);
        }
    }
}

void require_finite(const char *fn, const char *name, double x)
{
    if (!std::isfinite(x)) {
        char msg[200];
        snprintf(msg, sizeof msg, "%s = %g is not a finite number", name, x);
        wff_ff_fail(fn, msg);
    }
}

// Inputs far outside the model are refused, not evaluated (docs/limits.md,
// "Numbers"): an amplitude change must stay below the cell's quarter
// wavelength, |dA_k| < p_k0 (cells that draw a reference geometry); a strip
// stretch in [0.9, 1.5]; a preload yarn tension >= 0.
const double kStretchMin = 0.9, kStretchMax = 1.5;

void require_amplitudes_in_model(const char *fn, const wff_material &mat, const double dA[2],
                                 const char *where = "")
{
    const wff_cell_type *c = mat.cell;
    if (wff_cell_amplitudes(c) <= 0 || !wff_cell_has_reference_geometry(c))
        return;
    double pitch0[2], amplitude0[2];
    wff_cell_reference_geometry(&mat, pitch0, amplitude0);
    for (int k = 0; k < 2; k++)
        if (!(std::fabs(dA[k]) < pitch0[k])) {
            char msg[300 + sizeof mat.source];
            snprintf(msg, sizeof msg, "%sdA[%d] = %g m is outside the model: |dA_%d| must be "
                     "below the quarter wavelength p%d_0 = %g m (material %s)", where, k, dA[k],
                     k + 1, k + 1, pitch0[k], mat.source);
            wff_ff_fail(fn, msg);
        }
}

// The material (a file name loaded into *scratch, or a handle) of a function
// that fills `out` (refused without an out array).
template <class M>
const wff_material *material_for(const char *fn, const M &material, KN<double> *out,
                                 wff_material *scratch)
{
    if (!out)
        wff_ff_fail(fn, "no output array");
    return wff_ff_material_arg(fn, material, scratch);
}

// The start of the static solvers: unstretched, amplitudes as made.
wff_biaxial_state unstretched()
{
    wff_biaxial_state s = {};
    s.stretch[0] = s.stretch[1] = 1;
    return s;
}

// out = [l1, l2, dA1, dA2], with the resultants P11 P22 after them if asked.
void put_state(KN<double> *out, const wff_biaxial_state &s, bool resultants)
{
    out->resize(resultants ? 6 : 4);
    (*out)[0] = s.stretch[0];
    (*out)[1] = s.stretch[1];
    (*out)[2] = s.dA[0];
    (*out)[3] = s.dA[1];
    if (resultants) {
        (*out)[4] = s.resultant[0];
        (*out)[5] = s.resultant[1];
    }
}

// Refuse a point the cell found degenerate, naming it (`where`: "" or
// "point 17: ") with its F and the material.
[[noreturn]] void fail_degenerate(const char *fn, const char *where, const double F[6],
                                  const wff_material &mat)
{
    char msg[240 + sizeof mat.source];
    snprintf(msg, sizeof msg, "%sdegenerate point (a yarn direction has zero length or the "
             "yarns are parallel): F = [%g %g %g %g %g %g], material %s",
             where, F[0], F[1], F[2], F[3], F[4], F[5], mat.source);
    wff_ff_fail(fn, msg);
}

// A point's internal state from the binding's scalar gammaf: the cell's state
// named "gamma_f" (King, basket) takes it, every other state 0 (its start; a
// cell without such a state ignores gammaf). Returns that state's index or -1.
int state_from_gamma_f(const wff_material &mat, double gamma_f, double state[WFF_STATE_MAX])
{
    for (int i = 0; i < WFF_STATE_MAX; i++)
        state[i] = 0;
    int g = wff_material_state_index(&mat, "gamma_f");
    if (g >= 0)
        state[g] = gamma_f;
    return g;
}

// Evaluate one point (dt > 0 advances gamma_f by the cell's flow rule) and fill
// out with P, R, W and the diagnostics; extra entries are left for the caller.
template <class M>
void point(const char *fn, const M &material, KN<double> *Fv, KN<double> *dAv, double gamma_f,
           double dt, KN<double> *out, int extra, wff_point_result *r)
{
    double F[6], dA[2];
    take(fn, "F", Fv, 6, kFLayout, F);
    take(fn, "dA", dAv, 2, kDALayout, dA);
    require_finite(fn, "gammaf", gamma_f);
    require_finite(fn, "dt", dt);
    if (dt < 0) {
        char msg[120];
        snprintf(msg, sizeof msg, "dt = %g must be >= 0", dt);
        wff_ff_fail(fn, msg);
    }
    wff_material scratch;
    const wff_material *mat = material_for(fn, material, out, &scratch);
    require_amplitudes_in_model(fn, *mat, dA);
    double state[WFF_STATE_MAX];
    state_from_gamma_f(*mat, gamma_f, state);
    if (wff_material_evaluate(mat, F, dA, state, dt, r) != WFF_POINT_OK)
        fail_degenerate(fn, "", F, *mat);
    const int n_diag = wff_cell_n_diag(mat->cell);
    out->resize(kOutFixed + n_diag + extra);
    for (int i = 0; i < 6; i++)
        (*out)[i] = r->stress[i];
    (*out)[6] = r->residual[0];
    (*out)[7] = r->residual[1];
    (*out)[8] = r->energy;
    for (int i = 0; i < n_diag; i++)
        (*out)[kOutFixed + i] = r->diag[i];
}

template <class M>
double ffPoint(const M &material, KN<double> *const &Fv, KN<double> *const &dAv,
               const double &gamma_f, KN<double> *const &out)
{
    wff_point_result r;
    point("wovenffPoint", material, Fv, dAv, gamma_f, 0, out, 0, &r);
    return 0;
}

// wovenffPoint's out with gamma_f advanced over dt, and the new gamma_f last.
template <class M>
double ffPointStep(const M &material, KN<double> *const &Fv, KN<double> *const &dAv,
                   const double &gamma_f, const double &dt, KN<double> *const &out)
{
    wff_point_result r;
    point("wovenffPointStep", material, Fv, dAv, gamma_f, dt, out, 1, &r);
    wff_material scratch;
    double state[WFF_STATE_MAX];
    int g = state_from_gamma_f(*wff_ff_material_arg("wovenffPointStep", material, &scratch),
                               gamma_f, state);
    (*out)[out->N() - 1] = g >= 0 ? r.state[g] : gamma_f; /* (no flow: held) */
    return 0;
}

// n material points at once, gamma_f held (wovenffPoint's dt = 0): point p
// has F = F[6p .. 6p+5], dA = dA[2p, 2p+1], gamma_f = gammaf[p]; n is gammaf's
// size and F, dA must have 6n, 2n entries. out is resized to n rows of
// wovenffPoint's out (row-major: row p starts at p * (9 + the cell's
// diagnostics)); each row equals wovenffPoint's out for that point bit for
// bit (the same evaluation). Returns n.
template <class M>
double ffPoints(const M &material, KN<double> *const &Fv, KN<double> *const &dAv,
                KN<double> *const &gv, KN<double> *const &out)
{
    const char *fn = "wovenffPoints";
    if (!gv)
        wff_ff_fail(fn, "no gammaf array");
    const long n = gv->N();
    char layout[120];
    snprintf(layout, sizeof layout, "%s per point, %ld points (the size of gammaf)", kFLayout, n);
    wff_ff_require_size(fn, "F", Fv, 6 * n, layout);
    snprintf(layout, sizeof layout, "%s per point, %ld points (the size of gammaf)", kDALayout, n);
    wff_ff_require_size(fn, "dA", dAv, 2 * n, layout);
    if (out == Fv || out == dAv || out == gv)
        wff_ff_fail(fn, "out must be an array of its own (it is resized), not F, dA or gammaf");
    wff_material scratch;
    const wff_material *mat = material_for(fn, material, out, &scratch);
    const long cols = kOutFixed + wff_cell_n_diag(mat->cell);
    out->resize(n * cols);
    const char *const f_names[6] = {"F11", "F12", "F21", "F22", "F31", "F32"};
    for (long p = 0; p < n; p++) {
        double F[6], dA[2];
        const double gamma_f = (*gv)[p];
        for (int i = 0; i < 6; i++)
            F[i] = (*Fv)[6 * p + i];
        dA[0] = (*dAv)[2 * p];
        dA[1] = (*dAv)[2 * p + 1];
        bool finite = std::isfinite(gamma_f);
        for (int i = 0; i < 6; i++)
            finite = finite && std::isfinite(F[i]);
        finite = finite && std::isfinite(dA[0]) && std::isfinite(dA[1]);
        if (!finite) {
            char msg[300];
            int i = 0;
            while (i < 6 && std::isfinite(F[i]))
                i++;
            if (i < 6)
                snprintf(msg, sizeof msg, "point %ld: F[%ld] (its %s) = %g is not a finite number",
                         p, 6 * p + i, f_names[i], F[i]);
            else if (!std::isfinite(dA[0]) || !std::isfinite(dA[1])) {
                const int k = std::isfinite(dA[0]) ? 1 : 0;
                snprintf(msg, sizeof msg, "point %ld: dA[%ld] (its dA%d) = %g is not a finite "
                         "number", p, 2 * p + k, k + 1, dA[k]);
            } else
                snprintf(msg, sizeof msg, "point %ld: gammaf[%ld] = %g is not a finite number", p,
                         p, gamma_f);
            wff_ff_fail(fn, msg);
        }
        char where[40];
        snprintf(where, sizeof where, "point %ld: ", p);
        require_amplitudes_in_model(fn, *mat, dA, where);
        wff_point_result r;
        double state[WFF_STATE_MAX];
        state_from_gamma_f(*mat, gamma_f, state);
        if (wff_material_evaluate(mat, F, dA, state, 0, &r) != WFF_POINT_OK)
            fail_degenerate(fn, where, F, *mat);
        double *row = &(*out)[p * cols];
        for (int i = 0; i < 6; i++)
            row[i] = r.stress[i];
        row[6] = r.residual[0];
        row[7] = r.residual[1];
        row[8] = r.energy;
        for (int i = 0; i < wff_cell_n_diag(mat->cell); i++)
            row[kOutFixed + i] = r.diag[i];
    }
    return (double)n;
}

// The cell's energy_split; fails naming the cell if it has none.
const wff_cell_type *split_cell(const char *fn, const wff_material &mat)
{
    const wff_cell_type *c = mat.cell;
    if (!wff_cell_has_energy_split(c) || wff_cell_n_mech(c) <= 0) {
        std::string msg = std::string("cell '") + wff_cell_name(c) + "' (material " + mat.source +
                          ") has no energy split per mechanism";
        wff_ff_fail(fn, msg.c_str());
    }
    return c;
}

template <class M>
double ffEnergySplit(const M &material, KN<double> *const &Fv, KN<double> *const &dAv,
                     const double &gamma_f, KN<double> *const &out)
{
    const char *fn = "wovenffPointEnergySplit";
    double F[6], dA[2];
    take(fn, "F", Fv, 6, kFLayout, F);
    take(fn, "dA", dAv, 2, kDALayout, dA);
    require_finite(fn, "gammaf", gamma_f);
    wff_material scratch;
    const wff_material &mat = *material_for(fn, material, out, &scratch);
    require_amplitudes_in_model(fn, mat, dA);
    const wff_cell_type *c = split_cell(fn, mat);
    double mech[WFF_MECH_MAX];
    double state[WFF_STATE_MAX];
    state_from_gamma_f(mat, gamma_f, state);
    wff_cell_energy_split(&mat, F, dA, state, mech);
    for (int i = 0; i < wff_cell_n_mech(c); i++)
        if (!std::isfinite(mech[i]))
            fail_degenerate(fn, "", F, mat);
    out->resize(wff_cell_n_mech(c));
    for (int i = 0; i < wff_cell_n_mech(c); i++)
        (*out)[i] = mech[i];
    return 0;
}

template <class M>
string *ffMechNames(Stack stack, const M &material)
{
    const char *fn = "wovenffPointMechNames";
    wff_material scratch;
    const wff_cell_type *c = split_cell(fn, *wff_ff_material_arg(fn, material, &scratch));
    std::string text;
    for (int i = 0; i < wff_cell_n_mech(c); i++)
        text += (i ? " " : "") + std::string(wff_cell_mech_name(c, i));
    return Add2StackOfPtr2Free(stack, new string(text));
}

template <class M>
double balance(const char *fn, const M &material, KN<double> *Fv, KN<double> *dAv,
               double gamma_f)
{
    double F[6], dA[2];
    take(fn, "F", Fv, 6, kFLayout, F);
    take(fn, "dA", dAv, 2, kDALayout, dA);
    require_finite(fn, "gammaf", gamma_f);
    wff_material scratch;
    const wff_material *mat = wff_ff_material_arg(fn, material, &scratch);
    require_amplitudes_in_model(fn, *mat, dA);   // the guess
    wff_error err;
    double state[WFF_STATE_MAX];
    state_from_gamma_f(*mat, gamma_f, state);
    if (wff_balance_amplitudes(mat, F, state, dA, &err))
        wff_ff_fail(fn, err);
    (*dAv)[0] = dA[0];
    (*dAv)[1] = dA[1];
    return 0;
}

template <class M>
double ffBalance(const M &material, KN<double> *const &Fv, KN<double> *const &dAv)
{
    return balance("wovenffBalance", material, Fv, dAv, 0);
}

template <class M>
double ffBalanceHeld(const M &material, KN<double> *const &Fv, KN<double> *const &dAv,
                     const double &gamma_f)
{
    return balance("wovenffBalance", material, Fv, dAv, gamma_f);
}

template <class M>
double ffPreload(const M &material, const double &tension, KN<double> *const &out)
{
    const char *fn = "wovenffPreload";
    require_finite(fn, "yarnTension", tension);
    if (!(tension >= 0)) {
        char msg[160];
        snprintf(msg, sizeof msg, "yarnTension = %g N must be >= 0 (a preload pulls the "
                 "yarns; 0 = none)", tension);
        wff_ff_fail(fn, msg);
    }
    wff_material scratch;
    const wff_material *mat = material_for(fn, material, out, &scratch);
    wff_biaxial_state s = unstretched();
    wff_error err;
    if (wff_preload_equal_force(mat, tension, &s, &err))
        wff_ff_fail(fn, err);
    put_state(out, s, false);
    return 0;
}

// A copy of a material with values replaced ("K_d=0,kb_1=0"), validated and
// written atomically to outFile; returns 0.
double ffMaterialOverride(string *const &material, string *const &overrides,
                          string *const &outFile)
{
    wff_error err;
    if (wff_material_override(material->c_str(), overrides->c_str(), outFile->c_str(), &err))
        wff_ff_fail("wovenffMaterialOverride", err);
    return 0;
}

template <class M>
double ffUniaxial(const M &material, const long &family, const double &stretch,
                  KN<double> *const &out)
{
    const char *fn = "wovenffUniaxial";
    require_finite(fn, "stretch", stretch);
    if (!(stretch >= kStretchMin && stretch <= kStretchMax)) {
        char msg[200];
        snprintf(msg, sizeof msg, "stretch = %g is outside the model: a strip stretch must be "
                 "in [%g, %g] (a fabric carries no compression; Kevlar breaks near 1.04)",
                 stretch, kStretchMin, kStretchMax);
        wff_ff_fail(fn, msg);
    }
    if (family != 0 && family != 1) {
        char msg[120];
        snprintf(msg, sizeof msg, "family must be 0 (warp) or 1 (weft), got %ld", family);
        wff_ff_fail(fn, msg);
    }
    wff_material scratch;
    const wff_material *mat = material_for(fn, material, out, &scratch);
    wff_biaxial_state s = unstretched();
    wff_error err;
    if (wff_uniaxial_static(mat, (int)family, stretch, &s, &err))
        wff_ff_fail(fn, err);
    put_state(out, s, true);
    return 0;
}

template <class M>
string *ffCellInfo(Stack stack, const M &material)
{
    wff_material scratch;
    const wff_cell_type *c = wff_ff_material_arg("wovenffCellInfo", material, &scratch)->cell;
    std::string text = std::string("cell ") + wff_cell_name(c) + ": " + wff_cell_summary(c) + "\n" +
                       "wovenffPoint out layout (index name unit):\n";
    char line[120];
    for (int i = 0; i < kOutFixed + wff_cell_n_diag(c); i++) {
        bool fixed = i < kOutFixed;
        snprintf(line, sizeof line, "  %2d %-6s %s\n", i,
                 fixed ? kOutNames[i] : wff_cell_diag_name(c, i - kOutFixed),
                 fixed ? kOutUnits[i] : wff_cell_diag_unit(c, i - kOutFixed));
        text += line;
    }
    if (wff_cell_has_energy_split(c) && wff_cell_n_mech(c) > 0) {
        text += "wovenffPointEnergySplit out (J/m^2):";
        for (int i = 0; i < wff_cell_n_mech(c); i++)
            text += std::string(" ") + wff_cell_mech_name(c, i);
        text += "\n";
    }
    return Add2StackOfPtr2Free(stack, new string(text));
}

// Every function twice: the material as a file name (M = string *) or as a
// wovenffMaterial handle (M = long).
template <class M>
void register_point()
{
    Global.Add("wovenffPoint", "(",
               new OneOperator5_<double, M, KN<double> *, KN<double> *, double, KN<double> *>(
                   ffPoint<M>));
    Global.Add("wovenffPoints", "(",
               new OneOperator5_<double, M, KN<double> *, KN<double> *, KN<double> *,
                                 KN<double> *>(ffPoints<M>));
    Global.Add("wovenffBalance", "(",
               new OneOperator3_<double, M, KN<double> *, KN<double> *>(ffBalance<M>));
    Global.Add("wovenffBalance", "(",
               new OneOperator4_<double, M, KN<double> *, KN<double> *, double>(
                   ffBalanceHeld<M>));
    Global.Add("wovenffPreload", "(",
               new OneOperator3_<double, M, double, KN<double> *>(ffPreload<M>));
    Global.Add("wovenffUniaxial", "(",
               new OneOperator4_<double, M, long, double, KN<double> *>(ffUniaxial<M>));
    Global.Add("wovenffCellInfo", "(", new OneOperator1s_<string *, M>(ffCellInfo<M>));
    Global.Add("wovenffPointStep", "(",
               new OneOperator6_<double, M, KN<double> *, KN<double> *, double, double,
                                 KN<double> *>(ffPointStep<M>));
    Global.Add("wovenffPointEnergySplit", "(",
               new OneOperator5_<double, M, KN<double> *, KN<double> *, double, KN<double> *>(
                   ffEnergySplit<M>));
    Global.Add("wovenffPointMechNames", "(", new OneOperator1s_<string *, M>(ffMechNames<M>));
}

} // namespace

void wff_ff_register_point()
{
    register_point<string *>();
    register_point<long>();
    Global.Add("wovenffMaterialOverride", "(",
               new OneOperator3_<double, string *, string *, string *>(ffMaterialOverride));
}

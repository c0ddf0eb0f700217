// wovenff FreeFEM binding: the element operators for a script's own explicit
// loop (include/wovenff/solver.h, plugin/operators.c; docs/freefem_api.md
// "Your own loop"). Arrays of states, velocities, forces and masses are in the
// layout of fespace Vh5(Th, [P1,P1,P1,P1,P1]): 5 per vertex, node-major
// (ux uy uz dA1 dA2).
//   real W = wovenffForces(md, U, R)        // R = internal forces at U (N), γᶠ held, no side
//                                           // effect; W the stored energy at U (J, whole)
//   real W = wovenffForces(md, U, R, dt)    // the same, γᶠ and the dissipation advanced by dt
//   wovenffMass(md, M)                      // lumped mass of every DOF, kg
//   real dts = wovenffStableStep(md[, U])   // stable step (s, factor 1) now or at U
//   real dts = wovenffStableStep(md, U, V, R)  // the same, and the amplitudes' travel limit
//                                           // at velocities V under forces R
//   real dt = wovenffStep(md)               // one built-in step; the step taken, s
//   wovenffDofKinds(md, K[, Vp])            // 0 free, 1 fixed, 2 prescribed; Vp their velocity
//   int n = wovenffContactSearch(md, U)     // the projectile's candidate nodes at U
//   real D = wovenffContact(md, U, V, R, P, dt, dtmid)  // projectile contact on the predicted
//                                           // state: V corrected, contact forces added to R,
//                                           // P = [tip z, velocity]; D energy dissipated (J)
//   real D = wovenffClampCorrect(md, V, dtmid)          // friction clamp on V; D dissipated (J):
//                                           // the friction force over the slip left
//   real D = wovenffClampCorrect(md, V, R, dt, dtmid)   // the same as the built-in step: the
//                                           // friction forces added to R, D at the balance's
//                                           // measure (docs/model.md §14)
// No physics here: each is one call into the C core.
#include "ff++.hpp"
#include "AFunction_ext.hpp"

#include <string>

#include "ff_wovenff.hpp"

using namespace Fem2D;

namespace {

const char *kLayout = "5 per vertex: ux uy uz dA1 dA2";

// wff_ff_model_fail (the message kept as model id's last error) unless v has
// exactly n entries.
void require_size(const char *fn, const char *name, const KN<double> *v, long n,
                  const char *layout, long id)
{
    if (!v || v->N() != n)
        wff_ff_model_fail(fn, std::string(name) + " must have " + std::to_string(n) +
                          " entries (" + layout + "), got " +
                          std::to_string(v ? (long)v->N() : 0L), id);
}

// The array's entries, after checking it has exactly model id's DOF count.
double *dofs(const char *fn, const char *name, const wff_model *m, KN<double> *v, long id)
{
    require_size(fn, name, v, wff_model_dof_count(m), kLayout, id);
    return &(*v)[0];
}

// An output array sized to the model's DOFs.
double *dofs_out(const wff_model *m, KN<double> *v)
{
    if (v->N() != wff_model_dof_count(m))
        v->resize(wff_model_dof_count(m));
    return &(*v)[0];
}

double loop_forces(long id, KN<double> *U, KN<double> *R, double dt)
{
    const char *fn = "wovenffForces";
    wff_model *m = wff_ff_model(id, fn);
    const double *u = dofs(fn, "U", m, U, id);
    if ((void *)U == (void *)R)
        wff_ff_model_fail(fn, "U and R must be different arrays", id);
    double energy = 0;
    wff_error err;
    if (wff_model_forces(m, u, dofs_out(m, R), dt, &energy, &err))
        wff_ff_model_fail(fn, err.message, id);
    return energy;
}

double ffForces(const long &id, KN<double> *const &U, KN<double> *const &R)
{
    return loop_forces(id, U, R, 0);
}

double ffForcesDt(const long &id, KN<double> *const &U, KN<double> *const &R, const double &dt)
{
    if (!(dt > 0))
        wff_ff_model_fail("wovenffForces", "dt = " + std::to_string(dt) +
                          " s: must be > 0 (without dt: γᶠ held)", id);
    return loop_forces(id, U, R, dt);
}

long ffMass(const long &id, KN<double> *const &M)
{
    const wff_model *m = wff_ff_model(id, "wovenffMass");
    wff_model_masses(m, dofs_out(m, M));
    return wff_model_dof_count(m);
}

double loop_stable_step(long id, const double *u)
{
    const wff_model *m = wff_ff_model(id, "wovenffStableStep");
    double dt;
    wff_error err;
    if (wff_model_stable_step(m, u, &dt, nullptr, &err))
        wff_ff_model_fail("wovenffStableStep", err.message, id);
    return dt;
}

double ffStableStep(const long &id)
{
    return loop_stable_step(id, nullptr);
}

double ffStableStepAt(const long &id, KN<double> *const &U)
{
    const char *fn = "wovenffStableStep";
    return loop_stable_step(id, dofs(fn, "U", wff_ff_model(id, fn), U, id));
}

double ffStableStepMoving(const long &id, KN<double> *const &U, KN<double> *const &V,
                          KN<double> *const &R)
{
    const char *fn = "wovenffStableStep";
    const wff_model *m = wff_ff_model(id, fn);
    double dt = loop_stable_step(id, dofs(fn, "U", m, U, id)), travel;
    wff_error err;
    if (wff_model_travel_step(m, dofs(fn, "V", m, V, id), dofs(fn, "R", m, R, id), &travel,
                              &err))
        wff_ff_model_fail(fn, err.message, id);
    return travel < dt ? travel : dt;
}

double ffStep(const long &id)
{
    wff_model *m = wff_ff_model(id, "wovenffStep");
    double dt = 0;
    wff_error err;
    if (wff_model_step(m, &dt, &err))
        wff_ff_model_fail("wovenffStep", err.message, id);
    return dt;
}

long ffDofKinds(const long &id, KN<double> *const &K)
{
    const wff_model *m = wff_ff_model(id, "wovenffDofKinds");
    wff_model_dof_kinds(m, dofs_out(m, K), nullptr);
    return wff_model_dof_count(m);
}

long ffDofKindsV(const long &id, KN<double> *const &K, KN<double> *const &Vp)
{
    const wff_model *m = wff_ff_model(id, "wovenffDofKinds");
    wff_model_dof_kinds(m, dofs_out(m, K), dofs_out(m, Vp));
    return wff_model_dof_count(m);
}

long ffContactSearch(const long &id, KN<double> *const &U)
{
    const char *fn = "wovenffContactSearch";
    wff_model *m = wff_ff_model(id, fn);
    if (!wff_model_has_projectile(m))
        wff_ff_model_fail(fn, "no projectile: set one with wovenffProjectile first", id);
    return wff_model_contact_search(m, dofs(fn, "U", m, U, id));
}

double ffContact(const long &id, KN<double> *const &U, KN<double> *const &V,
                 KN<double> *const &R, KN<double> *const &P, const double &dt,
                 const double &dtmid)
{
    const char *fn = "wovenffContact";
    wff_model *m = wff_ff_model(id, fn);
    const double *u = dofs(fn, "U", m, U, id);
    double *v = dofs(fn, "V", m, V, id), *r = dofs(fn, "R", m, R, id);
    require_size(fn, "P", P, 2, "projectile nose tip z (m), velocity along +z (m/s)", id);
    double tip[2] = {(*P)[0], (*P)[1]}, dissipated = 0;
    wff_error err;
    if (wff_model_contact(m, u, v, r, tip, dt, dtmid, &dissipated, &err))
        wff_ff_model_fail(fn, err.message, id);
    (*P)[1] = tip[1];
    return dissipated;
}

double ffClampCorrect(const long &id, KN<double> *const &V, const double &dtmid)
{
    const char *fn = "wovenffClampCorrect";
    wff_model *m = wff_ff_model(id, fn);
    double *v = dofs(fn, "V", m, V, id);
    if (!(dtmid > 0))
        wff_ff_model_fail(fn, "dtmid = " + std::to_string(dtmid) + " s: must be > 0", id);
    return wff_model_clamp_correct(m, v, dtmid);
}

double ffClampCorrectBooked(const long &id, KN<double> *const &V, KN<double> *const &R,
                            const double &dt, const double &dtmid)
{
    const char *fn = "wovenffClampCorrect";
    wff_model *m = wff_ff_model(id, fn);
    double *v = dofs(fn, "V", m, V, id), *r = dofs(fn, "R", m, R, id), dissipated = 0;
    wff_error err;
    if (wff_model_clamp_correct_booked(m, v, r, dt, dtmid, &dissipated, &err))
        wff_ff_model_fail(fn, err.message, id);
    return dissipated;
}

} // namespace

void wff_ff_register_loop()
{
    Global.Add("wovenffForces", "(",
               new OneOperator3_<double, long, KN<double> *, KN<double> *>(ffForces));
    Global.Add("wovenffForces", "(",
               new OneOperator4_<double, long, KN<double> *, KN<double> *, double>(ffForcesDt));
    Global.Add("wovenffMass", "(", new OneOperator2_<long, long, KN<double> *>(ffMass));
    Global.Add("wovenffStableStep", "(", new OneOperator1_<double, long>(ffStableStep));
    Global.Add("wovenffStableStep", "(",
               new OneOperator2_<double, long, KN<double> *>(ffStableStepAt));
    Global.Add("wovenffStableStep", "(",
               new OneOperator4_<double, long, KN<double> *, KN<double> *, KN<double> *>(
                   ffStableStepMoving));
    Global.Add("wovenffStep", "(", new OneOperator1_<double, long>(ffStep));
    Global.Add("wovenffDofKinds", "(", new OneOperator2_<long, long, KN<double> *>(ffDofKinds));
    Global.Add("wovenffDofKinds", "(",
               new OneOperator3_<long, long, KN<double> *, KN<double> *>(ffDofKindsV));
    Global.Add("wovenffContactSearch", "(",
               new OneOperator2_<long, long, KN<double> *>(ffContactSearch));
    Global.Add("wovenffContact", "(",
               new OneOperator7_<double, long, KN<double> *, KN<double> *, KN<double> *,
                                 KN<double> *, double, double>(ffContact));
    Global.Add("wovenffClampCorrect", "(",
               new OneOperator3_<double, long, KN<double> *, double>(ffClampCorrect));
    Global.Add("wovenffClampCorrect", "(",
               new OneOperator5_<double, long, KN<double> *, KN<double> *, double, double>(
                   ffClampCorrectBooked));
}

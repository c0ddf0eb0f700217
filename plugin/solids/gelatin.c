/* gelatin.c: 10 % ordnance gelatin, a small-strain visco-elastic law: elastic
 * in bulk, a standard linear solid in shear (a spring G_∞ beside a Maxwell
 * branch G_1 with relaxation time τ_1), the branch integrated exactly for a
 * strain linear in time over the step (plugin/solids/solid_laws.h). */
#include "solid_laws.h"

#include <math.h>

/* Default parameters and what each rests on (docs/backing_laws.md): the
 * density and bulk modulus are water's order (gelatin at 10 % is ~90 %
 * water; assumed, not read); the shear moduli and relaxation time are
 * placeholders of a soft, strongly rate-dependent solid, to be fitted to the
 * published tests: Salisbury & Cronin (2009), "Mechanical properties of
 * ballistic gelatin at high deformation rates", Exp. Mech. 49; Cronin &
 * Falzon (2011), "Characterization of 10% ballistic gelatin to evaluate
 * temperature, aging and strain rate effects", Exp. Mech. 51 (their numbers
 * were not at hand here). One branch is one decade of rate; a calibration
 * over 10⁻³–10³ /s needs a Prony series of several. */
const wff_gelatin_params wff_gelatin_ordnance10 = {
    .density = 1030,          /* kg/m³: assumed (water and 10 % gelatin) */
    .bulk = 2.2e9,            /* Pa: water's, assumed */
    .shear_long = 0.1e6,      /* Pa: placeholder */
    .shear_branch = 1.0e6,    /* Pa: placeholder */
    .relaxation_time = 1e-4,  /* s: placeholder */
};

int wff_gelatin_check(const wff_gelatin_params *p, wff_error *err)
{
    if (!(p->density > 0))
        return wff_fail(err, "gelatin: density %g kg/m3 must be > 0", p->density);
    if (!(p->bulk > 0))
        return wff_fail(err, "gelatin: bulk modulus %g Pa must be > 0", p->bulk);
    if (!(p->shear_long >= 0) || !(p->shear_branch >= 0))
        return wff_fail(err, "gelatin: shear moduli G_inf %g Pa and G_1 %g Pa must be >= 0",
                        p->shear_long, p->shear_branch);
    if (!(p->relaxation_time > 0))
        return wff_fail(err, "gelatin: relaxation time %g s must be > 0", p->relaxation_time);
    return 0;
}

double wff_gelatin_energy(const wff_gelatin_params *p, const double strain[WFF_SYM],
                          const wff_gelatin_state *s)
{
    double dev[WFF_SYM], q[WFF_SYM];
    const double tr = wff_sym_dev(strain, dev);
    for (int i = 0; i < WFF_SYM; i++)
        q[i] = dev[i] - s->viscous_strain[i];
    return 0.5 * p->bulk * tr * tr + p->shear_long * wff_sym_dot(dev, dev) +
           p->shear_branch * wff_sym_dot(q, q);
}

void wff_gelatin_stress(const wff_gelatin_params *p, const double strain[WFF_SYM],
                        const wff_gelatin_state *s, double stress[WFF_SYM])
{
    double dev[WFF_SYM];
    const double tr = wff_sym_dev(strain, dev);
    for (int i = 0; i < WFF_SYM; i++)
        stress[i] = 2 * p->shear_long * dev[i] +
                    2 * p->shear_branch * (dev[i] - s->viscous_strain[i]) +
                    (i < 3 ? p->bulk * tr : 0);
}

/* The branch strain q = dev ε − e^v obeys q̇ = ė − q/τ (the dashpot's
 * 2 G_1 τ ė^v equals the branch stress 2 G_1 q). With ė = r constant over the
 * step (E = e^{−Δt/τ}):
 *   q(t) = a e^{−t/τ} + b,  a = q_n − τ r,  b = τ r,   q_{n+1} = q_n E + τ r (1 − E),
 * and the dashpot's dissipation ∫ 2 (G_1/τ) |q|² dt over the step
 *   = 2 (G_1/τ) [ |a|² τ/2 (1 − E²) + 2 a:b τ (1 − E) + |b|² Δt ]  (>= 0). */
void wff_gelatin_update(const wff_gelatin_params *p, const double strain[WFF_SYM], double dt,
                        const wff_gelatin_state *old, wff_gelatin_state *out,
                        double stress[WFF_SYM])
{
    const double tau = p->relaxation_time, G1 = p->shear_branch;
    double dev[WFF_SYM], q0[WFF_SYM], a[WFF_SYM], b[WFF_SYM], q1[WFF_SYM];
    wff_sym_dev(strain, dev);
    double dissipated = 0;
    if (dt > 0) {
        const double one_e = -expm1(-dt / tau), one_e2 = -expm1(-2 * dt / tau);
        for (int i = 0; i < WFF_SYM; i++) {
            q0[i] = old->last_dev[i] - old->viscous_strain[i];
            b[i] = tau * (dev[i] - old->last_dev[i]) / dt;
            a[i] = q0[i] - b[i];
            q1[i] = q0[i] * (1 - one_e) + b[i] * one_e;
        }
        dissipated = 2 * G1 / tau *
                     (wff_sym_dot(a, a) * 0.5 * tau * one_e2 + 2 * wff_sym_dot(a, b) * tau * one_e +
                      wff_sym_dot(b, b) * dt);
    } else {
        for (int i = 0; i < WFF_SYM; i++) /* an instant step: the dashpot does not move */
            q1[i] = old->last_dev[i] - old->viscous_strain[i] + dev[i] - old->last_dev[i];
    }
    const double before = old->dissipated;
    for (int i = 0; i < WFF_SYM; i++) {
        out->viscous_strain[i] = dev[i] - q1[i];
        out->last_dev[i] = dev[i];
    }
    out->dissipated = before + dissipated;
    wff_gelatin_stress(p, strain, out, stress);
}

double wff_gelatin_wave_speed(const wff_gelatin_params *p)
{
    return sqrt((p->bulk + 4 * (p->shear_long + p->shear_branch) / 3) / p->density);
}

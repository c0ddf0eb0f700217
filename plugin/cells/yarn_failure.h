/* wovenff — yarn failure, the one law every cell with yarns shares
 * (docs/model.md §20; issue 13).
 *
 * Per yarn family k a damage d_k, 0 intact .. 1 ruptured, grows linearly with
 * the largest engineering yarn strain ε_k reached, between the failure strain
 * ε_f,k (damage starts) and the rupture strain ε_r,k (the yarn carries
 * nothing), and never decreases:
 *
 *   d_k ← max(d_k, clamp((ε_k − ε_f,k φ)/((ε_r,k − ε_f,k) φ), 0, 1))
 *
 * φ scales both strains with the yarn strain rate (Cowper–Symonds, optional):
 *
 *   φ = 1 + (|ε̇_k|/C)^(1/p),   ε̇_k = (ε_k − ε_k^prev)/Δt
 *
 * (φ = 1 without the rate keys.) ε_k^prev is the strain of the previous
 * update, kept as a state of the point; a state starting at 0 under a
 * preloaded yarn gives one large apparent rate at the first step, which only
 * raises φ, so it can delay damage, never cause it. Δt = 0 holds everything
 * (d_k, ε_k^prev): the stress is then the exact derivative of the damaged
 * energy. Without the rate law the update is d_k = g(max ε_k) exactly (g
 * nondecreasing), "damage on the largest strain reached".
 *
 * Damage acts on tension only. With T_k the undamaged yarn tension and W_k
 * the yarn-stretch energy it derives from (T_k > 0 exactly where ε_k > 0):
 *
 *   T_k^d = (1 − d_k) T_k        if ε_k > 0, else T_k
 *   W_k^d = (1 − d_k) W_k^+ + W_k^−
 *
 * so at fixed d_k, T_k^d = ∂W_k^d/∂(stretch) still. An update that raises d_k
 * releases stored energy −∂W/∂d Δd = Δd_k W_k^+ (at the end-of-update strain):
 * failure_dissipated, so that work = ΔW + shear flow + failure dissipation.
 *
 * The engineering yarn strain is each cell's own: king_plain the truss along
 * the crimped path, (L_k − L_k⁰)/L_k⁰ (k_k = EA/L_k⁰, so T_k = EA ε_k);
 * basket_2x2 the half-repeat path (ℓ_k − ℓ_k⁰)/ℓ_k⁰; linear_yarns λ_k − 1.
 *
 * Crack band (optional key failure_band_length = h_ref, m; 0 or absent: none).
 * Softening inside one element releases, per unit crack length, h times the
 * energy per unit area a point releases on its way to rupture, which for a
 * linear yarn (W_k = c ε_k², the cells here) under a rising strain is
 *
 *   g(ε_f, ε_r) = ∫ W_k dd_k = c (ε_f² + ε_f ε_r + ε_r²)/3,
 *
 * onset energy included (c ε_f², 83 % of it at ε_r/ε_f = 1.19: the damage
 * takes the whole stored energy). With the band, a point of an element of
 * length h (its state element_length, set by the element code) takes the
 * span s(h) = ε_r(h) − ε_f that keeps g·h = g(ε_f, ε_r)·h_ref (onset ε_f
 * unchanged, both still times φ):
 *
 *   s² + 3 ε_f s = (h_ref/h)(ε_f² + ε_f ε_r + ε_r²) − 3 ε_f²,
 *
 * s = s₀ = ε_r − ε_f at h = h_ref (today's law exactly), larger for smaller
 * elements. Scaling the span alone, s₀ h_ref/h, would keep the onset energy
 * ∝ h (at h = h_ref/2, 0.59 of the energy instead of 1). Above the snap-back
 * length h* = h_ref (ε_f² + ε_f ε_r + ε_r²)/(3 ε_f²) (1.20 h_ref for 3.8 and
 * 4.52 %) no span releases as little as h_ref's element: there the span is
 * the floor WFF_YARN_BAND_SPAN_FLOOR s₀ (near-brittle, still well defined)
 * and the element releases more than h_ref's. Below h_ref the span is kept
 * ≤ max(ε_f, ε_r − ε_f): with ε_r(h) > 2 ε_f the tension (1 − d) T would
 * still rise past the onset (d/dε [(ε_r − ε) ε] > 0 at ε_f), the element
 * would harden rather than soften and damage spread beyond one element (a
 * bar pulled through rupture then releases more, not h_ref's); at the cap,
 * h < h_ref (7 ε_f²)⁻¹(ε_f² + ε_f ε_r + ε_r²) (0.515 h_ref for 3.8 and
 * 4.52 %), the element releases less than h_ref's. So the band holds exactly
 * between 0.515 and 1.20 h_ref for these strains. element_length 0 (the cell
 * suite, the explorer, wff_rest_state) means no scaling.
 *
 * Transverse cutting (optional key cutting_pressure = p_c, Pa; 0 or absent:
 * none; docs/model.md §25). Under the projectile's edge a yarn is pressed
 * across its axis as it is pulled along it; a pressed yarn fails at a lower
 * strain. With p the contact pressure at the point (its state
 * contact_pressure, Pa, set by the projectile's contact each step: the nose's
 * force on the point's node over the node's area; never changed by the cell)
 * both strains scale with
 *
 *   κ(p) = max(0, 1 − p/p_c):   ε_f κ φ  and  s(h) κ φ,
 *
 * so the damage is clamp((ε − ε_f κ φ)/(s κ φ), 0, 1); at p ≥ p_c a stretched
 * yarn (ε > 0) is cut through at once (d = 1), a slack one is not. κ = 1
 * (p = 0, or the key absent) is today's law bit for bit.
 *
 * Material keys (parsed here, once for every cell): failure (0 off, the
 * default; 1 on), fail_strain_1, fail_strain_2, rupture_strain_1,
 * rupture_strain_2 (−), failure_rate_C (1/s) and failure_rate_p (−), the rate
 * pair optional, failure_band_length (m, optional), cutting_pressure (Pa,
 * optional; the cell must carry the contact_pressure state: a cell that
 * does not refuses the key). The strains come as a set
 * of four; present with failure = 0 they are checked and kept but unused (a
 * scene switches failure on through the material override, which replaces
 * values of keys already in the file: hence failure_band_length = 0 for
 * none, so that a file can carry the key and a scene set it).
 *
 * Pure functions, no allocation, no state: included by cells, which are
 * compiled once per kernel variant. */
#ifndef WOVENFF_YARN_FAILURE_H
#define WOVENFF_YARN_FAILURE_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cell_laws.h"
#include "wovenff/material.h"

/* The failure law's parameters, kept inside a cell's parameter struct
 * (doubles only, so that it copies with the rest). */
typedef struct wff_yarn_failure {
    double enabled;              /* 1: yarns fail (failure = 1); 0: off, the keys unused */
    double fail_strain[2];       /* ε_f,k, engineering yarn strain where damage starts, − */
    double rupture_strain[2];    /* ε_r,k, where the yarn carries nothing, − */
    double rate_C;               /* C, 1/s; 0: no rate scaling (φ = 1) */
    double rate_p;               /* p, −; 0 without rate scaling */
    double band_length;          /* h_ref, m, the crack band's reference element length;
                                    0: no scaling (no element_length state) */
    double cutting_pressure;     /* p_c, Pa, the contact pressure at which a stretched yarn is
                                    cut through; 0: no cutting (no contact_pressure state) */
} wff_yarn_failure;

/* The smallest span with the crack band, a fraction of the unscaled ε_r − ε_f
 * (elements beyond the snap-back length h*; see the header comment). */
#define WFF_YARN_BAND_SPAN_FLOOR 0.1

/* The law's states, from d_1 on (a cell puts them after its own): d_1, d_2;
 * ε_1^prev, ε_2^prev with the rate law or the band; the element length h with
 * the band (the name a cell gives it: "element_length", unit m). */
enum { WFF_YARN_STATE_LENGTH = 4, WFF_YARN_STATES_MAX = 5 };

/* 1 when the points keep ε_k^prev (the rate law or the band: the states from
 * d_1 on are then at least d_1, d_2, ε_1, ε_2); what a cell passes as
 * strain_prev otherwise is 0. */
static inline int wff_yarn_failure_keeps_strain(const wff_yarn_failure *f)
{
    return f->rate_C > 0 || f->band_length > 0;
}

/* The per-point states the law adds to a cell's: d_1, d_2, and ε_1^prev,
 * ε_2^prev with the rate law or the band, then h with the band; 0 when
 * failure is off. */
static inline int wff_yarn_failure_states(const wff_yarn_failure *f)
{
    if (f->enabled == 0)
        return 0;
    if (f->band_length > 0)
        return 5;
    return f->rate_C > 0 ? 4 : 2;
}

/* Read and check the keys (see the header comment). Errors name the file,
 * the line and the key:
 *   failure other than 0 or 1; failure = 1 without the strains;
 *   some strain keys but not all four (e.g. one family only);
 *   a strain ≤ 0; rupture_strain_k ≤ fail_strain_k;
 *   one rate constant without the other, a rate constant ≤ 0, or the rate
 *   constants without the strains; failure_band_length < 0.
 * Returns 0 or -1. */
static inline int wff_yarn_failure_parse(wff_kv *kv, wff_yarn_failure *f, wff_error *err)
{
    static const char *const strain_key[4] = {"fail_strain_1", "fail_strain_2",
                                              "rupture_strain_1", "rupture_strain_2"};
    double failure, strain[4], rate_C, rate_p, band, cutting;
    f->enabled = f->rate_C = f->rate_p = f->band_length = f->cutting_pressure = 0;
    f->fail_strain[0] = f->fail_strain[1] = f->rupture_strain[0] = f->rupture_strain[1] = 0;
    if (wff_kv_number_or(kv, "failure", 0.0, &failure, err))
        return -1;
    /* NaN marks an absent key: a file's numbers are finite (wff_kv_number_or) */
    for (int i = 0; i < 4; i++)
        if (wff_kv_number_or(kv, strain_key[i], NAN, &strain[i], err))
            return -1;
    if (wff_kv_number_or(kv, "failure_rate_C", NAN, &rate_C, err) ||
        wff_kv_number_or(kv, "failure_rate_p", NAN, &rate_p, err) ||
        wff_kv_number_or(kv, "failure_band_length", 0.0, &band, err) ||
        wff_kv_number_or(kv, "cutting_pressure", 0.0, &cutting, err))
        return -1;
    if (failure != 0 && failure != 1)
        return wff_kv_reject(kv, "failure", err, "must be 0 (no yarn failure) or 1 (yarns fail "
                             "between fail_strain_k and rupture_strain_k)");

    int present = 0, first_present = -1;
    char missing[128] = "";
    for (int i = 0; i < 4; i++) {
        if (!isnan(strain[i])) {
            present++;
            if (first_present < 0)
                first_present = i;
        } else {
            size_t used = strlen(missing);
            snprintf(missing + used, sizeof missing - used, "%s%s", used ? ", " : "",
                     strain_key[i]);
        }
    }
    if (present > 0 && present < 4)
        return wff_kv_reject(kv, strain_key[first_present], err,
                             "yarn failure takes fail_strain_k and rupture_strain_k for both "
                             "families (k = 1, 2); missing: %s", missing);
    if (present == 0 && failure == 1)
        return wff_kv_reject(kv, "failure", err, "failure = 1 needs the yarn strains "
                             "fail_strain_1, fail_strain_2, rupture_strain_1, rupture_strain_2");
    for (int i = 0; i < present; i++)
        if (!(strain[i] > 0))
            return wff_kv_reject(kv, strain_key[i], err,
                                 "must be > 0 (an engineering yarn strain in tension)");
    for (int k = 0; k < 2 && present; k++)
        if (!(strain[2 + k] > strain[k]))
            return wff_kv_reject(kv, strain_key[2 + k], err,
                                 "rupture strain must be larger than %s = %g (damage grows "
                                 "between the two)", strain_key[k], strain[k]);

    int has_C = !isnan(rate_C), has_p = !isnan(rate_p);
    if (has_C != has_p)
        return wff_kv_reject(kv, has_C ? "failure_rate_C" : "failure_rate_p", err,
                             "the Cowper-Symonds rate scaling takes both failure_rate_C "
                             "(1/s) and failure_rate_p (-); %s is missing",
                             has_C ? "failure_rate_p" : "failure_rate_C");
    if (has_C && !(rate_C > 0))
        return wff_kv_reject(kv, "failure_rate_C", err, "must be > 0 1/s");
    if (has_p && !(rate_p > 0))
        return wff_kv_reject(kv, "failure_rate_p", err, "must be > 0");
    if (has_C && present == 0)
        return wff_kv_reject(kv, "failure_rate_C", err, "rate scaling of the failure strains "
                             "given without the strains (fail_strain_k, rupture_strain_k)");

    if (band < 0)
        return wff_kv_reject(kv, "failure_band_length", err,
                             "must be >= 0 m (the crack band's reference element length; "
                             "0: no scaling of the rupture strain with the element size)");

    if (cutting < 0)
        return wff_kv_reject(kv, "cutting_pressure", err,
                             "must be >= 0 Pa (the contact pressure that cuts a stretched "
                             "yarn through; 0: no transverse cutting)");
    if (cutting > 0 && present == 0)
        return wff_kv_reject(kv, "cutting_pressure", err, "transverse cutting lowers the "
                             "failure strains: it takes fail_strain_k and rupture_strain_k");

    f->enabled = failure;
    f->band_length = band;
    f->cutting_pressure = cutting;
    if (present) {
        f->fail_strain[0] = strain[0];
        f->fail_strain[1] = strain[1];
        f->rupture_strain[0] = strain[2];
        f->rupture_strain[1] = strain[3];
    }
    if (has_C) {
        f->rate_C = rate_C;
        f->rate_p = rate_p;
    }
    return 0;
}

/* For a cell without the contact_pressure state: refuse cutting_pressure > 0
 * (naming the key and the cell). Returns 0 or -1. */
static inline int wff_yarn_failure_no_cutting(wff_kv *kv, const wff_yarn_failure *f,
                                              const char *cell, wff_error *err)
{
    if (f->cutting_pressure > 0)
        return wff_kv_reject(kv, "cutting_pressure", err, "transverse cutting is the "
                             "king_plain cell's only (the %s cell carries no contact "
                             "pressure state)", cell);
    return 0;
}

/* φ = 1 + (|ε̇|/C)^(1/p), or 1 without rate scaling. */
WFF_INLINE double wff_yarn_failure_rate_factor(const wff_yarn_failure *f, double strain_rate)
{
    if (!(f->rate_C > 0))
        return 1.0;
    return 1.0 + pow(fabs(strain_rate) / f->rate_C, 1.0 / f->rate_p);
}

/* Family k's span ε_r(h) − ε_f at element length h (the crack band of the
 * header comment): ε_r − ε_f without the band, at h ≤ 0 or at h = h_ref;
 * never below WFF_YARN_BAND_SPAN_FLOOR (ε_r − ε_f), never above
 * max(ε_f, ε_r − ε_f). */
WFF_INLINE double wff_yarn_failure_span(const wff_yarn_failure *f, int k,
                                        double element_length)
{
    const double onset = f->fail_strain[k], span = f->rupture_strain[k] - onset;
    if (!(f->band_length > 0) || !(element_length > 0) || element_length == f->band_length)
        return span;
    const double ratio = f->band_length / element_length; /* h_ref/h */
    /* the right-hand side above, (h_ref/h)(3 ε_f² + 3 ε_f s₀ + s₀²) − 3 ε_f², without
     * the cancellation at h ≈ h_ref */
    const double excess = 3 * onset * onset * (ratio - 1) + ratio * span * (3 * onset + span);
    const double floor = WFF_YARN_BAND_SPAN_FLOOR * span;
    const double ceiling = onset > span ? onset : span;
    if (!(excess > 0))
        return floor;
    /* the positive root of s² + 3 ε_f s − excess, in the form without cancellation */
    const double s = 2 * excess / (3 * onset + sqrt(9 * onset * onset + 4 * excess));
    return s < floor ? floor : s > ceiling ? ceiling : s;
}

/* κ(p) = max(0, 1 − p/p_c), the factor transverse cutting puts on both strains at
 * contact pressure p (Pa); 1 without cutting or at p <= 0. */
WFF_INLINE double wff_yarn_cutting_factor(const wff_yarn_failure *f, double pressure)
{
    if (!(f->cutting_pressure > 0) || !(pressure > 0))
        return 1.0;
    const double kappa = 1 - pressure / f->cutting_pressure;
    return kappa > 0 ? kappa : 0.0;
}

/* The damage a strain ε alone would give family k at rate factor φ (times the
 * cutting factor κ) and element length h (0: no scaling):
 * clamp((ε − ε_f φ)/(s(h) φ), 0, 1); at φ = 0 (κ = 0, cut) 1 for ε > 0, else 0. */
WFF_INLINE double wff_yarn_damage_of_strain(const wff_yarn_failure *f, int k, double strain,
                                            double rate_factor, double element_length)
{
    if (!(rate_factor > 0))
        return strain > 0 ? 1.0 : 0.0;
    double onset = f->fail_strain[k] * rate_factor;
    double span = wff_yarn_failure_span(f, k, element_length) * rate_factor;
    double d = (strain - onset) / span;
    d = d > 0 ? d : 0.0;
    return d < 1 ? d : 1.0;
}

/* What the law does to one yarn family at one update. */
typedef struct wff_yarn_damage {
    double damage;        /* d_k after the update */
    double strain_prev;   /* ε_k^prev to keep (the strain now when Δt > 0, else held) */
    double factor;        /* multiplies T_k and W_k: 1 − d_k in tension, 1 in compression */
    double released;      /* (d_k − d_k,old) W_k^+, J per the cell's energy unit, ≥ 0 */
} wff_yarn_damage;

/* Family k at engineering strain `strain` with undamaged yarn-stretch energy
 * `energy` (W_k: its W^+ when strain > 0), state damage (d_k) and strain_prev
 * (ε_k^prev, unused without the rate law), the point's element length
 * (state element_length; 0: no scaling) and contact pressure (state
 * contact_pressure, Pa; unused without cutting), step dt: the update of the
 * header comment. Failure off: nothing changes, factor 1. */
WFF_INLINE wff_yarn_damage wff_yarn_damage_step_pressed(const wff_yarn_failure *f, int k,
                                                        double strain, double energy,
                                                        double damage, double strain_prev,
                                                        double element_length,
                                                        double pressure, double dt)
{
    wff_yarn_damage y;
    y.damage = damage;
    y.strain_prev = strain_prev;
    if (f->enabled != 0 && dt > 0) {
        double rate_factor = wff_yarn_failure_rate_factor(f, (strain - strain_prev) / dt);
        rate_factor *= wff_yarn_cutting_factor(f, pressure); /* (1 without cutting) */
        double d = wff_yarn_damage_of_strain(f, k, strain, rate_factor, element_length);
        y.damage = d > damage ? d : damage;
        y.strain_prev = strain;
    }
    int tension = strain > 0;
    y.factor = tension ? 1 - y.damage : 1.0;
    y.released = tension ? (y.damage - damage) * energy : 0.0;
    return y;
}

/* wff_yarn_damage_step_pressed without contact pressure (no cutting). */
WFF_INLINE wff_yarn_damage wff_yarn_damage_step(const wff_yarn_failure *f, int k, double strain,
                                                double energy, double damage,
                                                double strain_prev, double element_length,
                                                double dt)
{
    return wff_yarn_damage_step_pressed(f, k, strain, energy, damage, strain_prev,
                                        element_length, 0.0, dt);
}

/* The element length h of a point from the law's states fs (d_1 first):
 * fs[WFF_YARN_STATE_LENGTH] with the band, else 0 (no scaling). */
WFF_INLINE double wff_yarn_failure_length(const wff_yarn_failure *f, const double *fs)
{
    return f->band_length > 0 ? fs[WFF_YARN_STATE_LENGTH] : 0.0;
}

#endif

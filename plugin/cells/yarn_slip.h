/* wovenff — yarn slip at the crossovers, king_plain's (docs/model.md §24).
 *
 * Yarn slip at the crossovers (docs/model.md §24, optional: material key
 * yarn_friction = μ_yy > 0 with slip_crossovers = n_c): a slip strain s_k per
 * family, in series with the yarn's elastic stretch, moves yarn through the
 * crossovers, the truss's rest length L_k⁰(1 + s_k):
 *
 *   T_k = k_k (L_k − L_k⁰(1 + s_k)),   energy k_k (L_k − L_k⁰(1 + s_k))²,
 *
 * and Coulomb friction caps the tension: |T_k| ≤ T_slip = n_c μ_yy ⟨F_I⟩, the
 * friction of n_c crossovers each pressed by the crossover force F_I; a step
 * that would exceed it slips (the return map, king_family_slip), dissipating
 * the friction's work T_slip × 2 L_k⁰ |Δs_k|. States s_1, s_2 after
 * the others (n_state 8 with slip). The blocked kernels decline slip.
 *
 * king_plain.c's own part, split out of it as written: it includes this file
 * after king_params, its state enum and king_family, which it uses (not a
 * stand-alone header).
 */
#ifndef WOVENFF_YARN_SLIP_H
#define WOVENFF_YARN_SLIP_H

#include <math.h>

#include "cell_laws.h"
#include "wovenff/material.h"

/* What yarn slip does to one family in one update (king_family_slip). */
typedef struct king_slip {
    double slip;     /* s_k after the update, - */
    double released; /* the friction's work, T_slip × the slip, J per cell (>= 0) */
} king_slip;

/* docs/model.md §24, yarn slip at the crossovers on family f: the slip strain
 * s_k (state `slip`) moves yarn through the crossovers into the cell, the truss's
 * rest length becoming L_k⁰(1 + s_k):
 *   x_k = L_k − L_k⁰(1 + s_k)   (y->stretch; the tension_only floor as for the yarn)
 *   T_k = k_k x_k,  energy k_k x_k²            (the stored energy with s_k held)
 * With dt > 0, Coulomb friction at the crossovers caps the tension the truss
 * carries, c_k x_k with c_k = (1 − d_k) k_k where stretched (d_k the damage before
 * this update, 0 without failure) and k_k elsewhere, at the slip tension
 *   T_slip = n_c μ_yy ⟨F_I⟩                    (slip_tension, N)
 * by the return map of rate-independent friction (the yarn's own elasticity is
 * the stick's): where |c_k x_k| > T_slip (s_k held) the truss slips to
 *   x_k ← sign(x_k) T_slip / c_k,   s_k ← s_k + (x_k,trial − x_k)/L_k⁰
 * dissipating the friction's work, the slip tension times the yarn slid through
 * the crossovers, 2 T_slip L_k⁰ |Δs_k| ≥ 0 (two trusses per cell). That is what
 * the explicit step's work measure needs: in steady slip the force is T_slip and
 * the stored energy does not change, so the kinetic energy lost is T_slip times
 * the slip. (The stored energy the update releases at this geometry,
 * c_k (x_trial² − x_k²), is larger by c_k (L_k⁰ Δs_k)²: booked instead, it put the
 * balance of a slipping run off by a fifth of the slip's dissipation.) dt = 0 holds
 * s_k (then T_k and the energy are the exact derivatives' pair). Sets y->stretch,
 * y->tension (undamaged: king_family_fail applies 1 − d_k) and y->energy_yarn. */
WFF_INLINE king_slip king_family_slip(const king_params *k, int f, king_family *y, double slip,
                                      double damage, double slip_tension, double dt)
{
    const double rest0 = k->length0[f], stiffness = k->yarn_stiffness[f];
    const double stretch_floor = k->tension_only != 0 ? 0.0 : -INFINITY;
    king_slip out = {slip, 0.0};
    double stretch = (y->length - rest0) - rest0 * slip; /* x_k with s_k held */
    double carried = stretch > stretch_floor ? stretch : stretch_floor;
    if (dt > 0) {
        const double carrying = carried > 0 ? (1 - damage) * stiffness : stiffness; /* c_k */
        const double trial = carrying * carried; /* the tension with s_k held, N */
        if (fabs(trial) > slip_tension) {
            const double held = copysign(slip_tension, trial) / carrying; /* x_k at T_slip */
            out.slip = slip + (stretch - held) / rest0;
            out.released = 2 * slip_tension * fabs(stretch - held);
            stretch = carried = held;
        }
    }
    y->stretch = stretch;
    y->tension = stiffness * carried;
    y->energy_yarn = stiffness * carried * carried;
    return out;
}

/* The slip tension T_slip = n_c μ_yy ⟨F_I⟩ (docs/model.md §24), N: no friction
 * where the crossover is open (F_I ≤ 0). */
WFF_INLINE double king_slip_tension(const king_params *k, double crossover_force)
{
    return k->slip_capacity * (crossover_force > 0 ? crossover_force : 0.0);
}

/* A point's slip states (s_1, s_2), or NULL when the material has no yarn slip. */
static inline const double *king_slip_state(const king_params *k, const double *state)
{
    return k->slip_capacity > 0 ? state + STATE_SLIP1 : NULL;
}

/* docs/model.md §24: the yarn slip's keys, yarn_friction (μ_yy, default 0: no
 * slip) and slip_crossovers (n_c, required with μ_yy > 0; present with 0 it is
 * checked and kept, unused, so that a file can carry it and a scene set μ_yy). */
static int king_slip_parse(wff_kv *kv, king_params *k, wff_error *err)
{
    double crossovers;
    if (wff_kv_number_or(kv, "yarn_friction", 0.0, &k->yarn_friction, err) ||
        wff_kv_number_or(kv, "slip_crossovers", NAN, &crossovers, err))
        return -1;
    if (!(k->yarn_friction >= 0))
        return wff_kv_reject(kv, "yarn_friction", err, "must be >= 0 (the yarn-on-yarn "
                             "Coulomb friction coefficient at the crossovers; 0: no slip)");
    if (!isnan(crossovers) && !(crossovers >= 1))
        return wff_kv_reject(kv, "slip_crossovers", err, "must be >= 1 (the crossovers "
                             "whose friction anchors a family's tension)");
    if (k->yarn_friction > 0 && isnan(crossovers))
        return wff_kv_reject(kv, "yarn_friction", err, "yarn slip (yarn_friction > 0) needs "
                             "slip_crossovers, the crossovers whose friction anchors a "
                             "family's tension (docs/model.md §24)");
    k->slip_crossovers = isnan(crossovers) ? 0 : crossovers;
    k->slip_capacity = k->yarn_friction > 0 ? k->yarn_friction * k->slip_crossovers : 0;
    return 0;
}

#endif

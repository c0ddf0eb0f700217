/* wovenff — king_plain's blocked kernels: the lanes of the loops cell_lanes.h
 * generates (king_evaluate_tri_block, king_evaluate_point_block,
 * king_amplitude_tangent_block, king_wave_speeds_block; docs/model.md §11).
 * Each lane runs king_point_at, king_wave_speeds_at or king_residual_tangent_at
 * with c = 2 (and n = 1) as constants; what they decline goes back to the
 * general path.
 *
 * king_plain.c's own part, split out of it as written: it includes this file
 * once those functions are defined (not a stand-alone header).
 */
#ifndef WOVENFF_KING_LANES_H
#define WOVENFF_KING_LANES_H

#include "cell_lanes.h"

/* The blocked kernels run king_point_at with c = 2 and n = 1 as constants
 * (branch-free, vectorised); other exponents, yarn failure and yarn slip go
 * back to the general path (the wave speeds keep the undamaged bounds, so
 * failure does not matter to them, slip does: §24; the tangent has no flow). */
WFF_INLINE int king_blocks_accept(const king_params *k)
{
    return k->locking_exponent == 2 && k->flow_exponent == 1 && k->failure.enabled == 0 &&
           k->slip_capacity == 0;
}

WFF_INLINE int king_wave_accepts(const king_params *k)
{
    return k->locking_exponent == 2 && k->flow_exponent == 1 && k->slip_capacity == 0;
}

WFF_INLINE int king_tangent_accepts(const king_params *k)
{
    return k->locking_exponent == 2 && k->failure.enabled == 0 && k->slip_capacity == 0;
}

/* Lane b of a wave-speed block (king_wave_speeds_at, c = 2 and n = 1); ctx
 * holds the areal density. */
WFF_INLINE void king_wave_lane(const king_params *k, const wff_lane_arg *ctx, wff_wave_block *blk,
                               double flag[WFF_BLOCK], int b)
{
    (void)flag;
    const double F[6] = {blk->F[0][b], blk->F[1][b], blk->F[2][b],
                         blk->F[3][b], blk->F[4][b], blk->F[5][b]};
    const double dA[2] = {blk->dA[0][b], blk->dA[1][b]};
    double speed, omega;
    king_wave_speeds_at(k, ctx->value, F, dA, 2.0, 1.0, 0.0, &speed, &omega);
    blk->membrane_speed[b] = speed;
    blk->amplitude_omega[b] = omega;
}

/* What the lanes of a triangle block share (king_tri_setup): the flow step
 * and the stress scale p_k⁰/(4 p1⁰ p2⁰)/3. */
typedef struct king_tri_ctx {
    wff_shear_flow flow;
    double scale[FAMILIES];
} king_tri_ctx;

WFF_INLINE void king_tri_setup(const king_params *k, double dt, king_tri_ctx *ctx,
                               const wff_tri_block *blk)
{
    (void)blk;
    ctx->flow = king_flow(k, dt);
    const double inv_cell = 1 / k->cell_area, third = 1.0 / 3.0;
    ctx->scale[0] = k->pitch0[0] * inv_cell * third;
    ctx->scale[1] = k->pitch0[1] * inv_cell * third;
}

/* Lane b of a block: one triangle's three nodal points (weights 1/3) sharing
 * one F, the frame computed once (docs/model.md §11), king_point_at three
 * times, the stress from the summed Q_k coefficients; its degenerate test as
 * a double in flag[b] (cell_lanes.h). */
WFF_INLINE void king_tri_lane(const king_params *k, const king_tri_ctx *ctx, wff_tri_block *blk,
                              double flag[WFF_BLOCK], int b)
{
    const double F[6] = {blk->F[0][b], blk->F[1][b], blk->F[2][b],
                         blk->F[3][b], blk->F[4][b], blk->F[5][b]};
    wff_yarn_frame fr;
    (void)wff_yarn_kinematics(k->pitch0, F, &fr);
    flag[b] = fr.p[0] > 0 && fr.p[1] > 0 && fr.sin_t > 0 ? 0.0 : 1.0;
    double q[FAMILIES][FAMILIES] = {{0, 0}, {0, 0}}, energy = 0, dissipated = 0;
#pragma GCC unroll 3
    for (int p = 0; p < 3; p++) {
        const double dA[2] = {blk->dA[p][0][b], blk->dA[p][1][b]};
        king_point pt;
        king_point_at(k, &fr, dA, blk->state[p][STATE_GAMMA_F][b], NULL, NULL, 0, &ctx->flow,
                      2.0, 1.0, &pt);
        blk->residual[p][0][b] = pt.residual[0];
        blk->residual[p][1][b] = pt.residual[1];
        blk->state[p][STATE_GAMMA_F][b] = pt.gamma_f;
#pragma GCC unroll 2
        for (int f = 0; f < FAMILIES; f++)
#pragma GCC unroll 2
            for (int m = 0; m < FAMILIES; m++)
                q[f][m] += pt.q[f][m];
        energy += pt.energy;
        dissipated += pt.dissipated;
    }
    double stress[6];
    wff_stress_from_q(&fr, q, ctx->scale, stress);
#pragma GCC unroll 6
    for (int i = 0; i < 6; i++)
        blk->stress[i][b] = stress[i];
    const double inv_cell = 1 / k->cell_area, third = 1.0 / 3.0;
    blk->energy[b] = energy * third * inv_cell;
    blk->dissipated[b] = dissipated * third * inv_cell;
    blk->failure_dissipated[b] = 0;
    blk->slip_dissipated[b] = 0;
}

WFF_INLINE void king_tri_finish(const king_params *k, const king_tri_ctx *ctx,
                                const double flag[WFF_BLOCK], wff_tri_block *blk)
{
    (void)k;
    (void)ctx;
    for (int b = 0; b < WFF_BLOCK; b++)
        blk->degenerate[b] = flag[b] != 0;
}

/* What the lanes of a point block share: the flow step and the stress scale
 * p_k⁰/(4 p1⁰ p2⁰). */
typedef struct king_point_ctx {
    wff_shear_flow flow;
    double scale[FAMILIES];
} king_point_ctx;

WFF_INLINE void king_point_setup(const king_params *k, double dt, king_point_ctx *ctx,
                                 const wff_point_block *blk)
{
    (void)blk;
    ctx->flow = king_flow(k, dt);
    const double inv_cell = 1 / k->cell_area;
    ctx->scale[0] = k->pitch0[0] * inv_cell;
    ctx->scale[1] = k->pitch0[1] * inv_cell;
}

/* Lane b of a point block: one material point with its own F (a quad's Gauss
 * point), king_point_at once, its stress; plain scalars once inlined. */
WFF_INLINE void king_point_lane(const king_params *k, const king_point_ctx *ctx,
                                wff_point_block *blk, double flag[WFF_BLOCK], int b)
{
    (void)flag;
    const double F[6] = {blk->F[0][b], blk->F[1][b], blk->F[2][b],
                         blk->F[3][b], blk->F[4][b], blk->F[5][b]};
    wff_yarn_frame fr;
    blk->degenerate[b] = wff_yarn_kinematics(k->pitch0, F, &fr) != WFF_POINT_OK;
    const double dA[2] = {blk->dA[0][b], blk->dA[1][b]};
    king_point pt;
    king_point_at(k, &fr, dA, blk->state[STATE_GAMMA_F][b], NULL, NULL, 0, &ctx->flow, 2.0, 1.0,
                  &pt);
    blk->residual[0][b] = pt.residual[0];
    blk->residual[1][b] = pt.residual[1];
    blk->state[STATE_GAMMA_F][b] = pt.gamma_f;
    double stress[6];
    wff_stress_from_q(&fr, pt.q, ctx->scale, stress);
#pragma GCC unroll 6
    for (int i = 0; i < 6; i++)
        blk->stress[i][b] = stress[i];
    const double inv_cell = 1 / k->cell_area;
    blk->energy[b] = pt.energy * inv_cell;
    blk->dissipated[b] = pt.dissipated * inv_cell;
    blk->failure_dissipated[b] = 0;
    blk->slip_dissipated[b] = 0;
}

/* Lane b of a tangent block: king_residual_tangent_at with c = 2. */
WFF_INLINE void king_tangent_lane(const king_params *k, const wff_lane_arg *ctx,
                                  wff_tangent_block *blk, double flag[WFF_BLOCK], int b)
{
    (void)ctx;
    (void)flag;
    const double F[6] = {blk->F[0][b], blk->F[1][b], blk->F[2][b],
                         blk->F[3][b], blk->F[4][b], blk->F[5][b]};
    const double dA[2] = {blk->dA[0][b], blk->dA[1][b]};
    wff_yarn_frame fr;
    blk->degenerate[b] = wff_yarn_kinematics(k->pitch0, F, &fr) != WFF_POINT_OK;
    double residual[2], tangent[4];
    king_residual_tangent_at(k, &fr, dA, 2.0, NULL, NULL, residual, tangent);
    blk->residual[0][b] = residual[0];
    blk->residual[1][b] = residual[1];
#pragma GCC unroll 4
    for (int i = 0; i < 4; i++)
        blk->tangent[i][b] = tangent[i];
}

/* The blocked ops (cell_lanes.h), each one vectorised loop over the lanes
 * above: king_evaluate_tri_block, king_evaluate_point_block,
 * king_amplitude_tangent_block, king_wave_speeds_block. */
WFF_CELL_TRI_BLOCK(king, king_params, king_blocks_accept, king_tri_ctx, king_tri_setup,
                   king_tri_lane, king_tri_finish)
WFF_CELL_POINT_BLOCK(king, king_params, king_blocks_accept, king_point_ctx, king_point_setup,
                     king_point_lane, wff_lanes_nothing_after)
WFF_CELL_TANGENT_BLOCK(king, king_params, king_tangent_accepts, wff_lane_arg,
                       wff_lanes_keep_arg, king_tangent_lane, wff_lanes_nothing_after)
WFF_CELL_WAVE_BLOCK(king, king_params, king_wave_accepts, wff_lane_arg, wff_lanes_keep_arg,
                    king_wave_lane, wff_lanes_nothing_after)

#endif

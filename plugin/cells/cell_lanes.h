/* wovenff — the blocked lane adapters of the unit cells, written once.
 *
 * A cell file gives its pointwise physics (evaluate, amplitude_tangent,
 * wave_speeds, as always-inlined functions); the ops that take a block of
 * WFF_BLOCK lanes (evaluate_tri_block, evaluate_point_block,
 * amplitude_tangent_block, wave_speeds_block, cell.h) are generated here from
 * them, so every cell gets the vectorised paths and no cell file holds an
 * `omp simd` loop. Each generated op has one shape:
 *
 *   copy the parameters into a local (stores into the block cannot alias it,
 *   so they stay in registers across the lanes);
 *   decline (return −1) if accepts(k) is false: on the parameters only, never
 *   on the block's state (cell.h: a caller asks once per pass);
 *   setup(k, arg, &ctx, blk): what every lane shares (arg is dt, the areal
 *   density or 0), and stores outside the lanes' loop;
 *   #pragma omp simd over the WFF_BLOCK lanes: lane(k, &ctx, blk, flag, b),
 *   an always-inlined function of one lane (its locals plain scalars once
 *   inlined; inside an `omp simd` body they would become per-lane arrays);
 *   flag is a double per lane, a local array of the op's (not in ctx: gcc 12
 *   then left a scalar copy of the baseline's triangle loop), for a lane's
 *   degenerate test as a double (an int in the lane loop makes gcc take 16
 *   lanes for 512-bit vectors, more than the block has) that finish converts;
 *   a lane without one ignores it (dead, it costs nothing);
 *   finish(k, &ctx, flag, blk): what follows the loop.
 *
 * Two ways to get them:
 *   WFF_CELL_LANES(prefix, params_t, evaluate, amplitude_tangent, wave_speeds)
 *       all four ops, prefix##_evaluate_tri_block and friends, with the lanes
 *       generated from the cell's pointwise functions (each with the op's own
 *       signature, `const void *params` first, always inlined): a triangle
 *       lane evaluates its three nodal points at the one F and averages them
 *       (weights 1/3, as the element code's general path), a point lane
 *       evaluates one point. They never decline; params_t must have an int
 *       n_state (the material's states per point). One op alone:
 *       WFF_CELL_GENERATED(OP, prefix, params_t, pointwise), OP one of TRI,
 *       POINT, TANGENT, WAVE (a cell without amplitudes has no tangent).
 *   WFF_CELL_TRI_BLOCK(prefix, params_t, accepts, ctx_t, setup, lane, finish)
 *   (prefix##_evaluate_tri_block) and its siblings below, with lanes of the
 *   cell's own: a faster lane that shares more than the op's signature shows
 *   (king_plain: one frame per triangle, its exponents as constants), with
 *   its own accepts test.
 * A cell may mix them (linear_yarns: its own triangle lane, the generated
 * point and wave lanes). Nothing here allocates or keeps state. */
#ifndef WOVENFF_CELL_LANES_H
#define WOVENFF_CELL_LANES_H

#include "cell_laws.h"

/* ---- the adapters' one shape ------------------------------------------ */

/* int prefix##_evaluate_tri_block(const void *params, double dt, wff_tri_block *blk). */
#define WFF_CELL_TRI_BLOCK(prefix, params_t, accepts, ctx_t, setup, lane, finish)          \
    static int prefix##_evaluate_tri_block(const void *params, double dt,                  \
                                           wff_tri_block *blk)                             \
    {                                                                                      \
        const params_t local = *(const params_t *)params, *k = &local;                     \
        if (!accepts(k))                                                                   \
            return -1;                                                                     \
        ctx_t ctx;                                                                         \
        setup(k, dt, &ctx, blk);                                                           \
        double flag[WFF_BLOCK];                                                            \
        _Pragma("omp simd") for (int b = 0; b < WFF_BLOCK; b++)                            \
            lane(k, &ctx, blk, flag, b);                                                   \
        finish(k, &ctx, flag, blk);                                                        \
        return 0;                                                                          \
    }

/* int prefix##_evaluate_point_block(const void *params, double dt, wff_point_block *blk). */
#define WFF_CELL_POINT_BLOCK(prefix, params_t, accepts, ctx_t, setup, lane, finish)        \
    static int prefix##_evaluate_point_block(const void *params, double dt,                \
                                             wff_point_block *blk)                         \
    {                                                                                      \
        const params_t local = *(const params_t *)params, *k = &local;                     \
        if (!accepts(k))                                                                   \
            return -1;                                                                     \
        ctx_t ctx;                                                                         \
        setup(k, dt, &ctx, blk);                                                           \
        double flag[WFF_BLOCK];                                                            \
        _Pragma("omp simd") for (int b = 0; b < WFF_BLOCK; b++)                            \
            lane(k, &ctx, blk, flag, b);                                                   \
        finish(k, &ctx, flag, blk);                                                        \
        return 0;                                                                          \
    }

/* int prefix##_amplitude_tangent_block(const void *params, wff_tangent_block *blk)
 * (setup's arg is 0). */
#define WFF_CELL_TANGENT_BLOCK(prefix, params_t, accepts, ctx_t, setup, lane, finish)      \
    static int prefix##_amplitude_tangent_block(const void *params,                        \
                                                wff_tangent_block *blk)                    \
    {                                                                                      \
        const params_t local = *(const params_t *)params, *k = &local;                     \
        if (!accepts(k))                                                                   \
            return -1;                                                                     \
        ctx_t ctx;                                                                         \
        setup(k, 0.0, &ctx, blk);                                                          \
        double flag[WFF_BLOCK];                                                            \
        _Pragma("omp simd") for (int b = 0; b < WFF_BLOCK; b++)                            \
            lane(k, &ctx, blk, flag, b);                                                   \
        finish(k, &ctx, flag, blk);                                                        \
        return 0;                                                                          \
    }

/* int prefix##_wave_speeds_block(const void *params, double areal_density,
 * wff_wave_block *blk) (setup's arg is the areal density, kg/m²). */
#define WFF_CELL_WAVE_BLOCK(prefix, params_t, accepts, ctx_t, setup, lane, finish)         \
    static int prefix##_wave_speeds_block(const void *params, double areal_density,        \
                                          wff_wave_block *blk)                             \
    {                                                                                      \
        const params_t local = *(const params_t *)params, *k = &local;                     \
        if (!accepts(k))                                                                   \
            return -1;                                                                     \
        ctx_t ctx;                                                                         \
        setup(k, areal_density, &ctx, blk);                                                \
        double flag[WFF_BLOCK];                                                            \
        _Pragma("omp simd") for (int b = 0; b < WFF_BLOCK; b++)                            \
            lane(k, &ctx, blk, flag, b);                                                   \
        finish(k, &ctx, flag, blk);                                                        \
        return 0;                                                                          \
    }

/* ---- lanes generated from a cell's pointwise functions ------------------ */

/* What a generated lane shares: dt (s) for evaluations, the areal density
 * (kg/m²) for wave speeds, nothing for tangents. */
typedef struct wff_lane_arg {
    double value;
} wff_lane_arg;

WFF_INLINE int wff_lanes_always(const void *k)
{
    (void)k;
    return 1;
}

WFF_INLINE void wff_lanes_keep_arg(const void *k, double arg, wff_lane_arg *ctx,
                                   const void *blk)
{
    (void)k;
    (void)blk;
    ctx->value = arg;
}

WFF_INLINE void wff_lanes_nothing_after(const void *k, const void *ctx,
                                        const double flag[WFF_BLOCK], const void *blk)
{
    (void)k;
    (void)ctx;
    (void)flag;
    (void)blk;
}

/* Lane b's F, 3x2 row-major as evaluate takes it. */
#define WFF_LANE_F(blk, b)                                                                 \
    {(blk)->F[0][b], (blk)->F[1][b], (blk)->F[2][b], (blk)->F[3][b], (blk)->F[4][b],       \
     (blk)->F[5][b]}

/* A triangle lane from evaluate: its three nodal points at the lane's F, each
 * with its amplitudes and states over dt; the mean stress, energy and
 * dissipations (weights 1/3), each point's residual and state; degenerate
 * where any point is. */
#define WFF_CELL_TRI_LANE_FROM_POINT(lane, params_t, evaluate)                             \
    WFF_INLINE void lane(const params_t *k, const wff_lane_arg *ctx, wff_tri_block *blk,   \
                         double flag[WFF_BLOCK], int b)                                    \
    {                                                                                      \
        (void)flag;                                                                        \
        const double F[6] = WFF_LANE_F(blk, b);                                            \
        double stress[6] = {0, 0, 0, 0, 0, 0}, energy = 0, dissipated = 0, released = 0;   \
        double slipped = 0;                                                                \
        int bad = 0;                                                                       \
        for (int p = 0; p < 3; p++) {                                                      \
            const double dA[2] = {blk->dA[p][0][b], blk->dA[p][1][b]};                     \
            double state[WFF_STATE_MAX];                                                   \
            for (int i = 0; i < WFF_STATE_MAX; i++)                                        \
                state[i] = i < k->n_state ? blk->state[p][i][b] : 0.0;                     \
            wff_point_result r;                                                            \
            bad |= evaluate(k, F, dA, state, ctx->value, &r) != WFF_POINT_OK;              \
            for (int i = 0; i < 6; i++)                                                    \
                stress[i] += r.stress[i] / 3;                                              \
            blk->residual[p][0][b] = r.residual[0];                                        \
            blk->residual[p][1][b] = r.residual[1];                                        \
            energy += r.energy / 3;                                                        \
            dissipated += r.dissipated / 3;                                                \
            released += r.failure_dissipated / 3;                                          \
            slipped += r.slip_dissipated / 3;                                              \
            for (int i = 0; i < WFF_STATE_MAX; i++)                                        \
                if (i < k->n_state)                                                        \
                    blk->state[p][i][b] = r.state[i];                                      \
        }                                                                                  \
        for (int i = 0; i < 6; i++)                                                        \
            blk->stress[i][b] = stress[i];                                                 \
        blk->energy[b] = energy;                                                           \
        blk->dissipated[b] = dissipated;                                                   \
        blk->failure_dissipated[b] = released;                                             \
        blk->slip_dissipated[b] = slipped;                                                 \
        blk->degenerate[b] = bad;                                                          \
    }

/* A point lane from evaluate: one point with its own F, amplitudes and states. */
#define WFF_CELL_POINT_LANE_FROM_POINT(lane, params_t, evaluate)                           \
    WFF_INLINE void lane(const params_t *k, const wff_lane_arg *ctx, wff_point_block *blk, \
                         double flag[WFF_BLOCK], int b)                                    \
    {                                                                                      \
        (void)flag;                                                                        \
        const double F[6] = WFF_LANE_F(blk, b);                                            \
        const double dA[2] = {blk->dA[0][b], blk->dA[1][b]};                               \
        double state[WFF_STATE_MAX];                                                       \
        for (int i = 0; i < WFF_STATE_MAX; i++)                                            \
            state[i] = i < k->n_state ? blk->state[i][b] : 0.0;                            \
        wff_point_result r;                                                                \
        blk->degenerate[b] = evaluate(k, F, dA, state, ctx->value, &r) != WFF_POINT_OK;    \
        for (int i = 0; i < 6; i++)                                                        \
            blk->stress[i][b] = r.stress[i];                                               \
        blk->residual[0][b] = r.residual[0];                                               \
        blk->residual[1][b] = r.residual[1];                                               \
        blk->energy[b] = r.energy;                                                         \
        blk->dissipated[b] = r.dissipated;                                                 \
        blk->failure_dissipated[b] = r.failure_dissipated;                                 \
        blk->slip_dissipated[b] = r.slip_dissipated;                                       \
        for (int i = 0; i < WFF_STATE_MAX; i++)                                            \
            if (i < k->n_state)                                                            \
                blk->state[i][b] = r.state[i];                                             \
    }

/* A tangent lane from amplitude_tangent: R and ∂R_k/∂ΔA_m at one point, its
 * state held. */
#define WFF_CELL_TANGENT_LANE_FROM_POINT(lane, params_t, amplitude_tangent)                \
    WFF_INLINE void lane(const params_t *k, const wff_lane_arg *ctx,                       \
                         wff_tangent_block *blk, double flag[WFF_BLOCK], int b)            \
    {                                                                                      \
        (void)ctx;                                                                         \
        (void)flag;                                                                        \
        const double F[6] = WFF_LANE_F(blk, b);                                            \
        const double dA[2] = {blk->dA[0][b], blk->dA[1][b]};                               \
        double state[WFF_STATE_MAX], residual[2], tangent[4];                              \
        for (int i = 0; i < WFF_STATE_MAX; i++)                                            \
            state[i] = i < k->n_state ? blk->state[i][b] : 0.0;                            \
        blk->degenerate[b] =                                                               \
            amplitude_tangent(k, F, dA, state, residual, tangent) != WFF_POINT_OK;         \
        blk->residual[0][b] = residual[0];                                                 \
        blk->residual[1][b] = residual[1];                                                 \
        for (int i = 0; i < 4; i++)                                                        \
            blk->tangent[i][b] = tangent[i];                                               \
    }

/* A wave lane from wave_speeds. */
#define WFF_CELL_WAVE_LANE_FROM_POINT(lane, params_t, wave_speeds)                         \
    WFF_INLINE void lane(const params_t *k, const wff_lane_arg *ctx, wff_wave_block *blk,  \
                         double flag[WFF_BLOCK], int b)                                    \
    {                                                                                      \
        (void)flag;                                                                        \
        const double F[6] = WFF_LANE_F(blk, b);                                            \
        const double dA[2] = {blk->dA[0][b], blk->dA[1][b]};                               \
        double speed, omega;                                                               \
        wave_speeds(k, ctx->value, F, dA, &speed, &omega);                                 \
        blk->membrane_speed[b] = speed;                                                    \
        blk->amplitude_omega[b] = omega;                                                   \
    }

/* One generated op from the cell's pointwise function: OP is TRI, POINT,
 * TANGENT or WAVE; defines the lane prefix##_OP_lane_generated and the op. */
#define WFF_CELL_GENERATED(OP, prefix, params_t, pointwise)                                \
    WFF_CELL_##OP##_LANE_FROM_POINT(prefix##_##OP##_lane_generated, params_t, pointwise)   \
    WFF_CELL_##OP##_BLOCK(prefix, params_t, wff_lanes_always, wff_lane_arg,                \
                          wff_lanes_keep_arg, prefix##_##OP##_lane_generated,              \
                          wff_lanes_nothing_after)

/* Every blocked op of a cell from its pointwise functions:
 * prefix##_evaluate_tri_block, prefix##_evaluate_point_block,
 * prefix##_amplitude_tangent_block, prefix##_wave_speeds_block. */
#define WFF_CELL_LANES(prefix, params_t, evaluate, amplitude_tangent, wave_speeds)         \
    WFF_CELL_GENERATED(TRI, prefix, params_t, evaluate)                                    \
    WFF_CELL_GENERATED(POINT, prefix, params_t, evaluate)                                  \
    WFF_CELL_GENERATED(TANGENT, prefix, params_t, amplitude_tangent)                       \
    WFF_CELL_GENERATED(WAVE, prefix, params_t, wave_speeds)

#endif

/* The backing block through the model (plugin/backing.c, backing_contact.c):
 * a free 4 cm square ply (no clamp, no projectile) thrown at 20 m/s onto a
 * clay block 2 cm deep.
 *   - Momentum along z: the ply's and the block's together with the impulse
 *     the block's bottom (the only face held along z) took stay the ply's
 *     initial momentum, to round-off; the ply loses most of its own.
 *   - Energy: the model's balance (its term the block's intake and its own
 *     account) within 0.5 % of the energy given; the contact's loss >= 0;
 *     the block holds kinetic, stored and dissipated energy.
 *   - Settings refused with their names: a law other than 0, 1, 2; a
 *     backing setting after the run started; the values exist. */
#include "check.h"
#include "test_meshes.h"
#include "wovenff/backing.h"
#include "backing.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"

static double value(wff_model *m, const char *key)
{
    double v = NAN;
    wff_error err;
    wff_model_value(m, key, &v, &err);
    return v;
}

/* Σ m v_z of the ply and of the block (half-step velocities). */
static void momentum(const wff_model *m, double *ply, double *block)
{
    *ply = 0;
    for (int n = 0; n < m->n_nodes; n++)
        *ply += m->mass[D * n + WFF_UZ] * m->v[D * n + WFF_UZ];
    const wff_block *b = &m->backing->block;
    *block = 0;
    for (int n = 0; n < b->n_nodes; n++)
        *block += b->mass[3 * n + 2] * b->v[3 * n + 2];
}

int main(void)
{
    check_state st = {0, 0};
    wff_model m;
    wff_error err;
    const test_rect r = {0, 0.04, 0, 0.04, 8, 8, TEST_MESH_TRI, 1, 0, 0};
    if (test_model_rect(&m, &r, KEVLAR, &err)) {
        CHECK(&st, 0, "model: %s", err.message);
        return check_summary(&st, "test_backing");
    }
    CHECK(&st, wff_model_set_option(&m, "backing", 3, &err) != 0 && strstr(err.message, "backing"),
          "backing = 3 refused naming it: %s", err.message);
    CHECK(&st, wff_model_set_option(&m, "backing_depth", 0.02, &err) == 0 &&
                   wff_model_set_option(&m, "backing_element", 2e-3, &err) == 0 &&
                   wff_model_set_option(&m, "backing", 1, &err) == 0,
          "backing settings: %s", err.message);
    const double speed = 20;
    for (int n = 0; n < m.n_nodes; n++)
        m.v[D * n + WFF_UZ] = speed;
    double ply0 = 0;
    for (int n = 0; n < m.n_nodes; n++)
        ply0 += m.mass[D * n + WFF_UZ] * speed;
    const double given = 0.5 * ply0 * speed;
    /* to 40 µs, a step at a time: the impulse the box's bottom (the only face held
     * along z) takes, Σ f_z Δt_mid over its nodes (what the held DOFs' forces
     * would have given them), is the momentum the rest loses to it */
    double bottom = 0;
    while (m.time < 4e-5) {
        if (wff_model_advance(&m, 4e-5, 1, &err)) {
            CHECK(&st, 0, "advance: %s", err.message);
            wff_model_free(&m);
            return check_summary(&st, "test_backing");
        }
        const wff_block *b = &m.backing->block;
        for (int j = 0; j <= b->n[1]; j++)
            for (int i = 0; i <= b->n[0]; i++)
                bottom += b->f[3 * wff_block_node(b, i, j, b->n[2]) + 2] * m.dt_mid;
    }
    double ply, block;
    momentum(&m, &ply, &block);
    printf("momentum along z: ply %.6g -> %.6g kg m/s, block %.6g, the bottom's %.3g, the sum "
           "off by %.2e of the start; energy: given %.4g J, block kinetic %.4g stored %.4g "
           "dissipated %.4g, contact loss %.4g J\n", ply0, ply, block, -bottom, (ply + block + bottom - ply0) / ply0, given, value(&m, "backing_kinetic"), value(&m, "backing_stored"),
           value(&m, "backing_dissipated"), value(&m, "backing_contact_loss"));
    CHECK_CLOSE(&st, ply + block + bottom, ply0, 1e-10, 0,
                "momentum along z, ply + block + the bottom's impulse");
    CHECK(&st, ply < 0.5 * ply0, "the ply kept %g of its momentum", ply / ply0);
    wff_energies e;
    wff_model_energies(&m, &e);
    CHECK(&st, fabs(e.error) * e.reference < 5e-3 * given, "energy error %g J of %g J given",
          e.error * e.reference, given);
    CHECK(&st, value(&m, "backing_contact_loss") > -1e-6 * given, "the contact created %g J",
          -value(&m, "backing_contact_loss"));
    CHECK(&st, value(&m, "backing_kinetic") > 0 && value(&m, "backing_stored") > 0 &&
                   value(&m, "backing_dissipated") > 0, "the block holds no energy");
    CHECK(&st, value(&m, "backface_signature") > 0 && value(&m, "crater_volume") > 0,
          "no indentation");
    CHECK(&st, wff_model_set_option(&m, "backing_depth", 0.05, &err) != 0 &&
                   strstr(err.message, "started"), "a setting after the start: %s", err.message);
    wff_model_free(&m);
    return check_summary(&st, "test_backing");
}

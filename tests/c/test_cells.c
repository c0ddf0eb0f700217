/* Every registered unit cell through the same consistency suite.
 * A new cell: add one line to `cases`. */
#include "cell_suite.h"
#include "wovenff/material.h"

#include <string.h>

static const cell_case cases[] = {
    /* material file                               equal-family twin                 ΔA range  W-exact */
    {"freefem_scripts/materials/kevlar_s706.txt", "tests/data/king_symmetric.txt", 30e-6, 1},
    {"tests/data/king_tension_only.txt",          NULL,                            30e-6, 1},
    {"tests/data/king_flow_n3.txt",               NULL,                            30e-6, 1},
    {"tests/data/king_lever.txt",                 NULL,                            30e-6, 0},
    {"tests/data/king_slip.txt",                  NULL,                            30e-6, 1},
    {"tests/data/king_slip_tension_only.txt",     NULL,                            30e-6, 1},
    {"tests/data/king_slip_failure.txt",          NULL,                            30e-6, 1},
    {"tests/data/king_cutting.txt",               NULL,                            30e-6, 1},
    {"freefem_scripts/materials/kevlar_basket.txt", "tests/data/basket_symmetric.txt", 30e-6, 1},
    {"freefem_scripts/materials/kevlar_linear.txt", "tests/data/linear_symmetric.txt", 0, 1},
};

int main(void)
{
    check_state st = {0, 0};
    int n = (int)(sizeof cases / sizeof cases[0]);
    for (int i = 0; i < n; i++)
        cell_suite_run(&st, &cases[i]);
    /* every registered cell has at least one case */
    for (int c = 0; c < wff_cell_count(); c++) {
        int covered = 0;
        for (int i = 0; i < n; i++) {
            wff_material m;
            wff_error e;
            if (wff_material_load(cases[i].material, &m, &e) == 0 && m.cell == wff_cell_at(c))
                covered = 1;
        }
        CHECK(&st, covered, "registered cell '%s' has no case in test_cells.c",
              wff_cell_at(c)->name);
    }
    return check_summary(&st, "test_cells");
}

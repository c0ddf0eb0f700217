/* registry.c: the cell registry: the linker gathers every WFF_REGISTER_CELL
 * entry into the section "wff_cells" and provides its bounds. Constant data
 * only; names no cell (a new cell registers itself in its own file). */
#include "wovenff/cell.h"

#include <string.h>

extern const wff_cell_type *const __start_wff_cells[] __attribute__((weak));
extern const wff_cell_type *const __stop_wff_cells[] __attribute__((weak));

int wff_cell_count(void)
{
    if (!__start_wff_cells || !__stop_wff_cells)
        return 0;
    return (int)(__stop_wff_cells - __start_wff_cells);
}

const wff_cell_type *wff_cell_at(int index)
{
    if (index < 0 || index >= wff_cell_count())
        return NULL;
    return __start_wff_cells[index];
}

const wff_cell_type *wff_cell_find(const char *name)
{
    for (int i = 0; i < wff_cell_count(); i++)
        if (strcmp(wff_cell_name(__start_wff_cells[i]), name) == 0)
            return __start_wff_cells[i];
    return NULL;
}

/* The cell suite catches a cell that breaks cell.h's contract: the King cell
 * wrapped in an ops table whose wave speeds are 5 times too low (its stable
 * step 5 times too long) fails the suite, with a message saying the
 * stable-step bound is not an upper bound, while the King cell itself passes.
 * The wrapped table is built here and never registered (WFF_REGISTER_CELL
 * would put it into every test binary's registry). */
#include "cell_suite.h"
#include "wovenff/material.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define KEVLAR "freefem_scripts/materials/kevlar_s706.txt"
#define WAVE_SPEED_ERROR 5.0

/* king_plain's wave_speeds, divided by WAVE_SPEED_ERROR. */
static void slow_wave_speeds(const void *params, double areal_density, const double F[6],
                             const double dA[2], double *membrane_speed, double *amplitude_omega)
{
    wff_cell_find("king_plain")->wave_speeds(params, areal_density, F, dA, membrane_speed,
                                             amplitude_omega);
    *membrane_speed /= WAVE_SPEED_ERROR;
    *amplitude_omega /= WAVE_SPEED_ERROR;
}

/* The whole suite, or its stable-step checks alone; returns the failures. */
static int whole_suite(check_state *st, const cell_case *c, const wff_material *mat)
{
    cell_suite_check(st, c, mat);
    return st->failures;
}

static int stable_step_only(check_state *st, const cell_case *c, const wff_material *mat)
{
    return cell_suite_stable_step(st, mat, c->material);
}

/* Runs `run` on mat with its own check_state, stderr (where CHECK reports)
 * caught into text and shown on stdout as expected output; returns the
 * failures. */
static int caught_failures(int (*run)(check_state *, const cell_case *, const wff_material *),
                           const cell_case *c, const wff_material *mat, char *text, size_t size)
{
    check_state inner = {0, 0};
    FILE *caught = tmpfile();
    int saved = dup(2);
    if (!caught || saved < 0)
        return -1;
    fflush(stderr);
    dup2(fileno(caught), 2);
    int failures = run(&inner, c, mat);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    rewind(caught);
    size_t n = fread(text, 1, size - 1, caught);
    text[n] = '\0';
    fclose(caught);
    for (char *line = text; *line;) {
        char *end = strchr(line, '\n');
        int len = end ? (int)(end - line) : (int)strlen(line);
        printf("  (expected) %.*s\n", len, line);
        line += len + (end != NULL);
    }
    return failures;
}

int main(void)
{
    check_state st = {0, 0};
    const wff_cell_type *king = wff_cell_find("king_plain");
    CHECK(&st, king != NULL, "king_plain is registered");
    if (!king)
        return check_summary(&st, "test_cell_contract");
    wff_material mat;
    wff_error err;
    int rc = wff_material_load(KEVLAR, &mat, &err);
    CHECK(&st, rc == 0, "%s", err.message);
    if (rc)
        return check_summary(&st, "test_cell_contract");
    static char text[1 << 16];

    /* the King cell as registered passes */
    const cell_case honest = {KEVLAR, NULL, 30e-6, 1};
    int failures = caught_failures(whole_suite, &honest, &mat, text, sizeof text);
    CHECK(&st, failures == 0, "king_plain fails the suite %d times:\n%s", failures, text);

    /* wave speeds 5x too low: the suite fails, naming the stable-step bound */
    wff_cell_type slow = *king;
    slow.name = "king_plain_slow_waves";
    slow.wave_speeds = slow_wave_speeds;
    slow.wave_speeds_block = NULL; /* cell.h: a table that replaces wave_speeds clears it */
    mat.cell = &slow;
    const cell_case wrong = {"king_plain with wave speeds / 5", NULL, 30e-6, 1};
    failures = caught_failures(whole_suite, &wrong, &mat, text, sizeof text);
    CHECK(&st, failures > 0, "the suite passes a cell whose wave speeds are 5x too low");
    CHECK(&st, strstr(text, "stable-step bound is not an upper bound") != NULL,
          "the suite's message does not name the stable-step bound:\n%s", text);
    /* and only the stable-step checks fail (membrane and amplitude waves) */
    int step_failures = caught_failures(stable_step_only, &wrong, &mat, text, sizeof text);
    CHECK(&st, step_failures == failures && step_failures == 2,
          "%d stable-step failures of %d in all (want 2 and 2)", step_failures, failures);
    return check_summary(&st, "test_cell_contract");
}

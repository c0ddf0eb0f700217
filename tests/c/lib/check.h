/* Minimal checks for wovenff's C tests: print only on mismatch, count
 * failures, and end with check_summary() as the program's exit status. */
#ifndef WFF_TEST_CHECK_H
#define WFF_TEST_CHECK_H

#include <stdio.h>
#include <math.h>

typedef struct check_state { int checks, failures; } check_state;

#define CHECK(st, cond, ...)                                                   \
    do {                                                                       \
        (st)->checks++;                                                        \
        if (!(cond)) {                                                         \
            (st)->failures++;                                                  \
            fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                      \
            fputc('\n', stderr);                                               \
        }                                                                      \
    } while (0)

/* |a - b| <= tol * max(|b|, floor) */
#define CHECK_CLOSE(st, a, b, tol, floor_, what)                               \
    do {                                                                       \
        double a_ = (a), b_ = (b);                                             \
        double s_ = fabs(b_) > (floor_) ? fabs(b_) : (floor_);                 \
        CHECK(st, fabs(a_ - b_) <= (tol) * s_, "%s: got %.12g, want %.12g (tol %g)", \
              what, a_, b_, (double)(tol));                                    \
    } while (0)

static inline int check_summary(const check_state *st, const char *name)
{
    printf("%s: %d checks, %d failed\n", name, st->checks, st->failures);
    return st->failures ? 1 : 0;
}

#endif

/* Order-free sums (include/wovenff/fixed_sum.h): the sum of the same terms in
 * any order and any split into parts merged has the same bits; it is within
 * its quantum per term of the exact sum; non-finite and out-of-range (past
 * 2^95) terms mark it. */
#include "check.h"
#include "rng.h"
#include "wovenff/fixed_sum.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N 20000

int main(void)
{
    check_state st = {0, 0};
    static double x[N];
    static int order[N];
    wff_rng rng = {26};
    for (int i = 0; i < N; i++) {
        /* magnitudes from 1e-25 to 1e5, both signs */
        double magnitude = pow(10, -25 + 30 * wff_rng_uniform(&rng, 0, 1));
        x[i] = (wff_rng_uniform(&rng, 0, 1) < 0.5 ? -1 : 1) * magnitude * (1 + wff_rng_uniform(&rng, 0, 1));
        order[i] = i;
    }
    wff_fixed forward = wff_fixed_zero();
    long double exact = 0;
    for (int i = 0; i < N; i++) {
        wff_fixed_add(&forward, x[i]);
        exact += x[i];
    }
    /* shuffled, and split into 7 parts merged in another order */
    for (int trial = 0; trial < 5; trial++) {
        for (int i = N - 1; i > 0; i--) {
            int j = (int)(wff_rng_uniform(&rng, 0, 1) * (i + 1));
            int t = order[i];
            order[i] = order[j], order[j] = t;
        }
        wff_fixed part[7];
        for (int p = 0; p < 7; p++)
            part[p] = wff_fixed_zero();
        for (int i = 0; i < N; i++)
            wff_fixed_add(&part[(i * 7) / N], x[order[i]]);
        wff_fixed merged = wff_fixed_zero();
        for (int p = 6; p >= 0; p--)
            wff_fixed_merge(&merged, &part[p]);
        CHECK(&st, memcmp(&merged.v, &forward.v, sizeof merged.v) == 0 && merged.coarse == forward.coarse && !merged.bad,
              "trial %d: the shuffled, split sum differs", trial);
    }
    /* a double sum in another order does differ (the check checks something) */
    double plain = 0, reversed = 0;
    for (int i = 0; i < N; i++)
        plain += x[i], reversed += x[N - 1 - i];
    CHECK(&st, plain != reversed, "the double sums agree in both orders: pick other terms");
    const double quantum = ldexp(1, -WFF_FIXED_SHIFT), value = wff_fixed_value(&forward);
    const double error = fabs(value - (double)exact);
    printf("  %d terms: fixed %.17g, long double %.17Lg, difference %.3g (quantum %.3g); double "
           "sums %.17g, %.17g\n", N, value, exact, error, quantum, plain, reversed);
    CHECK(&st, error <= 0.5 * N * quantum + 2e-16 * fabs((double)exact),
          "the sum is %g off the exact one", error);
    /* exact terms are exact */
    wff_fixed s = wff_fixed_zero();
    wff_fixed_add(&s, 1.5);
    wff_fixed_add(&s, -0.25);
    wff_fixed_add(&s, 1e-30);
    CHECK(&st, wff_fixed_value(&s) == 1.25, "1.5 - 0.25 + 1e-30 = %.17g", wff_fixed_value(&s));
    /* a subnormal is nothing; a tiny term rounds to its quantum */
    s = wff_fixed_zero();
    wff_fixed_add(&s, 1e-310);
    CHECK(&st, s.v == 0 && !s.bad, "a subnormal term counts");
    /* non-finite and out of range */
    s = wff_fixed_zero();
    wff_fixed_add(&s, 1);
    wff_fixed_add(&s, NAN);
    CHECK(&st, s.bad && isnan(wff_fixed_value(&s)), "a NaN term leaves the sum finite");
    s = wff_fixed_zero();
    wff_fixed_add(&s, -INFINITY);
    CHECK(&st, s.bad, "an infinite term leaves the sum good");
    s = wff_fixed_zero();
    wff_fixed_add(&s, 1e29);
    CHECK(&st, s.bad, "a term past 2^95 leaves the sum good");
    s = wff_fixed_zero();
    wff_fixed_add(&s, 1e25);
    wff_fixed_add(&s, 1e-20);
    CHECK(&st, !s.bad && wff_fixed_value(&s) == 1e25 + 1e-20, "1e25 within the range: %g",
          wff_fixed_value(&s));
    /* a large term's digits below 2^-32 are kept */
    s = wff_fixed_zero();
    wff_fixed_add(&s, 1 + 0x1p-40);
    wff_fixed_add(&s, -1);
    CHECK(&st, wff_fixed_value(&s) == 0x1p-40, "1 + 2^-40 - 1 = %g", wff_fixed_value(&s));
    return check_summary(&st, "test_fixed_sum");
}

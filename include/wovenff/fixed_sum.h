/* fixed_sum.h: sums whose bits do not depend on the order of their terms.
 * Each term is rounded to a fixed-point number of quantum 2^-WFF_FIXED_SHIFT
 * (1.3e-29 in the term's unit) and added as integers: integer addition is
 * associative, so a sum over any split of its terms (threads, ranks) gives
 * the same bits, where a double sum's bits follow its order (issue
 * "Distributed runs": global sums "exact where they enter the state"). Two
 * 128-bit integers hold it: the term rounded to 2^-WFF_FIXED_COARSE (range
 * 2^(127 - WFF_FIXED_COARSE) = 2^95, 4e28) and what is left of it (below
 * 2^-WFF_FIXED_COARSE, exact in a double) rounded to the quantum. A term past
 * the range, or not finite, marks the sum (wff_fixed.bad) and its value is
 * NaN, as a double sum would be. Header only (inline): the per-step passes
 * call it per node or per block of elements. */
#ifndef WFF_FIXED_SUM_H
#define WFF_FIXED_SUM_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define WFF_FIXED_SHIFT 96
#define WFF_FIXED_COARSE 32

typedef struct wff_fixed {
    __int128 coarse; /* the terms rounded to 2^-WFF_FIXED_COARSE, × 2^WFF_FIXED_COARSE */
    __int128 v;      /* what is left of them, × 2^WFF_FIXED_SHIFT */
    int bad;         /* 1 once a term was not finite or out of range */
} wff_fixed;

static inline wff_fixed wff_fixed_zero(void)
{
    wff_fixed s = {0, 0, 0};
    return s;
}

/* x rounded to 2^-shift, × 2^shift, as an integer (ties away from zero); *bad
 * set for a non-finite x or one past 2^(126 - shift). From the bits of the
 * double: no library call, no rounding mode. */
static inline __int128 wff_fixed_scaled(double x, int shift_by, int *bad)
{
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    const int exponent = (int)((bits >> 52) & 0x7ff);
    if (exponent == 0x7ff) { /* inf or NaN */
        *bad = 1;
        return 0;
    }
    if (exponent == 0) /* zero or subnormal: far below the quantum */
        return 0;
    const uint64_t mantissa = (bits & ((UINT64_C(1) << 52) - 1)) | (UINT64_C(1) << 52);
    /* x = mantissa 2^(exponent - 1075); × 2^shift_by: shift mantissa by this */
    const int shift = exponent - 1075 + shift_by;
    __int128 q;
    if (shift >= 0) {
        if (shift > 126 - 53) { /* past the range */
            *bad = 1;
            return 0;
        }
        q = (__int128)mantissa << shift;
    } else if (shift > -54) {
        const uint64_t half = UINT64_C(1) << (-shift - 1);
        q = (__int128)((mantissa + half) >> -shift);
    } else {
        q = 0;
    }
    return (bits >> 63) ? -q : q;
}

static inline void wff_fixed_add(wff_fixed *s, double x)
{
    const __int128 coarse = wff_fixed_scaled(x, WFF_FIXED_COARSE, &s->bad);
    s->coarse += coarse;
    /* the rest, exact: x and its coarse part are multiples of x's last digit */
    const double rest = x - ldexp((double)coarse, -WFF_FIXED_COARSE);
    s->v += wff_fixed_scaled(rest, WFF_FIXED_SHIFT, &s->bad);
}

static inline void wff_fixed_merge(wff_fixed *s, const wff_fixed *t)
{
    s->coarse += t->coarse;
    s->v += t->v;
    s->bad |= t->bad;
}

/* The sum as a double (its two parts' values added), NaN if bad. */
static inline double wff_fixed_value(const wff_fixed *s)
{
    if (s->bad)
        return NAN;
    return ldexp((double)s->coarse, -WFF_FIXED_COARSE) + ldexp((double)s->v, -WFF_FIXED_SHIFT);
}

#endif

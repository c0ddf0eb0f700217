/* fixed_sum.h: sums whose bits do not depend on the order of their terms.
 * Each term is rounded to a fixed-point number of quantum 2^-WFF_FIXED_SHIFT
 * (8e-30 in the term's unit) and added as a 128-bit integer: integer addition
 * is associative, so a sum over any split of its terms (threads, ranks) gives
 * the same bits, where a double sum's bits follow its order (issue
 * "Distributed runs": global sums "exact where they enter the state"). Range:
 * a sum's magnitude below 2^(127 - WFF_FIXED_SHIFT) = 2^31 (2.1e9 J, N, ...); a
 * term past it, or not finite, marks the sum (wff_fixed.bad) and its value is
 * NaN, as a double sum would be. Header only (inline): the per-step passes
 * call it per node or per block of elements. */
#ifndef WFF_FIXED_SUM_H
#define WFF_FIXED_SUM_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define WFF_FIXED_SHIFT 96

typedef struct wff_fixed {
    __int128 v; /* the sum × 2^WFF_FIXED_SHIFT */
    int bad;    /* 1 once a term was not finite or out of range */
} wff_fixed;

static inline wff_fixed wff_fixed_zero(void)
{
    wff_fixed s = {0, 0};
    return s;
}

/* x rounded to the quantum, × 2^WFF_FIXED_SHIFT, as an integer (ties away from
 * zero); *bad set for a non-finite x or one past the range. From the bits of
 * the double: no library call, no rounding mode. */
static inline __int128 wff_fixed_of(double x, int *bad)
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
    /* x = mantissa 2^(exponent - 1075); × 2^SHIFT: shift mantissa by this */
    const int shift = exponent - 1075 + WFF_FIXED_SHIFT;
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
    s->v += wff_fixed_of(x, &s->bad);
}

static inline void wff_fixed_merge(wff_fixed *s, const wff_fixed *t)
{
    s->v += t->v;
    s->bad |= t->bad;
}

/* The sum as a double (the nearest to the fixed-point value), NaN if bad. */
static inline double wff_fixed_value(const wff_fixed *s)
{
    if (s->bad)
        return NAN;
    return ldexp((double)s->v, -WFF_FIXED_SHIFT);
}

#endif

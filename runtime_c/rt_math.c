/*
 * rt_math.c - the rule language's integer math: atan2, hypot, sqrt, sin and
 * cos.  Part of the runtime behind epuckrt.h; see epuckrt.c.
 *
 * No floating point: two small tables and integer operations, so every
 * target (the dsPIC, the AVR proxy, the host) gives the same results, and
 * no operation overflows or is undefined where int is 16 bits.  The checker
 * folds constants with a bit-exact Python model (epuckc/stdlib/imath.py);
 * tests/runtime/test_math.py compares the two over the whole 16-bit domain
 * and both with Python's math.  Conventions and error bounds: docs/runtime.md,
 * "Integer math".
 *
 * sqrt, hypot and atan2 take 32-bit values: a long beyond +-(2^31 - 1)
 * (LONG_MIN on the dsPIC, wider longs on a 64-bit host) counts as
 * +-(2^31 - 1).  sin and cos reduce any long modulo 360 exactly.
 */
#include "rt_internal.h"

#define RT_L32_MAX 2147483647UL

/* |v| as a 32-bit magnitude, at most 2^31 - 1. */
static unsigned long rt_mag32(long v)
{
    unsigned long m = v < 0 ? 0UL - (unsigned long)v : (unsigned long)v;
    return m > RT_L32_MAX ? RT_L32_MAX : m;
}

/* round(sqrt(v)) for v < 2^32: the floor by digits, then up when
 * v - r*r > r, i.e. v >= (r + 1/2)^2 (never a tie for an integer v). */
static unsigned long rt_isqrt32(unsigned long v)
{
    unsigned long root = 0, bit = 1UL << 30;

    while (bit > v)
        bit >>= 2;
    while (bit != 0) {
        if (v >= root + bit) {
            v -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return v > root ? root + 1 : root;   /* v is now the remainder */
}

/* The same for v < 2^63 (hypot beyond the 16-bit range only). */
static unsigned long long rt_isqrt64(unsigned long long v)
{
    unsigned long long root = 0, bit = 1ULL << 62;

    while (bit > v)
        bit >>= 2;
    while (bit != 0) {
        if (v >= root + bit) {
            v -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return v > root ? root + 1 : root;
}

/* sqrt(v) rounded to nearest; 0 for v <= 0.  At most 46341. */
long rt_sqrt(long v)
{
    return v <= 0 ? 0L : (long)rt_isqrt32(rt_mag32(v));
}

/* sqrt(x*x + y*y) rounded to nearest, exact over the whole 32-bit range;
 * a result above 2^31 - 1 (only when an argument is beyond 1.5e9)
 * saturates there. */
long rt_hypot(long x, long y)
{
    unsigned long ax = rt_mag32(x), ay = rt_mag32(y);
    unsigned long long r;

    if (ax <= 46340UL && ay <= 46340UL)   /* the sum fits 32 bits */
        return (long)rt_isqrt32(ax * ax + ay * ay);
    r = rt_isqrt64((unsigned long long)ax * ax + (unsigned long long)ay * ay);
    return r > RT_L32_MAX ? (long)RT_L32_MAX : (long)r;
}

/* ceil(65536 * tan((j + 1/2) deg)), j = 0..44: where the rounded angle of
 * the first octant steps from j to j + 1. */
static const unsigned int rt_tan_half[45] = {
    572, 1717, 2862, 4009, 5158, 6311, 7467, 8628, 9795, 10967,
    12147, 13334, 14529, 15734, 16949, 18175, 19413, 20664, 21929, 23208,
    24503, 25816, 27146, 28496, 29867, 31260, 32676, 34116, 35584, 37079,
    38604, 40161, 41752, 43378, 45042, 46747, 48495, 50288, 52130, 54024,
    55974, 57982, 60053, 62192, 64403
};

/* The angle of (x, y) in whole degrees, counter-clockwise from the positive
 * x axis, rounded to nearest: 0 for (0, 0); the sign of y, so 180 on the
 * negative x axis and -180 just below it.  Arguments beyond 16 bits are
 * halved together until both fit 16 bits (an error under 0.004 deg). */
int rt_atan2(long y, long x)
{
    unsigned long ax = rt_mag32(x), ay = rt_mag32(y), t;
    int lo = 0, hi = 45, mid, a, swapped = 0;

    while (ax > 0xFFFFUL || ay > 0xFFFFUL) {
        ax >>= 1;
        ay >>= 1;
    }
    if (ax == 0 && ay == 0)
        return 0;
    if (ay > ax) {   /* the second octant: 90 - the angle of (y, x) */
        t = ax;
        ax = ay;
        ay = t;
        swapped = 1;
    }
    /* the number of steps j with ay / ax >= tan((j + 1/2) deg) */
    while (lo < hi) {
        mid = (lo + hi) / 2;
        if ((ay << 16) >= (unsigned long)rt_tan_half[mid] * ax)
            lo = mid + 1;
        else
            hi = mid;
    }
    a = swapped ? 90 - lo : lo;
    if (x < 0)
        a = 180 - a;
    return y < 0 ? -a : a;
}

/* round(1000 * sin(d deg)), d = 0..90 */
static const int rt_sin_table[91] = {
    0, 17, 35, 52, 70, 87, 105, 122, 139, 156,
    174, 191, 208, 225, 242, 259, 276, 292, 309, 326,
    342, 358, 375, 391, 407, 423, 438, 454, 469, 485,
    500, 515, 530, 545, 559, 574, 588, 602, 616, 629,
    643, 656, 669, 682, 695, 707, 719, 731, 743, 755,
    766, 777, 788, 799, 809, 819, 829, 839, 848, 857,
    866, 875, 883, 891, 899, 906, 914, 921, 927, 934,
    940, 946, 951, 956, 961, 966, 970, 974, 978, 982,
    985, 988, 990, 993, 995, 996, 998, 999, 999, 1000,
    1000
};

/* deg modulo 360, exactly: 0..359 */
static int rt_deg360(long deg)
{
    int d;

    if (deg >= 0 && deg < 360)
        return (int)deg;
    if (deg >= -32768L && deg <= 32767L) {   /* a 16-bit division where int is 16 bits */
        d = (int)deg % 360;   /* C99: the sign of deg */
        return d < 0 ? d + 360 : d;
    }
    deg %= 360;
    return (int)(deg < 0 ? deg + 360 : deg);
}

static int rt_sin360(int d)
{
    if (d <= 90)
        return rt_sin_table[d];
    if (d <= 180)
        return rt_sin_table[180 - d];
    if (d <= 270)
        return -rt_sin_table[d - 180];
    return -rt_sin_table[360 - d];
}

/* 1000 * sin(deg degrees), rounded to nearest: -1000..1000 */
int rt_sin(long deg)
{
    return rt_sin360(rt_deg360(deg));
}

/* 1000 * cos(deg degrees), rounded to nearest: -1000..1000 */
int rt_cos(long deg)
{
    int d = rt_deg360(deg) + 90;

    return rt_sin360(d >= 360 ? d - 360 : d);
}

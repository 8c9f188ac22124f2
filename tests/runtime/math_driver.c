/*
 * math_driver.c - runs rt_math.c over the domains tests/runtime/test_math.py
 * checks against the Python model (epuckc/stdlib/imath.py), and prints one
 * line per call in hex ("s DEG R", "c DEG R", "q V R", "h X Y R",
 * "a Y X R").  Built for the host (putchar) and for the AVR (-DMATH_AVR:
 * bytes to GPIOR0, read by bench/avr/simavr_cycles.c, which also prints the
 * cycles between a write of 1 and of 2 to GPIOR1: "C NAME ARGS CYCLES").
 */
#include "rt_internal.h"

#ifdef MATH_AVR
#include <avr/io.h>
#include <avr/interrupt.h>
#include <avr/sleep.h>
#define PUT(c) (GPIOR0 = (unsigned char)(c))
#define MARK(v) (GPIOR1 = (v))
#else
#include <stdio.h>
#define PUT(c) putchar(c)
#define MARK(v) ((void)0)
#endif

static void put_hex(long v)
{
    unsigned long m = v < 0 ? 0UL - (unsigned long)v : (unsigned long)v;
    char digits[16];
    int n = 0;

    PUT(' ');
    if (v < 0)
        PUT('-');
    do {
        digits[n++] = "0123456789abcdef"[m & 15u];
        m >>= 4;
    } while (m != 0);
    while (n > 0)
        PUT(digits[--n]);
}

static void line(char f, long a, long b, int two, long r)
{
    PUT(f);
    put_hex(a);
    if (two)
        put_hex(b);
    put_hex(r);
    PUT('\n');
}

#define L32_MIN (-2147483647L - 1)
static const long edges[] = {
    0, 1, -1, 2, -2, 3, 45, -45, 90, 180, -180, 359, 360, -360, 32767, -32768,
    32768, -32769, 46340, 46341, -46341, 65535, 65536, -65536, 100000, -100000,
    359999L, -359999L, 1000000007L, -1000000007L, 1518500249L, 1518500250L,
    2147483646L, 2147483647L, -2147483647L, L32_MIN
};
#define N_EDGES (sizeof edges / sizeof edges[0])

static long grid(unsigned i)   /* the hypot and atan2 grid: edges, then a step */
{
    return i < N_EDGES ? edges[i] : -32768L + 331L * (long)(i - N_EDGES);
}
#define N_GRID (N_EDGES + 199u)

volatile long va, vb;   /* the cycle measurements' arguments, not folded */
volatile long vr;

#define CYCLES(name, call) do { \
        PUT('C'); PUT(' '); { const char *p_ = name; while (*p_) PUT(*p_++); } \
        put_hex(va); put_hex(vb); \
        MARK(1); vr = (call); MARK(2); PUT('\n'); \
    } while (0)

static void cycles(void)
{
    static const long args[][2] = {
        {45, 0}, {-1000, 0}, {1000000L, 0}, {1000, 0}, {2000000000L, 0},
        {3000, 4000}, {-32768, 32767}, {100000L, 200000L}, {300, -400}, {7, 100000L}
    };
    unsigned i;

    for (i = 0; i < sizeof args / sizeof args[0]; i++) {
        va = args[i][0];
        vb = args[i][1];
        CYCLES("sin", rt_sin(va));
        CYCLES("cos", rt_cos(va));
        CYCLES("sqrt", rt_sqrt(va));
        CYCLES("hypot", rt_hypot(va, vb));
        CYCLES("atan2", rt_atan2(va, vb));
    }
}

int main(void)
{
    long v;
    unsigned i, j;
    long r;

    cycles();
    for (v = -32768L; v <= 32767L; v++) {
        line('s', v, 0, 0, rt_sin(v));
        line('c', v, 0, 0, rt_cos(v));
        line('q', v, 0, 0, rt_sqrt(v));
    }
    for (i = 0; i < N_EDGES; i++) {
        line('s', edges[i], 0, 0, rt_sin(edges[i]));
        line('c', edges[i], 0, 0, rt_cos(edges[i]));
        line('q', edges[i], 0, 0, rt_sqrt(edges[i]));
    }
    for (r = 0; r <= 46340L; r += (r < 46300L ? 97 : 1)) {   /* around r*r and (r + 1/2)^2 */
        for (j = 0; j < 4; j++) {
            v = r * r + (j == 0 ? -1 : j == 1 ? 0 : j == 2 ? r : r + 1);
            if (v >= 0)
                line('q', v, 0, 0, rt_sqrt(v));
        }
    }
    for (i = 0; i < N_GRID; i++)
        for (j = 0; j < N_GRID; j++) {
            line('h', grid(i), grid(j), 1, rt_hypot(grid(i), grid(j)));
            line('a', grid(i), grid(j), 1, rt_atan2(grid(i), grid(j)));
        }
    for (v = -40; v <= 40; v++)   /* every small direction */
        for (r = -40; r <= 40; r++) {
            line('h', v, r, 1, rt_hypot(v, r));
            line('a', v, r, 1, rt_atan2(v, r));
        }
#ifdef MATH_AVR
    cli();
    sleep_cpu();
    for (;;) {
    }
#endif
    return 0;
}

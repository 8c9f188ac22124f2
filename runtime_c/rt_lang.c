/*
 * rt_lang.c - what the rule language's expressions compile to: saturating
 * arithmetic, the robot's readings (once per poll), random numbers,
 * variables with their trace, and the `when`, `every` and `after` events
 * (the odometry is rt_odometry.c).  A layer of the core on rt_registry.c;
 * part of the runtime behind epuckrt.h.
 *
 * Inside an expression values are exact while they fit 32 bits; these
 * operations saturate at -2147483648..2147483647 where they would not (the
 * generated C calls them only there: elsewhere it computes in plain int or
 * long).  long has at least 32 bits on every target and 64 on some hosts,
 * so each result is computed without overflow and then saturated to 32
 * bits explicitly: the same values on the dsPIC, the AVR and the host.
 * A value is stored saturated to 16 bits (rt_sat16).
 */
#include "rt_registry.h"

/* ---- arithmetic ------------------------------------------------------------ */

int rt_sat16(long v)
{
    return v < RT_INT_MIN ? RT_INT_MIN : v > RT_INT_MAX ? RT_INT_MAX : (int)v;
}

static long sat32(long v)
{
    return v < RT_LONG_MIN ? RT_LONG_MIN : v > RT_LONG_MAX ? RT_LONG_MAX : v;
}

long rt_add(long a, long b)
{
    if (b > 0 && a > RT_LONG_MAX - b)
        return RT_LONG_MAX;
    if (b < 0 && a < RT_LONG_MIN - b)
        return RT_LONG_MIN;
    return sat32(a + b);
}

long rt_sub(long a, long b)
{
    if (b < 0 && a > RT_LONG_MAX + b)
        return RT_LONG_MAX;
    if (b > 0 && a < RT_LONG_MIN + b)
        return RT_LONG_MIN;
    return sat32(a - b);
}

/* |a| * |b| compared with the bound by division, so no product overflows. */
long rt_mul(long a, long b)
{
    unsigned long ua, ub, limit;
    int negative = (a < 0) != (b < 0);
    if (a == 0 || b == 0)
        return 0;
    ua = a < 0 ? 0ul - (unsigned long)a : (unsigned long)a;
    ub = b < 0 ? 0ul - (unsigned long)b : (unsigned long)b;
    limit = negative ? 2147483648ul : 2147483647ul;
    if (ua > limit / ub)
        return negative ? RT_LONG_MIN : RT_LONG_MAX;
    return negative ? -(long)(ua * ub - 1ul) - 1 : (long)(ua * ub);
}

/* C99 division truncates towards zero, as the language's does. */
long rt_div(long a, long b)
{
    if (b == 0)
        return 0;
    if (b == -1)
        return rt_neg(a);
    return a / b;
}

long rt_mod(long a, long b)
{
    return b == 0 || b == -1 ? 0 : a % b;
}

long rt_neg(long a)
{
    return a <= RT_LONG_MIN ? RT_LONG_MAX : -a;
}

long rt_abs(long a)
{
    return a < 0 ? rt_neg(a) : a;
}

long rt_min(long a, long b)
{
    return a < b ? a : b;
}

long rt_max(long a, long b)
{
    return a > b ? a : b;
}

long rt_clamp(long x, long lo, long hi)
{
    long v = x < lo ? lo : x;
    return v > hi ? hi : v;
}

/* ---- shifts ------------------------------------------------------------------ */

/* `a << n` and `a >> n` on the 16-bit pattern of a (stdlib/arith.py: shl,
 * shr), defined for every count: a negative one shifts the other way, one
 * of 16 or more leaves no bit (`<<` gives 0, `>>` the sign).  Computed in
 * unsigned and with `~`, so that no shift of a negative int, no overflow
 * and no conversion out of range is left to the C compiler. */
int rt_shl(int a, int n)
{
    unsigned int bits;
    if (n < 0)
        return rt_shr(a, n <= -16 ? 16 : -n);
    if (n >= 16)
        return 0;
    bits = ((unsigned int)a << n) & 0xFFFFu;
    return (bits & 0x8000u) ? -(int)(0xFFFFu - bits) - 1 : (int)bits;
}

int rt_shr(int a, int n)
{
    if (n < 0)
        return rt_shl(a, n <= -16 ? 16 : -n);
    if (n > 15)
        n = 15;
    return a >= 0 ? a >> n : -1 - ((-1 - a) >> n);     /* floor(a / 2^n) */
}

/* ---- arrays ------------------------------------------------------------------ */

int rt_index(long i, int n)
{
    return i < 0 ? 0 : i >= n ? n - 1 : (int)i;
}

int rt_argmin(const long *values, int n)
{
    int k, best = 0;
    for (k = 1; k < n; k++)
        if (values[k] < values[best])
            best = k;
    return best;
}

int rt_argmax(const long *values, int n)
{
    int k, best = 0;
    for (k = 1; k < n; k++)
        if (values[k] > values[best])
            best = k;
    return best;
}

int rt_argmin_int(const int *values, int n)
{
    int k, best = 0;
    for (k = 1; k < n; k++)
        if (values[k] < values[best])
            best = k;
    return best;
}

int rt_argmax_int(const int *values, int n)
{
    int k, best = 0;
    for (k = 1; k < n; k++)
        if (values[k] > values[best])
            best = k;
    return best;
}

/* ---- random numbers: xorshift32, the same sequence on every target ------------ */

static unsigned long rng_state = 1;
static int rng_seeded;

void rt_seed(unsigned long seed)
{
    seed &= 0xFFFFFFFFUL;
    rng_state = seed != 0 ? seed : 0x2545F491UL;
    rng_seeded = 1;
}

static unsigned long rng_next(void)
{
    unsigned long x;

    if (!rng_seeded)
        rt_seed(rt_platform_seed());
    x = rng_state;
    x ^= (x << 13) & 0xFFFFFFFFUL;
    x ^= x >> 17;
    x ^= (x << 5) & 0xFFFFFFFFUL;
    rng_state = x;
    return x;
}

int rt_random(int lo, int hi)
{
    unsigned long span;

    if (hi <= lo)
        return lo;
    span = (unsigned long)((long)hi - lo) + 1UL;     /* 1..65536 */
    return (int)((long)lo + (long)(rng_next() % span));
}

/* ---- readings ------------------------------------------------------------------- */

/* Bit n of valid: reading n was read in this poll; cleared with the
 * proximity readings' at the start of each poll (rt_prox_valid == 0). */
static int ambient[8], mic[3], acc[3], selector;
static unsigned ambient_valid, other_valid;
static unsigned long poll_seen;

static void new_poll(void)
{
    if (poll_seen != rt_poll_count) {
        poll_seen = rt_poll_count;
        ambient_valid = 0;
        other_valid = 0;
    }
}

int rt_ir(int sensor)
{
    unsigned bit;

    if (sensor < 0 || sensor > 7)
        return 0;
    bit = 1u << sensor;     /* read once per poll (rt_read_prox's cache), without its loop */
    if (!(rt_prox_valid & bit)) {
        rt_prox[sensor] = e_get_prox((unsigned)sensor);
        rt_prox_valid |= bit;
    }
    return rt_prox[sensor];
}

const int *rt_proximity(unsigned mask)
{
    rt_read_prox(mask);
    return rt_prox;
}

int rt_ambient(int sensor)
{
    if (sensor < 0 || sensor > 7)
        return 0;
    new_poll();
    if (!(ambient_valid & (1u << sensor))) {
        ambient[sensor] = e_get_ambient_light((unsigned)sensor);
        ambient_valid |= 1u << sensor;
    }
    return ambient[sensor];
}

int rt_mic(int micro)
{
    if (micro < 0 || micro > 2)
        return 0;
    new_poll();
    if (!(other_valid & (1u << micro))) {
        mic[micro] = e_get_micro_volume((unsigned)micro);
        other_valid |= 1u << micro;
    }
    return mic[micro];
}

int rt_acc(int axis)
{
    if (axis < 0 || axis > 2)
        return 0;
    new_poll();
    if (!(other_valid & (8u << axis))) {
        acc[axis] = e_get_acc_filtered((unsigned)axis, 1);    /* raw: see rt_accel_sample */
        other_valid |= 8u << axis;
    }
    return acc[axis];
}

int rt_selector(void)
{
    new_poll();
    if (!(other_valid & 64u)) {
        selector = getselector() & 15;
        other_valid |= 64u;
    }
    return selector;
}

/* ---- variables --------------------------------------------------------------------- */

void rt_assign(int *var, int id, int value)
{
    if (*var == value)
        return;
    *var = value;
    rt_trace_set(id, value);
}

void action_fill(void *param)
{
    const param_fill *p = (const param_fill *)param;
    int k;
    for (k = 0; k < p->count; k++)
        rt_assign(&p->array[k], p->id + k, p->value);
}

#undef name_var
void name_var(int id, const char *name)
{
    rt_name_var(id, name);
}

/* ---- events ------------------------------------------------------------------------ */

void rt_when(void *status, int condition)
{
    event_status *st = (event_status *)status;

    st->occurred = condition && !st->memory;
    st->memory = condition != 0;
}

int rt_occurred(void *status)
{
    return ((event_status *)status)->occurred != 0;
}

void rt_guard(void *status, int guard)
{
    if (guard)
        return;
    ((event_status *)status)->occurred = 0;
    /* a guarded periodic rule lets the motors go at a period whose guard is false */
    if (rt_holds > 0 && rt_polled_event >= 0 && rt_hold_kind(rt_polled_event) == RT_HOLD_GUARD)
        rt_hold_release(rt_polled_event);
}

static void deadline(const param_event_every *p, event_status *st, int again)
{
    long now = rt_millis();

    st->occurred = 0;
    if (p == NULL || p->period <= 0)
        return;
    if (st->memory == 0) {                  /* armed now */
        st->memory = now + p->period + 1;
        return;
    }
    if (now - (st->memory - 1) >= 0) {
        st->occurred = 1;
        /* the next period from the one due, not from now: no drift */
        st->memory = again ? st->memory + p->period : st->memory;
    }
}

void event_every(void *param, void *status)
{
    deadline((const param_event_every *)param, (event_status *)status, 1);
}

void event_after(void *param, void *status)
{
    deadline((const param_event_every *)param, (event_status *)status, 0);
}

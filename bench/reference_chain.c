/*
 * reference_chain.c - the hand-written reference of bench/robot_bench.py:
 * what a C programmer would write for N sensor rules without any runtime,
 * an if-chain with an edge latch per rule.  Each poll reads the eight
 * proximity values once (the e-puck library's e_get_prox, here the host
 * stub's), then for every rule: condition, rising edge, latch.
 *
 * The rules come from chain_rules.h, written by the bench script from the
 * same list as the rule file it compiles with epuckc:
 *     RULE(i, sensor, threshold)     rule i: "ir<sensor> > <threshold>"
 *
 *     cc -O2 -Iruntime_c/epuck_api -Ibench/<dir> bench/reference_chain.c \
 *        runtime_c/host/epuck_stub.c ... -o chain && ./chain POLLS
 *
 * (with the rest of the library's simulation, resources.py's
 * LIBRARY_SIMULATION, whose few calls of its platform it answers: nothing
 * is traced here)
 */
#include <stdlib.h>

#include "a_d/advance_ad_scan/e_ad_conv.h"
#include "a_d/advance_ad_scan/e_prox.h"

#define RULE(i, sensor, threshold) + 1
enum { N_RULES = 0
#include "chain_rules.h"
};
#undef RULE

static unsigned char latch[N_RULES];    /* the condition at the previous poll */
static volatile int fired;              /* the rules' action: count firings */

static void poll(void)
{
    int ir[8], c;
    unsigned n;

    for (n = 0; n < 8; n++)
        ir[n] = e_get_prox(n);
#define RULE(i, sensor, threshold) \
    c = ir[sensor] > (threshold);   \
    if (c && !latch[i])             \
        fired++;                    \
    latch[i] = (unsigned char)c;
#include "chain_rules.h"
#undef RULE
}

int main(int argc, char **argv)
{
    long polls = argc > 1 ? atol(argv[1]) : 1000, k;

    e_init_ad_scan(ALL_ADC);
    for (k = 0; k < polls; k++)
        poll();
    return fired != 0;      /* the readings stay 0: nothing fires */
}

/* what the library's simulation asks of its platform (host/epuck_stub.h) */
void host_record(const char *kind, const char *name, const char *extra, const char *line);
void host_record(const char *kind, const char *name, const char *extra, const char *line)
{
    (void)kind;
    (void)name;
    (void)extra;
    (void)line;
}

void host_stop(const char *kind, const char *name, const char *extra, const char *line,
               int status);
void host_stop(const char *kind, const char *name, const char *extra, const char *line,
               int status)
{
    host_record(kind, name, extra, line);
    exit(status);
}

void stub_unsimulated(const char *function, const char *device);
void stub_unsimulated(const char *function, const char *device)
{
    (void)function;
    (void)device;
    exit(6);
}

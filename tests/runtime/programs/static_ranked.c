/* Static registration with priorities and modes, written by hand: the walk
 * by priority levels over table and dynamic events together (compiled
 * conditions included), table entries' modes, enter_mode re-arming a
 * mode's table events (latches and memories reset) except one cancelled
 * with cancel_event, disarm_event until the mode is entered again, and
 * set_event_priority ignoring table ids; a negative mode is refused.
 * Scenario static_ranked.scn: ir0 0 until 5 ms, then 900. */
#include <stdio.h>
#include "epuckrt.h"

static int visits, kills;

static void begin(void *p)
{
    (void)p;
    start_sensor(NULL);
    set_timer(NULL);
}

static void note(void *p) { (void)p; }

/* enters mode 2 at most twice */
static void to_2(void *p)
{
    (void)p;
    if (++visits <= 2)
        enter_mode(2);
}

/* the first time: event 7 cancelled for good, event 8 disarmed */
static void kill(void *p)
{
    (void)p;
    if (kills++ == 0) {
        cancel_event(7);
        disarm_event(8);
    }
}

static void conditions(const int *ir, unsigned *c)
{
    const int ir0 = ir[0];
    c[0] = 0;
    if (ir0 > 500) c[0] |= (1u << 1) | (1u << 2) | (1u << 5) | (1u << 6);
}

static const param_enter_mode m1 = {1};
static const param_event_timer t20 = {20L};

static const rt_action actions[] = {
    {begin, NULL},              /* 0 */
    {note, NULL},               /* 1 */
    {to_2, NULL},               /* 2 */
    {action_enter_mode, &m1},   /* 3 */
    {kill, NULL},               /* 4 */
    {exit_main, NULL},          /* 5 */
};

/* {function, param, action, flags, memory, priority, mode} */
static const rt_event events[] = {
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},            /* 0 */
    {NULL, NULL, 1, RT_REPEAT, RT_NO_MEMORY, 0, 0},         /* 1: ir0 > 500 */
    {NULL, NULL, 1, RT_REPEAT, RT_NO_MEMORY, 2, 0},         /* 2: ir0 > 500 */
    {event_enter_mode, NULL, 2, 0, 0, 0, 1},                /* 3: enters mode 1 */
    {event_enter_mode, NULL, 4, 0, 1, 0, 2},                /* 4: enters mode 2 */
    {NULL, NULL, 1, RT_REPEAT, RT_NO_MEMORY, 3, 2},         /* 5: ir0 > 500 */
    {NULL, NULL, 3, 0, RT_NO_MEMORY, 1, 2},                 /* 6: ir0 > 500 */
    {immediate, NULL, 1, RT_REPEAT, RT_NO_MEMORY, 2, 2},    /* 7: cancelled */
    {immediate, NULL, 1, RT_REPEAT, RT_NO_MEMORY, 2, 2},    /* 8: disarmed */
    {immediate, NULL, 1, 0, RT_NO_MEMORY, 0, 3},            /* 9: mode 3, never */
    {timer, &t20, 5, 0, 2, 0, 0},                           /* 10 */
};

static unsigned state[RT_STATE_WORDS(6, 11)];
static long memory[3];

int main(void)
{
    static const rt_event bad_mode[] = {{immediate, NULL, 0, 0, RT_NO_MEMORY, 0, -1}};
    rt_program bad = {actions, 6, bad_mode, 1, NULL, 0, state, NULL, NULL};
    rt_program p = {actions, 6, events, 11, conditions, 0x01, state, memory, NULL};
    /* the events by priority, highest first, then id (rt_program.order) */
    static const int order[] = {5, 2, 7, 8, 6, 0, 1, 3, 4, 9, 10};
    static const int ties_reversed[] = {5, 8, 7, 2, 6, 0, 1, 3, 4, 9, 10};
    static const int twice[] = {5, 2, 7, 8, 6, 0, 1, 3, 4, 9, 9};
    int e;

    p.order = ties_reversed;
    printf("bad order %d", register_program(&p));
    p.order = twice;
    printf(" %d\n", register_program(&p));
#ifdef WITH_ORDER
    p.order = order;
#else
    p.order = NULL;
    (void)order;
#endif
    printf("negative mode %d\n", register_program(&bad));
    printf("register %d\n", register_program(&p));
    set_event_priority(1, 9);           /* a table id: its entry's priority counts */
    set_event_mode(1, 3);
    e = register_event(immediate, NULL, 1);
    set_event_priority(e, 5);           /* a dynamic event: before everything */
    printf("dynamic %d\n", e);
    name_mode(1, "one");
    name_mode(2, "two");
    enter_mode(1);
    mainloop();
    return 0;
}

/* Static registration written by hand: register_program's refusals, the
 * ids that follow the tables, compiled conditions (sensors started: read from the
 * next poll), cancel and set_event_repeat on table entries, a timer with
 * memory, more than sixteen events (two words of state), and an event
 * registered by a table action polled in the same walk.
 * Scenario static_table.scn: ir0 900 from the start, 0 at 5 ms, 900 at 8. */
#include <stdio.h>
#include "epuckrt.h"

static int notes;
static void note(void *p) { (void)p; notes++; }
static void register_more(void *p)
{
    (void)p;
    printf("more %d\n", register_event(immediate, NULL, 1));
}

/* events 1 and 17: ir0 > 500 and ir0 > 800; 5..16: ir1 > 100 (never) */
static void conditions(const int *ir, unsigned *c)
{
    const int ir0 = ir[0], ir1 = ir[1];
    int k;
    c[0] = 0;
    c[1] = 0;
    if (ir0 > 500) c[0] |= 1u << 1;
    for (k = 5; k <= 16; k++) {
        if (ir1 > 100) c[k / 16] |= 1u << (k % 16);
    }
    if (ir0 > 800) c[1] |= 1u << 1;
}

static const param_event_timer t10 = {10L}, t30 = {30L};

static const rt_action actions[] = {
    {start_sensor, NULL},       /* 0 */
    {note, NULL},               /* 1 */
    {exit_main, NULL},          /* 2 */
    {register_more, NULL},      /* 3 */
    {note, NULL},               /* 4: cancelled */
};

#define NEVER {NULL, NULL, 1, RT_REPEAT, RT_NO_MEMORY, 0, 0}
static const rt_event events[] = {
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},      /* 0: starts the sensors */
    {NULL, NULL, 1, RT_REPEAT, RT_NO_MEMORY, 0, 0},   /* 1: ir0 > 500 */
    {timer, &t10, 3, 0, 0, 0, 0},                     /* 2 */
    {immediate, NULL, 4, 0, RT_NO_MEMORY, 0, 0},      /* 3: its action cancelled */
    {immediate, NULL, 1, 0, RT_NO_MEMORY, 0, 0},      /* 4: cancelled */
    NEVER, NEVER, NEVER, NEVER, NEVER, NEVER,   /* 5..10 */
    NEVER, NEVER, NEVER, NEVER, NEVER, NEVER,   /* 11..16 */
    {NULL, NULL, 1, 0, RT_NO_MEMORY, 0, 0},           /* 17: ir0 > 800, made repeating */
    {timer, &t30, 2, 0, 1, 0, 0},                     /* 18 */
};

static unsigned state[RT_STATE_WORDS(5, 19)];
static long memory[2];

int main(void)
{
    static rt_event bad_events[1] = {{immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0}};
    static const rt_action bad_action[] = {{NULL, NULL}};
    rt_program p = {actions, 5, events, 19, conditions, 0x03, state, memory, NULL};
    rt_program bad = p;

    printf("refuse %d", register_program(NULL));
    bad.events = bad_events;
    bad.n_events = 1;
    bad_events[0].action_id = 5;
    printf(" %d", register_program(&bad));              /* no action 5 */
    bad_events[0].action_id = 0;
    bad_events[0].event_function = NULL;
    bad.conditions = NULL;
    printf(" %d", register_program(&bad));              /* no conditions */
    bad_events[0].event_function = immediate;
    bad_events[0].memory = 0;
    bad.memory = NULL;
    printf(" %d", register_program(&bad));              /* no memory */
    bad = p;
    bad.actions = bad_action;
    bad.n_actions = 1;
    bad.n_events = 0;
    printf(" %d", register_program(&bad));              /* NULL action */
    bad = p;
    bad.state = NULL;
    printf(" %d\n", register_program(&bad));
    printf("register %d\n", register_program(&p));
    printf("again %d\n", register_program(&p));
    printf("ids %d\n", register_action(note, NULL));   /* after the table's 5 */
    cancel_action(4);
    cancel_event(4);
    set_event_repeat(17, 1);
    name_event(17, "ir0 > 800");
    name_action(1, "note");
    set_timer(NULL);
    fflush(stdout);
    mainloop();
    printf("notes %d\n", notes);
    return 0;
}

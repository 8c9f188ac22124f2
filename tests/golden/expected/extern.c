/*
 * extern.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them, then mainloop().  The actions and events are
 * const tables registered at once (register_program), which the robot keeps
 * in program memory; the rules' sensor conditions are compiled into one
 * function.  Tables: 2 actions, 2 events.
 */
#include "utility.h"
#include "extern_externs.h"

/* extern.epk:6: mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s) */
static const param_mark epk_p1_r1 = {3, 155, 776, 45, 2000L};
/* extern.epk:7: mark(1, 10 steps, 10, 1, 1) */
static const param_mark epk_p1_r2 = {1, 10, 10, 1, 1L};
/* extern.epk:7: elapsed(ms: 250) */
static const param_elapsed epk_when_r2 = {250L};

/* extern.epk:6: mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop */
static void epk_do_r1(void *epk_param)
{
    (void)epk_param;
    mark((void *)&epk_p1_r1);
    noop(NULL);
}

/* extern.epk:7: mark(1, 10 steps, 10, 1, 1), exit_main */
static void epk_do_r2(void *epk_param)
{
    (void)epk_param;
    mark((void *)&epk_p1_r2);
    exit_main(NULL);
}

/* The actions, {function, parameter}: an action's id is its index. */
static const rt_action epk_action_table[] = {
    {epk_do_r1, NULL},   /* 0: extern.epk:6: mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop */
    {epk_do_r2, NULL},   /* 1: extern.epk:7: mark(1, 10 steps, 10, 1, 1), exit_main */
};

/* The events, {function, parameter, action id, flags, memory, priority,
 * mode}: an event's id is its index, by priority, highest first, then in
 * file order (the order mainloop polls them in).  A NULL function is the rule's
 * condition in epk_event_conditions; memory is the event's slot in
 * epk_event_memory (timers keep their last firing); mode 0: in no mode,
 * always armed. */
static const rt_event epk_event_table[] = {
    /* 0: extern.epk:6: on immediate do mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop */
    {immediate, NULL, 0, 0, RT_NO_MEMORY, 0, 0},
    /* 1: extern.epk:7: on elapsed(ms: 250) do mark(1, 10 steps, 10, 1, 1), exit_main */
    {elapsed, &epk_when_r2, 1, 0, 0, 0, 0},
};

/* What changes while the program runs, the only part in RAM. */
static unsigned epk_event_state[RT_STATE_WORDS(2, 2)];
static long epk_event_memory[1];

static const rt_program epk_program = {
    epk_action_table, 2, epk_event_table, 2,
    NULL, 0x00, epk_event_state, epk_event_memory,
    NULL
};

int main(void)
{
    (void)register_program(&epk_program);

    /* Names in the host harness's trace; without them on the robot (EPUCKRT_NO_NAMES). */
    name_action(0, "mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop");
    name_action(1, "mark(1, 10 steps, 10, 1, 1), exit_main");
    name_event(0, "extern.epk:6 on immediate");
    name_event(1, "extern.epk:7 on elapsed(ms: 250)");

    mainloop();
    return 0;
}

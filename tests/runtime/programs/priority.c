/* Priorities: the events of a poll run highest priority first; a motion
 * belongs to the event whose action started it, and motor commands of
 * events of lower priority are suppressed until it ends. */
#include "epuckrt.h"

static param_start_straight slow_long = { 200, 0, 2000 };   /* 10 s */
static param_start_straight fast_short = { 500, 0, 500 };   /* 1 s */
static param_event_timer at_500 = { 500 };
static param_event_timer at_3000 = { 3000 };
static const action steps[] = { { start_straight, &slow_long } };
static param_sequence seq = { steps, 1 };

int main(void)
{
    int a_slow = register_action(start_straight, &slow_long);
    int a_fast = register_action(start_straight, &fast_short);
    int a_stop = register_action(stop_motor, NULL);
    int a_seq = register_action(run_sequence, &seq);
    int a_exit = register_action(exit_main, NULL);
    int e;

    e = register_event(immediate, NULL, a_slow);        /* #0, priority 0 */
    name_event(e, "wander");
    e = register_event(immediate, NULL, a_fast);        /* #1, priority 2: runs first */
    name_event(e, "escape");
    set_event_priority(e, 2);
    e = register_event(timer, &at_500, a_stop);         /* #2: stop, priority 0: suppressed */
    name_event(e, "low stop");
    e = register_event(timer, &at_500, a_seq);          /* #3: sequence, priority 1: suppressed */
    name_event(e, "low sequence");
    set_event_priority(e, 1);
    e = register_event(event_stop_motor, NULL, a_slow); /* #4: after escape's motion: allowed */
    name_event(e, "resume");
    e = register_event(timer, &at_3000, a_stop);        /* #5: equal priority 0: stops wander */
    name_event(e, "equal stop");
    e = register_event(timer, &at_3000, a_exit);        /* #6 */
    set_event_priority(99, 5);                          /* unknown ids are ignored */
    set_event_priority(-1, 5);
    set_timer(NULL);
    mainloop();
    return 0;
}

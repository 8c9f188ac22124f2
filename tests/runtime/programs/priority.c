/* Priorities: the events of a poll run highest priority first; a motion
 * (and a sequence) belongs to the event whose action started it, and the
 * motor commands of events of lower priority are suppressed until it ends;
 * a lower event's sequence runs, but its motor steps are suppressed. */
#include "epuckrt.h"

static param_straight_steps slow_long = { 200, 2000 };      /* 10 s */
static param_straight_steps fast_short = { 500, 500 };      /* 1 s */
static param_straight_steps guard_step = { 500, 100 };      /* 200 ms */
static param_event_timer at_500 = { 500 }, at_2400 = { 2400 }, at_2500 = { 2500 };
static param_event_timer at_3000 = { 3000 };
static const action one[] = { { straight_steps, &slow_long } };
static param_sequence low_seq = { one, 1 };
static const action twice[] = { { straight_steps, &fast_short }, { straight_steps, &fast_short } };
static param_sequence escape_seq = { twice, 2 };

static void add(event_func f, void *param, int action_id, const char *name, int priority,
                  int repeat)
{
    int e = register_event(f, param, action_id);
    name_event(e, name);
    set_event_priority(e, priority);
    set_event_repeat(e, repeat);
}

int main(void)
{
    int a_slow = register_action(straight_steps, &slow_long);
    int a_escape = register_action(run_sequence, &escape_seq);
    int a_guard = register_action(straight_steps, &guard_step);
    int a_stop = register_action(stop_motor, NULL);
    int a_seq = register_action(run_sequence, &low_seq);
    int a_exit = register_action(exit_main, NULL);

    add(immediate, NULL, a_slow, "wander", 0, 0);         /* #0: suppressed */
    add(immediate, NULL, a_escape, "escape", 2, 0);       /* #1: runs first: 2 x 1 s */
    add(timer, &at_500, a_stop, "low stop", 0, 0);        /* #2: suppressed */
    add(timer, &at_500, a_seq, "low sequence", 1, 0);     /* #3: would replace escape's */
    add(event_stop_motor, NULL, a_slow, "resume", 0, 1);  /* #4: after a motion: allowed */
    add(timer, &at_2400, a_guard, "guard", 3, 0);         /* #5: 2400..2600 ms */
    add(timer, &at_2500, a_seq, "late sequence", 0, 0);   /* #6: runs; its straight doesn't */
    add(timer, &at_3000, a_stop, "equal stop", 0, 0);     /* #7: stops resume's drive */
    add(timer, &at_3000, a_exit, "end", 0, 0);            /* #8 */
    set_event_priority(99, 5);                              /* unknown ids are ignored */
    set_event_priority(-1, 5);
    set_timer(NULL);
    mainloop();
    return 0;
}

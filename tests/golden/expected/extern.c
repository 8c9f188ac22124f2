/*
 * extern.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 2 actions, 2 events.
 */
#include "utility.h"

/* Parameters of the extern actions and events, in declared order. */
typedef struct {
    int count;
    int length;
    int pace;
    int turn;
    long wait;
} param_mark;
typedef struct {
    long ms;
} param_after;

/* The user's C, which defines the extern actions and events. */
#include "user/mark.c"
#include "user/after.c"

/* extern.epk:6: mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s) */
static param_mark p1_r1 = {3, 155, 776, 45, 2000L};
/* extern.epk:7: mark(1, 10 steps, 10, 1, 1) */
static param_mark p1_r2 = {1, 10, 10, 1, 1L};
/* extern.epk:7: after(ms: 250) */
static param_after when_r2 = {250L};

/* extern.epk:6: mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop */
static void do_r1(void *param)
{
    (void)param;
    mark(&p1_r1);
    noop(NULL);
}

/* extern.epk:7: mark(1, 10 steps, 10, 1, 1), exit_main */
static void do_r2(void *param)
{
    (void)param;
    mark(&p1_r2);
    exit_main(NULL);
}

int main(void)
{
    int a1, a2;
    int e1, e2;

    /* extern.epk:6: on immediate do mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop */
    a1 = register_action(do_r1, NULL);
    name_action(a1, "mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop");
    e1 = register_event(immediate, NULL, a1);
    name_event(e1, "extern.epk:6 on immediate");

    /* extern.epk:7: on after(ms: 250) do mark(1, 10 steps, 10, 1, 1), exit_main */
    a2 = register_action(do_r2, NULL);
    name_action(a2, "mark(1, 10 steps, 10, 1, 1), exit_main");
    e2 = register_event(after, &when_r2, a2);
    name_event(e2, "extern.epk:7 on after(ms: 250)");

    mainloop();
    return 0;
}

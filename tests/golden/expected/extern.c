/*
 * extern.epk, compiled by epuckc 0.1.0. Do not edit: edit the rule file.
 *
 * As in the paper's figure 2: parameter structs, then the actions and the
 * events that trigger them registered with the runtime, then mainloop().
 * Registrations: 2 actions, 2 events.
 */
#include "utility.h"
#include "extern_externs.h"

/* extern.epk:6: mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s) */
static param_mark epk_p1_r1 = {3, 155, 776, 45, 2000L};
/* extern.epk:7: mark(1, 10 steps, 10, 1, 1) */
static param_mark epk_p1_r2 = {1, 10, 10, 1, 1L};
/* extern.epk:7: after(ms: 250) */
static param_after epk_when_r2 = {250L};

/* extern.epk:6: mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop */
static void epk_do_r1(void *epk_param)
{
    (void)epk_param;
    mark(&epk_p1_r1);
    noop(NULL);
}

/* extern.epk:7: mark(1, 10 steps, 10, 1, 1), exit_main */
static void epk_do_r2(void *epk_param)
{
    (void)epk_param;
    mark(&epk_p1_r2);
    exit_main(NULL);
}

int main(void)
{
    int epk_a1, epk_a2;
    int epk_e1, epk_e2;

    /* extern.epk:6: on immediate do mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop */
    epk_a1 = register_action(epk_do_r1, NULL);
    name_action(epk_a1, "mark(count: 3, length: 2 cm, pace: 100 mm/s, turn: 45 deg, wait: 2 s), noop");
    epk_e1 = register_event(immediate, NULL, epk_a1);
    name_event(epk_e1, "extern.epk:6 on immediate");

    /* extern.epk:7: on after(ms: 250) do mark(1, 10 steps, 10, 1, 1), exit_main */
    epk_a2 = register_action(epk_do_r2, NULL);
    name_action(epk_a2, "mark(1, 10 steps, 10, 1, 1), exit_main");
    epk_e2 = register_event(after, &epk_when_r2, epk_a2);
    name_event(epk_e2, "extern.epk:7 on after(ms: 250)");

    mainloop();
    return 0;
}

/* Entering modes, two rules of docs/language.md section 2.7: a rule that
 * enters its own mode again is re-armed with the rest of the mode (A's
 * one-shot timer rule fires three times), and the poll after an entry
 * starts with the mode's `on enter` events, before its rules of higher
 * priority (B's priority-1 timer rule sees the timer B's entry set, not
 * the one A left running). */
#include "epuckrt.h"

static param_enter_mode to_a = { 1 }, to_b = { 2 };
static param_event_timer t50 = { 50 }, t20 = { 20 };
static int again;

static void a_again(void *p)
{
    (void)p;
    enter_mode(++again < 3 ? 1 : 2);
}

int main(void)
{
    int a_set = register_action(set_timer, NULL);
    int a_again_id = register_action(a_again, NULL);
    int a_exit = register_action(exit_main, NULL);
    int e;

    (void)to_a;
    (void)to_b;
    name_mode(1, "A");
    name_mode(2, "B");
    e = register_event(event_enter_mode, NULL, a_set);      /* #0 */
    name_event(e, "A enter");
    set_event_mode(e, 1);
    e = register_event(timer, &t50, a_again_id);             /* #1, one-shot */
    name_event(e, "A again");
    set_event_mode(e, 1);
    e = register_event(timer, &t20, a_exit);                 /* #2 */
    name_event(e, "B early");
    set_event_mode(e, 2);
    set_event_priority(e, 1);
    e = register_event(event_enter_mode, NULL, a_set);      /* #3 */
    name_event(e, "B enter");
    set_event_mode(e, 2);
    enter_mode(1);
    mainloop();
    return 0;
}

/* Modes: only the current mode's events are polled; entering re-arms the
 * mode's events (one-shot ones too) and fires its enter events at the next
 * poll; leaving a mode abandons its sequence and stops its motion without a
 * stop_motor event; disarm_event lasts until the mode is entered again. */
#include "epuckrt.h"

static param_enter_mode to_a = { 1 }, to_b = { 2 };
static param_straight_steps drive = { 500, 5000 };       /* 10 s */
static param_straight_steps back = { -500, 100 };
static const action steps[] = { { straight_steps, &drive }, { straight_steps, &back } };
static param_sequence seq = { steps, 2 };
static param_event_selector sel1 = { 1 }, sel2 = { 2 };
static param_event_timer every_100 = { 100 }, at_2000 = { 2000 };
static int e_beep, entries_b;

static void disarm_beep_once(void *p)
{
    (void)p;
    if (entries_b++ == 0)
        disarm_event(e_beep);
}

static void beep(void *p)
{
    (void)p;
}

int main(void)
{
    int a_to_a = register_action(action_enter_mode, &to_a);
    int a_to_b = register_action(action_enter_mode, &to_b);
    int a_seq = register_action(run_sequence, &seq);
    int a_disarm = register_action(disarm_beep_once, NULL);
    int a_beep = register_action(beep, NULL);
    int a_exit = register_action(exit_main, NULL);
    int e;

    name_mode(1, "A");
    name_mode(2, "B");
    e = register_event(event_enter_mode, NULL, a_seq);      /* #0 */
    name_event(e, "A enter");
    set_event_mode(e, 1);
    e = register_event(event_selector, &sel1, a_to_b);      /* #1 */
    name_event(e, "A selector 1");
    set_event_mode(e, 1);
    e = register_event(event_stop_motor, NULL, a_exit);     /* #2: must never fire */
    name_event(e, "B stop_motor");
    set_event_mode(e, 2);
    set_event_repeat(e, 1);
    e = register_event(event_enter_mode, NULL, a_disarm);   /* #3 */
    name_event(e, "B enter");
    set_event_mode(e, 2);
    e = register_event(event_selector, &sel2, a_to_a);      /* #4 */
    name_event(e, "B selector 2");
    set_event_mode(e, 2);
    e_beep = register_event(timer, &every_100, a_beep);     /* #5 */
    name_event(e_beep, "B beep");
    set_event_mode(e_beep, 2);
    set_event_repeat(e_beep, 1);
    e = register_event(timer, &at_2000, a_exit);            /* #6: no mode */
    name_event(e, "end");
    set_timer(NULL);
    enter_mode(1);
    mainloop();
    return 0;
}

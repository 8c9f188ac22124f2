/* The 16-bit step counters wrap (set near their ends, then driven past
 * them, forwards and back) and the distances are still right. */
#include "epuckrt.h"
#include "motor_led/advance_one_timer/e_motors.h"

static param_start_straight fwd = { 1000, 100 };   /* 776 steps */
static void preset_and_go(void *unused)
{
    (void)unused;
    e_set_steps_left(32500);
    e_set_steps_right(-32500);
    start_straight(&fwd);
}

int main(void)
{
    static param_start_straight back = { -1000, 100 };
    static param_event_timer t3000 = { 3000 };
    int a1 = register_action(preset_and_go, NULL);
    int a2 = register_action(start_straight, &back);
    int a3 = register_action(exit_main, NULL);
    int e;

    set_timer(NULL);
    register_event(immediate, NULL, a1);
    e = register_event(event_stop_motor, NULL, a2);
    set_event_repeat(e, 1);     /* fires at both stops; driving back twice */
    register_event(timer, &t3000, a3);
    mainloop();
    return 0;
}

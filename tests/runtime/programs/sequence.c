/* A sequence: straight, (set_timer: no motion, runs at once), spin 90 deg,
 * straight back.  The user's stop_motor event sees one stop, at the end. */
#include "epuckrt.h"

int main(void)
{
    static param_straight_steps fwd = { 1000, 200 };
    static param_start_curve spin = { 0, 90, 500 };
    static param_straight_steps back = { -1000, 100 };
    static const action steps[] = {
        { straight_steps, &fwd },
        { set_timer, NULL },
        { start_curve, &spin },
        { action_straight_steps, &back },
    };
    static param_sequence seq = { steps, 4 };
    int a_seq = register_action(run_sequence, &seq);
    int a_exit = register_action(exit_main, NULL);

    name_action(a_seq, "square");
    register_event(immediate, NULL, a_seq);
    register_event(event_stop_motor, NULL, a_exit);
    mainloop();
    return 0;
}

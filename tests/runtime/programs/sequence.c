/* A sequence: straight, (set_timer: no motion, runs at once), spin 90 deg,
 * straight back.  The user's stop_motor event sees one stop, at the end. */
#include "epuckrt.h"

int main(void)
{
    static param_start_straight fwd = { 1000, 0, 200 };
    static param_start_curve spin = { 0, 90, 500, 0, 0 };
    static param_start_straight back = { -1000, 0, 100 };
    static const action steps[] = {
        { start_straight, &fwd },
        { set_timer, NULL },
        { start_curve, &spin },
        { action_start_straight, &back },
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

/* A motion started outside a waiting sequence abandons it; exit_main as a
 * step ends mainloop. */
#include "epuckrt.h"

int main(void)
{
    static param_straight_steps s1 = { 1000, 1000 };
    static param_straight_steps s2 = { 1000, 50 };
    static param_straight_steps other = { -1000, 20 };
    static const action steps[] = { { straight_steps, &s1 }, { straight_steps, &s1 } };
    static const action steps2[] = { { straight_steps, &s2 }, { exit_main, NULL },
                                     { straight_steps, &s2 } };
    static param_sequence seq = { steps, 2 };
    static param_sequence seq2 = { steps2, 3 };
    static param_event_timer t300 = { 300 };
    int a_seq = register_action(run_sequence, &seq);
    int a_other = register_action(straight_steps, &other);
    int a_seq2 = register_action(action_run_sequence, &seq2);

    set_timer(NULL);
    register_event(immediate, NULL, a_seq);
    register_event(event_timer, &t300, a_other);
    register_event(event_stop_motor, NULL, a_seq2);
    mainloop();
    return 0;
}

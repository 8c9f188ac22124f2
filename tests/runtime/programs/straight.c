/* The paper's figure 2 motion with the long names; the parameters can be
 * changed with -DSPEED=.. -DDIST=.. -DSTEPS=.. */
#include "epuckrt.h"
#ifndef SPEED
#define SPEED 250
#endif
#ifndef DIST
#define DIST 100
#endif

int main(void)
{
#ifdef STEPS
    /* the extension in exact steps */
    static param_straight_steps p = { SPEED, STEPS };
    int a1 = register_action(action_straight_steps, &p);
#else
    static param_start_straight p = { SPEED, DIST };
    int a1 = register_action(action_start_straight, &p);
#endif
    int a2 = register_action(action_exit_main, NULL);
    register_event(event_immediate, NULL, a1);
    register_event(event_stop_motor, NULL, a2);
    mainloop();
    return 0;
}

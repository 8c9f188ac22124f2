/* The paper's figure 2 motion with the long names; the parameters can be
 * changed with -DSPEED=.. -DDIST=.. -DSTEPS=.. */
#include "epuckrt.h"
#ifndef SPEED
#define SPEED 250
#endif
#ifndef DIST
#define DIST 100
#endif
#ifndef STEPS
#define STEPS 0
#endif

int main(void)
{
    static param_start_straight p = { SPEED, DIST, STEPS };
    int a1 = register_action(action_start_straight, &p);
    int a2 = register_action(action_exit_main, NULL);
    register_event(event_immediate, NULL, a1);
    register_event(event_stop_motor, NULL, a2);
    mainloop();
    return 0;
}

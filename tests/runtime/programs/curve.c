/* One curve; -DRADIUS=.. -DDEGREES=.. -DSPEED=.. -DOUTER=.. -DINNER=.. */
#include "epuckrt.h"
#ifndef RADIUS
#define RADIUS 0
#endif
#ifndef DEGREES
#define DEGREES 90
#endif
#ifndef SPEED
#define SPEED 500
#endif

int main(void)
{
#ifdef STEPS
    /* the extension in exact steps: LEFT, RIGHT wheel speeds */
    static param_curve_steps p = { LEFT, RIGHT, STEPS };
    int a1 = register_action(curve_steps, &p);
#else
    static param_start_curve p = { RADIUS, DEGREES, SPEED };
    int a1 = register_action(start_curve, &p);
#endif
    int a2 = register_action(exit_main, NULL);
    register_event(immediate, NULL, a1);
    register_event(event_stop_motor, NULL, a2);
    mainloop();
    return 0;
}

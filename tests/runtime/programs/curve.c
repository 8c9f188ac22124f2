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
#ifndef OUTER
#define OUTER 0
#endif
#ifndef INNER
#define INNER 0
#endif

int main(void)
{
    static param_start_curve p = { RADIUS, DEGREES, SPEED, OUTER, INNER };
    int a1 = register_action(start_curve, &p);
    int a2 = register_action(exit_main, NULL);
    register_event(immediate, NULL, a1);
    register_event(event_stop_motor, NULL, a2);
    mainloop();
    return 0;
}

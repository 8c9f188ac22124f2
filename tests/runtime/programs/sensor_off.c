/* Without start_sensor (and after stop_sensor) sensor conditions are false.
 * ir0 is 1000 all the time (sensor_off.scn); the repeating event turns the
 * sensors off each time it fires, the timers turn them on at 150 and 250. */
#include "epuckrt.h"

int main(void)
{
    static param_event_sensor near = { { 500, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF,
                                         SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF }, 0 };
    static param_event_timer t150 = { 150 }, t250 = { 250 }, t400 = { 400 };
    int a_on = register_action(start_sensor, NULL);
    int a_off = register_action(stop_sensor, NULL);
    int a_exit = register_action(exit_main, NULL);
    int e;

    set_timer(NULL);
    e = register_event(sensor, &near, a_off);     /* 0: repeat */
    set_event_repeat(e, 1);
    register_event(timer, &t150, a_on);           /* 1 */
    register_event(timer, &t250, a_on);           /* 2 */
    register_event(timer, &t400, a_exit);         /* 3 */
    mainloop();
    return 0;
}

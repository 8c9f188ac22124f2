/* Sensor events fire on rising edges of their condition.  Scenario
 * sensor_edge.scn: ir0 0 -> 900 at 100 ms -> 0 at 200 -> 900 at 300. */
#include "epuckrt.h"

int main(void)
{
    static param_event_sensor above = { { 500, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF,
                                          SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF }, 0 };
    static param_event_sensor below = { { 500, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF,
                                          SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF }, 1 };
    static param_event_sensor other = { { SENSOR_OFF, 100, SENSOR_OFF, SENSOR_OFF,
                                          SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF }, 0 };
    static param_event_timer end = { 400 };
    int a_on = register_action(start_sensor, NULL);
    int a_note = register_action(start_sensor, NULL); /* harmless: already on */
    int a_exit = register_action(exit_main, NULL);
    int e;

    set_timer(NULL);
    register_event(immediate, NULL, a_on);               /* 0 */
    e = register_event(sensor, &above, a_note);          /* 1: repeat */
    set_event_repeat(e, 1);
    register_event(event_sensor, &above, a_note);        /* 2: one-shot */
    e = register_event(sensor, &below, a_note);          /* 3: repeat, below */
    set_event_repeat(e, 1);
    register_event(sensor, &other, a_note);              /* 4: ir1 stays 0 */
    register_event(timer, &end, a_exit);                 /* 5 */
    mainloop();
    return 0;
}

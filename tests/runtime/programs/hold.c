/* Holding the motors on the paper's API (docs/runtime.md, "Holding the
 * motors"): a sensor event of priority 1 that sets the wheels' speeds holds
 * them while its condition is true, so the renewed commands of a lower
 * timer event are suppressed exactly then; an event rule's sequence that
 * ends in set_speed holds them only until its last step; a sequence holds
 * them through its wait. */
#include "epuckrt.h"

static param_event_sensor near = { { 500, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF, SENSOR_OFF,
                                     SENSOR_OFF, SENSOR_OFF, SENSOR_OFF }, 0 };
static param_set_speed back = { -200, -200 }, cruise = { 300, 300 }, spin = { -300, 300 };
static param_event_timer every_10 = { 10 }, at_600 = { 600 }, at_1500 = { 1500 };
static param_curve_steps quarter = { -300, 300, 150 };      /* 500 ms */
static param_wait pause = { 100 };
static const action turn_then_spin[] = {
    { curve_steps, &quarter }, { action_wait, &pause }, { action_set_speed, &spin } };
static param_sequence turn = { turn_then_spin, 3 };

static void add(event_func f, void *param, int action_id, const char *name, int priority,
                int repeat)
{
    int e = register_event(f, param, action_id);
    name_event(e, name);
    set_event_priority(e, priority);
    set_event_repeat(e, repeat);
}

int main(void)
{
    add(immediate, NULL, register_action(start_sensor, NULL), "start", 0, 0);
    add(event_sensor, &near, register_action(action_set_speed, &back), "back off", 1, 1);
    add(timer, &every_10, register_action(action_set_speed, &cruise), "cruise", 0, 1);
    add(timer, &at_600, register_action(run_sequence, &turn), "turn", 1, 0);
    add(timer, &at_1500, register_action(exit_main, NULL), "end", 9, 0);
    set_timer(NULL);
    mainloop();
    return 0;
}

/* Extreme geometry and parameters: the conversions of millimetres and
 * degrees saturate instead of overflowing (run under UBSan).  Each motion
 * is replaced by the next one 5 ms later; out-of-range geometry is ignored. */
#include <limits.h>
#include "epuckrt.h"

static param_start_straight far_fwd = { INT_MAX, INT_MAX };
static param_start_straight far_back = { INT_MIN, INT_MIN };
static param_start_curve wide_left = { INT_MAX, INT_MAX, INT_MAX };
static param_start_curve wide_right = { INT_MIN, INT_MIN, INT_MIN };
static param_straight_steps steps_min = { INT_MIN, INT_MIN };
static param_curve_steps wheels_min = { INT_MIN, INT_MAX, INT_MIN };

static void extremes(void *unused)
{
    (void)unused;
    set_robot_geometry(EPUCK_MAX_GEOMETRY_UM + 1, 1, 1);       /* ignored */
    set_robot_geometry(LONG_MAX, LONG_MAX, LONG_MAX);          /* ignored */
    set_robot_geometry(1, EPUCK_MAX_GEOMETRY_UM, EPUCK_MAX_STEPS_PER_REV);
    start_straight(&far_fwd);
    start_straight(&far_back);
    start_curve(&wide_left);
    start_curve(&wide_right);
    set_robot_geometry(EPUCK_MAX_GEOMETRY_UM, 1, 1);
    start_curve(&wide_left);
    start_straight(&far_fwd);
    straight_steps(&steps_min);
    curve_steps(&wheels_min);
}

int main(void)
{
    static param_event_timer t5 = { 5 };
    int a1 = register_action(extremes, NULL);
    int a2 = register_action(exit_main, NULL);

    set_timer(NULL);
    register_event(immediate, NULL, a1);
    register_event(timer, &t5, a2);
    mainloop();
    return 0;
}

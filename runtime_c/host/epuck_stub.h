/*
 * epuck_stub.h - the host side of the stub e-puck library (epuck_stub.c):
 * the calls platform_host.c uses to drive the virtual robot.  User programs
 * and the core use only the e-puck library API (../epuck_api/).
 */
#ifndef EPUCK_STUB_H
#define EPUCK_STUB_H

/* Advance the wheels by 1 ms at the commanded speeds (steps are whole:
 * a wheel at s steps/s steps every 1000/s ms), update the pose. */
void stub_motors_1ms(void);
/* Run the active agendas for 1 ms (10 agenda ticks of 0.1 ms) when agenda
 * processing has been started. */
void stub_agendas_1ms(void);
/* Set the reading of proximity sensor n (0..7). */
void stub_set_prox(int n, int value);
/* Total signed steps of each wheel since start (not wrapped). */
long stub_total_steps_left(void);
long stub_total_steps_right(void);
/* Odometry pose from the wheel steps with the default geometry: x, y in mm
 * (start 0,0 facing +x), heading in degrees in (-180, 180], positive = left. */
void stub_pose(double *x_mm, double *y_mm, double *heading_deg);
/* The geometry of the odometry (set_robot_geometry); defaults from epuckrt.h. */
void stub_set_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev);

#endif

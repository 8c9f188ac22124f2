/*
 * rt_odometry.h - the robot's geometry and its odometry (rt_odometry.c).
 * Builds on rt_clock.h.
 */
#ifndef RT_ODOMETRY_H
#define RT_ODOMETRY_H

#include "rt_clock.h"

extern long rt_geo_circumference_um;   /* the geometry (set_robot_geometry) */
extern long rt_geo_axle_um;
extern long rt_geo_steps_per_rev;
void rt_odometry(long dl, long dr);   /* the wheels' steps of this poll */
extern int rt_odometry_used;   /* the program reads x, y or heading */

#endif

/*
 * rt_sensors.h - what the standard events, the timer and the sensors
 * (rt_sensors.c) share with the layers above them.  Builds on rt_clock.h.
 */
#ifndef RT_SENSORS_H
#define RT_SENSORS_H

#include "rt_clock.h"

extern int rt_timer_running;   /* set_timer ran, reset_timer did not since */
extern long rt_timer_start;   /* rt_millis() at set_timer */
extern int rt_sensors_on;
extern int rt_sensors_starting;   /* start_sensor ran: on from the next poll */
extern int rt_prox[8];
extern unsigned rt_prox_valid;
void rt_read_prox(unsigned mask);
/* the stop_motor condition of this poll, sampled by the walk before it polls */
extern int rt_stop_sample;
/* The accelerometer: sampled once a poll while a program has an event_tap
 * or event_tilt (rt_accel_wanted). */
extern int rt_accel_wanted;
void rt_accel_sample(void);
/* An event_remote was registered: its receiver starts now, or at the
 * library's initialisation (rt_remote_start, from mainloop's start). */
void rt_remote_want(void);
void rt_remote_start(void);

#endif

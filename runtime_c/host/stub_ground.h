/*
 * stub_ground.h - the host's ground-sensor module (stub_ground.c): what
 * the scenario (groundN=V) and the Enki world (robot_glue.c: Enki's ground
 * sensors over the floor) set.  Programs read it through the e-puck2
 * firmware's API (sensors/ground.h).
 */
#ifndef STUB_GROUND_H
#define STUB_GROUND_H
/* The light the floor reflects under ground sensor n (0 left, 1 centre,
 * 2 right), as get_ground_prox reports it; each holds until changed.
 * STUB_GROUND_WHITE at start: white paper under all three. */
#define STUB_GROUND_SENSORS 3
#define STUB_GROUND_WHITE 1000
void stub_set_ground(int n, int value);
#endif

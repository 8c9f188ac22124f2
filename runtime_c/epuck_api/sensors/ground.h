/* The e-puck2 firmware's ground-sensor module (e-puck2_main-processor
 * src/sensors/ground.h): declarations only, for the builds without the
 * firmware.  The module (GCtronic's, an I2C device at 0x60, 0xC0 as the
 * e-puck library writes addresses) has three IR sensors under the front of
 * the robot, facing the floor: 0 left, 1 centre, 2 right (the e-puck2's
 * cliff module adds 3 and 4).  get_ground_prox gives the light reflected
 * by the floor (the module's reading with its LED on less the one with it
 * off), get_ground_ambient_light the one with it off.  The host
 * (host/stub_ground.c) and the e-puck (../ground_i2c.c) provide them. */
#ifndef GROUND_H
#define GROUND_H
#define GROUND_NB_CHANNELS 5
void ground_start(void);
void ground_stop(void);
int get_ground_prox(unsigned int sensor_number);
int get_ground_ambient_light(unsigned int sensor_number);
#endif

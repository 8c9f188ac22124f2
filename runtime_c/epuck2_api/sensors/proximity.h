/* The e-puck2 firmware's proximity module (e-puck2_main-processor
 * src/sensors/proximity.h): the one call rt_comm.c makes before libIrcom
 * takes the IR sensors.  Declarations only, for compiling without the
 * firmware. */
#ifndef PROXIMITY_H
#define PROXIMITY_H
void proximity_stop(void);
#endif

/* The e-puck2's time-of-flight sensor as its firmware has it
 * (e-puck2_main-processor src/sensors/VL53L0X/VL53L0X.h): declarations
 * only, for the host build (host/stub_devices.c implements them). */
#ifndef VL53L0X_H
#define VL53L0X_H
#include <stdint.h>
void VL53L0X_start(void);
uint16_t VL53L0X_get_dist_mm(void);
#endif

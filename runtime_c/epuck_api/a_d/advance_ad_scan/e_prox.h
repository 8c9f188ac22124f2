/* e-puck library API, proximity sensors over the advanced A/D scan
 * (library/a_d/advance_ad_scan/e_prox.h), declarations only (see
 * ../../README.md).  Readings 0..4095. */
#ifndef EPUCK_API_E_PROX_H
#define EPUCK_API_E_PROX_H

void e_calibrate_ir(void);
int e_get_prox(unsigned int sensor_number);
int e_get_calibrated_prox(unsigned int sensor_number);
int e_get_ambient_light(unsigned int sensor_number);

#endif

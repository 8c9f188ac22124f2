/* e-puck library API, declarations only (see ../README.md).
 * isEpuckVersion1_3: 1, the simulated robot is an e-puck 1.3 (it has the
 * LSM330 accelerometer and gyroscope). */
#ifndef EPUCK_API_E_INIT_PORT_H
#define EPUCK_API_E_INIT_PORT_H

void e_init_port(void);
unsigned char isEpuckVersion1_3(void);

#endif

/* e-puck library API, accelerometer over the advanced A/D scan,
 * declarations only (see ../../README.md).  captor 0 x, 1 y, 2 z; raw
 * 12-bit readings. */
#ifndef EPUCK_API_E_ACC_H
#define EPUCK_API_E_ACC_H

int e_get_acc(unsigned int captor);
int e_get_acc_filtered(unsigned int captor, unsigned int filter_size);
void e_acc_calibr(void);

#endif

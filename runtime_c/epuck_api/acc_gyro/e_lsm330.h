/* e-puck library API, the LSM330 accelerometer and gyroscope of the e-puck
 * 1.3 (library/acc_gyro/e_lsm330.h), declarations only (see ../README.md).
 * On the simulated robot the floor is flat: the accelerometer measures
 * gravity only (z = 1 g = 16384 at +-2 g full scale); the gyroscope the
 * body's rotation about z (8.75 mdps a unit at +-250 dps), x and y 0. */
#ifndef EPUCK_API_E_LSM330_H
#define EPUCK_API_E_LSM330_H

void initAccAndGyro(void);
void getAllAxesAccRaw(unsigned char *arr);
void getAllAxesAcc(signed int *x, signed int *y, signed int *z);
void getAllAxesGyroRaw(unsigned char *arr);
void getAllAxesGyro(signed int *x, signed int *y, signed int *z);
signed char getTemperature(void);
int getXAxisAcc(void);
int getYAxisAcc(void);
int getZAxisAcc(void);
int getXAxisGyro(void);
int getYAxisGyro(void);
int getZAxisGyro(void);
void calibrateGyroscope(void);
float rawToDps(int value);
float rawToDpms(int value);

#endif

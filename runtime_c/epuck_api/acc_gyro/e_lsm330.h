/* e-puck library API, the LSM330 accelerometer and gyroscope of the e-puck
 * 1.3 (library/acc_gyro/e_lsm330.h), declarations only (see ../README.md;
 * host/imu.c).  The accelerometer: the specific force on the body, 16384
 * a g (X the robot's front, Y its left, Z up: 1 g up at rest); the
 * gyroscope: the body's rate of turn, 8.75 mdps a unit, at the sensor's
 * 760 samples a second through its 30 Hz low-pass, as the library sets
 * it.  The declarations with empty parentheses are the library's (its
 * calibrateGyroscope takes the number of samples). */
#ifndef EPUCK_API_E_LSM330_H
#define EPUCK_API_E_LSM330_H

void initAccAndGyro(void);
void getAllAxesAccRaw(unsigned char *arr);
void getAllAxesAcc(signed int *x, signed int *y, signed int *z);
void getAllAxesGyroRaw(unsigned char *arr);
void getAllAxesGyro(signed int *x, signed int *y, signed int *z);
signed char getTemperature(void);
int getXAxisAcc();
int getYAxisAcc();
int getZAxisAcc();
int getXAxisGyro();
int getYAxisGyro();
int getZAxisGyro();
void calibrateGyroscope();
float rawToDps(int value);
float rawToDpms(int value);

#endif

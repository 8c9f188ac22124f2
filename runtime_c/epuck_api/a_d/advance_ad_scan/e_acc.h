/* e-puck library API, the accelerometer over the advanced A/D scan
 * (library/a_d/advance_ad_scan/e_acc.h), declarations only (see
 * ../../README.md; host/imu.c computes them as the library does on the
 * e-puck 1.3, over its LSM330).  captor 0 x (the robot's left), 1 y (its
 * front), 2 z (up). */
#ifndef EPUCK_API_E_ACC_H
#define EPUCK_API_E_ACC_H

#define CST_RADIAN		(180.0/3.1415)
#define ANGLE_ERROR		666.0
#define FILTER_SIZE		5

#define ACCX_BUFFER	0
#define ACCY_BUFFER	1
#define ACCZ_BUFFER	2

#define GRAVITY 768
#define GRAVITY_LSM330 16384

typedef struct
{
	float acceleration;
	float orientation;
	float inclination;
} TypeAccSpheric;

typedef struct
{
	int acc_x;
	int acc_y;
	int acc_z;
} TypeAccRaw;

int e_get_acc(unsigned int captor);
int e_get_acc_filtered(unsigned int captor, unsigned int filter_size);
TypeAccSpheric e_read_acc_spheric(void);
float e_read_orientation(void);
float e_read_inclination(void);
float e_read_acc(void);
TypeAccRaw e_read_acc_xyz(void);
int e_read_acc_x(void);
int e_read_acc_y(void);
int e_read_acc_z(void);
void e_acc_calibr(void);
void e_display_angle(void);

#endif

/* e-puck library API: contrib/LIS_sensors_turret/e_sensext.h, which the simulated e-puck does not
 * model (the LIS sensors turret): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the LIS sensors turret (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _SENSEXT
#define _SENSEXT
#define I2C_ADDR_SENSEXT 0b10100010
#define I2C_ADDR_SRF08 0xE0
#define I2C_ADDR_SRF10 0xE0
#define I2C_ADDR_CMPS03 0xC0
#define I2C_ADDR_SRF235 0xE0
void e_init_sensext(void);
int e_sensext_process(int* sensext_param, unsigned int* sensext_value);
void e_stop_sensext_wait(void);
void e_start_sensext_wait(void);
int e_get_sensext_wait(void);
#endif

/* e-puck library API: contrib/LIS_sensors_turret/e_devantech.h, which the simulated e-puck does not
 * model (the LIS sensors turret): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the LIS sensors turret (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _devantech
#define _devantech
#include "I2C/e_I2C_master_module.h"
#include "motor_led/e_epuck_ports.h"
void e_init_devantech(void);
void e_disable_devantech(void);
unsigned int e_get_dist_devantech(char device_add);
unsigned int e_get_delay_devantech(char device_add);
char e_get_sr_devantech(char device_add);
unsigned int e_get_light_devantech(char device_add);
void e_set_gain_devantech(char device_add, char gain);
void e_set_range_devantech(char device_add, char range);
void e_i2cd_write (char device_add, char reg, char value);
char e_i2cd_readb(char device_add, char reg);
unsigned int e_i2cd_readw(char device_add, char reg);
#endif

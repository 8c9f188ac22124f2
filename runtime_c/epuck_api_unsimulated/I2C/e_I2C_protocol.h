/* e-puck library API: I2C/e_I2C_protocol.h, which the simulated e-puck does not
 * model (the I2C bus): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the I2C bus (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _I2C_PROTOCOL
#define _I2C_PROTOCOL
#include "I2C/e_I2C_master_module.h"
#include "motor_led/e_epuck_ports.h"
void e_i2cp_init(void);
void e_i2cp_deinit(void);
char e_i2cp_write (char device_add,char reg, char value);
char e_i2cp_read(char device_add,char reg);
char e_i2cp_read_string(char device_add, unsigned char read_buffer[], char start_address, char string_length);
char e_i2cp_write_string (char device_add, unsigned char write_buffer[], char start_address, char string_length);
void e_i2cp_enable(void);
void e_i2cp_disable(void);
#endif

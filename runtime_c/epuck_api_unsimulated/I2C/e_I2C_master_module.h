/* e-puck library API: I2C/e_I2C_master_module.h, which the simulated e-puck does not
 * model (the I2C bus): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the I2C bus (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _I2C_MASTER_MODULE
#define _I2C_MASTER_MODULE
#include "p30F6014A.h"
#define START 1
#define WRITE 2
#define ACKNOWLEDGE 3
#define READ 4
#define STOP 5
#define RESTART 6
#define ERROR 10
#define OPERATION_OK 0
char e_i2c_init(void);
char e_i2c_deinit(void);
char e_i2c_start(void);
char e_i2c_restart(void);
char e_i2c_ack(void);
char e_i2c_nack(void);
char e_i2c_read(char *buf);
char e_i2c_stop(void);
char e_i2c_write(char byte);
char e_i2c_enable(void);
char e_i2c_disable(void);
char e_i2c_reset(void);
#endif

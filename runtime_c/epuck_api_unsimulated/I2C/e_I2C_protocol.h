/* e-puck library API: I2C/e_I2C_protocol.h, which the simulated e-puck does not model
 * (the I2C bus); a program that includes it stops at the build with this
 * message (docs/runtime.md, C programs), never at a link error. */
#ifndef EPUCK_API_I2C_E_I2C_PROTOCOL_H
#define EPUCK_API_I2C_E_I2C_PROTOCOL_H
#error "I2C/e_I2C_protocol.h: the I2C bus is not simulated by epuckc; the simulated e-puck has the motors, LEDs, IR, agendas, UART, accelerometer and gyroscope, sound and microphones"
#endif

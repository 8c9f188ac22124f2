/* e-puck library API: bluetooth/e_bluetooth.h, which the simulated e-puck does not model
 * (Bluetooth); a program that includes it stops at the build with this
 * message (docs/runtime.md, C programs), never at a link error. */
#ifndef EPUCK_API_BLUETOOTH_E_BLUETOOTH_H
#define EPUCK_API_BLUETOOTH_E_BLUETOOTH_H
#error "bluetooth/e_bluetooth.h: Bluetooth is not simulated by epuckc; the simulated e-puck has the motors, LEDs, IR, agendas, UART, accelerometer and gyroscope, sound and microphones"
#endif

/* e-puck library API: camera/fast_2_timer/e_po3030k.h, which the simulated e-puck does not model
 * (the camera); a program that includes it stops at the build with this
 * message (docs/runtime.md, C programs), never at a link error. */
#ifndef EPUCK_API_CAMERA_FAST_2_TIMER_E_PO3030K_H
#define EPUCK_API_CAMERA_FAST_2_TIMER_E_PO3030K_H
#error "camera/fast_2_timer/e_po3030k.h: the camera is not simulated by epuckc; the simulated e-puck has the motors, LEDs, IR, agendas, UART, accelerometer and gyroscope, sound and microphones"
#endif

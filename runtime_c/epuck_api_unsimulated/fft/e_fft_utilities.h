/* e-puck library API: fft/e_fft_utilities.h, which the simulated e-puck does not model
 * (the FFT of the microphones' samples); a program that includes it stops at the build with this
 * message (docs/runtime.md, C programs), never at a link error. */
#ifndef EPUCK_API_FFT_E_FFT_UTILITIES_H
#define EPUCK_API_FFT_E_FFT_UTILITIES_H
#error "fft/e_fft_utilities.h: the FFT of the microphones' samples is not simulated by epuckc; the simulated e-puck has the motors, LEDs, IR, agendas, UART, accelerometer and gyroscope, sound and microphones"
#endif

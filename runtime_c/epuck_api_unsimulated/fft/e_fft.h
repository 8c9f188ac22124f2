/* e-puck library API: fft/e_fft.h, which the simulated e-puck does not
 * model (the FFT of the microphones' samples): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the FFT of the microphones' samples (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef FFT_H
#define FFT_H
#include <dsp.h>
#define FFT_BLOCK_LENGTH 256
#if (FFT_BLOCK_LENGTH == 64)
#define LOG2_BLOCK_LENGTH 6
#endif
#if (FFT_BLOCK_LENGTH == 128)
#define LOG2_BLOCK_LENGTH 7
#endif
#if (FFT_BLOCK_LENGTH == 256)
#define LOG2_BLOCK_LENGTH 8
#endif
#if (FFT_BLOCK_LENGTH == 512)
#define LOG2_BLOCK_LENGTH 9
#endif
void e_doFFT_asm(fractcomplex* sigCmpx);
#endif

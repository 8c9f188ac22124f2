/* e-puck library API: fft/e_fft_utilities.h, which the simulated e-puck does not
 * model (the FFT of the microphones' samples): the library's declarations, so that a program
 * that includes it builds and links; a call of one of its functions
 * ends the run with a message naming the FFT of the microphones' samples (host/unsimulated.c;
 * docs/runtime.md, "What is not simulated"). */
#ifndef _FFT_UTILITIES
#define _FFT_UTILITIES
void e_fast_copy(int* in_array, int* out_array, int size);
void e_subtract_mean(int* array, int size, int log2size);
#endif

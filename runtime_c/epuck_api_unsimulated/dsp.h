/* The types of Microchip's DSP library for the dsPIC (dsp.h) that the
 * e-puck library's FFT declares its functions with (fft/e_fft.h); the FFT
 * is not simulated (host/unsimulated.c). */
#ifndef EPUCK_API_DSP_H
#define EPUCK_API_DSP_H

typedef int fractional;

typedef struct {
    fractional real;
    fractional imag;
} fractcomplex;

#endif

/* e-puck library API, advanced A/D scan, declarations only
 * (see ../../README.md). */
#ifndef EPUCK_API_E_AD_CONV_H
#define EPUCK_API_E_AD_CONV_H

#define ALL_ADC 0
#define MICRO_ONLY 1

/* the A/D interrupt's rate and period (utility.h's timing counts its ticks) */
#define MIC_SAMP_FREQ 16384.0
#define ADC_ISR_PERIOD_MS 0.061

void e_init_ad_scan(unsigned char only_micro);

#endif

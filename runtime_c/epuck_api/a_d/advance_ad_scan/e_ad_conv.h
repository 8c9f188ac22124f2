/* e-puck library API, advanced A/D scan, declarations only
 * (see ../../README.md). */
#ifndef EPUCK_API_E_AD_CONV_H
#define EPUCK_API_E_AD_CONV_H

#define ALL_ADC 0
#define MICRO_ONLY 1

void e_init_ad_scan(unsigned char only_micro);

#endif

/* e-puck library API, the advanced A/D scan (library/a_d/advance_ad_scan/
 * e_ad_conv.h), declarations only (see ../../README.md): the scan's rates
 * (utility.h's timing counts its ticks: ADC_ISR_PERIOD_MS each) and the
 * sizes of its buffers, which the library's programs declare themselves
 * (`extern int e_mic_scan[3][MIC_SAMP_NB];`). */
#ifndef EPUCK_API_E_AD_CONV_H
#define EPUCK_API_E_AD_CONV_H

#define MIC_SAMP_FREQ 16384.0
#define ACC_PROX_SAMP_FREQ 256.0
#define PULSE_LENGHT 0.0003
#define ACC_PROX_PERIOD (int)(MIC_SAMP_FREQ/ACC_PROX_SAMP_FREQ)
#define PULSE_PERIOD (int)(PULSE_LENGHT*MIC_SAMP_FREQ)
#define ADCS_3_CHAN (int)(2.0*FCY/(MIC_SAMP_FREQ*(14+1)*3)-1)
#define ADCS_5_CHAN (int)(2.0*FCY/(MIC_SAMP_FREQ*(14+1)*5)-1)
#define ADCS_6_CHAN (int)(2.0*FCY/(MIC_SAMP_FREQ*(14+1)*6)-1)
#define ADCS_2_CHAN (int)(2.0*FCY/(MIC_SAMP_FREQ*(14+1)*2)-1)

#define MIC_SAMP_NB 100
#define ACC_SAMP_NB 50

#define MICRO_ONLY 1
#define ALL_ADC 0

#define ADC_ISR_PERIOD_MS 0.061

void e_init_ad_scan(unsigned char only_micro);
unsigned char e_ad_is_array_filled(void);
unsigned char e_ad_is_acquisition_completed(void);
void e_ad_scan_on(void);
void e_ad_scan_off(void);

#endif

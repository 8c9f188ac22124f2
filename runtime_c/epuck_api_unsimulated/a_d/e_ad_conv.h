/* e-puck library API: a_d/e_ad_conv.h, the timer-driven A/D variant (A/D), which
 * the simulated e-puck does not model: it has the advanced scan, whose
 * functions differ (e_get_micro, e_get_acc); stop at the build, never at a
 * link error. */
#ifndef EPUCK_API_A_D_E_AD_CONV_H
#define EPUCK_API_A_D_E_AD_CONV_H
#error "a_d/e_ad_conv.h: the timer-driven A/D variant is not simulated by epuckc; include <a_d/advance_ad_scan/e_ad_conv.h> (the advanced A/D scan, e_init_ad_scan(ALL_ADC))"
#endif

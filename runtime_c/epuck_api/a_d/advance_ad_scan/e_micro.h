/* e-puck library API, microphones over the advanced A/D scan (library/
 * a_d/advance_ad_scan/e_micro.h), declarations only (see ../../README.md;
 * host/sound.c).  micro_id 0..2. */
#ifndef EPUCK_API_E_MICRO_H
#define EPUCK_API_E_MICRO_H

#define MIC0_BUFFER	0
#define MIC1_BUFFER	1
#define MIC2_BUFFER	2

int e_get_micro(unsigned int micro_id);
int e_get_micro_average(unsigned int micro_id, unsigned int filter_size);
int e_get_micro_volume (unsigned int micro_id);

#endif

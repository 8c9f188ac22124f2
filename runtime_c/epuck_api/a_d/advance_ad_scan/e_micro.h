/* e-puck library API, microphones over the advanced A/D scan,
 * declarations only (see ../../README.md).  micro_id 0..2. */
#ifndef EPUCK_API_E_MICRO_H
#define EPUCK_API_E_MICRO_H

int e_get_micro(unsigned int micro_id);
int e_get_micro_average(unsigned int micro_id, unsigned int filter_size);
int e_get_micro_volume(unsigned int micro_id);

#endif

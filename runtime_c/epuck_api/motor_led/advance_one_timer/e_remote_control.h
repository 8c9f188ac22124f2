/* e-puck library API, the RC5 infrared remote control receiver (it uses an
 * agenda), declarations only (see ../../README.md).  e_get_check toggles at
 * each new key press; e_get_data is the key: 0..9 digits, 12 standby,
 * 13 mute, 16/17 volume up/down, 32/33 channel up/down. */
#ifndef EPUCK_API_E_REMOTE_CONTROL_H
#define EPUCK_API_E_REMOTE_CONTROL_H

void e_init_remote_control(void);
unsigned char e_get_check(void);
unsigned char e_get_address(void);
unsigned char e_get_data(void);

#endif

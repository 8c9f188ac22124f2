/* e-puck library API, the RC5 infrared remote control receiver (library/
 * motor_led/advance_one_timer/e_remote_control.h), declarations only (see
 * ../../README.md).  e_get_check toggles at each new key press; e_get_data
 * is the key: 0..9 digits, 12 standby, 13 mute, 16/17 volume up/down,
 * 32/33 channel up/down. */
#ifndef _IR_REMOTE_CONTROLE
#define _IR_REMOTE_CONTROLE

#define BOTTOMR		10 	// -/-- key
#define BOTTOMl		11 	// p<p key
#define	STANDBY		12
#define MUTE		13
#define VOL_UP		16
#define VOL_DOWN	17
#define CHAN_UP		32
#define CHAN_DOWN	33
#define I_II		35
#define OUT_AUX_1	56

void e_init_remote_control(void);
void e_read_remote_control(void);
unsigned char e_get_check(void);
unsigned char e_get_address(void);
unsigned char e_get_data(void);

#endif

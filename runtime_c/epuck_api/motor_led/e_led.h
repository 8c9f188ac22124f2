/* e-puck library API, LEDs, declarations only (see ../README.md).
 * e_set_led: led_number 0..7 a ring LED, 8 all of them; value 0 off,
 * 1 on, 2 toggle.  The body and front LEDs: 0 off, 1 on, 2 toggle. */
#ifndef EPUCK_API_E_LED_H
#define EPUCK_API_E_LED_H

void e_set_led(unsigned int led_number, unsigned int value);
void e_led_clear(void);
void e_set_body_led(unsigned int value);
void e_set_front_led(unsigned int value);

#endif

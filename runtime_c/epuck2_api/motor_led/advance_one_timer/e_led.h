/* The e-puck2 firmware's epuck1x layer, LEDs, declarations only: its
 * e_led.h is at this path there (src/epuck1x/motor_led/advance_one_timer/),
 * with the e-puck library's prototypes (see ../../../epuck_api/README.md). */
#ifndef EPUCK2_API_E_LED_H
#define EPUCK2_API_E_LED_H

void e_set_led(unsigned int led_number, unsigned int value);
void e_led_clear(void);
void e_set_body_led(unsigned int value);
void e_set_front_led(unsigned int value);

#endif

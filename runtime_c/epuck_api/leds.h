/*
 * leds.h - the e-puck2's RGB LEDs as its firmware declares them
 * (e-puck2_main-processor src/leds.h: the part the runtime's rt_rgb.c
 * uses), for the host, whose host/stub_devices.c provides set_rgb_led.
 * The e-puck2's build takes the firmware's own header instead.
 */
#ifndef EPUCKRT_HOST_LEDS_H
#define EPUCKRT_HOST_LEDS_H

#include <stdint.h>

#define RGB_MAX_INTENSITY 100   /* percent */

typedef enum {
    LED2,
    LED4,
    LED6,
    LED8,
    NUM_RGB_LED
} rgb_led_name_t;

void set_rgb_led(rgb_led_name_t led_number, uint8_t red_val, uint8_t green_val,
                 uint8_t blue_val);

#endif

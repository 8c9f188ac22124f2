/*
 * rt_rgb.c - the e-puck2's four RGB LEDs: the action led_rgb (epuckrt.h)
 * over the firmware's set_rgb_led (e-puck2_main-processor src/leds.h; on
 * the host host/stub_devices.c, which traces the colour).  The e-puck has
 * none: the checker refuses led_rgb for the dspic target (E070) and this
 * file is not in its project.
 */
#include "rt_clock.h"

#include "leds.h"

static uint8_t percent(int v)
{
    return (uint8_t)(v < 0 ? 0 : v > RGB_MAX_INTENSITY ? RGB_MAX_INTENSITY : v);
}

void action_led_rgb(void *param)
{
    const param_led_rgb *p = (const param_led_rgb *)param;

    if (p == NULL || p->led < 0 || p->led >= NUM_RGB_LED)
        return;
    set_rgb_led((rgb_led_name_t)p->led, percent(p->red), percent(p->green), percent(p->blue));
}

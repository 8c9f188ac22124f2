/* The e-puck2 firmware's epuck1x layer keeps e_led.h at this path
 * (src/epuck1x/motor_led/advance_one_timer/) with the e-puck library's
 * prototypes: the same declarations (see ../../../epuck_api/README.md). */
#include "../../../epuck_api/motor_led/e_led.h"

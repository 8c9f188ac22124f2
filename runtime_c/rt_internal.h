/*
 * rt_internal.h - the base of the runtime's own headers, which nothing
 * outside the runtime sees: the e-puck library's headers and the bit planes
 * of the static tables.  Each core file's header builds on the headers of
 * the layers below it (docs/runtime.md, "The layers of the core"):
 *
 *   rt_clock.h     the ms clock, the poll count, the device hook
 *   rt_sensors.h   the standard events, the timer, the sensors
 *   rt_registry.h  the arrays and the table, priorities, modes, holds, what runs now
 *   rt_odometry.h  the geometry and the odometry
 *   rt_motion.h    motion and the sequencer
 *   rt_modes.h     modes
 *
 * rt_lang.c builds on rt_registry.h; the walk (epuckrt.c) and rt_idle.c on
 * rt_modes.h; the devices on rt_clock.h.  Every name in them starts with
 * rt_ (or RT_), so none can clash with the user's C that is linked with the
 * runtime.  epuckrt.h stays the paper's API.
 */
#ifndef RT_INTERNAL_H
#define RT_INTERNAL_H

#include <stddef.h>

#include "epuckrt.h"
#include "rt_platform.h"

#include "motor_led/e_init_port.h"
#include "motor_led/advance_one_timer/e_motors.h"
#include "motor_led/advance_one_timer/e_agenda.h"
#include "a_d/advance_ad_scan/e_prox.h"
#include "a_d/advance_ad_scan/e_ad_conv.h"
#include "a_d/advance_ad_scan/e_micro.h"
#include "a_d/advance_ad_scan/e_acc.h"
#ifdef EPUCKRT_EPUCK2
#include "motor_led/advance_one_timer/e_led.h"     /* the e-puck2's epuck1x layer */
#else
#include "motor_led/e_led.h"
#endif
#include "motor_led/advance_one_timer/e_remote_control.h"
#include "codec/e_sound.h"
#include "utility/utility.h"

/* Bit planes of the static tables: bit k % 16 of word k / 16 for entry k. */
#define WORD_MASK 0xFFFFu
#define BIT_OF(k) (1u << ((unsigned)(k) & 15u))
#define BIT_GET(plane, k) (((plane)[(k) >> 4] & BIT_OF(k)) != 0)
#define BIT_SET(plane, k) ((plane)[(k) >> 4] |= BIT_OF(k))
#define BIT_CLEAR(plane, k) ((plane)[(k) >> 4] &= ~BIT_OF(k))

#endif

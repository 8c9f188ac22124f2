/*
 * rt_internal.h - what the runtime's files share and nothing else sees:
 * the e-puck library's headers, the bit planes of the static tables, and
 * the state and helpers one concern keeps and another reads.  Every name
 * here starts with rt_ (or RT_), so none can clash with the user's C that is
 * linked with the runtime.  epuckrt.h stays the paper's API.
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

/* Extension state of each event of the arrays, kept beside the paper's
 * struct: its priority (set_event_priority) and mode (set_event_mode, 0:
 * none).  A table event's are in its rt_event. */
struct rt_event_ext {
    int priority;
    int mode;
    int hold;       /* holds the motors by its condition or guard */
};

/* Motion: at most one at a time.  Progress is measured from the 16-bit step
 * counters at each poll and accumulated in long. */
enum { WATCH_BOTH, WATCH_LEFT, WATCH_RIGHT };
struct rt_motion {
    int active;     /* 1 from its start until its target is reached */
    int watch;      /* which wheel's progress ends it (BOTH: the larger) */
    long target;    /* steps, >= 0 */
    long left;      /* signed steps turned since the start */
    long right;
    int owner;      /* event whose action started it (-1: none); the
                       motors are its until the motion ends */
    int endless;    /* set_speed: no target; a sequence does not wait for it */
};

/* ---- shared state and helpers, by the file that defines them ---- */

/* epuckrt.c: registry, static tables, clock, main loop */
extern int rt_s_events;   /* the static table's events: ids 0..rt_s_events-1 */
extern struct rt_event_ext rt_event_ext[MAX_EVENTS];
extern event rt_events[MAX_EVENTS];
extern int rt_n_events;
extern const rt_program *rt_prog;   /* NULL: none registered */
extern unsigned *rt_ev_armed;   /* the event is armed (valid_flag) */
extern unsigned *rt_ev_latch;   /* compiled condition at its last poll */
extern unsigned *rt_ev_dead;   /* cancel_event: not re-armed by enter_mode */
extern unsigned *rt_ev_hold;   /* holds the motors by its condition or guard */
int rt_event_priority(int id);
int rt_hold_kind(int id);   /* RT_HOLD_WHILE, RT_HOLD_GUARD or 0 */
void rt_holds_update(void);   /* before the walk: conditions that became false let go */
int rt_event_mode(int id);
extern int rt_initialised;
extern int rt_remote_started;   /* e_init_remote_control() has run */
extern int rt_accel_wanted;   /* an event_tap or event_tilt was registered */
/* Counts the changes a poll can make to what the next poll sees: an event
 * fired, a sequence's step ran, a motion ended, a hold began or ended.  A
 * poll that left it as it was changed nothing but time (rt_idle.c). */
extern unsigned rt_stir;
extern int rt_looping;   /* mainloop is polling */
extern int rt_exit_requested;   /* set by exit_main, checked by mainloop */
extern int rt_current_action_id;   /* the action being run by mainloop */
extern int rt_current_event_id;   /* the event whose action runs (-1: none) */
extern int rt_current_rearmed;   /* its action entered its mode again: it stays armed */
extern int rt_firing_event;   /* the event whose action mainloop runs (-1: none) */
extern int rt_polled_event;   /* the event whose function was called last */
extern unsigned long rt_poll_count;   /* polls so far: readings are read once in each */
/* A device that works at every poll (rt_comm.c: its transmitter and
 * receiver) sets this at its first use; the poll calls it first.  NULL:
 * none, and the core links without the device's files. */
extern void (*rt_device_poll)(void);
/* Set with it: 1 when the device's poll would change nothing while the
 * inputs stay as they are (rt_idle.c); NULL: unknown. */
extern int (*rt_device_idle)(void);

/* rt_motion.c: motion and the sequencer */
extern struct rt_motion rt_motion;
/* Traces who holds the motors when that changed since it last did (after
 * any change of rt_motion.active or .owner); rt_motors_retrace traces it
 * again at mainloop's start (a trace opens there). */
void rt_motors_changed(void);
void rt_motors_retrace(void);
extern int rt_last_left;   /* raw counters at the previous poll */
extern int rt_last_right;
extern int rt_seen_moving;
extern int rt_stop_sample;   /* the stop_motor condition of this poll */
extern const param_sequence *rt_seq;   /* NULL: none */
extern int rt_seq_event_id;   /* the event whose action started it */
extern int rt_seq_waiting;   /* a step's motion is under way */
extern unsigned rt_seq_generation;   /* changes when a sequence replaces one */
extern int rt_seq_delay;   /* a wait step runs: the sequence goes on at rt_seq_until */
extern long rt_seq_until;
extern long rt_geo_circumference_um;   /* the geometry (set_robot_geometry) */
extern long rt_geo_axle_um;
extern long rt_geo_steps_per_rev;
void rt_wheels(int left, int right);
extern int rt_holds;   /* events holding the motors by their condition or guard */
void rt_hold_release(int id);
void rt_holds_release(int mode);   /* those of the events of `mode`; all: -1 */
int rt_next_holder(int id);   /* the first event from id on that holds by its condition or guard */
void rt_motion_update(void);
int rt_motion_idle(void);   /* an idle poll's phase (2); 0: the motion would end */
void rt_sequence_advance(void);

/* rt_lang.c: the rule language's expressions, odometry, random numbers */
void rt_odometry(long dl, long dr);   /* the wheels' steps of this poll */
extern int rt_odometry_used;   /* the program reads x, y or heading */

/* rt_math.c: integer atan2, hypot, sqrt, sin, cos: declared in epuckrt.h */

/* rt_sensors.c: standard events, sensors and devices */
extern int rt_timer_running;   /* set_timer ran, reset_timer did not since */
extern long rt_timer_start;   /* rt_millis() at set_timer */
extern int rt_sensors_on;
extern int rt_sensors_starting;   /* start_sensor ran: on from the next poll */
extern int rt_prox[8];
extern unsigned rt_prox_valid;
void rt_read_prox(unsigned mask);
void rt_accel_sample(void);

/* rt_modes.c: modes */
extern int rt_current_mode;
extern int rt_mode_entered_in_poll;
extern int rt_mode_entry_pending;   /* a mode was entered: its `on enter` events go first */
extern int rt_mode_trace_pending;   /* enter_mode before mainloop */
extern int rt_mode_arm_pending;   /* the current mode's table events wait to be armed */
void rt_mode_arm(void);

#endif

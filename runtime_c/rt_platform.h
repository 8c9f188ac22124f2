/*
 * rt_platform.h - the runtime's internal platform interface (not for user
 * programs).  The core (epuckrt.c) drives the hardware only through the
 * e-puck library API; what differs between the robot and the host harness
 * is behind these few functions:
 *
 *   platform_robot.c      on the e-puck: wait for the 1 ms tick; no trace
 *                         (with EPUCKRT_TRACE: rt_trace.c's, below).
 *   platform/platform_host.c  on a PC: virtual time, virtual robot, trace.
 */
#ifndef RT_PLATFORM_H
#define RT_PLATFORM_H

/* Called once, by the core, after the e-puck library has been initialised
 * (e_init_port, agendas, motors, A/D scan) and the 1 ms clock agenda started. */
void rt_platform_init(void);

/* Called once at the start of every poll cycle.  Robot: returns when the
 * millisecond clock has ticked since the previous call.  Host: advances the
 * virtual robot and virtual time by exactly 1 ms (the agendas run, so the
 * core's clock ticks); may end the process when the time limit is reached. */
void rt_platform_idle(void);

/* Trace hooks, called by the core.  step is -1 for an action run by an event;
 * for a step of a sequence it is the step index (0-based; the trace shows
 * it from 1) and steps the step count
 * (action_id is then the sequence action's id). */
void rt_trace_event(int event_id);
void rt_trace_action(int action_id, int step, int steps);
void rt_trace_exit(void);
/* Extension (priorities and modes): a motor command of event_id's action
 * suppressed because owner_event_id's motion of higher priority runs;
 * command is "start_straight", "start_curve", "stop_motor" or
 * "run_sequence".  And a change of the current mode (0: none). */
void rt_trace_suppressed(int event_id, int priority, int owner_event_id,
                         int owner_priority, const char *command);
void rt_trace_mode(int mode);
/* Extension (the rule language): variable `id` changed to `value`. */
void rt_trace_set(int id, int value);
/* Extension (pictures of a run): who holds the motors changed.  active 0:
 * no motion runs (the motors are free); else the motion in progress belongs
 * to owner_event_id's action (-1: started outside any event, by main). */
void rt_trace_motors(int active, int owner_event_id);

/* Registration and names, for the trace.  The core calls rt_new_action /
 * rt_new_event at each registration (the host names standard functions
 * after themselves, e.g. "start_straight"; the function tables stay out of
 * the robot build), and rt_name_action / rt_name_event for name_action /
 * name_event (the host copies the string; NULL: back to "action#<id>").
 * The robot ignores all four. */
#include "epuckrt.h"
void rt_new_action(int action_id, action_func f);
void rt_new_event(int event_id, event_func f);
void rt_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev);
void rt_name_action(int action_id, const char *name);
void rt_name_steps(int action_id, const char *const *names, int count);
void rt_name_event(int event_id, const char *name);
void rt_name_mode(int mode, const char *name);
void rt_name_var(int id, const char *name);
/* The seed of `random` at start: the host's from EPUCK_SEED (default 1),
 * the robot's from the sensors' noise. */
unsigned long rt_platform_seed(void);

/* Provided by the core: milliseconds since the runtime was initialised,
 * counted by a 1 ms e-puck agenda; 0 before.  Wraps to 0 after 2^31-1 ms
 * (24.8 days). */
long rt_millis(void);
/* Provided by the core: one millisecond more on that clock.  The core's
 * 1 ms agenda calls it where the e-puck library runs agendas (the e-puck,
 * the host); a platform whose library has none calls it itself (the
 * e-puck2's epuck1x layer: platform_epuck2.c). */
void rt_clock_tick(void);
/* Provided by the core: k >= 0 milliseconds more at once, as k calls of
 * rt_clock_tick would make them (for a host that advances several ms at
 * once: stub_agendas_ms). */
void rt_clock_ticks(long k);

/* Provided by the core (rt_idle.c) to a platform that simulates time (the
 * host's), which may call it at the start of each poll cycle, before it
 * advances time: the number n >= 1 of ms from now to the first poll that
 * can do more than count; the polls of the n - 1 ms before it would change
 * nothing but time, provided the inputs stay as they are and neither wheel
 * makes *left (*right) steps or more (0: no such bound) — the poll of the
 * ms where that happens must run.  The platform that advanced k ms at once
 * says so with rt_idle_skipped(k - 1): the polls it did not run.  In the
 * host builds only (docs/runtime.md, "Idle polls in bulk"). */
long rt_idle_horizon(long *left, long *right);
void rt_idle_skipped(long polls);
/* 1 when the platform must advance the skipped ms one at a time and hand
 * each to rt_idle_ms (the program reads the odometry, which sums the steps
 * of every poll), which measures the wheels as that ms's poll would and
 * returns 0 when the poll must run after all (the motion ends in it). */
int rt_idle_each_ms(void);
int rt_idle_ms(void);

/* ---- The robot's trace (rt_trace.c; `epuckc build --trace`) --------------
 * With EPUCKRT_TRACE defined, the trace hooks above are rt_trace.c's: each
 * record is encoded compactly (ids, raw values, the ms clock, the wheels'
 * step counters), framed (COBS, a CRC-16 each) and queued in a bounded ring
 * that the link drains; the poll never waits for the link, and what does
 * not fit is dropped and counted (docs/runtime.md, "The robot's trace").
 * The hooks below reach it from the core and the devices; without
 * EPUCKRT_TRACE they are nothing at all (not even their arguments are
 * evaluated), and rt_trace.c is not built. */
#ifdef EPUCKRT_TRACE
void rt_tracer_poll(void);          /* once a poll: periodic frames, the link */
void rt_tracer_poll_end(void);      /* a poll ends: the LEDs that changed in it */
void rt_tracer_led(int led, int value);     /* led 0..7, SET_LED_ALL, _BODY, _FRONT */
void rt_tracer_sound(int sound);            /* SOUND_HAA .. */
void rt_tracer_send(int value);             /* a message went on the air */
void rt_tracer_message(int value, int bearing, int range);  /* one was received */
void rt_tracer_timeout(void);       /* a time limit (the 16-bit simulator's) */
/* The link, one file per platform: rt_trace_uart1.c (the e-puck's UART1,
 * and the 16-bit simulator's model of it), rt_trace_chibios.c (the
 * e-puck2's UART3 or USB serial).  start: once, before the first send;
 * busy: nonzero while the bytes of the last send are still being read
 * from the ring; send: takes up to n bytes (the count it took) that stay
 * in place until busy is 0; wait: returns when the link has moved on (the
 * piece in flight sent, or about a millisecond passed), for the end of the
 * run, which empties the ring. */
void rt_trace_port_start(void);
int rt_trace_port_busy(void);
int rt_trace_port_send(const unsigned char *bytes, int n);
void rt_trace_port_wait(void);
#define RT_TRACE_POLL() rt_tracer_poll()
#define RT_TRACE_POLL_END() rt_tracer_poll_end()
#define RT_TRACE_LED(led, value) rt_tracer_led((led), (value))
#define RT_TRACE_SOUND(sound) rt_tracer_sound(sound)
#define RT_TRACE_SEND(value) rt_tracer_send(value)
#define RT_TRACE_MESSAGE(value, bearing, range) rt_tracer_message((value), (bearing), (range))
#else
#define RT_TRACE_POLL() ((void)0)
#define RT_TRACE_POLL_END() ((void)0)
#define RT_TRACE_LED(led, value) ((void)0)
#define RT_TRACE_SOUND(sound) ((void)0)
#define RT_TRACE_SEND(value) ((void)0)
#define RT_TRACE_MESSAGE(value, bearing, range) ((void)0)
#endif

#endif /* RT_PLATFORM_H */

/*
 * rt_registry.h - what is registered (rt_registry.c): the arrays and the
 * static table, each event's priority, mode and hold, the current mode, and
 * which event's action runs now.  Builds on rt_sensors.h.  The walk
 * (epuckrt.c) reads and writes the bit planes and the arrays' events in
 * place, sixteen events a word, and rt_idle.c reads them; every other file
 * changes what is registered through the functions below.
 */
#ifndef RT_REGISTRY_H
#define RT_REGISTRY_H

#include "rt_sensors.h"

/* Extension state of each event of the arrays, kept beside the paper's
 * struct: its priority (set_event_priority) and mode (set_event_mode, 0:
 * none).  A table event's are in its rt_event. */
struct rt_event_ext {
    int priority;
    int mode;
    int hold;       /* holds the motors by its condition or guard */
};

/* The arrays' events: ids rt_s_events.. (the table's come first). */
extern event rt_events[MAX_EVENTS];
extern struct rt_event_ext rt_event_ext[MAX_EVENTS];
extern int rt_n_events;
/* The static table (register_program): NULL and 0 without one. */
extern const rt_program *rt_prog;
extern int rt_s_events;   /* the static table's events: ids 0..rt_s_events-1 */
extern unsigned rt_s_words;   /* RT_WORDS(rt_s_events) */
/* Its bit planes, one bit an event (rt_internal.h's BIT_ macros). */
extern unsigned *rt_ev_armed;   /* the event is armed (valid_flag) */
extern unsigned *rt_ev_repeat;   /* repeat_flag */
extern unsigned *rt_ev_latch;   /* compiled condition at its last poll */
extern unsigned *rt_ev_now;   /* compiled conditions of this poll (the walk's) */
extern unsigned *rt_ev_compiled;   /* the event is a compiled condition */
extern unsigned *rt_ev_hold;   /* holds the motors by its condition or guard */
/* 1 once any event has a priority or a mode: the walk goes by levels. */
extern int rt_ranked;

int rt_action_of(int id, action_func *f, void **param);   /* 0: cancelled */
int rt_event_priority(int id);
int rt_event_mode(int id);
int rt_hold_kind(int id);   /* RT_HOLD_WHILE, RT_HOLD_GUARD or 0 */

/* What runs now. */
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

/* The current mode (rt_modes.c enters one). */
extern int rt_current_mode;   /* 0: none */
extern int rt_mode_entered_in_poll;
extern int rt_mode_entry_pending;   /* a mode was entered: its `on enter` events go first */
extern int rt_mode_arm_pending;   /* the current mode's table events wait to be armed */
void rt_disarm_table_modes(void);   /* the table's events of every mode */
void rt_arm_table_mode(int mode);   /* as at registration, unless cancelled */
void rt_arm_array_mode(int mode);

/* Who holds the motors by a condition or guard (docs/runtime.md, "Holding
 * the motors"); motion (rt_motion.c) arbitrates with it. */
extern int rt_holds;   /* events holding the motors by their condition or guard */
void rt_hold_put(int id, int on);
void rt_hold_release(int id);
void rt_holds_release(int mode);   /* those of the events of `mode`; all: -1 */
int rt_next_holder(int id);   /* the first event from id on that holds by its condition or guard */

#endif

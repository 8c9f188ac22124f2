/*
 * rt_motion.h - motion and the sequencer (rt_motion.c), for modes and the
 * walk above them.  Builds on rt_registry.h and rt_odometry.h.
 */
#ifndef RT_MOTION_H
#define RT_MOTION_H

#include "rt_registry.h"
#include "rt_odometry.h"

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

extern struct rt_motion rt_motion;
/* Traces who holds the motors when that changed since it last did (after
 * any change of rt_motion.active or .owner); rt_motors_retrace traces it
 * again at mainloop's start (a trace opens there). */
void rt_motors_changed(void);
void rt_motors_retrace(void);
extern int rt_seen_moving;
extern const param_sequence *rt_seq;   /* NULL: none */
extern int rt_seq_waiting;   /* a step's motion is under way */
extern int rt_seq_delay;   /* a wait step runs: the sequence goes on at rt_seq_until */
extern long rt_seq_until;
void rt_wheels(int left, int right);
void rt_motion_update(void);
int rt_motion_idle(void);   /* an idle poll's phase (2); 0: the motion would end */
void rt_sequence_advance(void);
void rt_motion_loop_start(void);   /* mainloop starts: the counters as they are */
int rt_motion_stop_sample(void);   /* phase (4): moving at the last poll, at rest now */
void rt_motion_halt(void);   /* exit_main */
void rt_motion_leave_mode(int left);   /* the mode's sequence and motion end */

#endif

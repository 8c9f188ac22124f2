/*
 * enki_bridge.h - what a robot (its program, the runtime, platform_host.c
 * and the e-puck library over Enki, all in one shared object) and the Enki
 * world runner (world_runner.cpp) exchange.  One struct per robot, owned by
 * the runner; the robot's glue (robot_glue.c) gets a pointer to it.
 *
 * Time: the world steps every `step_ms` ms of virtual time.  Between two
 * world steps each robot runs `step_ms` poll cycles of its own (1 ms each,
 * as on the stub harness), counting its wheel steps; then it hands control
 * back to the runner (a coroutine switch), which turns those steps into
 * Enki wheel speeds, steps the world and hands back the new pose and
 * proximity readings.
 */
#ifndef ENKI_BRIDGE_H
#define ENKI_BRIDGE_H

#define ENKI_BRIDGE_VERSION 6
#define ENKI_MAX_SETTINGS 12
#define ENKI_MAX_SENT 16        /* values a robot sends in one world step, at most */
#define ENKI_MAX_INBOX 64       /* messages delivered to a robot in one world step */
#define ENKI_CAMERA_PIXELS 60   /* Enki's e-puck camera: 60 pixels over 60 degrees */

/* A message the world's channel delivered (world_channel.h): what libIrcom
 * reports (value, estimated distance, the receiving sensor's direction)
 * and, for the trace, who sent it from where. */
typedef struct enki_message {
    long value;
    double distance_cm;
    double direction_rad;           /* counter-clockwise from the heading, 0..2 pi */
    int sensor;
    const char *from;               /* the sender's name (the runner's) */
    double from_x_mm, from_y_mm;
} enki_message;

typedef struct enki_robot_io {
    /* What each world step reads and writes comes first, together (a few
     * cache lines for every robot at every step); the settings, the
     * camera's pixels and the inbox after it. */
    int version;                    /* ENKI_BRIDGE_VERSION */
    int step_ms;                    /* ms of virtual time per world step */

    /* robot -> world */
    int ms_in_window;
    int finished;                   /* main returned or exit() was called */
    int status;                     /* its value */
    int n_sent;                     /* values sent (ircomSend) in the world step */
    long window_left, window_right; /* wheel steps in the world step just ended */
    long pending_left, pending_right; /* steps Enki has not integrated yet */
    double mm_per_step, axle_mm;    /* the program's geometry */

    /* the runner's coroutine switch: back to the world until it has stepped
     * (never returns once `finished` is set) */
    void (*yield)(struct enki_robot_io *robot);
    void *runner;                   /* the runner's own data */

    /* world -> robot, at each world step */
    double x_mm, y_mm;              /* Enki's pose of the body (world frame) */
    double heading_rad;             /* counter-clockwise from +x */
    int prox[8];                    /* IR readings, library units 0..4095 */
    int distance_mm;                /* the ToF ray (VL53L0X_get_dist_mm) */
    int camera_on;                  /* (at attach) the world fills camera[] */
    int n_inbox;                    /* messages delivered in the world step */
    int message_frame_ms;           /* (at attach) one message's time on the air */
    long sent[ENKI_MAX_SENT];       /* robot -> world: the values sent */
    unsigned char camera[3 * ENKI_CAMERA_PIXELS];   /* r, g, b of each pixel, leftmost first */
    /* settings the robot's getenv() sees instead of the process
     * environment (EPUCK_TRACE, EPUCK_TIME_LIMIT_MS, ...); NULL-terminated
     * name/value pairs.  Any other EPUCK_* name reads as unset. */
    const char *settings[2 * ENKI_MAX_SETTINGS + 2];
    enki_message inbox[ENKI_MAX_INBOX];

    /* GCtronic's ground-sensor module and the microphones (world_ground.h,
     * world_sound.h), at each world step */
    int ground_on;                  /* (at attach) the world fills ground[] */
    int ground[3];                  /* world -> robot: what get_ground_prox reads */
    int mic[3];                     /* world -> robot: what each microphone hears of the world
                                       (e_get_micro_volume's units) */
    int sound_started;              /* robot -> world: 1 + the ms in the step at which a sample
                                       started playing (e_play_sound); 0: none */
    long sound_words;               /* its length in words */
} enki_robot_io;

#endif

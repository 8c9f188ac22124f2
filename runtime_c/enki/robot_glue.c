/*
 * robot_glue.c - the e-puck library over Enki, robot side.
 *
 * A robot of an Enki world is one shared object: the program, the runtime
 * (epuckrt.c), the host platform layer (platform/platform_host.c), the stub
 * e-puck library (host/epuck_stub.c: stepper motors with 16-bit counters,
 * agendas, proximity registers) and this file, linked with
 *
 *   -Wl,--wrap=stub_motors_1ms,--wrap=stub_motors_ms,--wrap=stub_motors_ms_end,
 *   -Wl,--wrap=stub_pose,
 *   -Wl,--wrap=stub_set_geometry
 *   -Wl,--wrap=getenv,--wrap=exit,--wrap=main -Wl,-Bsymbolic
 *   -Wl,--wrap=stub_set_observer,--wrap=stub_set_micro
 *
 * so that, without a change to any of those sources:
 *   - the wheels still step exactly as on the stub harness (the same
 *     e_set_speed_left/e_get_steps_left code), but every `step_ms` ms the
 *     steps made are handed to the world runner, which drives the robot's
 *     Enki body with them and steps the physics (stub_motors_ms, the
 *     idle ms in bulk, stops there too);
 *   - e_get_prox() reads what Enki's eight IR sensors measured (the runner
 *     writes them into the stub's proximity registers with stub_set_prox);
 *   - libIrcom's sends (host/stub_devices.c) go to the world's channel
 *     (world_channel.h) and the messages it delivered come back into the
 *     stub's queue; VL53L0X_get_dist_mm reads the world's ToF ray, and
 *     the camera (e_poxxxx) Enki's CircularCam;
 *   - get_ground_prox (host/stub_ground.c) reads Enki's ground sensors over
 *     the world's floor, and the microphones hear the world's sounds
 *     (world_sound.h), added to what a scenario gives them (stub_set_micro,
 *     wrapped); a sample the robot plays (the outputs' observer, wrapped)
 *     is told to the world, whose robots then hear it;
 *   - the pose in the trace is the Enki body's pose in the world frame, plus
 *     the steps the world has not integrated yet (dead reckoning);
 *   - getenv() sees this robot's own settings (trace file, time limit, ...);
 *   - exit() (time-out, bad setting) ends this robot only, not the process;
 *   - main starts from host/cmain.c's __wrap_main (a reset starts it again);
 *   - the gyroscope learns how far the world's physics turned the body
 *     beyond what the wheels' steps did (collisions, the wheels' noise).
 *
 * The robots of one program share its loaded object, each with its own
 * copy of the object's globals, which the runner swaps in while the robot's
 * code runs (robot_loader.h); -Bsymbolic binds the object's references to
 * its own definitions.
 */
#include <math.h>

#define GLUE_PI 3.14159265358979323846
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "enki_bridge.h"
#include "epuck_stub.h"
#include "stub_ground.h"

static enki_robot_io *io;
static double last_heading;         /* Enki's, at the last world step */

/* ---- sound: the world's, and the robot's own samples -------------------------------
 * A microphone hears the world (io->mic, at each step) and what a scenario
 * sets (stub_set_micro from outside this file): the two volumes add, as
 * the peaks of two sounds can meet, up to the 12 bits. */
#define GLUE_MAX_VOLUME 4095
void __real_stub_set_micro(int n, int volume);
void __real_stub_set_observer(stub_observer f);
static int scenario_mic[3];
static stub_observer next_observer;

static void set_micro(int n)
{
    long v = (long)scenario_mic[n] + io->mic[n];
    __real_stub_set_micro(n, (int)(v > GLUE_MAX_VOLUME ? GLUE_MAX_VOLUME : v));
}

void __wrap_stub_set_micro(int n, int volume)
{
    if (n < 0 || n > 2)
        return;
    scenario_mic[n] = volume;
    set_micro(n);
}

/* Every output the platform observes goes on to it; a sample that starts
 * ("sound", its name, its length in words) is the world's too. */
static void observe(const char *device, const char *name, int value)
{
    if (strcmp(device, "sound") == 0) {
        io->sound_started = io->ms_in_window + 1;
        io->sound_words = value;
    }
    if (next_observer != NULL)
        next_observer(device, name, value);
}

void __wrap_stub_set_observer(stub_observer f)
{
    next_observer = f;
    __real_stub_set_observer(observe);
}

/* What the world measured in its last step: the ground and the sounds. */
static void take_world_inputs(void)
{
    int n;
    if (io->ground_on)          /* else the stub's white paper (open ground) */
        for (n = 0; n < 3; n++)
            stub_set_ground(n, io->ground[n]);
    for (n = 0; n < 3; n++)
        set_micro(n);
}

void __real_stub_motors_1ms(void);
void __real_stub_set_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev);
char *__real_getenv(const char *name);

/* The runner's hook: called once, before the robot's main runs. */
int enki_robot_attach(enki_robot_io *robot)
{
    int n;
    if (robot == NULL || robot->version != ENKI_BRIDGE_VERSION)
        return 1;
    io = robot;
    last_heading = io->heading_rad;
    for (n = 0; n < 8; n++)
        stub_set_prox(n, io->prox[n]);
    stub_set_distance(io->distance_mm);
    stub_set_camera(io->camera, ENKI_CAMERA_PIXELS);
    stub_ircom_set_frame_ms(io->message_frame_ms);
    take_world_inputs();
    if (next_observer == NULL)          /* the platform sets its own later, through the wrap */
        __real_stub_set_observer(observe);
    return 0;
}

/* Hand control to the world; returns when it has stepped: the body turned
 * by what Enki says, beyond what the steps it integrated would have (the
 * gyroscope's correction, imu.c). */
static void yield_to_world(void)
{
    int n;
    double turned, stepped;
    /* what the step about to be taken integrates: the steps pending now */
    long left = io->pending_left, right = io->pending_right;
    io->n_sent = stub_ircom_take_sent(io->sent, ENKI_MAX_SENT);
    io->yield(io);
    turned = fmod(io->heading_rad - last_heading, 2.0 * GLUE_PI);
    if (turned > GLUE_PI)
        turned -= 2.0 * GLUE_PI;
    else if (turned < -GLUE_PI)
        turned += 2.0 * GLUE_PI;
    stepped = (double)(right - left) * io->mm_per_step / io->axle_mm;
    last_heading = io->heading_rad;
    stub_set_turn_correction((turned - stepped) * 180.0 / GLUE_PI * 1000.0 / (double)io->step_ms);
    for (n = 0; n < 8; n++)
        stub_set_prox(n, io->prox[n]);
    stub_set_distance(io->distance_mm);
    if (io->camera_on)          /* else the pixels stay as they were: black */
        stub_set_camera(io->camera, ENKI_CAMERA_PIXELS);
    take_world_inputs();
    for (n = 0; n < io->n_inbox; n++) {
        const enki_message *m = &io->inbox[n];
        stub_ircom_receive(m->value, m->distance_cm, m->direction_rad, m->sensor, m->from,
                           m->from_x_mm, m->from_y_mm);
    }
    io->n_inbox = 0;
}

void __wrap_stub_motors_1ms(void)
{
    long l = stub_total_steps_left(), r = stub_total_steps_right();
    __real_stub_motors_1ms();
    io->window_left += stub_total_steps_left() - l;
    io->window_right += stub_total_steps_right() - r;
    if (++io->ms_in_window >= io->step_ms)
        yield_to_world();
}

/* Several ms at once (rt_idle.c): never past the end of the world's step;
 * when they end it, the world steps at stub_motors_ms_end, once the host's
 * clock is at the last of them (what it hands over is traced then). */
long __real_stub_motors_ms(long n, long left, long right);
long __wrap_stub_motors_ms(long n, long left, long right)
{
    long l = stub_total_steps_left(), r = stub_total_steps_right(), done;
    long room = (long)(io->step_ms - io->ms_in_window);
    done = __real_stub_motors_ms(n < room ? n : room, left, right);
    io->window_left += stub_total_steps_left() - l;
    io->window_right += stub_total_steps_right() - r;
    io->ms_in_window += (int)done;
    return done;
}

void __wrap_stub_motors_ms_end(void)
{
    if (io->ms_in_window >= io->step_ms)
        yield_to_world();
}

void __wrap_stub_set_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev)
{
    __real_stub_set_geometry(wheel_circumference_um, axle_um, steps_per_rev);
    io->mm_per_step = (double)wheel_circumference_um / 1000.0 / (double)steps_per_rev;
    io->axle_mm = (double)axle_um / 1000.0;
}

void __wrap_stub_pose(double *x_mm, double *y_mm, double *heading_deg)
{
    /* the steps not yet in Enki's pose, as one arc from its heading */
    double dl = (double)(io->pending_left + io->window_left) * io->mm_per_step;
    double dr = (double)(io->pending_right + io->window_right) * io->mm_per_step;
    double dth = (dr - dl) / io->axle_mm;
    double ds = (dl + dr) / 2.0;
    double mid = io->heading_rad + dth / 2.0;
    double h = fmod(io->heading_rad + dth, 2.0 * GLUE_PI);
    if (h > GLUE_PI)
        h -= 2.0 * GLUE_PI;
    else if (h <= -GLUE_PI)
        h += 2.0 * GLUE_PI;
    *x_mm = io->x_mm + ds * cos(mid);
    *y_mm = io->y_mm + ds * sin(mid);
    *heading_deg = h * 180.0 / GLUE_PI;
}

/* Before the runner attaches the robot (a constructor, a sanitizer's
 * start), there are no settings of its own yet: the process's. */
char *__wrap_getenv(const char *name)
{
    int i;
    if (io == NULL)
        return __real_getenv(name);
    for (i = 0; io->settings[i] != NULL; i += 2)
        if (strcmp(io->settings[i], name) == 0)
            return (char *)io->settings[i + 1];
    if (strncmp(name, "EPUCK_", 6) == 0)
        return NULL;
    return __real_getenv(name);
}

void __real_exit(int status);
void __wrap_exit(int status)
{
    if (io == NULL)             /* (not attached: no robot to end) */
        __real_exit(status);
    io->status = status;
    io->finished = 1;
    io->yield(io);
    abort();    /* a finished robot is never resumed */
}

/*
 * robot_glue.c - the e-puck library over Enki, robot side.
 *
 * A robot of an Enki world is one shared object: the program, the runtime
 * (epuckrt.c), the host platform layer (host/platform_host.c), the stub
 * e-puck library (host/epuck_stub.c: stepper motors with 16-bit counters,
 * agendas, proximity registers) and this file, linked with
 *
 *   -Wl,--wrap=stub_motors_1ms,--wrap=stub_motors_ms,--wrap=stub_motors_ms_end,
 *   -Wl,--wrap=stub_pose,
 *   -Wl,--wrap=stub_set_geometry
 *   -Wl,--wrap=getenv,--wrap=exit -Wl,-Bsymbolic
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
 *   - the pose in the trace is the Enki body's pose in the world frame, plus
 *     the steps the world has not integrated yet (dead reckoning);
 *   - getenv() sees this robot's own settings (trace file, time limit, ...);
 *   - exit() (time-out, bad setting) ends this robot only, not the process.
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

static enki_robot_io *io;

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
    for (n = 0; n < 8; n++)
        stub_set_prox(n, io->prox[n]);
    stub_set_distance(io->distance_mm);
    stub_set_camera(io->camera, ENKI_CAMERA_PIXELS);
    stub_ircom_set_frame_ms(io->message_frame_ms);
    return 0;
}

/* Hand control to the world; returns when it has stepped. */
static void yield_to_world(void)
{
    int n;
    io->n_sent = stub_ircom_take_sent(io->sent, ENKI_MAX_SENT);
    io->yield(io);
    for (n = 0; n < 8; n++)
        stub_set_prox(n, io->prox[n]);
    stub_set_distance(io->distance_mm);
    if (io->camera_on)          /* else the pixels stay as they were: black */
        stub_set_camera(io->camera, ENKI_CAMERA_PIXELS);
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

char *__wrap_getenv(const char *name)
{
    int i;
    for (i = 0; io->settings[i] != NULL; i += 2)
        if (strcmp(io->settings[i], name) == 0)
            return (char *)io->settings[i + 1];
    if (strncmp(name, "EPUCK_", 6) == 0)
        return NULL;
    return __real_getenv(name);
}

void __wrap_exit(int status)
{
    io->status = status;
    io->finished = 1;
    io->yield(io);
    abort();    /* a finished robot is never resumed */
}

/*
 * epuck_stub.h - the host side of the e-puck library's simulation (the
 * files of resources.py's LIBRARY_SIMULATION: epuck_stub.c, outputs.c,
 * sound.c, imu.c, camera.c, stub_devices.c, epuck_more.c, dspic.c,
 * unsimulated.c): the calls the platforms (platform_host.c, cmain.c,
 * platform_int16.c, the Enki glue) make to drive the virtual robot.  User
 * programs and the core use only the e-puck library API (../epuck_api/).
 */
#ifndef EPUCK_STUB_H
#define EPUCK_STUB_H

/* ---- time ------------------------------------------------------------------
 * The simulated ms ends at `now_ms`: the library's devices move on (the
 * codec's interrupts, the A/D's ticks) and the outputs' records are
 * written (below).  Every platform calls it once a simulated ms, before
 * its clock passes it; stub_devices_ms for `n` of them at once (the idle
 * polls in bulk). */
void stub_devices_ms(long now_ms, long n);
/* The first ms at whose stub_devices_ms a device changes what the program
 * reads without an input being set (a frame of the camera ready); -1:
 * none coming.  A platform that advances several ms at once stops there. */
long stub_devices_next_ms(void);

/* Main's clock in the dsPIC's cycles (FCY 14.7456 MHz): stub_clock_hook's,
 * which cmain.c (the C main model) and platform_int16.c set; without one,
 * the last ms stub_devices_ms was told of.  stub_wait_cycles: main spends
 * that many cycles waiting (a device busy), through stub_cost_hook. */
#define STUB_CYCLES_PER_MS 14746L
#define STUB_FCY 14745600UL
extern unsigned long long (*stub_clock_hook)(void);
unsigned long long stub_now_cycles(void);
/* ms * STUB_FCY / 1000, exact, in 32-bit arithmetic but one product */
unsigned long long stub_ms_cycles(long ms);
/* Main's own clock (cycles its C spent), also while the simulator steps or
 * the rules poll (which take none of it): stub_main_hook's (cmain.c,
 * platform_int16.c); 0 without one. */
extern unsigned long long (*stub_main_hook)(void);
void stub_wait_cycles(long cycles);

/* Advance the wheels by 1 ms at the commanded speeds (steps are whole:
 * a wheel at s steps/s steps every 1000/s ms), update the pose. */
void stub_motors_1ms(void);
/* Run the active agendas for 1 ms (10 agenda ticks of 0.1 ms) when agenda
 * processing has been started. */
void stub_agendas_1ms(void);
/* Several ms at once, for a host that skips idle polls (rt_idle.c):
 * stub_motors_ms advances the wheels as n calls of stub_motors_1ms would,
 * but stops after the ms in which the left wheel made its `left`-th step
 * or the right one its `right`-th (0: no such stop); returns the ms
 * advanced (1..n); stub_motors_ms_end follows once the host's clock is at
 * the last of them (a world steps there when they end its step: the glue
 * wraps both).  stub_agendas_ms runs the agendas as n calls of
 * stub_agendas_1ms would; when stub_agendas_count_only(clock), every agenda
 * that processing calls is `clock` (the runtime's, which only counts ms) or
 * one that the stub made with stub_activate_counter (its own, which only
 * counts: libIrcom's frame on the air), and their calls are made agenda
 * after agenda, at once: `clock`'s k calls as one call of clock_ticks(k),
 * which does what they do. */
long stub_motors_ms(long n, long left, long right);
void stub_motors_ms_end(void);
/* A count of the calls of the inputs' setters (stub_set_prox ... and the
 * devices' of stub_devices.c, which call stub_input_set): what a reading
 * gives may have changed since it last was what it is now. */
unsigned long stub_inputs_epoch(void);
void stub_input_set(void);
int stub_agendas_count_only(void (*clock)(void));
void stub_agendas_ms(long n, void (*clock)(void), void (*clock_ticks)(long));
int stub_activate_counter(void (*func)(void), int cycle);
int stub_agendas_running(void);
int stub_ad_scan_running(void);
/* Set the reading of proximity sensor n (0..7). */
void stub_set_prox(int n, int value);
/* Total signed steps of each wheel since start (not wrapped). */
long stub_total_steps_left(void);
long stub_total_steps_right(void);
/* The wheels' commanded speeds (steps/s) and the geometry's mm a step
 * and axle (the gyroscope's rate of turn, imu.c). */
int stub_speed_left(void);
int stub_speed_right(void);
void stub_geometry(double *mm_per_step, double *axle_mm);
/* Odometry pose from the wheel steps with the default geometry: x, y in mm
 * (start 0,0 facing +x), heading in degrees in (-180, 180], positive = left. */
void stub_pose(double *x_mm, double *y_mm, double *heading_deg);
/* The geometry of the odometry (set_robot_geometry); defaults from epuckrt.h. */
void stub_set_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev);

/* The other simulated inputs, each holding until changed: the ambient
 * light of IR sensor n (0..7), the volume of microphone n (0..2), the
 * accelerometer's axis (0 the robot's left, 1 its front, 2 up) on the
 * scale of the e-puck's analog accelerometer that the library keeps on
 * the 1.3 (e_get_acc_filtered's: STUB_ACC_ZERO_G no acceleration,
 * STUB_ACC_ONE_G a g; at start a flat floor: 0, 0 and 1 g up), the rate
 * at which a hand turns the robot about its axis (0 x, 1 y, 2 z; degrees/s,
 * counter-clockwise seen from the axis's end), the selector (0..15); and a
 * key press on the remote control (lost unless e_init_remote_control ran). */
#define STUB_ACC_ZERO_G 2048
#define STUB_ACC_ONE_G 768
void stub_set_ambient(int n, int value);
void stub_set_micro(int n, int volume);
void stub_set_acc(int axis, int value);
void stub_set_hand_rate(int axis, int dps);
void stub_set_selector(int position);
void stub_press_key(int key);

/* ---- the outputs' records (outputs.c) ------------------------------------------
 * LED n (0..7 ring, 9 body, 10 front) is on: its pin's latch (LED0 is
 * _LATA6 ...).  The observer is told of each change of the robot's
 * outputs: the LEDs ("led", "led3" | "all" | "body" | "front", its new
 * state; "all" when the eight of the ring changed, with led0's state)
 * when they differ from what it was last told: before any other record,
 * as they are (stub_outputs_flush, which the platforms' record writers
 * call), and at the end of each simulated ms, lit if on for a tenth of
 * it (stub_outputs_ms_end, which the platforms call before their clock
 * passes it); every sound that starts ("sound", the
 * sample's name, its length in words), and the devices' records of
 * stub_devices.c ("send", "message", "rgb", with their JSON keys as name).
 * So the trace grows with what the robot does, not with how often a
 * program sets its LEDs. */
int stub_led(int n);
typedef void (*stub_observer)(const char *device, const char *name, int value);
void stub_set_observer(stub_observer f);
void stub_observe(const char *device, const char *name, int value);
void stub_outputs_flush(void);
void stub_outputs_ms_end(void);
/* The LEDs' pins as they are now were so from now on (the library wrote
 * them itself, e_display_angle; main calls the library, cmain.c: what it
 * wrote before counts from then). */
void stub_outputs_mark(void);
/* The run ends: what is still to be told (a UART's line not ended yet),
 * before the record that closes the trace. */
void stub_outputs_end(void);

/* The devices of host/stub_devices.c: libIrcom's IR messages and the
 * e-puck2's ToF sensor.  A send is on the air for stub_ircom_set_frame_ms
 * ms (STUB_IRCOM_FRAME_MS at start; counted by an agenda), a "send"
 * record (host_record); stub_ircom_take_sent gives the world the values
 * sent since it last asked (at most `max`).  stub_ircom_receive puts a
 * message in libIrcom's queue (20; full: the oldest goes), a "message"
 * record, with its readable line like every other record's.  stub_set_distance: what VL53L0X_get_dist_mm
 * reads (STUB_DISTANCE_NONE at start: nothing in range). */
#define STUB_IRCOM_FRAME_MS 100
#define STUB_DISTANCE_NONE 8190
void stub_ircom_set_frame_ms(int ms);
int stub_ircom_take_sent(long *values, int max);
void stub_ircom_receive(long value, double distance_cm, double direction_rad, int sensor,
                        const char *from, double from_x_mm, double from_y_mm);
void stub_set_distance(int mm);
/* What the camera sees (camera.c): `pixels` (at most STUB_CAMERA_PIXELS)
 * r, g, b triples, 0..255, leftmost first, over the middle 60 degrees of
 * its field (Enki's camera: a degree a pixel). */
#define STUB_CAMERA_PIXELS 60
void stub_set_camera(const unsigned char *rgb, int pixels);
/* The gyroscope (imu.c): what the world's physics turned the body by
 * beyond what its wheels' steps did, in degrees/s over the last world step
 * (collisions, wheel noise); 0 on the stub harness alone. */
void stub_set_turn_correction(double dps);

/* ---- the C main model (cmain.c, docs/runtime.md) ----------------------------
 * The dsPIC's time for what main does between the simulator's steps: its
 * library calls and busy loops call stub_cost_hook(count, cycles_each),
 * which cmain.c sets (NULL elsewhere, e.g. the AVR trace build: no cost).
 * STUB_WAIT_LOOP_CYCLES: one turn of the library's busy loop over a long
 * (`for (i = 0; i < num; i++);`: XC16 -O1 keeps i in two registers:
 * add, addc, sub, subb and a taken branch, 6 cycles); STUB_CALL_CYCLES: a
 * library call that reads or sets a variable of the library (call, body,
 * return). */
#define STUB_WAIT_LOOP_CYCLES 6
#define STUB_CALL_CYCLES 20
extern void (*stub_cost_hook)(long count, int cycles_each);

/* The chip's instructions that programs write inline (dspic.c: codes of
 * epuck_dspic_execute, build/dspic_asm.py), carried out by
 * stub_chip_hook (cmain.c; none: nothing happens): a reset starts main
 * again, after stub_reset_library put the library's simulation (the
 * registers, the devices, the agendas) back as at reset; sleep stops main
 * for good (stub_sleep_library: the agendas and the motors stop); idle
 * waits for the next interrupt. */
#define STUB_INSN_RESET 1
#define STUB_INSN_SLEEP 2
#define STUB_INSN_IDLE 3
void epuck_dspic_execute(int instruction);
void epuck_dspic_trap(void);        /* assembly: saves every register around it */
extern void (*stub_chip_hook)(int instruction);
void stub_reset_chip(void);
void stub_sleep_chip(void);
void stub_idle_chip(void);
void stub_reset_library(void);
void stub_sleep_library(void);
void stub_dspic_reset_registers(void);

/* Each file's state as at reset (stub_reset_library calls them). */
void stub_motors_reset(void);
void stub_outputs_reset(void);
void stub_sound_reset(void);
void stub_imu_reset(void);
void stub_camera_reset(void);
void stub_more_reset(void);

/* A call of what the simulation does not model (unsimulated.c): the run
 * ends, naming the function and its device (the platform's). */
#if defined(__GNUC__)
__attribute__((noreturn))
#endif
void stub_unsimulated(const char *function, const char *device);

/* platform_host.c, for cmain.c: called at every rt_platform_init (by
 * mainloop, or main's first call); virtual time; a record of another
 * file's (`extra`: more JSON keys; `line`: its readable line, or NULL). */
extern void (*host_init_hook)(void);
long host_now_ms(void);
void host_record(const char *kind, const char *name, const char *extra, const char *line);
/* The run ends with `status` (exit(), which a world's glue makes this
 * robot's end), the trace closed with a record of `kind`. */
#if defined(__GNUC__)
__attribute__((noreturn))
#endif
void host_stop(const char *kind, const char *name, const char *extra, const char *line,
               int status);

/* cmain.c: a tick of its timers, which the Enki world runner gives the
 * robot that runs (its robots share the process's timers). */
void epuck_cmain_signal(int wall);

#endif

/*
 * epuck_stub.h - the host side of the stub e-puck library (epuck_stub.c):
 * the calls platform_host.c uses to drive the virtual robot.  User programs
 * and the core use only the e-puck library API (../epuck_api/).
 */
#ifndef EPUCK_STUB_H
#define EPUCK_STUB_H

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
/* Set the reading of proximity sensor n (0..7). */
void stub_set_prox(int n, int value);
/* Total signed steps of each wheel since start (not wrapped). */
long stub_total_steps_left(void);
long stub_total_steps_right(void);
/* Odometry pose from the wheel steps with the default geometry: x, y in mm
 * (start 0,0 facing +x), heading in degrees in (-180, 180], positive = left. */
void stub_pose(double *x_mm, double *y_mm, double *heading_deg);
/* The geometry of the odometry (set_robot_geometry); defaults from epuckrt.h. */
void stub_set_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev);

/* The other simulated inputs, each holding until changed: the ambient
 * light of IR sensor n (0..7), the volume of microphone n (0..2), the raw
 * accelerometer axis (0 x, 1 y, 2 z; STUB_ACC_REST at start), the selector
 * (0..15); and a key press on the remote control (lost unless
 * e_init_remote_control ran). */
#define STUB_ACC_REST 2048
void stub_set_ambient(int n, int value);
void stub_set_micro(int n, int volume);
void stub_set_acc(int axis, int value);
void stub_set_selector(int position);
void stub_press_key(int key);
/* The robot's outputs as the harness sees them: LED n (0..7 ring, 9 body,
 * 10 front) is on, and an observer called at every LED command ("led",
 * "led3" | "all" | "body" | "front", its new state) and every sound played
 * ("sound", the sample's name, its length in words). */
int stub_led(int n);
typedef void (*stub_observer)(const char *device, const char *name, int value);
void stub_set_observer(stub_observer f);
void stub_observe(const char *device, const char *name, int value);

/* The devices of host/stub_devices.c: libIrcom's IR messages and the
 * e-puck2's ToF sensor.  A send is on the air for stub_ircom_set_frame_ms
 * ms (STUB_IRCOM_FRAME_MS at start; counted by an agenda), observed as
 * ("send", EXTRA, value); stub_ircom_take_sent gives the world the values
 * sent since it last asked (at most `max`).  stub_ircom_receive puts a
 * message in libIrcom's queue (20; full: the oldest goes), observed as
 * ("message", EXTRA, value).  EXTRA is the trace record's own keys in JSON
 * (", \"value\": 3, ...").  stub_set_distance: what VL53L0X_get_dist_mm
 * reads (STUB_DISTANCE_NONE at start: nothing in range). */
#define STUB_IRCOM_FRAME_MS 100
#define STUB_DISTANCE_NONE 8190
void stub_ircom_set_frame_ms(int ms);
int stub_ircom_take_sent(long *values, int max);
void stub_ircom_receive(long value, double distance_cm, double direction_rad, int sensor,
                        const char *from, double from_x_mm, double from_y_mm);
void stub_set_distance(int mm);
/* What the camera sees: `pixels` (at most 60) r, g, b triples, 0..255,
 * leftmost first. */
void stub_set_camera(const unsigned char *rgb, int pixels);

/* A program wrote the LED pins of motor_led/e_epuck_ports.h: the LEDs take
 * them (traced); called every simulated ms. */
void stub_sync_led_ports(void);

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

/* platform_host.c, for cmain.c: called at every rt_platform_init (by
 * mainloop, or main's first call); virtual time; a record of another
 * file's (`extra`: more JSON keys; `line`: its readable line, or NULL). */
extern void (*host_init_hook)(void);
long host_now_ms(void);
void host_record(const char *kind, const char *name, const char *extra, const char *line);

/* cmain.c: the body's rate of turn about z over the last simulated ms, in
 * degrees/s, positive = left (the gyroscope; measured from the first call
 * on); and a tick of its timers, which the Enki world runner gives the
 * robot that runs (its robots share the process's timers). */
double stub_turn_rate_dps(void);
void epuck_cmain_signal(int wall);

#endif

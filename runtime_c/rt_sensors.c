/*
 * rt_sensors.c - the standard events (immediate, stop_motor, timer, sensor),
 * the timer and proximity actions, and the devices of the extension: LEDs,
 * sound, selector, microphones, accelerometer, remote control, ambient
 * light, and the paper's short spellings of the timer's, the sensors' and
 * the standard events' functions.  A layer of the core on rt_clock.c
 * (rt_sensors.h); part of the runtime behind epuckrt.h.
 */
#include "rt_sensors.h"

/* stop_motor event latch: see event_stop_motor (the walk samples it). */
int rt_stop_sample;

/* Timer (set_timer / reset_timer / event_timer). */
int rt_timer_running;
long rt_timer_start;            /* rt_millis() at set_timer */

/* Proximity polling (start_sensor / stop_sensor); off at start.  The
 * sensors started by start_sensor are read from the next poll on: no
 * sensor event can occur in the poll that started them. */
int rt_sensors_on;
int rt_sensors_starting;

/* The proximity readings, read once per poll: bit n of prox_valid says
 * prox[n] was read in this poll (cleared at the start of each poll). */
int rt_prox[8];
unsigned rt_prox_valid;

void rt_read_prox(unsigned mask)
{
    unsigned n, todo = mask & ~rt_prox_valid & 0xFFu;

    if (todo == 0)
        return;
    for (n = 0; todo != 0; n++, todo >>= 1) {
        if (todo & 1u)
            rt_prox[n] = e_get_prox(n);
    }
    rt_prox_valid |= mask & 0xFFu;
}

/* ---- the other standard actions ------------------------------------------- */

void action_set_timer(void *param)
{
    (void)param;
    rt_timer_running = 1;
    rt_timer_start = rt_millis();
}

void action_reset_timer(void *param)
{
    (void)param;
    rt_timer_running = 0;
}

void action_start_sensor(void *param)
{
    (void)param;
    if (!rt_sensors_on)
        rt_sensors_starting = 1;
}

void action_stop_sensor(void *param)
{
    (void)param;
    rt_sensors_on = 0;
    rt_sensors_starting = 0;
}

/* ---- standard events -------------------------------------------------------- */

void event_immediate(void *param, void *status)
{
    (void)param;
    ((event_status *)status)->occurred = 1;
}

/* "The wheels went from moving to at rest between two polls": stop_sample,
 * computed once per poll before the events are polled. */
void event_stop_motor(void *param, void *status)
{
    (void)param;
    ((event_status *)status)->occurred = rt_stop_sample;
}

/* Occurs when the timer runs and has run >= time ms.  status->memory holds
 * 1 + the clock time of the last firing (0: never), so that a repeating
 * event fires at time, 2*time, ... of the timer, and a restarted timer
 * restarts the phase. */
void event_timer(void *param, void *status)
{
    const param_event_timer *p = (const param_event_timer *)param;
    event_status *st = (event_status *)status;
    long now, elapsed, base = 0;

    st->occurred = 0;
    if (p == NULL || !rt_timer_running)
        return;
    now = rt_millis();
    elapsed = now - rt_timer_start;
    if (p->time > 0 && st->memory != 0 && st->memory - 1 >= rt_timer_start) {
        /* fired before in this run of the timer: the current period
         * starts at the last multiple of time not after that firing */
        long since = st->memory - 1 - rt_timer_start;
        base = since - since % p->time;
    }
    if (elapsed - base >= p->time) {
        st->occurred = 1;
        st->memory = now + 1;
    }
}

/* Occurs when the condition becomes true (status->memory: the condition at
 * the previous poll, 0 before the first). */
static int thresholds_passed(const param_event_sensor *p, int (*reading)(unsigned int))
{
    unsigned n;

    for (n = 0; n < 8; n++) {
        int threshold = p->sensef[n];
        int value;
        if (threshold == SENSOR_OFF)
            continue;
        value = reading(n);
        if ((p->below >> n) & 1u ? value < threshold : value > threshold)
            return 1;
    }
    return 0;
}

/* Rising edge of cond: status->memory holds the condition at the previous
 * poll (0 before the first). */
static void edge(event_status *st, int cond)
{
    st->occurred = cond && st->memory == 0;
    st->memory = cond;
}

void event_sensor(void *param, void *status)
{
    const param_event_sensor *p = (const param_event_sensor *)param;

    event_status *st = (event_status *)status;
    int cond = 0;
    unsigned n;

    if (p != NULL && rt_sensors_on) {
        if (rt_prox_valid != 0xFFu)
            rt_read_prox(0xFFu);       /* the first sensor event of this poll */
        for (n = 0; n < 8; n++) {
            int threshold = p->sensef[n];
            int value = rt_prox[n];
            if (threshold == SENSOR_OFF)
                continue;
            if ((p->below >> n) & 1u ? value < threshold : value > threshold) {
                cond = 1;
                break;
            }
        }
    }
    edge(st, cond);
}

/* ---- extension: LEDs and sound --------------------------------------------------- */

void action_set_led(void *param)
{
    const param_set_led *p = (const param_set_led *)param;
    unsigned k;

    if (p == NULL || p->value < SET_LED_OFF || p->value > SET_LED_TOGGLE)
        return;
    if (p->led == SET_LED_ALL && p->value == SET_LED_TOGGLE) {
        /* the library toggles one LED; for "all" it writes the value's low bit */
        for (k = 0; k < 8; k++)
            e_set_led(k, SET_LED_TOGGLE);
    } else if (p->led >= 0 && p->led <= SET_LED_ALL) {
        e_set_led((unsigned)p->led, (unsigned)p->value);
    } else if (p->led == SET_LED_BODY) {
        e_set_body_led((unsigned)p->value);
    } else if (p->led == SET_LED_FRONT) {
        e_set_front_led((unsigned)p->value);
    } else {
        return;
    }
    RT_TRACE_LED(p->led, p->value);     /* the robot's trace (nothing without it) */
}

static void ring(unsigned bits)
{
    unsigned k;
    for (k = 0; k < 8; k++) {
        e_set_led(k, (bits >> k) & 1u);
        RT_TRACE_LED((int)k, (int)((bits >> k) & 1u));
    }
}

void action_led_ring(void *param)
{
    const param_led_ring *p = (const param_led_ring *)param;
    int count;

    if (p == NULL)
        return;
    count = p->count < 0 ? 0 : p->count > 8 ? 8 : p->count;
    ring((1u << count) - 1u);
}

void action_led_bits(void *param)
{
    const param_led_bits *p = (const param_led_bits *)param;

    if (p != NULL)
        ring((unsigned)p->bits & 0xFFu);
}

/* [offset, length] in words of the library's samples (codec/e_const_sound.s) */
static const int sound_samples[5][2] = {
    { 0, 2112 }, { 2116, 1760 }, { 3878, 3412 }, { 7294, 3732 }, { 11028, 8016 }
};
static int sound_ready;

void action_play_sound(void *param)
{
    const param_play_sound *p = (const param_play_sound *)param;

    if (p == NULL || p->sound < 0 || p->sound > SOUND_WOUAAAAAAAAH)
        return;
    if (!sound_ready) {
        sound_ready = 1;
        e_init_sound();
    }
    e_play_sound(sound_samples[p->sound][0], sound_samples[p->sound][1]);
    RT_TRACE_SOUND(p->sound);
}

/* ---- extension: selector, microphones, accelerometer, remote, ambient light ----- */

void event_selector(void *param, void *status)
{
    const param_event_selector *p = (const param_event_selector *)param;

    edge((event_status *)status, p != NULL && getselector() == p->position);
}

void event_clap(void *param, void *status)
{
    const param_event_clap *p = (const param_event_clap *)param;
    int cond = 0;
    unsigned m;

    if (p != NULL)
        for (m = 0; m < 3 && !cond; m++)
            cond = e_get_micro_volume(m) > p->volume;
    edge((event_status *)status, cond);
}

/* Accelerometer samples, taken once per poll (phase 4) when a tap or tilt
 * event is registered: this poll's, the previous poll's, and the first
 * (the robot at rest).  e_get_acc_filtered over one sample: the raw 12
 * bits, 2048 at no acceleration, on every e-puck (the library keeps that
 * scale on the 1.3's LSM330, and the e-puck2's epuck1x layer too), where
 * e_get_acc is centred differently from one robot to the next.  Not before
 * RT_ACC_SETTLE_MS: the library reads the e-puck 1.3's LSM330 every 3.9 ms
 * of its A/D scan, and reports 0 g until it first did. */
#define RT_ACC_SETTLE_MS 5
static int acc_now[3], acc_prev[3], acc_rest[3];
static int acc_samples;

void rt_accel_sample(void)
{
    unsigned k;

    if (rt_millis() < RT_ACC_SETTLE_MS)
        return;

    for (k = 0; k < 3; k++) {
        acc_prev[k] = acc_now[k];
        acc_now[k] = e_get_acc_filtered(k, 1);
        if (acc_samples == 0) {
            acc_prev[k] = acc_now[k];
            acc_rest[k] = acc_now[k];
        }
    }
    acc_samples = 1;
}

static int differs(int a, int b, int threshold)
{
    long d = (long)a - b;
    return (d < 0 ? -d : d) > threshold;
}

void event_tap(void *param, void *status)
{
    const param_event_accel *p = (const param_event_accel *)param;
    int cond = 0;
    unsigned k;

    if (p != NULL && acc_samples)
        for (k = 0; k < 3 && !cond; k++)
            cond = differs(acc_now[k], acc_prev[k], p->threshold);
    edge((event_status *)status, cond);
}

void event_tilt(void *param, void *status)
{
    const param_event_accel *p = (const param_event_accel *)param;
    int cond = 0;
    unsigned k;

    if (p != NULL && acc_samples)
        for (k = 0; k < 2 && !cond; k++)
            cond = differs(acc_now[k], acc_rest[k], p->threshold);
    edge((event_status *)status, cond);
}

/* The remote control's receiver is started only for programs with an
 * event_remote (registered or in the table), once the library is. */
static int remote_wanted;
static int remote_started;      /* e_init_remote_control() has run */
int rt_accel_wanted;            /* an event_tap or event_tilt was registered */

void rt_remote_want(void)
{
    remote_wanted = 1;
    rt_remote_start();
}

void rt_remote_start(void)
{
    if (remote_wanted && rt_initialised && !remote_started) {
        remote_started = 1;
        e_init_remote_control();
    }
}

/* status->memory: 0 before the first poll, else 1 + the check bit seen at
 * the previous poll; a new press toggles the bit. */
void event_remote(void *param, void *status)
{
    const param_event_remote *p = (const param_event_remote *)param;
    event_status *st = (event_status *)status;
    int check;

    st->occurred = 0;
    if (p == NULL || !remote_started)
        return;
    check = e_get_check() != 0;
    st->occurred = st->memory != 0 && check != st->memory - 1 && e_get_data() == p->key;
    st->memory = check + 1;
}

static int ambient_reading(unsigned int n)
{
    return e_get_ambient_light(n);
}

void event_ambient(void *param, void *status)
{
    const param_event_sensor *p = (const param_event_sensor *)param;

    edge((event_status *)status, p != NULL && thresholds_passed(p, ambient_reading));
}

/* ---- the paper's short spellings -------------------------------------------- */

void set_timer(void *param) { action_set_timer(param); }
void reset_timer(void *param) { action_reset_timer(param); }
void start_sensor(void *param) { action_start_sensor(param); }
void stop_sensor(void *param) { action_stop_sensor(param); }
void sensor(void *param, void *status) { event_sensor(param, status); }
void timer(void *param, void *status) { event_timer(param, status); }
void immediate(void *param, void *status) { event_immediate(param, status); }

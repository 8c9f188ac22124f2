/*
 * platform_host.c - the runtime's platform layer on a PC (the "stub
 * harness"): virtual time (1 ms per poll cycle), the virtual robot of
 * epuck_stub.c, a scenario of proximity readings, a time limit, and the
 * trace (JSON lines to a file, readable lines to stdout).  Each robot of an
 * Enki world uses it too, unchanged (runtime_c/enki/robot_glue.c).
 *
 * Settings come from the environment (the paper's main() has no arguments),
 * read by rt_platform_init, i.e. when mainloop first runs:
 *   EPUCK_SCENARIO       scenario file (.scn); none: every reading is 0
 *   EPUCK_TRACE          JSON-lines trace output path; none: no JSON trace
 *   EPUCK_TIME_LIMIT_MS  virtual time limit, default 60000
 *   EPUCK_QUIET          set and not "0": no readable trace on stdout
 *   EPUCK_FRONTEND       "epuckc": messages name epuckc's options (--trace)
 *   EPUCK_POSE_MS        also a "pose" record every so many ms (JSON only)
 *   EPUCK_TRACE_VARS     the variables whose changes are traced (var_traced)
 *   EPUCK_POLL_EVERY_MS  set and not "0": poll at every ms, none skipped in
 *                        bulk (the same trace, slower: for tests)
 *   EPUCK_POLL_STATS     a file: "ms N skipped K" appended at the end
 * Exit statuses: 2 bad setting or scenario, 3 time limit reached, 6 a call
 * of what the simulation does not model (host/unsimulated.c).
 * docs/runtime.md describes the formats.
 */
#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "epuckrt.h"
#include "rt_platform.h"
#include "epuck_stub.h"
#include "host_harness.h"

#define EXIT_BAD_SETTING 2
#define EXIT_TIMEOUT 3
#define EXIT_UNSIMULATED 6
#define DEFAULT_TIME_LIMIT_MS 60000L

static long now_ms;                 /* virtual time */
static long limit_ms = DEFAULT_TIME_LIMIT_MS;
static FILE *trace_file;
static int quiet = -1;              /* -1: EPUCK_QUIET not read yet */
static long events_fired, actions_run, steps_run, pose_every_ms;  /* pose: 0 none */
static int bulk = 1;                /* idle polls in bulk; 0: every ms polled (EPUCK_POLL_EVERY_MS) */

/* ---- names ------------------------------------------------------------------ */

typedef struct {
    char **names;   /* malloc'd copies, NULL: no name */
    int size;
} name_table;

static name_table action_names, event_names, mode_names, var_names;

static char *copy_string(const char *s)
{
    size_t n = strlen(s) + 1;
    char *c = malloc(n);
    if (c != NULL)
        memcpy(c, s, n);
    return c;
}

static void set_name(name_table *t, int id, const char *name)
{
    if (id < 0)
        return;
    if (id >= t->size) {
        int size = id + 16, i;
        char **grown = realloc(t->names, (size_t)size * sizeof *grown);
        if (grown == NULL)
            return;     /* out of memory: the trace shows the id instead */
        for (i = t->size; i < size; i++)
            grown[i] = NULL;
        t->names = grown;
        t->size = size;
    }
    free(t->names[id]);
    t->names[id] = name != NULL ? copy_string(name) : NULL;
}

/* The name for the trace, or fallback#id. */
static const char *get_name(const name_table *t, int id, const char *fallback,
                            char *buf, size_t bufsize)
{
    if (id >= 0 && id < t->size && t->names[id] != NULL)
        return t->names[id];
    snprintf(buf, bufsize, "%s#%d", fallback, id);
    return buf;
}

/* standard functions are named after themselves in the trace */
static const struct {
    action_func f;
    const char *name;
} std_action_names[] = {
    { action_start_straight, "action_start_straight" }, { action_start_curve, "action_start_curve" },
    { action_stop_motor, "action_stop_motor" }, { action_set_timer, "action_set_timer" },
    { action_reset_timer, "action_reset_timer" }, { action_start_sensor, "action_start_sensor" },
    { action_stop_sensor, "action_stop_sensor" }, { action_exit_main, "action_exit_main" },
    { action_run_sequence, "action_run_sequence" }, { action_straight_steps, "action_straight_steps" },
    { action_curve_steps, "action_curve_steps" }, { start_straight, "start_straight" },
    { start_curve, "start_curve" }, { stop_motor, "stop_motor" },
    { set_timer, "set_timer" }, { reset_timer, "reset_timer" },
    { start_sensor, "start_sensor" }, { stop_sensor, "stop_sensor" },
    { exit_main, "exit_main" }, { run_sequence, "run_sequence" },
    { straight_steps, "straight_steps" }, { curve_steps, "curve_steps" },
    { action_enter_mode, "action_enter_mode" }, { action_set_led, "action_set_led" },
    { action_play_sound, "action_play_sound" },
};

static const struct {
    event_func f;
    const char *name;
} std_event_names[] = {
    { event_sensor, "event_sensor" }, { event_timer, "event_timer" },
    { event_immediate, "event_immediate" }, { event_stop_motor, "event_stop_motor" },
    { sensor, "sensor" }, { timer, "timer" }, { immediate, "immediate" },
    { event_enter_mode, "event_enter_mode" }, { event_selector, "event_selector" },
    { event_clap, "event_clap" }, { event_tap, "event_tap" }, { event_tilt, "event_tilt" },
    { event_remote, "event_remote" }, { event_ambient, "event_ambient" },
};

void rt_new_action(int action_id, action_func f)
{
    const char *name = NULL;
    size_t i;
    for (i = 0; i < sizeof std_action_names / sizeof std_action_names[0]; i++)
        if (std_action_names[i].f == f)
            name = std_action_names[i].name;
    set_name(&action_names, action_id, name);
}

void rt_new_event(int event_id, event_func f)
{
    const char *name = NULL;
    size_t i;
    for (i = 0; i < sizeof std_event_names / sizeof std_event_names[0]; i++)
        if (std_event_names[i].f == f)
            name = std_event_names[i].name;
    set_name(&event_names, event_id, name);
}

void rt_geometry(long wheel_circumference_um, long axle_um, long steps_per_rev)
{
    stub_set_geometry(wheel_circumference_um, axle_um, steps_per_rev);
}

void rt_name_action(int action_id, const char *name)
{
    set_name(&action_names, action_id, name);
}

void rt_name_event(int event_id, const char *name)
{
    set_name(&event_names, event_id, name);
}

/* The texts of a sequence's steps, by the id of the action that runs it
 * (name_steps; the arrays are the program's, kept as they are). */
static struct step_names {
    const char *const *names;
    int count;
} *step_names;
static int n_step_names;

void rt_name_steps(int action_id, const char *const *names, int count)
{
    if (action_id >= n_step_names) {
        int n = action_id + 1;
        struct step_names *grown = realloc(step_names, (size_t)n * sizeof *grown);
        if (grown == NULL)
            return;
        memset(grown + n_step_names, 0, (size_t)(n - n_step_names) * sizeof *grown);
        step_names = grown;
        n_step_names = n;
    }
    step_names[action_id].names = names;
    step_names[action_id].count = count;
}

static const char *step_name(int action_id, int step)
{
    if (action_id < 0 || action_id >= n_step_names || step >= step_names[action_id].count)
        return NULL;
    return step_names[action_id].names[step];
}

void rt_name_mode(int mode, const char *name)
{
    set_name(&mode_names, mode, name);
}

void rt_name_var(int id, const char *name)
{
    set_name(&var_names, id, name);
}

/* ---- settings errors ------------------------------------------------------ */

/* Run by `epuckc run` (EPUCK_FRONTEND=epuckc), messages name the options the
 * user typed rather than the environment variables they became. */
static const char *setting_name(const char *variable)
{
    static const char *const options[][2] = {
        {"EPUCK_TIME_LIMIT_MS", "--time-limit"},
        {"EPUCK_TRACE", "--trace"},
        {"EPUCK_SCENARIO", "--scenario"},
        {"EPUCK_POSE_MS", "--pose-interval"},
        {"EPUCK_SEED", "--seed"},
    };
    const char *frontend = getenv("EPUCK_FRONTEND");
    size_t i;
    if (frontend == NULL || strcmp(frontend, "epuckc") != 0)
        return variable;
    for (i = 0; i < sizeof options / sizeof options[0]; i++)
        if (strcmp(options[i][0], variable) == 0)
            return options[i][1];
    return variable;
}

void host_fail(const char *fmt, ...)
{
    va_list ap;
    fputs("epuck host: ", stderr);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
    exit(EXIT_BAD_SETTING);
}

/* ---- trace ----------------------------------------------------------------------- */

/* %.1f, without "-0.0" */
static double tidy(double v)
{
    return v > -0.05 && v < 0.05 ? 0.0 : v;
}

static void json_string(FILE *f, const char *s)
{
    fputc('"', f);
    for (; *s != '\0'; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (c < 0x20)
            fprintf(f, "\\u%04x", c);
        else
            fputc(c, f);
    }
    fputc('"', f);
}

static void record_extra(const char *kind, const char *name, int id, int step, int steps,
                         const char *extra);

static void record(const char *kind, const char *name, int id, int step, int steps)
{
    record_extra(kind, name, id, step, steps, "");
}

/* extra: more keys, already JSON (", \"key\": value ..."), after the pose */
static void record_extra(const char *kind, const char *name, int id, int step, int steps,
                         const char *extra)
{
    double x, y, h;
    stub_outputs_flush();       /* the LEDs as they are, before anything else */
    stub_pose(&x, &y, &h);
    if (trace_file == NULL)
        return;
    fprintf(trace_file, "{\"t_ms\": %ld, \"kind\": \"%s\", \"name\": ", now_ms, kind);
    json_string(trace_file, name);
    fprintf(trace_file, ", \"id\": %d, \"left_steps\": %ld, \"right_steps\": %ld, "
            "\"x_mm\": %.1f, \"y_mm\": %.1f, \"heading_deg\": %.1f",
            id, stub_total_steps_left(), stub_total_steps_right(),
            tidy(x), tidy(y), tidy(h));
    if (step >= 0)
        fprintf(trace_file, ", \"step\": %d, \"steps\": %d", step + 1, steps);
    fputs(extra, trace_file);
    fputs("}\n", trace_file);
    fflush(trace_file);
}

/* EPUCK_QUIET is read at the first output, which may come before mainloop
 * (a sequence run from main, say). */
static int is_quiet(void)
{
    if (quiet < 0) {
        const char *q = getenv("EPUCK_QUIET");
        quiet = q != NULL && *q != '\0' && strcmp(q, "0") != 0;
    }
    return quiet;
}

static void print_pose(void)
{
    double x, y, h;
    stub_pose(&x, &y, &h);
    printf("pose (%.1f, %.1f) %.1f deg", tidy(x), tidy(y), tidy(h));
}

/* EPUCK_POLL_STATS: a line appended to that file at the end, the ms run and
 * how many of their polls were skipped in bulk (for tests and benches). */
static long polls_skipped;

static void poll_stats(void)
{
    const char *path = getenv("EPUCK_POLL_STATS");
    FILE *f;

    if (path == NULL || *path == '\0' || (f = fopen(path, "a")) == NULL)
        return;
    fprintf(f, "ms %ld skipped %ld\n", now_ms, polls_skipped);
    fclose(f);
}

static void summary(const char *how)
{
    poll_stats();
    if (is_quiet())
        return;
    printf("%s at %ld ms: ", how, now_ms);
    print_pose();
    printf(", %ld events fired, %ld actions run, %ld sequence steps\n",
           events_fired, actions_run, steps_run);
    fflush(stdout);
}

void rt_trace_event(int event_id)
{
    char buf[32];
    const char *name = get_name(&event_names, event_id, "event", buf, sizeof buf);
    events_fired++;
    record("event", name, event_id, -1, 0);
    if (!is_quiet()) {
        printf("[%6ld ms] event  #%d %-23s ", now_ms, event_id, name);
        print_pose();
        putchar('\n');
    }
}

void rt_trace_action(int action_id, int step, int steps)
{
    char buf[32];
    const char *name = get_name(&action_names, action_id, "action", buf, sizeof buf);
    if (step < 0)
        actions_run++;
    else
        steps_run++;
    record("action", name, action_id, step, steps);
    if (!is_quiet()) {
        printf("[%6ld ms] action #%d %s", now_ms, action_id, name);
        if (step >= 0) {
            const char *call = step_name(action_id, step);
            printf(" step %d of %d", step + 1, steps);
            if (call != NULL)
                printf(": %s", call);
        }
        putchar('\n');
    }
}

void rt_trace_suppressed(int event_id, int priority, int owner_event_id,
                         int owner_priority, const char *command)
{
    char buf[32], owner_buf[32], extra[512];
    const char *name = get_name(&event_names, event_id, "event", buf, sizeof buf);
    const char *owner = get_name(&event_names, owner_event_id, "event", owner_buf,
                                 sizeof owner_buf);
    size_t used;

    /* the owner's name is JSON-escaped like the record's own (names are
     * short: longer ones are cut) */
    used = (size_t)snprintf(extra, sizeof extra, ", \"command\": \"%s\", \"priority\": %d, "
                            "\"owner\": %d, \"owner_name\": \"", command, priority,
                            owner_event_id);
    for (; *owner != '\0' && used + 16 < sizeof extra; owner++) {
        unsigned char c = (unsigned char)*owner;
        if (c == '"' || c == '\\')
            used += (size_t)snprintf(extra + used, sizeof extra - used, "\\%c", c);
        else if (c < 0x20)
            used += (size_t)snprintf(extra + used, sizeof extra - used, "\\u%04x", c);
        else
            extra[used++] = (char)c;
    }
    snprintf(extra + used, sizeof extra - used, "\", \"owner_priority\": %d", owner_priority);
    record_extra("suppressed", name, event_id, -1, 0, extra);
    if (!is_quiet())
        printf("[%6ld ms] suppressed %s of #%d %s (priority %d); motors owned by #%d %s "
               "(priority %d)\n", now_ms, command, event_id, name, priority, owner_event_id,
               get_name(&event_names, owner_event_id, "event", owner_buf, sizeof owner_buf),
               owner_priority);
}

void rt_trace_mode(int mode)
{
    char buf[32];
    const char *name = get_name(&mode_names, mode, "mode", buf, sizeof buf);
    record("mode", name, mode, -1, 0);
    if (!is_quiet())
        printf("[%6ld ms] mode      %s\n", now_ms, name);
}

/* EPUCK_TRACE_VARS (`epuckc run --trace-vars`): the variables whose
 * changes are traced, their names separated by commas (an array's name
 * stands for its elements, `counts` for `counts[2]`), empty for none;
 * unset: every variable (epuckc/sim/tracevars.py is the same rule). */
static int var_traced(const char *name)
{
    static int read;
    static const char *list;
    const char *p;
    size_t n;

    if (!read) {
        list = getenv("EPUCK_TRACE_VARS");
        read = 1;
    }
    if (list == NULL)
        return 1;
    for (p = list; *p != '\0'; p += n + (p[n] == ',')) {
        n = strcspn(p, ",");
        if (n > 0 && strncmp(p, name, n) == 0 && (name[n] == '\0' || name[n] == '['))
            return 1;
    }
    return 0;
}

/* a variable changed: one line of its own, {"t_ms", "kind": "set", "var", "value"} */
void rt_trace_set(int id, int value)
{
    char buf[32];
    const char *name = get_name(&var_names, id, "var", buf, sizeof buf);

    if (!var_traced(name))
        return;

    stub_outputs_flush();
    if (trace_file != NULL) {
        fprintf(trace_file, "{\"t_ms\": %ld, \"kind\": \"set\", \"var\": ", now_ms);
        json_string(trace_file, name);
        fprintf(trace_file, ", \"value\": %d}\n", value);
        fflush(trace_file);
    }
    if (!is_quiet())
        printf("[%6ld ms] set       %s = %d\n", now_ms, name, value);
}

/* who holds the motors changed: a "motors" record (JSON only, like pose),
 * name the owner event's, "main" for a motion main started, "free" */
void rt_trace_motors(int active, int owner_event_id)
{
    char buf[32];
    record("motors", !active ? "free" : owner_event_id < 0 ? "main"
           : get_name(&event_names, owner_event_id, "event", buf, sizeof buf),
           active ? owner_event_id : -1, -1, 0);
}

/* The seed of `random`: EPUCK_SEED (`epuckc run --seed N`), 1 without it. */
unsigned long rt_platform_seed(void)
{
    const char *seed = getenv("EPUCK_SEED");
    char *end;
    unsigned long v;

    if (seed == NULL || *seed == '\0')
        return 1UL;
    errno = 0;
    v = strtoul(seed, &end, 10);
    if (errno != 0 || *end != '\0' || !isdigit((unsigned char)*seed) || v > 0xFFFFFFFFUL)
        host_fail("%s: expected a whole number from 0 to 4294967295, got '%s'",
             setting_name("EPUCK_SEED"), seed);
    return v;
}

/* the harness's view of the robot's outputs */
static void observe_output(const char *device, const char *name, int value)
{
    char extra[160];
    int n;

    if (strcmp(device, "led") == 0) {
        char ring[9];
        for (n = 0; n < 8; n++)
            ring[n] = (char)('0' + stub_led(n));
        ring[8] = '\0';
        snprintf(extra, sizeof extra, ", \"state\": %d, \"ring\": \"%s\", \"body\": %d, "
                 "\"front\": %d", value, ring, stub_led(9), stub_led(10));
        record_extra("led", name, -1, -1, 0, extra);
        if (!is_quiet())
            printf("[%6ld ms] led       %-5s %-3s ring %s body %d front %d\n", now_ms, name,
                   value ? "on" : "off", ring, stub_led(9), stub_led(10));
    } else {
        snprintf(extra, sizeof extra, ", \"length\": %d", value);
        record_extra("sound", name, -1, -1, 0, extra);
        if (!is_quiet())
            printf("[%6ld ms] sound     %s\n", now_ms, name);
    }
}

void host_record_input(const char *name, int index, int value)
{
    char extra[64], full[16];
    if (index >= 0 && (strcmp(name, "acc") == 0 || strcmp(name, "rot") == 0))
        snprintf(full, sizeof full, "%s%c", name, 'x' + index);
    else if (index >= 0)
        snprintf(full, sizeof full, "%s%d", name, index);
    else
        snprintf(full, sizeof full, "%s", name);
    snprintf(extra, sizeof extra, ", \"value\": %d", value);
    record_extra("input", full, -1, -1, 0, extra);
    if (!is_quiet())
        printf("[%6ld ms] input     %s=%d\n", now_ms, full, value);
}

void rt_trace_exit(void)
{
    stub_outputs_end();
    record("exit", "exit_main", -1, -1, 0);
    if (!is_quiet()) {
        printf("[%6ld ms] exit      ", now_ms);
        print_pose();
        putchar('\n');
    }
    summary("exit");
}

/* the C main model (cmain.c): the clock, and records of its own (uart, watchdog) */
long host_now_ms(void) { return now_ms; }

void host_record(const char *kind, const char *name, const char *extra, const char *line)
{
    record_extra(kind, name, -1, -1, 0, extra);
    if (line != NULL && !is_quiet())
        printf("[%6ld ms] %s\n", now_ms, line);
}

/* the run ends here: what is still to say, the record, the summary */
void host_stop(const char *kind, const char *name, const char *extra, const char *line,
               int status)
{
    stub_outputs_end();
    host_record(kind, name, extra, line);
    summary(kind);
    if (trace_file != NULL)
        fclose(trace_file);
    trace_file = NULL;
    exit(status);
}

/* a call of what the simulation does not model (unsimulated.c) */
void stub_unsimulated(const char *function, const char *device)
{
    char extra[512], line[600];
    fflush(stdout);
    fprintf(stderr, "epuckc: %s: %s is not simulated, and the run ends here at %ld ms "
            "(the simulated e-puck has the motors, LEDs, proximity sensors, agendas, UARTs, "
            "accelerometer and gyroscope, camera, sound and microphones, remote control, "
            "selector and EEPROM)\n", function, device, now_ms);
    snprintf(extra, sizeof extra, ", \"device\": \"%.400s\"", device);
    snprintf(line, sizeof line, "unsimulated %s: %.400s is not simulated", function, device);
    host_stop("unsimulated", function, extra, line, EXIT_UNSIMULATED);
}

/* ---- platform ------------------------------------------------------------------- */

static long ms_setting(const char *variable, const char *value)
{
    char *end;
    long v;
    errno = 0;
    v = strtol(value, &end, 10);
    if (errno != 0 || *end != '\0' || v <= 0 || v > MAX_SCENARIO_MS || !isdigit((unsigned char)*value))
        host_fail("%s: expected a whole number of milliseconds from 1 to %ld, got '%s'",
             setting_name(variable), MAX_SCENARIO_MS, value);
    return v;
}

void (*host_init_hook)(void);     /* set by cmain.c */
void rt_platform_init(void)
{
    static int done;
    const char *limit = getenv("EPUCK_TIME_LIMIT_MS");
    const char *pose = getenv("EPUCK_POSE_MS");
    const char *scn = getenv("EPUCK_SCENARIO");
    const char *trace = getenv("EPUCK_TRACE");
    const char *every = getenv("EPUCK_POLL_EVERY_MS");

    if (host_init_hook != NULL)
        host_init_hook();       /* cmain.c: mainloop runs, or main's first call */
    if (done++ > 0)
        return;
    if (limit != NULL && *limit != '\0')
        limit_ms = ms_setting("EPUCK_TIME_LIMIT_MS", limit);
    if (pose != NULL && *pose != '\0')
        pose_every_ms = ms_setting("EPUCK_POSE_MS", pose);
    bulk = every == NULL || *every == '\0' || strcmp(every, "0") == 0;
    if (scn != NULL && *scn != '\0')
        host_load_scenario(scn);
    if (trace != NULL && *trace != '\0') {
        trace_file = fopen(trace, "w");
        if (trace_file == NULL)
            host_fail("%s: cannot write '%s': %s", setting_name("EPUCK_TRACE"), trace, strerror(errno));
    }
    stub_set_observer(observe_output);
    host_scenario_apply(0);
    if (pose_every_ms > 0)
        record("pose", "pose", -1, -1, 0);
}

/* How many ms this poll cycle may advance at once (docs/runtime.md, "Idle
 * polls in bulk"): the runtime's horizon (rt_idle.c) while the agendas only
 * count (the runtime's clock, libIrcom's frame), within the time limit (its
 * poll runs), before the next pose record, the scenario's next line and
 * the next change of a device of its own (the camera's frame ready). */
static long bulk_ms(long *left, long *right)
{
    long n, t;

    *left = *right = 0;
    if (!bulk)
        return 1;
    n = rt_idle_horizon(left, right);
    if (n <= 1 || !stub_agendas_count_only(rt_clock_tick))
        return 1;
    if (n > limit_ms - now_ms)
        n = limit_ms - now_ms;
    if (pose_every_ms > 0 && n > pose_every_ms - now_ms % pose_every_ms)
        n = pose_every_ms - now_ms % pose_every_ms;
    t = host_scenario_next_ms();
    if (t >= 0 && n > t - now_ms)
        n = t - now_ms;
    t = stub_devices_next_ms();
    if (t >= 0 && n > t - now_ms)
        n = t - now_ms;
    return n < 1 ? 1 : n;
}

/* One poll cycle = 1 ms of virtual time; or several, when the polls before
 * the last would change nothing but time. */
void rt_platform_idle(void)
{
    long n, left, right;

    stub_outputs_ms_end();      /* the ms's LEDs, at its time */
    if (now_ms >= limit_ms) {
        stub_outputs_end();
        record("timeout", "timeout", -1, -1, 0);
        if (!is_quiet()) {
            printf("[%6ld ms] timeout   ", now_ms);
            print_pose();
            putchar('\n');
        }
        summary("timeout");
        if (trace_file != NULL)
            fclose(trace_file);
        exit(EXIT_TIMEOUT);
    }
    n = bulk_ms(&left, &right);
    if (n > 1 && rt_idle_each_ms()) {
        /* the same, one ms at a time, each measured as its poll would (the
         * odometry), stopping at a change of the inputs or the motion's end */
        unsigned long inputs = stub_inputs_epoch();
        for (;;) {
            stub_motors_1ms();
            now_ms++;
            host_scenario_apply(now_ms);
            stub_devices_ms(now_ms, 1);
            stub_agendas_1ms();
            if (--n == 0 || stub_inputs_epoch() != inputs || !rt_idle_ms())
                break;
            rt_idle_skipped(1);
            polls_skipped++;
        }
    } else if (n > 1) {
        /* the ms of the polls that would change nothing, and the next one's
         * (fewer when a wheel reached the motion's end, or a world's step
         * ended: its poll runs), as one ms after another would make them */
        n = stub_motors_ms(n, left, right);
        now_ms += n - 1;
        stub_motors_ms_end();   /* a world steps at the end of its step, at this ms */
        now_ms++;
        host_scenario_apply(now_ms);    /* no line before it */
        stub_devices_ms(now_ms, n);
        stub_agendas_ms(n, rt_clock_tick, rt_clock_ticks);
        rt_idle_skipped(n - 1);
        polls_skipped += n - 1;
    } else {
        stub_motors_1ms();      /* the wheels move during the ms ... */
        now_ms++;
        host_scenario_apply(now_ms); /* ... the readings of the new ms hold ... */
        stub_devices_ms(now_ms, 1);  /* ... the devices move on ... */
        stub_agendas_1ms();     /* ... and the clock agenda ticks */
    }
    if (pose_every_ms > 0 && now_ms % pose_every_ms == 0)
        record("pose", "pose", -1, -1, 0);
}

/*
 * static_path.c - runs a runtime test program, written with the paper's
 * dynamic API, on the static registration path (register_program): the
 * program is compiled with -include static_path.h, which sends its calls
 * here.  Registrations are collected into an rt_program's tables, with the
 * ids the tables will give them, until the program calls anything else
 * (cancel, enter_mode, mainloop; set_event_repeat, names, priorities
 * and modes of collected entries are collected with them) or makes a registration the
 * tables cannot hold (a NULL function, an unknown action): then the tables
 * are registered with register_program and every later call goes to the
 * runtime as it is, so later registrations are dynamic and get the ids that
 * follow the tables'.  set_event_priority and set_event_mode of a
 * collected event go into its table entry (its rt_event's priority and
 * mode, as epuckc generates them).  A program that calls register_program itself runs
 * as it is.  A sensor event (event_sensor / sensor with a
 * parameter) becomes a compiled condition, as epuckc generates them: a
 * NULL event function and a bit set by conditions() below.
 */
#include <stdio.h>
#include <stdlib.h>

#include "epuckrt.h"

#define CAP 256

static rt_action acts[CAP];
static rt_event evs[CAP];
static const param_event_sensor *sensor_params[CAP];   /* compiled: its thresholds */
static const char *sensor_names[CAP];
static const char *action_names[CAP], *event_names[CAP];   /* named while collected */
#define MODES 16
static const char *mode_names[MODES];
static long memory[CAP];
static unsigned state[RT_STATE_WORDS(CAP, CAP)];
static int n_acts, n_evs, recording = 1;
static rt_program program;
static int order[CAP];          /* the events by priority, as epuckc emits it */

/* The sensor conditions, evaluated like event_sensor's (a generic version
 * of what epuckc generates per program). */
static void conditions(const int *ir, unsigned *bits)
{
    int k;
    unsigned n;
    for (k = 0; k < RT_WORDS(n_evs); k++)
        bits[k] = 0;
    for (k = 0; k < n_evs; k++) {
        const param_event_sensor *p = sensor_params[k];
        if (p == NULL)
            continue;
        for (n = 0; n < 8; n++) {
            if (p->sensef[n] != SENSOR_OFF
                    && ((p->below >> n) & 1u ? ir[n] < p->sensef[n] : ir[n] > p->sensef[n])) {
                bits[k / 16] |= 1u << (k % 16);
                break;
            }
        }
    }
}

static void flush(void)
{
    int k;
    if (!recording)
        return;
    recording = 0;
    if (n_acts == 0 && n_evs == 0)
        return;
    program.actions = acts;
    program.n_actions = n_acts;
    program.events = evs;
    program.n_events = n_evs;
    program.conditions = conditions;
    program.sensors = 0xFF;
    program.state = state;
    program.memory = memory;
    /* with priorities, the order epuckc's programs give (rt_program.order):
     * by priority, highest first, then id (an insertion sort keeps ties in
     * id order) */
    program.order = NULL;
    for (k = 0; k < n_evs; k++) {
        if (evs[k].priority != 0)
            program.order = order;
    }
    if (program.order != NULL) {
        for (k = 0; k < n_evs; k++) {
            int j = k;
            while (j > 0 && evs[order[j - 1]].priority < evs[k].priority) {
                order[j] = order[j - 1];
                j--;
            }
            order[j] = k;
        }
    }
    if (register_program(&program) != 0) {
        fprintf(stderr, "static_path: register_program refused the tables\n");
        exit(99);
    }
    /* the names the host gives event_sensor / sensor when registered, then
     * those the program gave while its registrations were collected */
    for (k = 0; k < n_evs; k++) {
        if (sensor_names[k] != NULL)
            name_event(k, sensor_names[k]);
        if (event_names[k] != NULL)
            name_event(k, event_names[k]);
    }
    for (k = 0; k < n_acts; k++) {
        if (action_names[k] != NULL)
            name_action(k, action_names[k]);
    }
    for (k = 0; k < MODES; k++) {
        if (mode_names[k] != NULL)
            name_mode(k, mode_names[k]);
    }
}

int sp_register_action(action_func f, void *param)
{
    if (recording && f != NULL && n_acts < CAP) {
        acts[n_acts].action_function = f;
        acts[n_acts].action_param = param;
        return n_acts++;
    }
    flush();
    return register_action(f, param);
}

int sp_register_event(event_func f, void *param, int action_id)
{
    if (recording && f != NULL && action_id >= 0 && action_id < n_acts && n_evs < CAP) {
        rt_event *e = &evs[n_evs];
        e->event_param = param;
        e->action_id = action_id;
        e->flags = 0;
        e->memory = n_evs;
        e->priority = 0;
        e->mode = 0;
        e->event_function = f;
        if ((f == event_sensor || f == sensor) && param != NULL) {
            e->event_function = NULL;
            e->event_param = NULL;
            e->memory = RT_NO_MEMORY;
            sensor_params[n_evs] = (const param_event_sensor *)param;
            sensor_names[n_evs] = f == sensor ? "sensor" : "event_sensor";
        }
        return n_evs++;
    }
    flush();
    return register_event(f, param, action_id);
}

void sp_cancel_action(int id) { flush(); cancel_action(id); }
void sp_cancel_event(int id) { flush(); cancel_event(id); }
void sp_set_event_repeat(int id, int repeat)
{
    if (recording && id >= 0 && id < n_evs) {
        evs[id].flags = repeat ? RT_REPEAT : 0;
        return;
    }
    flush();
    set_event_repeat(id, repeat);
}

/* Names given while collecting are kept (the pointers: string literals)
 * and given at the flush, so naming does not end the tables. */
void sp_name_action(int id, const char *name)
{
    if (recording && id >= 0 && id < n_acts) {
        action_names[id] = name;
        return;
    }
    flush();
    name_action(id, name);
}

void sp_name_event(int id, const char *name)
{
    if (recording && id >= 0 && id < n_evs) {
        event_names[id] = name;
        return;
    }
    flush();
    name_event(id, name);
}
void sp_mainloop(void) { flush(); mainloop(); }
/* a program that registers its own tables: nothing to collect */
int sp_register_program(const rt_program *p) { flush(); return register_program(p); }
void sp_set_event_priority(int id, int priority)
{
    if (recording && id >= 0 && id < n_evs) {
        evs[id].priority = priority;
        return;
    }
    flush();
    set_event_priority(id, priority);
}

void sp_set_event_mode(int id, int mode)
{
    if (recording && id >= 0 && id < n_evs && mode >= 0) {
        evs[id].mode = mode;
        return;
    }
    flush();
    set_event_mode(id, mode);
}

void sp_enter_mode(int mode) { flush(); enter_mode(mode); }
void sp_disarm_event(int id) { flush(); disarm_event(id); }
void sp_name_mode(int mode, const char *name)
{
    if (recording && mode > 0 && mode < MODES) {
        mode_names[mode] = name;
        return;
    }
    flush();
    name_mode(mode, name);
}

/*
 * rt_comm.c - IR messages between robots: `send`, `on message` and the
 * readings `message`, `message_bearing`, `message_range` (epuckrt.h).
 *
 * Below it, libIrcom's API: ircomStart, ircomEnableContinuousListening,
 * ircomListen, ircomSend, ircomIsSending, ircomPopMessage.  On the e-puck2
 * the firmware's src/ircom; on the host (the stub harness and Enki worlds)
 * host/stub_devices.c.  The e-puck (dspic) build has no libIrcom: the
 * checker refuses these names for that target (E070), and this file is not
 * in its project.
 *
 * The runtime keeps its own queue of RT_MESSAGE_QUEUE messages: at every
 * poll (rt_device_poll, set at the first use) it moves what the library
 * received into it, so libIrcom's own queue (20, IRCOM_MESSAGES_MAX) never
 * overflows while the program runs; when the runtime's is full, the
 * oldest message is dropped for the new one (the newest say most about
 * where the others are now).  event_message takes one message a poll.
 * Messages with a transmission error (libIrcom's CRC) are dropped.
 */
#include "rt_clock.h"

#include "ircom/ircom.h"
#include "ircom/ircomSend.h"
#include "ircom/ircomReceive.h"
#include "ircom/ircomMessages.h"
#ifdef EPUCKRT_EPUCK2
#include "sensors/proximity.h"
#endif

#define RT_PI 3.14159265358979f

struct rt_message {
    int value;
    int bearing;    /* deg, -180..179, counter-clockwise */
    int range;      /* mm */
};

static struct rt_message queue[RT_MESSAGE_QUEUE];
static struct rt_message current;   /* the message of the last event_message */
static int q_begin, q_count;
static unsigned long dropped;
static int started;
static int waiting = -1;            /* a value waiting for the transmitter */
static unsigned long moved_in = 0;  /* rt_poll_count of the last move (0: none) */
static unsigned long taken_in = 0;  /* rt_poll_count of the last take */
static int taken;                   /* event_message took one in that poll */

static void comm_poll(void);
static int comm_idle(void);

static void start(void)
{
    if (started)
        return;
    started = 1;
#ifdef EPUCKRT_EPUCK2
    /* libIrcom samples the IR receivers itself (its ircomStart wants the
     * proximity module stopped) and keeps the proximity readings at 5 Hz */
    proximity_stop();
#endif
    ircomStart();
#ifdef EPUCKRT_EPUCK2
    ircomEnableProximity();
#endif
    ircomEnableContinuousListening();
    ircomListen();
    rt_device_poll = comm_poll;
    rt_device_idle = comm_idle;
}

static void push(const struct rt_message *m)
{
    if (q_count == RT_MESSAGE_QUEUE) {  /* full: the oldest goes */
        q_begin = (q_begin + 1) % RT_MESSAGE_QUEUE;
        q_count--;
        dropped++;
    }
    queue[(q_begin + q_count) % RT_MESSAGE_QUEUE] = *m;
    q_count++;
}

/* direction (rad, 0..2 pi) to whole degrees -180..179 */
static int degrees(float direction)
{
    long d = (long)(direction * 180.0f / RT_PI + 0.5f) % 360L;
    if (d < 0)
        d += 360L;
    return (int)(d >= 180L ? d - 360L : d);
}

/* Once per poll: the transmitter and what the library received. */
static void comm_poll(void)
{
    IrcomMessage m;
    int n;

    if (moved_in == rt_poll_count)
        return;
    moved_in = rt_poll_count;
    if (waiting >= 0 && !ircomIsSending()) {
        ircomSend((long)waiting);
        RT_TRACE_SEND(waiting);
        waiting = -1;
    }
    for (n = 0; n < IRCOM_MESSAGES_MAX; n++) {
        struct rt_message r;
        float mm;
        ircomPopMessage(&m);
        if (m.error == -1)
            break;
        if (m.error != 0)
            continue;
        mm = m.distance * 10.0f + 0.5f;
        r.value = (int)(m.value & 0xFFL);
        r.bearing = degrees(m.direction);
        r.range = mm <= 0.0f ? 0 : mm >= 1000.0f ? 1000 : (int)mm;
        RT_TRACE_MESSAGE(r.value, r.bearing, r.range);
        push(&r);
    }
}

/* The poll of a cycle that rt_idle.c skips would do nothing: no value
 * waits for the transmitter (what the library received comes with the
 * inputs, which end a bulk; each poll moves it all into the queue, and a
 * message event takes one a poll, which is a change). */
static int comm_idle(void)
{
    return waiting < 0;
}

void action_send(void *param)
{
    const param_send *p = (const param_send *)param;
    int value;

    if (p == NULL)
        return;
    start();
    value = (int)((unsigned)p->value & 0xFFu);
    if (ircomIsSending())
        waiting = value;
    else {
        ircomSend((long)value);
        RT_TRACE_SEND(value);
    }
}

void event_message(void *param, void *status)
{
    event_status *st = (event_status *)status;

    (void)param;
    start();
    comm_poll();
    if (taken_in != rt_poll_count) {     /* one message a poll, for every rule */
        taken_in = rt_poll_count;
        taken = q_count > 0;
        if (taken) {
            current = queue[q_begin];
            q_begin = (q_begin + 1) % RT_MESSAGE_QUEUE;
            q_count--;
        }
    }
    st->occurred = taken;
}

int rt_message(void)
{
    return current.value;
}

int rt_message_bearing(void)
{
    return current.bearing;
}

int rt_message_range(void)
{
    return current.range;
}

unsigned long rt_messages_dropped(void)
{
    return dropped;
}

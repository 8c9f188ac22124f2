/*
 * rt_trace.c - the robot's trace (`epuckc build --trace`; docs/runtime.md,
 * "The robot's trace"): the records the host harness traces (events with
 * their rule, actions and sequence steps, variables, modes, suppressed
 * motor commands, who holds the motors, LEDs, sounds, messages, the exit),
 * each a frame of a few bytes on the robot's serial link, which `epuckc
 * monitor` decodes with the table the build wrote beside the program
 * (epuckc/link/).  Built only with EPUCKRT_TRACE; it then provides the
 * trace hooks of rt_platform.h in place of the platform's.
 *
 * A frame on the wire: COBS(payload, its CRC-16 low byte first), then a 0
 * byte.  The 0 ends every frame and COBS keeps it out of the frame, so a
 * reader that lost or mangled bytes starts again at the next 0; the CRC
 * (CRC-16/MCRF4XX: polynomial 0x1021 reflected, initial value 0xFFFF, check
 * value 0x6F91) tells a mangled frame from a whole one, and the frames'
 * sequence number (a byte, one more each frame sent) tells how many were
 * lost, even when nothing of them arrived.  A payload is its kind (a
 * byte), its sequence number, the low 16 bits of the ms clock (rt_millis;
 * a hello has the whole clock), then its fields: ids and counts unsigned LEB128 (7 bits a byte, low first), signed
 * values zigzag LEB128, the wheels' 16-bit step counters as the library
 * gives them (the reader unwraps them), 16- and 32-bit numbers
 * little-endian.
 *
 * Records wait in a ring of EPUCKRT_TRACE_BUFFER bytes, as payloads (a
 * length byte, then the payload): a hook writes its record there, hands
 * the link what it can take and returns; it never waits.  The framing (the
 * CRC, COBS) happens when the link has room: the ring's next payloads are
 * framed into one piece of up to 96 bytes that the link sends (rt_trace_
 * port_*, one file per platform), so a poll that traces much pays for its
 * records, and the frames are made at the pace of the link.  A record that
 * does not fit is dropped whole and counted; the count goes out before
 * any later record (a `dropped` record), and in every hello.  A
 * hello starts the stream and comes again every second: the fingerprint
 * of the program's table (EPUCKRT_TRACE_ID, from the build), the format,
 * the whole ms clock, the drops so far, the wheels; a tick gives the
 * wheels' counters every 100 ms while they turn (for the reader's
 * odometry).  Correct where int is 16 bits.
 */
#include <string.h>

#include "rt_internal.h"

#ifndef EPUCKRT_TRACE_BUFFER
#define EPUCKRT_TRACE_BUFFER 256
#endif
#ifndef EPUCKRT_TRACE_ID
#define EPUCKRT_TRACE_ID 0UL        /* the build gives the table's fingerprint */
#endif

#define FORMAT 1u
#define HELLO_MS 1000L
#define TICK_MS 100L
#define MAX_PAYLOAD 40u         /* the longest payload (a hello's 21 bytes) and its
                                   CRC, far below COBS's 254: one code byte a frame */
#define SMALLEST_FRAME 10u      /* a payload of no field and its length, and a few:
                                   what drops a record before anything of it is made */
#define FLUSH_WAITS 250         /* at the end: at most so many waits without progress */

/* the payloads' kinds (epuckc/link/stream.py has the same) */
#define K_HELLO 1u
#define K_TICK 2u
#define K_DROPPED 3u
#define K_EVENT 16u
#define K_ACTION 17u
#define K_SET 18u
#define K_SUPPRESSED 19u
#define K_MODE 20u
#define K_MOTORS 21u
#define K_LED 22u
#define K_SOUND 23u
#define K_SEND 24u
#define K_MESSAGE 25u
#define K_EXIT 26u
#define K_TIMEOUT 27u

#if EPUCKRT_TRACE_BUFFER < 64 || EPUCKRT_TRACE_BUFFER > 16384 \
    || (EPUCKRT_TRACE_BUFFER & (EPUCKRT_TRACE_BUFFER - 1)) != 0
#error "EPUCKRT_TRACE_BUFFER: a power of two, 64 to 16384 bytes"
#endif

static unsigned char ring[EPUCKRT_TRACE_BUFFER];
static unsigned head, tail, used;     /* the ring of payloads waiting for the link */
static unsigned char payload[MAX_PAYLOAD];
static unsigned char length;
static unsigned char started, sequence;
static unsigned long dropped, dropped_told;     /* records dropped; of which told */
static long hello_at, tick_at;
static unsigned ticked_left, ticked_right;
static unsigned char led_ring, led_body, led_front;    /* the LEDs as commanded */
static unsigned char told_ring, told_body, told_front; /* as the last LED records said */
static void leds_changed(void);

/* ---- the frame ---------------------------------------------------------------- */

#define PUT(v) (payload[length++] = (unsigned char)((v) & 0xFFu))

static void put16(unsigned v)
{
    PUT(v);
    PUT(v >> 8);
}

static void put32(unsigned long v)
{
    put16((unsigned)(v & 0xFFFFUL));
    put16((unsigned)(v >> 16));
}

/* unsigned LEB128 of an id, a count, a zigzag value */
static void put_uvar(unsigned v)
{
    while (v >= 0x80u) {
        PUT((v & 0x7Fu) | 0x80u);
        v >>= 7;
    }
    PUT(v);
}

static void put_uvar_long(unsigned long v)
{
    while (v >= 0x80UL) {
        PUT((unsigned)(v & 0x7FUL) | 0x80u);
        v >>= 7;
    }
    PUT((unsigned)v);
}

/* zigzag: 0, -1, 1, -2 ... as 0, 1, 2, 3 ... (no signed overflow) */
static void put_svar(int v)
{
    put_uvar(v < 0 ? ((unsigned)(-(v + 1)) << 1) | 1u : (unsigned)v << 1);
}

/* an id that may be -1 (none, main): id + 1 */
static void put_id(int id)
{
    put_uvar(id < 0 ? 0u : (unsigned)id + 1u);
}

static void put_steps(void)
{
    put16((unsigned)e_get_steps_left());
    put16((unsigned)e_get_steps_right());
}

static void start_payload(unsigned kind)
{
    length = 0;
    PUT(kind);
    PUT(0);                     /* the sequence number, when it is framed */
    put16((unsigned)((unsigned long)rt_millis() & 0xFFFFUL));
}

#define MASK (EPUCKRT_TRACE_BUFFER - 1u)

/* The payload into the ring as it is, its length first: 1, or 0 (and
 * nothing written) when it does not fit.  The framing waits for the link
 * (below), so that a poll that traces much pays for its records, not for
 * their frames.  Locals throughout: a store into the ring may alias any
 * global. */
static int queue(void)
{
    const unsigned char *p = payload;
    unsigned at = head, n = length;

    if (EPUCKRT_TRACE_BUFFER - used < n + 1u)
        return 0;
    ring[at] = (unsigned char)n;
    at = (at + 1u) & MASK;
    if (at + n <= EPUCKRT_TRACE_BUFFER) {
        memcpy(ring + at, p, n);
    } else {
        unsigned first = EPUCKRT_TRACE_BUFFER - at;
        memcpy(ring + at, p, first);
        memcpy(ring, p + first, n - first);
    }
    head = (at + n) & MASK;
    used += n + 1u;
    return 1;
}

/* ---- the link ------------------------------------------------------------------- */

/* The frames being sent: as many of the ring's payloads as fit, framed
 * when the link has sent the ones before (one piece for the link, which
 * keeps it until it is sent). */
#define WIRE_BYTES 96u
static unsigned char wire[WIRE_BYTES];
static unsigned char wire_length, wire_sent, inflight;

/* The CRC a byte at a time in 8-bit halves: with x = byte ^ low, x ^= x <<
 * 4, the new low is high ^ x >> 4 ^ x << 3 and the new high is x ^ x >> 5
 * (the 16-bit x << 8 ^ x << 3 ^ x >> 4 of the reflected 0x1021). */
#define CRC(b) do { \
        unsigned char x_ = (unsigned char)((b) ^ lo); \
        x_ ^= (unsigned char)(x_ << 4); \
        lo = (unsigned char)(hi ^ (x_ >> 4) ^ (unsigned char)(x_ << 3)); \
        hi = (unsigned char)(x_ ^ (x_ >> 5)); \
    } while (0)
/* one byte of COBS: a 0 closes the block its code byte opened */
#define COBS_PUT(b) do { \
        if ((b) == 0) { *code_at = code; code_at = out++; code = 1; } \
        else { *out++ = (b); code++; } \
    } while (0)

/* The ring's next payloads as frames into the wire, while they fit: each
 * COBS(payload, CRC low byte first) and a 0, its sequence number set. */
static void frame_next(void)
{
    unsigned char *out = wire;

    wire_length = wire_sent = 0;
    while (used != 0) {
        unsigned n = ring[tail], at = (tail + 1u) & MASK, k;
        unsigned char lo = 0xFFu, hi = 0xFFu, code = 1, *code_at;

        if ((unsigned)(out - wire) + n + 4u > WIRE_BYTES)
            break;              /* the next piece's */
        code_at = out++;
        for (k = 0; k < n; k++) {
            unsigned char b = k == 1u ? sequence : ring[at];
            CRC(b);
            COBS_PUT(b);
            at = (at + 1u) & MASK;
        }
        COBS_PUT(lo);
        COBS_PUT(hi);
        *code_at = code;
        *out++ = 0;
        sequence++;
        tail = at;
        used -= n + 1u;
    }
    wire_length = (unsigned char)(out - wire);
}

/* Hand the link what it can take now; never waits. */
static void drain(void)
{
    for (;;) {
        if (inflight != 0) {
            if (rt_trace_port_busy())
                return;
            wire_sent = (unsigned char)(wire_sent + inflight);
            inflight = 0;
        }
        if (wire_sent == wire_length) {
            if (used == 0)
                return;
            frame_next();
        }
        inflight = (unsigned char)rt_trace_port_send(wire + wire_sent,
                                                     (int)(wire_length - wire_sent));
        if (inflight == 0)
            return;             /* the link takes nothing now */
    }
}

static void start(void);

/* The end of the run: what is queued goes out (a bounded wait: a link
 * that takes nothing for FLUSH_WAITS waits is given up). */
static void flush(void)
{
    unsigned before = used + WIRE_BYTES + 1u;
    int waits = 0;

    if (!started)
        start();
    drain();
    while ((used != 0 || wire_sent != wire_length) && waits < FLUSH_WAITS) {
        unsigned left = used + (unsigned)(wire_length - wire_sent);
        rt_trace_port_wait();
        drain();
        if (left < before) {
            before = left;
            waits = 0;
        } else {
            waits++;
        }
    }
    rt_trace_port_wait();       /* the last bytes leave the transmitter */
}

/* ---- hello, tick, drops --------------------------------------------------------- */

static int hello(unsigned first)
{
    long now = rt_millis();

    length = 0;
    PUT(K_HELLO);
    PUT(0);
    PUT(FORMAT);
    PUT(first);
    put32(EPUCKRT_TRACE_ID);
    put32((unsigned long)now);
    put_uvar_long(dropped);
    put_steps();
    if (!queue())
        return 0;
    hello_at = now;
    dropped_told = dropped;
    return 1;
}

static void start(void)
{
    started = 1;
    rt_trace_port_start();
    tick_at = rt_millis();
    ticked_left = (unsigned)e_get_steps_left();
    ticked_right = (unsigned)e_get_steps_right();
    (void)hello(1u);
}

/* A record begins: 0 when it is dropped at once (the drops not yet told
 * do not fit before it: a record never overtakes them). */
static int begin(unsigned kind)
{
    if (!started)
        start();
    if (kind != K_LED)
        leds_changed();         /* the LEDs' changes before any other record */
    if (EPUCKRT_TRACE_BUFFER - used < SMALLEST_FRAME) {
        dropped++;              /* not even the smallest frame fits: at once */
        return 0;
    }
    if (dropped != dropped_told) {
        start_payload(K_DROPPED);
        put_uvar_long(dropped);
        if (!queue()) {
            dropped++;
            return 0;
        }
        dropped_told = dropped;
    }
    start_payload(kind);
    return 1;
}

static void end(void)
{
    if (!queue())
        dropped++;
    drain();
}

void rt_tracer_poll(void)
{
    long now = rt_millis();

    if (!started)
        start();
    if (now - hello_at >= HELLO_MS) {
        (void)hello(0u);
    } else if (now - tick_at >= TICK_MS) {
        unsigned left = (unsigned)e_get_steps_left(), right = (unsigned)e_get_steps_right();
        if (left != ticked_left || right != ticked_right) {
            start_payload(K_TICK);
            put16(left);
            put16(right);
            if (queue()) {
                ticked_left = left;
                ticked_right = right;
                tick_at = now;
            }
        } else {
            tick_at = now;
        }
    }
    drain();
}

/* ---- the hooks (rt_platform.h) ---------------------------------------------------- */

void rt_trace_event(int event_id)
{
    if (!begin(K_EVENT))
        return;
    put_uvar((unsigned)event_id);
    put_steps();
    end();
}

void rt_trace_action(int action_id, int step, int steps)
{
    if (!begin(K_ACTION))
        return;
    put_uvar((unsigned)action_id);
    put_steps();
    if (step >= 0) {
        put_uvar((unsigned)step);
        put_uvar((unsigned)steps);
    }
    end();
}

/* The end of the run: the poll is over, so the end's record waits for
 * room (the ring emptied first) rather than be dropped. */
static void last_record(unsigned kind)
{
    flush();
    if (begin(kind)) {
        put_steps();
        end();
    }
    flush();
}

void rt_trace_exit(void)
{
    last_record(K_EXIT);
}

void rt_tracer_timeout(void)
{
    last_record(K_TIMEOUT);
}

/* the commands rt_motion.c names (epuckc/link/stream.py: COMMANDS) */
static const char *const commands[] = {
    "start_straight", "start_curve", "set_speed", "stop_motor", "run_sequence"
};

void rt_trace_suppressed(int event_id, int priority, int owner_event_id,
                         int owner_priority, const char *command)
{
    unsigned k;

    if (!begin(K_SUPPRESSED))
        return;
    put_id(event_id);
    put_svar(priority);
    put_id(owner_event_id);
    put_svar(owner_priority);
    for (k = 0; k < sizeof commands / sizeof commands[0]; k++)
        if (strcmp(commands[k], command) == 0)
            break;
    PUT(k);                     /* past the list: a command the reader names by number */
    put_steps();
    end();
}

void rt_trace_mode(int mode)
{
    if (!begin(K_MODE))
        return;
    put_uvar((unsigned)mode);
    put_steps();
    end();
}

void rt_trace_set(int id, int value)
{
    if (!begin(K_SET))
        return;
    put_uvar((unsigned)id);
    put_svar(value);
    end();
}

void rt_trace_motors(int active, int owner_event_id)
{
    if (!begin(K_MOTORS))
        return;
    PUT(active != 0);
    put_id(owner_event_id);
    put_steps();
    end();
}

/* 0 off, 1 on, anything else toggles, as the library */
static unsigned char led_value(unsigned char old, int value)
{
    return (unsigned char)(value == 0 ? 0 : value == 1 ? 1 : !old);
}

/* The LEDs as the host's trace has them (host/outputs.c): a record when
 * they differ from what the last records said, before any other record
 * and at the poll's end (rt_tracer_poll_end), not one per call: the whole
 * ring in one "all" record when all eight changed, else each LED that did,
 * then the body and front LEDs; each record with the LEDs as they are. */
void rt_tracer_led(int led, int value)
{
    if (led == SET_LED_BODY) {
        led_body = led_value(led_body, value);
    } else if (led == SET_LED_FRONT) {
        led_front = led_value(led_front, value);
    } else if (led >= 0 && led < SET_LED_ALL) {
        unsigned char bit = (unsigned char)(1u << (unsigned)led);
        unsigned char state = led_value((led_ring & bit) != 0, value);
        led_ring = (unsigned char)(state ? led_ring | bit : led_ring & ~bit);
    } else {                    /* all eight, each as e_set_led does */
        led_ring = (unsigned char)(value == 0 ? 0x00u : value == 1 ? 0xFFu : led_ring ^ 0xFFu);
    }
}

static void led_record(unsigned led, unsigned state)
{
    if (!begin(K_LED))
        return;
    PUT(led | state << 4 | (unsigned)led_body << 5 | (unsigned)led_front << 6);
    PUT(led_ring);
    put_steps();
    end();
}

static void leds_changed(void)
{
    unsigned char ring_changed = (unsigned char)(led_ring ^ told_ring);
    unsigned char body = (unsigned char)(led_body != told_body);
    unsigned char front = (unsigned char)(led_front != told_front);
    unsigned n;

    told_ring = led_ring;
    told_body = led_body;
    told_front = led_front;
    if (ring_changed == 0xFFu)
        led_record((unsigned)SET_LED_ALL, led_ring & 1u);
    else
        for (n = 0; n < 8; n++)
            if (ring_changed & (1u << n))
                led_record(n, (led_ring >> n) & 1u);
    if (body)
        led_record((unsigned)SET_LED_BODY, led_body);
    if (front)
        led_record((unsigned)SET_LED_FRONT, led_front);
}

void rt_tracer_poll_end(void)
{
    leds_changed();
}

void rt_tracer_sound(int sound)
{
    if (!begin(K_SOUND))
        return;
    PUT((unsigned)sound);
    put_steps();
    end();
}

void rt_tracer_send(int value)
{
    if (!begin(K_SEND))
        return;
    PUT((unsigned)value);
    put_steps();
    end();
}

void rt_tracer_message(int value, int bearing, int range)
{
    if (!begin(K_MESSAGE))
        return;
    PUT((unsigned)value);
    put_svar(bearing);
    put_uvar(range < 0 ? 0u : (unsigned)range);
    put_steps();
    end();
}

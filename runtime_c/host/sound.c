/*
 * sound.c - the e-puck's sound, as the library drives it (codec/e_sound.h,
 * a_d/advance_ad_scan/e_micro.h; written from the library's documented
 * behaviour, none of its code).
 *
 * The speaker.  e_play_sound(offset, length) plays `length` words of the
 * samples of codec/e_const_sound.s from `offset`, through the Si3000 codec
 * at the DCI's 7200 samples a second, four a DCI interrupt: the flags the
 * library's programs wait on are as on the robot, e_dci_unavailable
 * non-zero (-1) while a sample plays, for its real length (8016 words:
 * 1113 ms), and e_stop_flag, which a program sets to stop the sample at
 * the next interrupt, and the interrupt sets (-1) when the sample ends.
 * A sample that starts is an output record ("sound": its name, its length
 * in words); playing the one that plays again, in the ms it started, is
 * not another.  Without e_init_sound the codec is off: silence.
 *
 * The microphones.  What the scenario gives is each microphone's volume
 * (what e_get_micro_volume reports: the largest less the smallest of the
 * last MIC_SAMP_NB samples); the samples (e_mic_scan, e_get_micro) swing
 * around the middle of the A/D's 12 bits by that much.
 */
#include <stddef.h>

#include "epuck_stub.h"
#include "library_sim.h"
#include "p30F6014A.h"
#include "motor_led/e_epuck_ports.h"
#include "codec/e_sound.h"
#include "a_d/advance_ad_scan/e_micro.h"

#define SAMPLES_PER_S 7200L
#define WORDS_A_INTERRUPT 4L

int e_dci_unavailable;
int e_stop_flag;

static int codec_on;
static long left;                   /* words still to send */
static unsigned long long started;  /* cycles, the play's start */
static long interrupts;             /* the DCI interrupts of this play so far */
static long started_ms = -1;
static int last_offset = -1, last_length = -1;

void e_init_dci_master(void)
{
}

void e_init_codec_slave(void)
{
    codec_on = 1;
}

/* As the library: the codec powered (AUDIO_ON), a busy loop of 10000, the
 * DCI and the codec set up. */
void e_init_sound(void)
{
    AUDIO_ON = 1;
    if (stub_cost_hook != NULL)
        stub_cost_hook(10000L, 4);
    e_init_dci_master();
    e_init_codec_slave();
}

void e_close_sound(void)
{
    AUDIO_ON = 0;
    codec_on = 0;
}

static const char *sample_name(int offset, int length)
{
    static const struct {
        int offset, length;
        const char *name;
    } samples[] = {
        { 0, 2112, "haa" }, { 2116, 1760, "spaah" }, { 3878, 3412, "ouah" },
        { 7294, 3732, "yaouh" }, { 11028, 8016, "wouaaaaaaaah" }
    };
    size_t i;
    for (i = 0; i < sizeof samples / sizeof samples[0]; i++)
        if (samples[i].offset == offset && samples[i].length == length)
            return samples[i].name;
    return "sample";
}

/* The first four words go at once, the rest four an interrupt. */
void e_sub_dci_kickoff(int sound_offset, int sound_length)
{
    long now_ms = (long)(stub_now_cycles() * 1000ULL / STUB_FCY);
    if (!codec_on || !AUDIO_ON) {
        e_dci_unavailable = 0;      /* silence: nothing will ever send */
        return;
    }
    if (!(now_ms == started_ms && sound_offset == last_offset && sound_length == last_length))
        stub_observe("sound", sample_name(sound_offset, sound_length), sound_length);
    started_ms = now_ms;
    last_offset = sound_offset;
    last_length = sound_length;
    left = (long)sound_length - WORDS_A_INTERRUPT;
    started = stub_now_cycles();
    interrupts = 0;
}

void e_play_sound(int sound_offset, int sound_length)
{
    if (stub_cost_hook != NULL)
        stub_cost_hook(1L, STUB_CALL_CYCLES);
    e_dci_unavailable = -1;
    e_stop_flag = 0;
    e_sub_dci_kickoff(sound_offset, sound_length);
}

/* The DCI's interrupts up to now: each sends four more words, or ends the
 * play (nothing left, or told to stop). */
void stub_sound_ms(long now_ms, long n)
{
    unsigned long long due;
    (void)now_ms;
    (void)n;
    if (!e_dci_unavailable)
        return;
    due = (stub_now_cycles() - started) * (unsigned long long)SAMPLES_PER_S
          / (STUB_FCY * (unsigned long long)WORDS_A_INTERRUPT);
    while ((unsigned long long)interrupts < due && e_dci_unavailable) {
        interrupts++;
        if (e_stop_flag || left <= 0) {
            e_dci_unavailable = 0;
            e_stop_flag = -1;
        } else {
            left -= WORDS_A_INTERRUPT;
        }
    }
}

void stub_sound_reset(void)
{
    codec_on = 0;
    e_dci_unavailable = 0;
    e_stop_flag = 0;
    left = 0;
}

/* ---- microphones ------------------------------------------------------------------------ */

static int micro_volume[3];

void stub_set_micro(int n, int volume)
{
    stub_input_set();
    if (n >= 0 && n < 3)
        micro_volume[n] = volume;
}

/* the last samples: alternately half the volume above and below the middle */
static void fill_samples(void)
{
    int m, i;
    for (m = 0; m < 3; m++)
        for (i = 0; i < MIC_SAMP_NB; i++)
            e_mic_scan[m][i] = 2048 + ((i & 1) ? micro_volume[m] - micro_volume[m] / 2
                                                : -(micro_volume[m] / 2));
}

int e_get_micro(unsigned int micro_id)
{
    if (stub_cost_hook != NULL)
        stub_cost_hook(1L, STUB_CALL_CYCLES);
    if (micro_id > 2 || !stub_ad_scan_running())
        return 0;
    fill_samples();
    return e_mic_scan[micro_id][e_last_mic_scan_id % MIC_SAMP_NB];
}

int e_get_micro_average(unsigned int micro_id, unsigned int filter_size)
{
    long sum = 0;
    unsigned int i;
    if (micro_id > 2 || filter_size == 0 || filter_size > MIC_SAMP_NB || !stub_ad_scan_running())
        return 0;
    fill_samples();
    for (i = 0; i < filter_size; i++)
        sum += e_mic_scan[micro_id][(e_last_mic_scan_id + MIC_SAMP_NB - i) % MIC_SAMP_NB];
    return (int)(sum / (long)filter_size);
}

int e_get_micro_volume(unsigned int micro_id)
{
    if (stub_cost_hook != NULL)
        stub_cost_hook(1L, STUB_CALL_CYCLES);
    if (micro_id > 2 || !stub_ad_scan_running())
        return 0;
    fill_samples();
    return micro_volume[micro_id];
}

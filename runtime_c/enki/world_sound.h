/*
 * world_sound.h - sound in a world: its sound sources and the robots'
 * speakers, what plays in each world step, and the model by which each
 * robot's three microphones hear them (world_runner.cpp and its physics
 * providers; docs/world.md, "Sound").  Nothing here needs Enki: the Enki
 * provider (physics_enki.cpp) hears through Enki's Microphone over
 * ActiveSoundObjects, another (physics_chipmunk.cpp) through `volume`
 * below, the same sums in the same order.
 *
 * SPEC line:
 *   sound X Y HZ DB N ON OFF ...   a source at (X, Y) cm playing HZ at DB dB SPL
 *                                  1 m away, during N intervals [ON, OFF) ms
 *                                  (OFF -1: to the end; N 0: all the time)
 *
 * Enki's model (interactions/Microphone.h, ActiveSoundSource.h): a
 * microphone on a robot's body adds up, channel by channel, what its
 * response model makes of each ActiveSoundObject's pitch at the distance
 * between the object's centre and the microphone.  Here a channel is a
 * frequency (one for each of the world's, and the speakers'), a pitch the
 * pressure amplitude 1 m from the source (Pa), and the response spherical
 * spreading: the amplitude falls as 1 / distance (6 dB each time the
 * distance doubles; 1 cm at least).  Enki's World::step never calls its
 * microphones (their init and objectStep do not override LocalInteraction's:
 * the arguments are in another order), so the runner has them hear, after
 * each physics step, the coming step's sounds.
 *
 * A microphone's reading is what e_get_micro_volume gives on the robot:
 * the peak-to-peak of its last samples, in A/D units (12 bits, 0..4095):
 * twice the amplitudes it hears, summed over every source (their peaks
 * can meet), times COUNTS_PER_PA; silence reads 0.  The microphones are
 * where the e-puck2's are (its PCB's coordinates; the e-puck's keep the
 * numbering): 0 on the right, 1 on the left, 2 at the back.  The robot's
 * body does not shadow a sound; nothing echoes.
 *
 * A robot that plays a sample (e_play_sound) is a source at its centre
 * for the sample's length (its words at the codec's 7200 a second), at
 * SPEAKER_DB and SPEAKER_HZ; it hears itself too, as an e-puck does.
 */
#ifndef WORLD_SOUND_H
#define WORLD_SOUND_H

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "world_channel.h"

namespace sound {

const int MICS = 3;
// cm, x forward and y to the left of the axle's middle (the e-puck2's PCB:
// right and left 30.3 mm out and 8.35 mm ahead, back 23.05 mm behind)
const double MIC_AT[MICS][2] = {{0.835, -3.03}, {0.835, 3.03}, {-2.305, 0.0}};
// A/D units per pascal of amplitude: 100 dB SPL (2.83 Pa at its peaks)
// fills the 12 bits (an assumption: the sensitivity was not measured)
const double COUNTS_PER_PA = 4095.0 / (2.0 * 2.0 * std::sqrt(2.0));
const double MAX_VOLUME = 4095.0;
const double SPEAKER_DB = 60.0;         // an e-puck's speaker, 1 m away (80 dB at 10 cm)
const double SPEAKER_HZ = 1000.0;
const double CODEC_WORDS_PER_S = 7200.0;
const double MIN_DISTANCE_CM = 1.0;

// dB SPL (re 20 uPa, an RMS) to a tone's amplitude in Pa
inline double amplitude_pa(double db) { return 20e-6 * std::pow(10.0, db / 20.0) * std::sqrt(2.0); }

// Enki's MicrophoneResponseModel: the amplitude at `distance` cm of a
// source whose amplitude 1 m away is `pitch`
inline double spreading(double pitch, double distance)
{
    return pitch * 100.0 / std::max(distance, MIN_DISTANCE_CM);
}

// What the microphones add up, in A/D units (rounded, at most 4095).
inline int volume_of(double amplitude)
{
    double v = std::floor(2.0 * amplitude * COUNTS_PER_PA + 0.5);
    return (int)(v > MAX_VOLUME ? MAX_VOLUME : v);
}

// Microphone m of a body at `p`, in the world (Enki's owner->pos + rot * pos).
inline void mic_position(const channel::Pose &p, int m, double *x, double *y)
{
    const double c = std::cos(p.angle), s = std::sin(p.angle);
    *x = p.x + (MIC_AT[m][0] * c + MIC_AT[m][1] * -s);
    *y = p.y + (MIC_AT[m][0] * s + MIC_AT[m][1] * c);
}

struct Source {
    double x = 0, y = 0, hz = 0, db = 0;
    unsigned channel = 0;
    std::vector<long> on;               // ON, OFF, ...: [ON, OFF) ms, OFF -1: no end

    // it plays during some of [from, to)
    bool playing(long from, long to) const
    {
        if (on.empty())
            return true;
        for (size_t i = 0; i + 1 < on.size(); i += 2)
            if (on[i] < to && (on[i + 1] < 0 || on[i + 1] > from))
                return true;
        return false;
    }
};

// What plays in one world step, in the order the microphones add it up:
// the world's sources, then the robots' speakers.
struct Playing {
    std::vector<size_t> sources;        // indexes into Scene::sources()
    std::vector<size_t> speakers;       // robots
    bool silent() const { return sources.empty() && speakers.empty(); }
};

class Scene {
public:
    // a `sound ...` line; false with *error when it cannot be read
    bool add_source(const char *line, std::string *error)
    {
        Source s;
        int n = 0, used = 0;
        if (std::sscanf(line, "sound %lf %lf %lf %lf %d%n", &s.x, &s.y, &s.hz, &s.db, &n, &used) != 5
                || n < 0 || n > 1000) {
            *error = "a sound line is `sound X Y HZ DB N ON OFF ...`";
            return false;
        }
        const char *p = line + used;
        for (int i = 0; i < 2 * n; i++) {
            long t;
            int k = 0;
            if (std::sscanf(p, "%ld%n", &t, &k) != 1) {
                *error = "a sound line has fewer times than it says";
                return false;
            }
            s.on.push_back(t);
            p += k;
        }
        sources_.push_back(s);
        return true;
    }

    // Once every source is read: the channels (one per frequency) and
    // each of `robots` robots' speaker, silent.
    void listen(size_t robots)
    {
        hz_.assign(1, SPEAKER_HZ);
        for (const Source &s : sources_)
            hz_.push_back(s.hz);
        std::sort(hz_.begin(), hz_.end());
        hz_.erase(std::unique(hz_.begin(), hz_.end()), hz_.end());
        for (Source &s : sources_)
            s.channel = channel(s.hz);
        speaker_from_.assign(robots, 0);
        speaker_to_.assign(robots, -1);
    }

    unsigned channels() const { return (unsigned)hz_.size(); }
    unsigned channel(double hz) const
    {
        return (unsigned)(std::lower_bound(hz_.begin(), hz_.end(), hz) - hz_.begin());
    }
    const std::vector<Source> &sources() const { return sources_; }

    // Robot i started a sample of `words` words at `at_ms`: its speaker
    // plays it (and stops the one it played)
    void played(size_t i, long at_ms, long words)
    {
        speaker_from_[i] = at_ms;
        speaker_to_[i] = at_ms + (long)std::ceil(words * 1000.0 / CODEC_WORDS_PER_S);
        any_speaker_ = true;
    }

    // What plays during [from, to) ms.
    void playing(long from, long to, Playing *out) const
    {
        out->sources.clear();
        out->speakers.clear();
        for (size_t k = 0; k < sources_.size(); k++)
            if (sources_[k].playing(from, to))
                out->sources.push_back(k);
        if (any_speaker_)
            for (size_t i = 0; i < speaker_to_.size(); i++)
                if (speaker_to_[i] > from && speaker_from_[i] < to)
                    out->speakers.push_back(i);
    }

    // What a microphone at (x, y) hears of `playing`, the robots where
    // `poses` has them, in A/D units: Enki's Microphone's sums, channel by
    // channel in the order of `playing`, then over the channels.
    int volume(const Playing &playing, const std::vector<channel::Pose> &poses, double x,
               double y) const
    {
        thread_local std::vector<double> heard;
        const unsigned n = channels();
        heard.assign(n, 0.0);
        const unsigned speaker = channel(SPEAKER_HZ);
        const double speaker_pitch = amplitude_pa(SPEAKER_DB);
        for (size_t k : playing.sources) {
            const Source &s = sources_[k];
            const double dx = s.x - x, dy = s.y - y;
            heard[s.channel] += spreading(amplitude_pa(s.db), std::sqrt(dx * dx + dy * dy));
        }
        for (size_t i : playing.speakers) {
            const double dx = poses[i].x - x, dy = poses[i].y - y;
            heard[speaker] += spreading(speaker_pitch, std::sqrt(dx * dx + dy * dy));
        }
        double amplitude = 0;
        for (unsigned c = 0; c < n; c++)
            amplitude += heard[c];
        return volume_of(amplitude);
    }

private:
    std::vector<Source> sources_;
    std::vector<double> hz_{SPEAKER_HZ};
    std::vector<long> speaker_from_, speaker_to_;   // [from, to) ms each plays; to < 0: never
    bool any_speaker_ = false;
};

}  // namespace sound

#endif

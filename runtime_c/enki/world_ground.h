/*
 * world_ground.h - the floor of a world and the robots' ground sensors
 * (world_runner.cpp and its physics providers; docs/world.md, "The floor
 * and the ground sensors").  Nothing here needs Enki: the Enki provider
 * (physics_enki.cpp) hands the floor to Enki as its ground texture and
 * reads Enki's GroundSensors; another provider (physics_chipmunk.cpp)
 * reads the same floor with the same model through `Sensor` below.
 *
 * SPEC lines:
 *   floor W H PATH     the floor: W x H pixels of r, g, b bytes in PATH, the
 *                      row of y = 0 first, spanning the arena (epuckc/sim/
 *                      floor.py draws it from the world's `floor` lines)
 *   ground             (after a robot) it carries GCtronic's ground-sensor
 *                      module: its program reads ground0..2
 *
 * The floor is the arena's ground texture (Enki's World::GroundTexture);
 * a walled world without a floor line gets white paper.  The module is
 * three ground sensors (Enki's GroundSensor, as Enki's Thymio carries two;
 * Enki's e-puck has none) on the robot's body, 3 cm ahead of its axle, at
 * 1 cm to the left, under the centre and 1 cm to the right (Webots'
 * e-puck has its gs0..gs2 there).  Each reads the floor's grey level (the
 * mean of r, g, b, 0..1) under a spot: 9 x 9 samples 0.25 cm apart over
 * 2 x 2 cm, weighed by a Gaussian of SD 2 mm (Enki's kernel, normalised),
 * a point outside the texture reading the walls' grey as Enki's
 * World::getGroundColor does; then Enki's sigmoid response, set so that
 * white (grey 1) gives 1000 and black (0) 0, as GCtronic's module reads
 * white paper and black tape, plus Gaussian noise (SD 5), rounded and kept
 * in 0..4095.  Open ground has no floor (Enki's has no texture there): a
 * robot's ground sensors are not attached, and read the stub's white paper.
 */
#ifndef WORLD_GROUND_H
#define WORLD_GROUND_H

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace ground {

const int SENSORS = 3;
const double AHEAD_CM = 3.0, APART_CM = 1.0;    // ground0 at +1 cm (left), ground2 at -1 cm
const double SPOT_SD_CM = 0.2, NOISE_SD = 5.0;
// Enki's response: sigm(v - C, S) * M + A, with M and A such that grey 0
// gives 0 and grey 1 gives WHITE (sigm(x, s) = 1 / (1 + e^(-x s)))
const double C = 0.5, S = 4.0, WHITE = 1000.0;
const double MAX_READING = 4095.0;

inline double sigm(double x) { return 1.0 / (1.0 + std::exp(-x * S)); }
inline double response_m() { return WHITE / (sigm(1.0 - C) - sigm(-C)); }
inline double response_a() { return -response_m() * sigm(-C); }

// A sensor's value as get_ground_prox reads it: rounded, 0..4095.
inline int reading(double value)
{
    double v = std::floor(value + 0.5);
    return (int)(v < 0 ? 0 : v > MAX_READING ? MAX_READING : v);
}

// The floor's texture, from a `floor W H PATH` line (none: white).
struct Floor {
    unsigned width = 0, height = 0;
    std::vector<uint32_t> argb;

    // false with *error set when the line's file cannot be used
    bool load(const char *line, std::string *error)
    {
        unsigned w = 0, h = 0;
        char path[4096];
        if (std::sscanf(line, "floor %u %u %4095[^\n]", &w, &h, path) != 3 || w == 0 || h == 0
                || w > 16384 || h > 16384) {
            *error = "a floor line is `floor W H PATH`";
            return false;
        }
        FILE *f = std::fopen(path, "rb");
        if (f == nullptr) {
            *error = std::string("cannot read the floor ") + path;
            return false;
        }
        std::vector<unsigned char> rgb((size_t)w * h * 3);
        size_t got = std::fread(rgb.data(), 1, rgb.size(), f);
        std::fclose(f);
        if (got != rgb.size()) {
            *error = std::string("the floor ") + path + " is shorter than its pixels";
            return false;
        }
        width = w;
        height = h;
        argb.resize((size_t)w * h);
        for (size_t i = 0; i < argb.size(); i++)
            argb[i] = 0xFF000000u | (uint32_t)rgb[3 * i] << 16 | (uint32_t)rgb[3 * i + 1] << 8
                      | (uint32_t)rgb[3 * i + 2];
        return true;
    }

    // Its pixels as the arena's texture: white paper without a floor line.
    unsigned texture_width() const { return argb.empty() ? 1 : width; }
    unsigned texture_height() const { return argb.empty() ? 1 : height; }
    const uint32_t *texture() const
    {
        static const uint32_t white = 0xFFFFFFFFu;
        return argb.empty() ? &white : argb.data();
    }

    // The grey level at (x, y) of a W x H arena whose walls are
    // `wall_grey` (Enki's World::getGroundColor, then Color::toGray).
    double grey(double x, double y, double arena_w, double arena_h, double wall_grey) const
    {
        const unsigned tw = texture_width(), th = texture_height();
        int tx = (int)(x * tw / arena_w), ty = (int)(y * th / arena_h);
        if (tx < 0 || tx >= (int)tw || ty < 0 || ty >= (int)th)
            return wall_grey;
        uint32_t c = texture()[(size_t)ty * tw + tx];
        return (((c >> 16) & 0xff) / 255.0 + ((c >> 8) & 0xff) / 255.0 + (c & 0xff) / 255.0) / 3;
    }
};

// The sensors' spot: Enki's 9 x 9 Gaussian kernel, normalised.
struct Kernel {
    double weight[9][9];
    Kernel()
    {
        const double var = SPOT_SD_CM * SPOT_SD_CM;
        double sum = 0;
        for (int i = 0; i < 9; i++)
            for (int j = 0; j < 9; j++) {
                const double x = (i - 4) / 4.0, y = (j - 4) / 4.0;
                weight[i][j] = std::exp(-(x * x + y * y) / (2 * var));
                sum += weight[i][j];
            }
        for (int i = 0; i < 9; i++)
            for (int j = 0; j < 9; j++)
                weight[i][j] /= sum;
    }
};

// Sensor n's value, noiseless, for a body at (x, y) heading `angle` over
// `floor`: Enki's GroundSensor::init.
inline double noiseless(const Kernel &k, const Floor &floor, int n, double x, double y,
                        double angle, double arena_w, double arena_h, double wall_grey)
{
    const double c = std::cos(angle), s = std::sin(angle);
    const double px = AHEAD_CM, py = APART_CM * (1 - n);
    const double ax = x + (px * c + py * -s), ay = y + (px * s + py * c);
    double v = 0;
    for (int i = 0; i < 9; i++)
        for (int j = 0; j < 9; j++)
            v += k.weight[i][j] * floor.grey(ax + (i - 4) / 4.0, ay + (j - 4) / 4.0, arena_w, arena_h,
                                             wall_grey);
    return sigm(v - C) * response_m() + response_a();
}

}  // namespace ground

#endif

/*
 * world_channel.h - the world's model of the e-puck's IR messages (libIrcom)
 * and of the e-puck2's time-of-flight ray, for world_runner.cpp.  Geometry
 * only, in Enki's units (cm, radians, counter-clockwise); docs/world.md
 * says where each default comes from.
 *
 * A message sent by robot S reaches robot R when, at the end of the world
 * step in which it was sent:
 *   - their centres are at most `range` apart;
 *   - the direction of R seen from S lies in the emitter cone of one of
 *     S's eight IR sensors, and the direction of S seen from R in the
 *     receiver cone of one of R's (each cone centred on the sensor's
 *     direction, `emitter` and `receiver` wide);
 *   - the segment between the centres crosses no box and no cylinder
 *     (other robots do not shadow: their IR sensors sit above their bodies);
 *   - the loss draw passes (probability `loss`, from the channel's own
 *     generator, seeded by the world's seed: a run is reproducible).
 * R is told what libIrcom tells: the value, the direction of the receiving
 * sensor nearest to the true direction (libIrcom's ircomEstimateDirection:
 * the bearing's error is at most half the widest gap between two sensors,
 * 30 degrees), and the distance times a uniform factor in
 * [1 - range_noise, 1 + range_noise] (its estimate from the signal's
 * strength).  How often a robot sends is the robot's own library's:
 * a message is on the air for `interval` ms (host/stub_devices.c), and
 * the runtime waits for it (rt_comm.c).
 */
#ifndef WORLD_CHANNEL_H
#define WORLD_CHANNEL_H

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace channel {

const double PI = 3.14159265358979323846;
const double ROBOT_RADIUS_CM = 3.7;
const double TOF_MAX_CM = 200.0;          // the VL53L0X's long-range mode: 2 m
const int TOF_NONE_MM = 8190;             // what the VL53L0X reads with nothing in range

// The directions of the e-puck's IR sensors, as libIrcom's
// ircomEstimateDirection (src/ircom/ircomTools.c) gives them, in radians.
const double SENSOR_RAD[8] = {5.986479, 5.410521, 4.712389, 3.665191,
                              2.617994, 1.570796, 0.8726646, 0.296706};

struct Settings {
    double range_cm = 22.5;
    double loss = 0.05;
    double emitter_rad = 60.0 * PI / 180.0;     // full width of a cone
    double receiver_rad = 60.0 * PI / 180.0;
    double range_noise = 0.10;
    int interval_ms = 100;
};

struct Obstacle {
    bool box;
    double x, y, a, b, angle, h;    // box: a x b turned by angle; cylinder: radius a
    double rgb[3];                  // its colour, 0..1
};

// -pi..pi
inline double wrap(double a)
{
    a = std::fmod(a, 2 * PI);
    if (a > PI)
        a -= 2 * PI;
    else if (a <= -PI)
        a += 2 * PI;
    return a;
}

// The sensor whose direction is nearest to `bearing` (radians from the
// heading) and within half a cone of it; -1: none.
inline int sensor_for(double bearing, double cone_rad)
{
    int best = -1;
    double best_d = cone_rad / 2;
    for (int k = 0; k < 8; k++) {
        double d = std::fabs(wrap(bearing - SENSOR_RAD[k]));
        if (d <= best_d) {
            best_d = d;
            best = k;
        }
    }
    return best;
}

// The first t >= 0 where p + t d (|d| = 1) enters the obstacle; infinity: never.
inline double hit(const Obstacle &o, double px, double py, double dx, double dy)
{
    const double none = std::numeric_limits<double>::infinity();
    if (!o.box) {
        double fx = px - o.x, fy = py - o.y;
        double b = fx * dx + fy * dy, c = fx * fx + fy * fy - o.a * o.a;
        if (c <= 0)
            return 0;
        double disc = b * b - c;
        if (disc < 0)
            return none;
        double t = -b - std::sqrt(disc);
        return t >= 0 ? t : none;
    }
    // into the box's frame, then slabs
    double ca = std::cos(o.angle), sa = std::sin(o.angle);
    double lx = (px - o.x) * ca + (py - o.y) * sa, ly = -(px - o.x) * sa + (py - o.y) * ca;
    double ldx = dx * ca + dy * sa, ldy = -dx * sa + dy * ca;
    double t0 = 0, t1 = none;
    const double half[2] = {o.a / 2, o.b / 2}, pos[2] = {lx, ly}, dir[2] = {ldx, ldy};
    for (int i = 0; i < 2; i++) {
        if (std::fabs(dir[i]) < 1e-12) {
            if (pos[i] < -half[i] || pos[i] > half[i])
                return none;
            continue;
        }
        double ta = (-half[i] - pos[i]) / dir[i], tb = (half[i] - pos[i]) / dir[i];
        if (ta > tb)
            std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 > t1)
            return none;
    }
    return t0;
}

// Whether the segment between two points crosses an obstacle.
inline bool blocked(const std::vector<Obstacle> &obstacles, double ax, double ay,
                    double bx, double by)
{
    double len = std::hypot(bx - ax, by - ay);
    if (len <= 0)
        return false;
    double dx = (bx - ax) / len, dy = (by - ay) / len;
    for (const Obstacle &o : obstacles)
        if (hit(o, ax, ay, dx, dy) < len)
            return true;
    return false;
}

// The channel's own generator (xorshift64*): its draws do not disturb
// Enki's, so adding messages to a world changes no wheel noise.
struct Random {
    uint64_t state;
    explicit Random(uint64_t seed) : state(seed * 0x9E3779B97F4A7C15ULL + 0x2545F4914F6CDD1DULL)
    {
        if (state == 0)
            state = 1;
    }
    double uniform()    // [0, 1)
    {
        state ^= state >> 12;
        state ^= state << 25;
        state ^= state >> 27;
        return (double)((state * 0x2545F4914F6CDD1DULL) >> 11) / 9007199254740992.0;
    }
};

struct Pose {
    double x, y, angle;     // cm, radians
};

// What robot R at `to` hears of a message from `from`: false when nothing;
// else the receiving sensor, the reported direction and distance.
// `blocked(from, to)`: whether an obstacle lies between them (the physics
// answers it, from its spatial index where it has one).
template <class Blocked>
inline bool deliver(const Settings &s, Blocked blocked, Random &random, const Pose &from,
                    const Pose &to, int *sensor, double *direction_rad, double *distance_cm)
{
    double dx = to.x - from.x, dy = to.y - from.y;
    double d = std::hypot(dx, dy);
    if (d > s.range_cm || d <= 0)
        return false;
    double world_dir = std::atan2(dy, dx);
    if (sensor_for(wrap(world_dir - from.angle), s.emitter_rad) < 0)
        return false;
    int k = sensor_for(wrap(world_dir + PI - to.angle), s.receiver_rad);
    if (k < 0 || blocked(from, to))
        return false;
    if (random.uniform() < s.loss)
        return false;
    *sensor = k;
    *direction_rad = SENSOR_RAD[k];
    *distance_cm = d * (1.0 + s.range_noise * (2.0 * random.uniform() - 1.0));
    return true;
}

// How far along the ray from p (|d| = 1) the arena's walls are.
inline double walls_ahead(const Pose &p, double dx, double dy, double width, double height)
{
    double best = std::numeric_limits<double>::infinity();
    if (dx > 1e-12)
        best = std::min(best, (width - p.x) / dx);
    if (dx < -1e-12)
        best = std::min(best, -p.x / dx);
    if (dy > 1e-12)
        best = std::min(best, (height - p.y) / dy);
    if (dy < -1e-12)
        best = std::min(best, -p.y / dy);
    return best;
}

// The ToF reading for the first thing `best` cm along the ray from the
// body's centre.
inline int tof_reading(double best)
{
    double ahead = best - ROBOT_RADIUS_CM;
    if (!(ahead <= TOF_MAX_CM))
        return TOF_NONE_MM;
    return ahead <= 0 ? 0 : (int)std::floor(ahead * 10.0 + 0.5);
}

// The ToF ray straight ahead from the body's edge: mm to the first wall,
// obstacle or other robot, TOF_NONE_MM beyond TOF_MAX_CM.
inline int tof_mm(const Pose &p, const std::vector<Obstacle> &obstacles,
                  const std::vector<Pose> &robots, bool walls, double width, double height)
{
    double dx = std::cos(p.angle), dy = std::sin(p.angle);
    double best = std::numeric_limits<double>::infinity();
    for (const Obstacle &o : obstacles)
        best = std::min(best, hit(o, p.x, p.y, dx, dy));
    for (const Pose &r : robots) {
        if (r.x == p.x && r.y == p.y)
            continue;       // itself
        Obstacle body{false, r.x, r.y, ROBOT_RADIUS_CM, 0, 0, 0, {0, 0, 0}};
        best = std::min(best, hit(body, p.x, p.y, dx, dy));
    }
    if (walls)
        best = std::min(best, walls_ahead(p, dx, dy, width, height));
    return tof_reading(best);
}

}  // namespace channel

#endif

/*
 * physics.h - what the world runner's core (world_runner.cpp) asks of the
 * physics under it.  The core parses the SPEC, loads the robots' shared
 * objects, runs their coroutines (on one thread or several), carries their
 * messages and output; a provider moves their bodies and answers their
 * sensors.  Two providers implement this interface, each in its own file,
 * and each world runner executable links one of them:
 *
 *   physics_enki.cpp      Enki (the reference): every pair of objects and
 *                         every sensor against every object, at each step
 *   physics_chipmunk.cpp  Chipmunk 7, a 2-D physics engine with a broad
 *                         phase: the same e-puck model (epuck_model.h)
 *                         answered from the space's spatial index, for
 *                         worlds of thousands of robots
 *
 * Lengths in cm, angles in radians (counter-clockwise), times in s unless
 * named otherwise; robots are numbered in the SPEC's order from 0.
 */
#ifndef PHYSICS_H
#define PHYSICS_H

#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "enki_bridge.h"
#include "world_channel.h"
#include "world_ground.h"
#include "world_sound.h"

namespace physics {

// The world as the SPEC gives it, before any robot.
struct Scene {
    bool walls = false;             // a W x H arena with its corner at (0, 0)
    double width = 0, height = 0;
    double wall_rgb[3] = {0.5, 0.5, 0.5};
    std::vector<channel::Obstacle> obstacles;
    unsigned long seed = 1;         // the physics' noise (wheels, IR sensors)
    double noise = 0.05;            // wheel speed noise, +- this fraction
    double dt = 0.01;               // one step
    // the floor (walled worlds) and the sound sources, the core's, for the
    // whole run (world_ground.h, world_sound.h: listen() called already)
    const ground::Floor *floor = nullptr;
    const sound::Scene *sounds = nullptr;
};

// A robot's body as placed, and the costly sensors its program reads.
struct Placement {
    double x = 0, y = 0, angle = 0;
    double rgb[3] = {0.5, 0.5, 0.5};
    bool camera = false, tof = false;
    bool ground = false;            // the ground-sensor module (read in a walled world)
};

// What a robot touched: the physics steps in which it touched a wall, an
// obstacle, another robot (a step counts once for each kind touched in it,
// however many things of that kind), the steps in which it touched
// anything, and the time of the step of its first contact (-1: none).
struct Contacts {
    long walls = 0, objects = 0, robots = 0;
    long steps = 0;
    long first_ms = -1;
};

class World {
public:
    virtual ~World() {}
    // every robot, in the SPEC's order, before the first step
    virtual void add(const Placement &p) = 0;
    // the wheel speeds (cm/s) and axle (cm) robot i drives with: its
    // body moves by them in the step after the next one, as Enki's does
    virtual void drive(size_t i, double left, double right, double axle) = 0;
    // one step of `dt`; its contacts are dated `now_ms`
    virtual void step(long now_ms) = 0;
    virtual channel::Pose pose(size_t i) const = 0;
    // what plays in the coming step (sound::Scene::playing), after step()
    // and before the robots' sense(): what their microphones hear
    virtual void hear(const sound::Playing &playing) = 0;
    // robot i's sensors as the last step left them, into its io (prox,
    // camera, distance, ground when io.ground_on, mic); from any thread,
    // never two at once for one robot, never during step() or hear()
    virtual void sense(size_t i, enki_robot_io &io) = 0;
    // the robots that may be within `range` of robot i's centre (a
    // superset is fine), i left out, in ascending order
    virtual void near(size_t i, double range, std::vector<size_t> *out) = 0;
    // whether a box or a cylinder lies on the segment from a to b
    virtual bool blocked(const channel::Pose &a, const channel::Pose &b) = 0;
    virtual Contacts contacts(size_t i) const = 0;
};

// The provider linked into this runner (physics_enki.cpp or
// physics_chipmunk.cpp); null with *error when the scene cannot be made.
std::unique_ptr<World> make(const Scene &scene, std::string *error);
// its name, as a world file's `physics` line gives it
extern const char *const NAME;

// An IR sensor's value as the e-puck library reads it: rounded, 0..4095.
inline int prox_reading(double value)
{
    double v = std::floor(value + 0.5);
    return (int)(v < 0 ? 0 : v > 4095 ? 4095 : v);
}

// The camera's pixels as Enki's CircularCam gives them (index 0 at the
// right edge of the view, counter-clockwise; components 0..1) into the
// camera line, leftmost pixel first, 0..255.
inline void store_camera(enki_robot_io &io, const double (*image)[3])
{
    for (int i = 0; i < ENKI_CAMERA_PIXELS; i++) {
        const double *c = image[ENKI_CAMERA_PIXELS - 1 - i];
        for (int k = 0; k < 3; k++) {
            double v = std::floor(c[k] * 255.0 + 0.5);
            io.camera[3 * i + k] = (unsigned char)(v < 0 ? 0 : v > 255 ? 255 : v);
        }
    }
}

}  // namespace physics

#endif

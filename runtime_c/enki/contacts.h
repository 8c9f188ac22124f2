/*
 * contacts.h - what a robot touched, for the Enki provider
 * (physics_enki.cpp): a wall, an obstacle (a box or a cylinder of the
 * world) or another robot, counted in physics steps (physics::Contacts).
 * Chipmunk's provider needs none of this: its collision handlers see the
 * shape hit, tagged with its kind.
 *
 * Enki names the other body of a collision only when both can move: a
 * robot's collision with another robot comes with that robot, but one with
 * anything that cannot move (PhysicalObject::collideWithStaticObject) comes
 * with none, the world's walls and its static boxes and cylinders alike.
 * So a collision without a partner is told apart here from the world's own
 * objects, by where the robot is when Enki reports it.  World::step runs,
 * in each physics step, first every collision between two objects (an
 * obstacle's included), each pushing the robot out of the obstacle before
 * it is reported: the robot then touches that obstacle; then, robot by
 * robot, its collisions with the walls, each reported before the robot is
 * pushed back: it then reaches over that wall.  Each obstacle and each
 * wall is reported at most once a physics step.  Hence, for a collision
 * without a partner:
 *   - once a wall was reported in this step, it is a wall (the walls come
 *     last);
 *   - else an obstacle not yet reported in this step that the robot
 *     touches (within TOUCH_CM), the nearest;
 *   - else a wall the robot reaches over, not yet reported;
 *   - else (rounding at the edge of both) whichever of them is nearest.
 * A robot wedged between a box and a wall is in contact with both in that
 * step.  A step counts once for each kind touched in it, however many
 * things of that kind.
 */
#ifndef CONTACTS_H
#define CONTACTS_H

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "world_channel.h"

namespace contacts {

enum Kind { WALL = 0, OBJECT = 1, ROBOT = 2, KINDS = 3 };

// After Enki's push out of an obstacle the robot's edge lies on the
// obstacle's, up to rounding (1e-12 cm here); 1e-6 cm leaves room for it.
const double TOUCH_CM = 1e-6;

// What the robots may touch: the world's obstacles and its walls.
struct Scene {
    const std::vector<channel::Obstacle> *obstacles = nullptr;
    bool walls = false;
    double width = 0, height = 0;
};

// How far the edge of a circle (centre x, y, radius r) is from an
// obstacle's (< 0: inside it), in cm.
inline double gap(const channel::Obstacle &o, double x, double y, double r)
{
    if (!o.box)
        return std::hypot(x - o.x, y - o.y) - o.a - r;
    double ca = std::cos(o.angle), sa = std::sin(o.angle);
    double lx = (x - o.x) * ca + (y - o.y) * sa, ly = -(x - o.x) * sa + (y - o.y) * ca;
    double dx = std::fabs(lx) - o.a / 2, dy = std::fabs(ly) - o.b / 2;
    double outside = std::hypot(std::max(dx, 0.0), std::max(dy, 0.0));
    return outside + std::min(std::max(dx, dy), 0.0) - r;
}

// How far a circle reaches over each wall (left, bottom, right, top; > 0:
// over it), Enki's order of them.
inline void over_walls(const Scene &s, double x, double y, double r, double out[4])
{
    out[0] = r - x;
    out[1] = r - y;
    out[2] = x + r - s.width;
    out[3] = y + r - s.height;
}

// One robot's contacts: which kinds it touched in the physics step under
// way, and the steps it touched each kind in.
class Counter {
public:
    long steps[KINDS] = {0, 0, 0};
    long any_steps = 0;                 // steps in contact with anything

    void begin_step()
    {
        touched[WALL] = touched[OBJECT] = touched[ROBOT] = false;
        walls_reported = 0;
        in_walls = false;
        reported.clear();
    }
    void end_step()
    {
        for (int k = 0; k < KINDS; k++)
            steps[k] += touched[k] ? 1 : 0;
        any_steps += touched[WALL] || touched[OBJECT] || touched[ROBOT] ? 1 : 0;
    }
    // Enki reported a collision with another robot.
    void robot() { touched[ROBOT] = true; }
    // Enki reported a collision without a partner, the robot's circle at
    // (x, y) with radius r; returns the kind it was.
    Kind unnamed(const Scene &s, double x, double y, double r)
    {
        Kind k = classify(s, x, y, r);
        touched[k] = true;
        return k;
    }

private:
    bool touched[KINDS] = {false, false, false};
    unsigned walls_reported = 0;        // bits: left, bottom, right, top
    bool in_walls = false;
    std::vector<size_t> reported;       // obstacles reported in this step

    Kind classify(const Scene &s, double x, double y, double r)
    {
        if (in_walls)
            return WALL;
        const double inf = std::numeric_limits<double>::infinity();
        const std::vector<channel::Obstacle> &obstacles = *s.obstacles;
        size_t best = obstacles.size();
        double best_gap = inf;
        for (size_t i = 0; i < obstacles.size(); i++) {
            double g = std::fabs(gap(obstacles[i], x, y, r));
            if (g < best_gap && std::find(reported.begin(), reported.end(), i) == reported.end()) {
                best_gap = g;
                best = i;
            }
        }
        if (best < obstacles.size() && best_gap <= TOUCH_CM) {
            reported.push_back(best);
            return OBJECT;
        }
        double over[4] = {-inf, -inf, -inf, -inf};
        if (s.walls)
            over_walls(s, x, y, r, over);
        for (int w = 0; w < 4; w++)
            if (over[w] > 0 && !(walls_reported & (1u << w))) {
                walls_reported |= 1u << w;
                in_walls = true;
                return WALL;
            }
        // neither quite: the nearer of the two
        double wall_gap = inf;
        for (int w = 0; w < 4; w++)
            wall_gap = std::min(wall_gap, std::fabs(over[w]));
        if (best < obstacles.size() && best_gap <= wall_gap)
            return OBJECT;
        return s.walls ? WALL : OBJECT;
    }
};

}  // namespace contacts

#endif

/*
 * physics_chipmunk.cpp - the world runner's physics on Chipmunk 7
 * (physics.h): `physics chipmunk` in a world file, for worlds of thousands
 * of robots, where Enki's every pair of objects costs more than the robots
 * (docs/world.md, "Large worlds").
 *
 * Bodies.  Each robot is a frictionless disc of the e-puck's radius and
 * mass (epuck_model.h); the boxes and cylinders are static shapes, the
 * arena's walls four static boxes around it.  A robot's velocity is what
 * its wheels give, set inside Chipmunk's step before its solver runs (the
 * body's velocity function), as Enki's e-puck sets its speed from its
 * wheels at each step: the solver then takes out what would push into a
 * wall, an obstacle or another robot (two robots share a push equally, as
 * Enki's do), and the next step moves the body by the result.  Hence the
 * same delay as Enki's, a command moving the body in the step after the
 * next, and the same wheel noise (each wheel's speed times a uniform
 * factor in [1 - noise, 1 + noise] at each step), drawn from each robot's
 * own generator.
 *
 * Sensors.  Every sensor asks the space's spatial index (its bounding-box
 * trees, Chipmunk's broad phase) what is near: the IR sensors one box
 * around the body, the ToF ray a segment query, the camera boxes that
 * grow until every pixel has met something, the messages a box of the
 * range around the sender and a segment query for obstacles between two
 * robots.  What the index gives is then measured with Enki's own model of
 * each sensor (epuck_model.h): the same response curve, the same rays,
 * the same noise (from the robot's generator), the same pixels.  The
 * indexes are read without Chipmunk's space lock, whose counter is not
 * atomic, so that the robots' threads may all read them at once
 * (workers.h); nothing writes them outside the step.
 *
 * Floor and sound.  A robot's ground sensors read the floor's texture
 * with Enki's GroundSensor model (world_ground.h: the same spot, response
 * and noise, from the robot's generator); its microphones hear what plays
 * through Enki's Microphone model (world_sound.h's Scene::volume: the same
 * sums in the same order, so the same readings as on Enki).
 *
 * Contacts.  A robot touches a wall, an obstacle or another robot in a
 * step when Chipmunk's solver pushes it off that thing in that step (a
 * non-zero impulse): as Enki's counts, a push into something, not a body
 * resting against it.  The shape pushed off is tagged with its kind, so
 * that, as physics::Contacts has it, a step counts once for each kind
 * touched in it, and once among the steps in contact with anything.
 */
#include <fcntl.h>
#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <chipmunk/chipmunk.h>
#include <chipmunk/chipmunk_structs.h>      // the space's spatial indexes

#include "epuck_model.h"
#include "physics.h"
#include "robot_grid.h"

namespace {

enum Kind : cpCollisionType { WALL = 1, OBJECT = 2, ROBOT = 3 };

// What a shape is, for the sensors: a robot (its number), an obstacle
// (the scene's) or a wall.
struct Thing {
    Kind kind;
    size_t index;
};

// An obstacle as the sensors measure it: a box's corners (counter-
// clockwise) and its bounding circle's radius, about its centre.
struct Obstacle {
    channel::Obstacle o;
    double corners[4][2];
    double radius;
};

const double WALL_THICKNESS_CM = 100;
// A robot's push off something in a step counts from this impulse on
// (g cm/s: a thousandth of what a robot's stop from 1 mm/s takes).
const double TOUCH_IMPULSE = 152 * 0.1 / 1000;
const double CAMERA_FIRST_CM = 32;  // the camera's first search, doubled until done
const double GRID_CM = 20;          // robot_grid.h's cells: a few around an IR query

struct Robot {
    cpBody *body = nullptr;
    Thing thing;
    double rgb[3];
    bool tof = false, ground = false;
    double speed = 0, turn = 0;     // from the wheels, for the next velocity update
    channel::Random random;         // its noise (wheels and IR sensors)
    double spare = 0;               // the second normal draw of a pair
    bool has_spare = false;
    bool touched[3] = {false, false, false};
    physics::Contacts contacts;
    explicit Robot(uint64_t seed) : random(seed) {}
};

// The body's velocity inside Chipmunk's step, before its solver: what the
// wheels give.  Translation along the heading half a step on at the
// angular speed it had (Enki's DifferentialWheeled::applyForces).
void wheel_velocity(cpBody *body, cpVect, cpFloat, cpFloat dt)
{
    // (the fields themselves: the setters' checks, in Debian's debug build
    // of Chipmunk, took a tenth of a step)
    const Robot *r = static_cast<const Robot *>(body->userData);
    double a = body->a + body->w * dt * 0.5;
    body->v = cpv(r->speed * std::cos(a), r->speed * std::sin(a));
    body->w = r->turn;
}

// The solver pushed robot A (the wildcard handler's own) off B.
void pushed(cpArbiter *arb, cpSpace *, cpDataPointer)
{
    CP_ARBITER_GET_SHAPES(arb, a, b);
    if (cpvlengthsq(cpArbiterTotalImpulse(arb)) <= TOUCH_IMPULSE * TOUCH_IMPULSE)
        return;
    Robot *r = static_cast<Robot *>(cpBodyGetUserData(cpShapeGetBody(a)));
    cpCollisionType other = cpShapeGetCollisionType(b);
    r->touched[other == WALL ? 0 : other == OBJECT ? 1 : 2] = true;
}

cpCollisionID collect(void *, void *shape, cpCollisionID id, void *data)
{
    static_cast<std::vector<const Thing *> *>(data)->push_back(
        static_cast<const Thing *>(static_cast<cpShape *>(shape)->userData));
    return id;
}

// A ray's query of the index: the nearest hit so far (cm) along it.
struct Ray {
    const class ChipmunkWorld *world;
    size_t self;
    double x, y, dx, dy, length;
    double best;
};
cpFloat ray_hit(void *, void *shape, void *data);

// One thread's scratch: what a query found, and which things the camera
// has drawn (by stamp).
thread_local std::vector<const Thing *> found;
thread_local std::vector<unsigned> drawn;
thread_local unsigned drawing;

// A new space.  Debian's Chipmunk is built in debug mode, whose first
// space prints a banner on stdout: the robots' output, kept from it.
cpSpace *quiet_space()
{
    std::fflush(stdout);
    int saved = dup(1), none = open("/dev/null", O_WRONLY);
    if (saved >= 0 && none >= 0)
        dup2(none, 1);
    cpSpace *space = cpSpaceNew();
    std::fflush(stdout);
    if (saved >= 0 && none >= 0)
        dup2(saved, 1);
    if (none >= 0)
        close(none);
    if (saved >= 0)
        close(saved);
    return space;
}

class ChipmunkWorld : public physics::World {
public:
    explicit ChipmunkWorld(const physics::Scene &scene) : scene_(scene)
    {
        space_ = quiet_space();
        cpSpaceSetIterations(space_, 10);
        // overlap left after a step: 0.1 mm; what remains is taken out at
        // 90 % a step
        cpSpaceSetCollisionSlop(space_, 0.01);
        cpSpaceSetCollisionBias(space_, std::pow(0.1, 1.0 / scene.dt));
        cpCollisionHandler *h = cpSpaceAddWildcardHandler(space_, ROBOT);
        h->postSolveFunc = pushed;
        cpBody *ground = cpSpaceGetStaticBody(space_);
        things_.reserve(scene.obstacles.size() + 4);
        static_bb_ = cpBBNew(0, 0, 0, 0);
        bool any = false;
        for (size_t k = 0; k < scene.obstacles.size(); k++) {
            const channel::Obstacle &o = scene.obstacles[k];
            Obstacle ob{o, {}, o.a};
            cpShape *shape;
            if (o.box) {
                double c = std::cos(o.angle), s = std::sin(o.angle);
                const double local[4][2] = {{-o.a / 2, -o.b / 2}, {o.a / 2, -o.b / 2},
                                            {o.a / 2, o.b / 2}, {-o.a / 2, o.b / 2}};
                cpVect v[4];
                for (int i = 0; i < 4; i++) {
                    ob.corners[i][0] = o.x + c * local[i][0] - s * local[i][1];
                    ob.corners[i][1] = o.y + s * local[i][0] + c * local[i][1];
                    v[i] = cpv(ob.corners[i][0], ob.corners[i][1]);
                }
                ob.radius = std::hypot(o.a / 2, o.b / 2);
                shape = cpPolyShapeNew(ground, 4, v, cpTransformIdentity, 0);
            } else {
                shape = cpCircleShapeNew(ground, o.a, cpv(o.x, o.y));
                max_static_radius_ = std::max(max_static_radius_, o.a);
            }
            obstacles_.push_back(ob);
            things_.push_back(Thing{OBJECT, k});
            static_shape(shape, OBJECT);
            cpBB bb = cpBBNewForCircle(cpv(o.x, o.y), ob.radius);
            static_bb_ = any ? cpBBMerge(static_bb_, bb) : bb;
            obstacles_bb_ = k > 0 ? cpBBMerge(obstacles_bb_, bb) : bb;
            any = true;
        }
        if (scene.walls) {
            const double w = scene.width, hh = scene.height, t = WALL_THICKNESS_CM;
            const cpBB sides[4] = {cpBBNew(-t, -t, 0, hh + t), cpBBNew(-t, -t, w + t, 0),
                                   cpBBNew(w, -t, w + t, hh + t), cpBBNew(-t, hh, w + t, hh + t)};
            for (const cpBB &side : sides) {
                things_.push_back(Thing{WALL, 0});
                static_shape(cpBoxShapeNew2(ground, side, 0), WALL);
            }
            cpBB arena = cpBBNew(0, 0, w, hh);
            static_bb_ = any ? cpBBMerge(static_bb_, arena) : arena;
            any = true;
        }
        has_static_bb_ = any;
        for (int k = 0; k < 8; k++) {
            reach_[k] = epuck::ir_reach(k);
            max_reach_ = std::max(max_reach_, reach_[k]);
        }
        ir_extent_ = epuck::ir_extent();
    }

    void add(const physics::Placement &p) override
    {
        const size_t i = robots_.size();
        // each robot its own generator, from the world's seed and its number
        robots_.emplace_back(new Robot(scene_.seed * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL
                                       * (i + 1)));
        Robot &r = *robots_.back();
        r.thing = Thing{ROBOT, i};
        std::copy(p.rgb, p.rgb + 3, r.rgb);
        r.tof = p.tof;
        r.ground = p.ground && scene_.walls;    // open ground has no floor
        poses_.push_back(channel::Pose{p.x, p.y, p.angle});
        r.body = cpSpaceAddBody(space_, cpBodyNew(epuck::MASS, cpMomentForCircle(
                                                      epuck::MASS, 0, epuck::RADIUS, cpvzero)));
        cpBodySetPosition(r.body, cpv(p.x, p.y));
        cpBodySetAngle(r.body, p.angle);
        cpBodySetUserData(r.body, &r);
        cpBodySetVelocityUpdateFunc(r.body, wheel_velocity);
        cpShape *shape = cpSpaceAddShape(space_, cpCircleShapeNew(r.body, epuck::RADIUS, cpvzero));
        cpShapeSetFriction(shape, 0);
        cpShapeSetElasticity(shape, 0);
        cpShapeSetCollisionType(shape, ROBOT);
        cpShapeSetUserData(shape, &r.thing);
    }

    void drive(size_t i, double left, double right, double axle) override
    {
        // Enki's DifferentialWheeled::controlStep: each wheel's own noise,
        // the speed clamped at 1000 cm/s (as the runner sets Enki's)
        Robot &r = *robots_[i];
        const double noise = scene_.noise, most = 1000.0;
        double l = left * (1 - noise + 2 * noise * r.random.uniform());
        double rr = right * (1 - noise + 2 * noise * r.random.uniform());
        l = std::max(-most, std::min(most, l));
        rr = std::max(-most, std::min(most, rr));
        r.speed = (l + rr) * 0.5;
        r.turn = (rr - l) / axle;
    }

    void step(long now_ms) override
    {
        cpSpaceStep(space_, scene_.dt);
        bool any = false;
        for (size_t i = 0; i < robots_.size(); i++) {
            Robot &r = *robots_[i];
            cpVect at = cpBodyGetPosition(r.body);
            poses_[i] = channel::Pose{at.x, at.y, epuck::wrap(cpBodyGetAngle(r.body))};
            long *counts[3] = {&r.contacts.walls, &r.contacts.objects, &r.contacts.robots};
            bool touched = false;
            for (int k = 0; k < 3; k++) {
                if (r.touched[k])
                    ++*counts[k];
                touched = touched || r.touched[k];
                r.touched[k] = false;
            }
            if (touched) {
                r.contacts.steps++;
                if (r.contacts.first_ms < 0)
                    r.contacts.first_ms = now_ms;
            }
            cpBB bb = cpBBNewForCircle(at, epuck::RADIUS);
            robots_bb_ = any ? cpBBMerge(robots_bb_, bb) : bb;
            any = true;
        }
        grid_.build(poses_, GRID_CM);
    }

    channel::Pose pose(size_t i) const override { return poses_[i]; }

    void hear(const sound::Playing &playing) override { playing_ = &playing; }

    void sense(size_t i, enki_robot_io &io) override
    {
        Robot &r = *robots_[i];
        const channel::Pose &p = poses_[i];
        sense_ir(i, r, io);
        io.distance_mm = r.tof ? tof(i, p) : channel::TOF_NONE_MM;
        if (io.camera_on)
            camera(i, p, io);
        if (io.ground_on && r.ground) {
            static const ground::Floor white;
            const ground::Floor &floor = scene_.floor != nullptr ? *scene_.floor : white;
            const double wall_grey = (scene_.wall_rgb[0] + scene_.wall_rgb[1] + scene_.wall_rgb[2]) / 3;
            for (int n = 0; n < ground::SENSORS; n++)
                io.ground[n] = ground::reading(gaussian(
                    r, ground::noiseless(kernel_, floor, n, p.x, p.y, p.angle, scene_.width,
                                         scene_.height, wall_grey), ground::NOISE_SD));
        }
        if (playing_ == nullptr || playing_->silent()) {
            std::memset(io.mic, 0, sizeof io.mic);
        } else {
            for (int m = 0; m < sound::MICS; m++) {
                double x, y;
                sound::mic_position(p, m, &x, &y);
                io.mic[m] = scene_.sounds->volume(*playing_, poses_, x, y);
            }
        }
    }

    void near(size_t i, double range, std::vector<size_t> *out) override
    {
        const channel::Pose &p = poses_[i];
        out->clear();
        grid_.each(p.x - range, p.y - range, p.x + range, p.y + range, [&](size_t k) {
            if (k != i)
                out->push_back(k);
        });
        std::sort(out->begin(), out->end());
    }

    bool blocked(const channel::Pose &a, const channel::Pose &b) override
    {
        double len = std::hypot(b.x - a.x, b.y - a.y);
        if (len <= 0)
            return false;
        Ray ray{this, robots_.size(), a.x, a.y, (b.x - a.x) / len, (b.y - a.y) / len, len, len};
        cpSpatialIndexSegmentQuery(space_->staticShapes, nullptr, cpv(a.x, a.y), cpv(b.x, b.y), 1,
                                   ray_hit, &ray);
        return ray.best < len;
    }

    physics::Contacts contacts(size_t i) const override { return robots_[i]->contacts; }

    // How far along `ray` a thing is (infinity: not on it); walls are the
    // callers' to measure, and a ray leaves out the robot it starts from.
    double along(const Ray &ray, const Thing &t) const
    {
        const double none = std::numeric_limits<double>::infinity();
        if (t.kind == WALL || (t.kind == ROBOT && t.index == ray.self))
            return none;
        if (t.kind == OBJECT)
            return channel::hit(obstacles_[t.index].o, ray.x, ray.y, ray.dx, ray.dy);
        const channel::Pose &p = poses_[t.index];
        channel::Obstacle body{false, p.x, p.y, epuck::RADIUS, 0, 0, 0, {0, 0, 0}};
        return channel::hit(body, ray.x, ray.y, ray.dx, ray.dy);
    }

private:
    physics::Scene scene_;
    cpSpace *space_;
    std::vector<std::unique_ptr<Robot>> robots_;
    std::vector<Obstacle> obstacles_;
    std::vector<Thing> things_;                 // the static shapes'
    cpBB static_bb_, robots_bb_ = cpBBNew(0, 0, 0, 0);
    bool has_static_bb_ = false;
    double max_static_radius_ = 0;
    double reach_[8], max_reach_ = 0;
    double ir_extent_;
    cpBB obstacles_bb_ = cpBBNew(0, 0, 0, 0);
    epuck::IrFrame frame_;
    std::vector<channel::Pose> poses_;          // every robot's, after the last step
    grid::Grid grid_;                           // their centres
    ground::Kernel kernel_;                     // the ground sensors' spot
    const sound::Playing *playing_ = nullptr;   // what plays in the coming step

    // things_ holds room for every static shape from the start: their
    // user data point into it
    void static_shape(cpShape *shape, Kind kind)
    {
        cpShapeSetFriction(shape, 0);
        cpShapeSetElasticity(shape, 0);
        cpShapeSetCollisionType(shape, kind);
        cpShapeSetUserData(shape, &things_.back());
        cpSpaceAddShape(space_, shape);
    }

    // Enki's e-puck IR model against what is around the body: the other
    // robots from the grid, the obstacles from Chipmunk's static tree.  A
    // sensor's rays are traced only once something may meet them.
    void sense_ir(size_t i, Robot &r, enki_robot_io &io)
    {
        const channel::Pose &p = poses_[i];
        epuck::IrSensor s[8];
        bool started[8] = {false, false, false, false, false, false, false, false};
        const double c = std::cos(p.angle), sn = std::sin(p.angle);
        auto sensor = [&](int k) -> epuck::IrSensor & {
            if (!started[k]) {
                s[k].start(frame_, k, p.x, p.y, c, sn);
                started[k] = true;
            }
            return s[k];
        };
        // an object is tried by sensor k when its bounding circle is within
        // the sensor's reach of the body's centre (Enki's Robot::doLocalInteractions)
        auto meet = [&](double ox, double oy, double radius, double height, const Obstacle *ob) {
            double d2 = (ox - p.x) * (ox - p.x) + (oy - p.y) * (oy - p.y);
            double most = max_reach_ + radius;
            if (d2 >= most * most)
                return;
            for (int k = 0; k < 8; k++) {
                double reach = reach_[k] + radius;
                if (d2 >= reach * reach || !sensor(k).tries(ox, oy, radius, height))
                    continue;
                if (ob != nullptr && ob->o.box)
                    s[k].polygon(ob->corners, 4, ox, oy, radius);
                else
                    s[k].cylinder(ox, oy, radius);
            }
        };
        const double e = ir_extent_ + epuck::RADIUS;
        grid_.each(p.x - e, p.y - e, p.x + e, p.y + e, [&](size_t k) {
            if (k != i)
                meet(poses_[k].x, poses_[k].y, epuck::RADIUS, epuck::HEIGHT, nullptr);
        });
        cpBB around = cpBBNewForCircle(cpv(p.x, p.y), ir_extent_);
        if (!obstacles_.empty() && cpBBIntersects(around, obstacles_bb_)) {
            found.clear();
            cpSpatialIndexQuery(space_->staticShapes, nullptr, around, collect, &found);
            for (const Thing *t : found) {
                if (t->kind != OBJECT)
                    continue;
                const Obstacle &ob = obstacles_[t->index];
                meet(ob.o.x, ob.o.y, ob.radius, ob.o.h, &ob);
            }
        }
        if (scene_.walls) {
            double wall = std::min(std::min(p.x, p.y),
                                   std::min(scene_.width - p.x, scene_.height - p.y));
            for (int k = 0; k < 8; k++)
                if (!(wall > reach_[k]))
                    sensor(k).walls(scene_.width, scene_.height);
        }
        for (int k = 0; k < 8; k++) {
            double v = gaussian(r, started[k] ? s[k].sum() : 0.0, epuck::IR_NOISE_SD);
            io.prox[k] = physics::prox_reading(std::max(0.0, std::min(epuck::IR_M, v)));
        }
    }

    // Enki's gaussianRand: the polar method, whose two independent draws
    // are both used here (Enki drops one)
    static double gaussian(Robot &r, double mean, double sd)
    {
        if (r.has_spare) {
            r.has_spare = false;
            return sd * r.spare + mean;
        }
        double x, y, r2;
        do {
            x = r.random.uniform() * 2 - 1;
            y = r.random.uniform() * 2 - 1;
            r2 = x * x + y * y;
        } while (r2 > 1.0 || r2 == 0);
        double f = std::sqrt(-2.0 * std::log(r2) / r2);
        r.spare = x * f;
        r.has_spare = true;
        return sd * y * f + mean;
    }

    int tof(size_t i, const channel::Pose &p)
    {
        double dx = std::cos(p.angle), dy = std::sin(p.angle);
        double len = channel::TOF_MAX_CM + epuck::RADIUS + 1;
        const double none = std::numeric_limits<double>::infinity();
        Ray ray{this, i, p.x, p.y, dx, dy, len, none};
        cpVect a = cpv(p.x, p.y), b = cpv(p.x + dx * len, p.y + dy * len);
        cpSpatialIndexSegmentQuery(space_->staticShapes, nullptr, a, b, 1, ray_hit, &ray);
        cpSpatialIndexSegmentQuery(space_->dynamicShapes, nullptr, a, b, 1, ray_hit, &ray);
        double best = ray.best;
        if (scene_.walls)
            best = std::min(best, channel::walls_ahead(p, dx, dy, scene_.width, scene_.height));
        return channel::tof_reading(best);
    }

    // Enki's CircularCam from boxes that grow until every pixel has met
    // something nearer than the box reaches, or the box holds the world.
    void camera(size_t i, const channel::Pose &p, enki_robot_io &io)
    {
        epuck::Camera cam;
        cam.start(p.x, p.y, p.angle, scene_.wall_rgb);
        if (scene_.walls)
            cam.walls(scene_.width, scene_.height, scene_.wall_rgb);
        cpBB world = has_static_bb_ ? cpBBMerge(static_bb_, robots_bb_) : robots_bb_;
        double extent = 0;
        for (double cx : {world.l, world.r})
            for (double cy : {world.b, world.t})
                extent = std::max(extent, std::hypot(cx - cam.x, cy - cam.y));
        if (drawn.size() < things_.size() + robots_.size())
            drawn.assign(things_.size() + robots_.size(), 0);
        drawing++;
        for (double d = CAMERA_FIRST_CM;; d *= 2) {
            found.clear();
            // what is static, within d of the camera; the robots, whose
            // discs reach into the view within d
            cpSpatialIndexQuery(space_->staticShapes, nullptr,
                                cpBBNewForCircle(cpv(cam.x, cam.y), d), collect, &found);
            cpSpatialIndexQuery(space_->dynamicShapes, nullptr, view(cam, d), collect, &found);
            for (const Thing *t : found)
                draw(i, *t, cam);
            if (cam.within(d) || d >= extent)
                break;
        }
        physics::store_camera(io, cam.image);
    }

    // the box of the camera's view up to d, and of a robot's disc beside it
    static cpBB view(const epuck::Camera &cam, double d)
    {
        const double f = epuck::CAMERA_HALF_FOV;
        cpBB bb = cpBBNew(cam.x, cam.y, cam.x, cam.y);
        double ends[2] = {cam.heading - f, cam.heading + f};
        for (double a : ends)
            bb = cpBBExpand(bb, cpv(cam.x + d * std::cos(a), cam.y + d * std::sin(a)));
        for (int q = 0; q < 4; q++) {
            double a = q * epuck::PI / 2;
            if (std::fabs(epuck::wrap(a - cam.heading)) <= f)
                bb = cpBBExpand(bb, cpv(cam.x + d * std::cos(a), cam.y + d * std::sin(a)));
        }
        return cpBBNew(bb.l - epuck::RADIUS, bb.b - epuck::RADIUS, bb.r + epuck::RADIUS,
                       bb.t + epuck::RADIUS);
    }

    void draw(size_t i, const Thing &t, epuck::Camera &cam)
    {
        if (t.kind == WALL || (t.kind == ROBOT && t.index == i))
            return;
        size_t id = t.kind == ROBOT ? things_.size() + t.index : (size_t)(&t - &things_[0]);
        if (drawn[id] == drawing)
            return;
        drawn[id] = drawing;
        if (t.kind == ROBOT) {
            const channel::Pose &o = poses_[t.index];
            cam.cylinder(o.x, o.y, epuck::RADIUS, robots_[t.index]->rgb);
            return;
        }
        const Obstacle &ob = obstacles_[t.index];
        if (epuck::CAMERA_HEIGHT > ob.o.h)
            return;
        if (!ob.o.box) {
            cam.cylinder(ob.o.x, ob.o.y, ob.o.a, ob.o.rgb);
            return;
        }
        for (int k = 0; k < 4; k++)
            cam.line(ob.corners[k][0], ob.corners[k][1], ob.corners[(k + 1) % 4][0],
                     ob.corners[(k + 1) % 4][1], ob.o.rgb);
    }
};

cpFloat ray_hit(void *, void *shape, void *data)
{
    Ray &ray = *static_cast<Ray *>(data);
    const Thing *t = static_cast<const Thing *>(cpShapeGetUserData(static_cast<cpShape *>(shape)));
    ray.best = std::min(ray.best, ray.world->along(ray, *t));
    // nothing beyond the nearest so far can be nearer
    return ray.best < ray.length ? ray.best / ray.length : 1;
}

}  // namespace

namespace physics {

const char *const NAME = "chipmunk";

std::unique_ptr<World> make(const Scene &scene, std::string *)
{
    return std::unique_ptr<World>(new ChipmunkWorld(scene));
}

}  // namespace physics

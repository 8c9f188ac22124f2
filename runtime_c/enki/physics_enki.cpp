/*
 * physics_enki.cpp - the world runner's physics on Enki (physics.h): the
 * reference provider, `physics enki` in a world file.
 *
 * Each robot is Enki's e-puck with its eight IR sensors (and its camera
 * when its program reads it), driven at the wheel speeds the core hands
 * over; Enki steps every object against every other and every sensor
 * against every object, and computes the IR values (its calibrated
 * e-puck model and sensor noise) and the camera's pixels inside its step.
 * The ToF ray and the message channel's geometry are world_channel.h's.
 * The floor is Enki's ground texture and a robot's ground-sensor module
 * three of Enki's GroundSensors on its body (world_ground.h); its
 * microphones are Enki's Microphones, which hear Enki's
 * ActiveSoundObjects: one for each sound source and each robot's speaker
 * (world_sound.h).
 */
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <enki/PhysicalEngine.h>
#include <enki/interactions/ActiveSoundSource.h>
#include <enki/interactions/GroundSensor.h>
#include <enki/interactions/Microphone.h>
#include <enki/robots/e-puck/EPuck.h>

#include "contacts.h"
#include "physics.h"

namespace {

// Enki's e-puck with the program's wheel geometry and its contacts.
struct Body : public Enki::EPuck {
    contacts::Counter contacts;
    const contacts::Scene *scene = nullptr;     // what a collision without a partner may be with
    long first_contact_ms = -1;
    long now_ms = 0;
    // its ground-sensor module, when it has one (world_ground.h)
    std::unique_ptr<Enki::GroundSensor> ground[ground::SENSORS];

    // Enki's EPuck(CAPABILITY_BASIC_SENSORS) also adds the scanner turret
    // (its test is `capabilities & CAPABILITY_SCANNER_TURRET`, and that
    // constant is 0x3), which costs most of a step and is never read here:
    // only the eight IR sensors are added.
    explicit Body(bool with_camera) : Enki::EPuck(CAPABILITY_NONE)
    {
        if (with_camera)
            addLocalInteraction(&camera);
        addLocalInteraction(&infraredSensor0);
        addLocalInteraction(&infraredSensor1);
        addLocalInteraction(&infraredSensor2);
        addLocalInteraction(&infraredSensor3);
        addLocalInteraction(&infraredSensor4);
        addLocalInteraction(&infraredSensor5);
        addLocalInteraction(&infraredSensor6);
        addLocalInteraction(&infraredSensor7);
    }
    void setGeometry(double axle_cm, double max_speed_cm_s, double noise)
    {
        distBetweenWheels = axle_cm;
        maxSpeed = max_speed_cm_s;
        noiseAmount = noise;
    }
    // Enki names the other body only when it can move: a robot; without
    // one, a wall or an obstacle (contacts.h tells which)
    void collisionEvent(Enki::PhysicalObject *o) override
    {
        if (o == nullptr)
            contacts.unnamed(*scene, pos.x, pos.y, getRadius());
        else
            contacts.robot();
        if (first_contact_ms < 0)
            first_contact_ms = now_ms;
    }
};

// What Enki's microphones hear: a point that plays (a source, a speaker)
struct Emitter : public Enki::PhysicalObject, public Enki::ActiveSoundObject {
    Emitter(unsigned channels, unsigned channel, double pitch)
        : Enki::ActiveSoundObject(nullptr, 0.0, channels)
    {
        speaker.setSound(channel, pitch);
    }
};

// A robot's three microphones and its speaker.
struct Ears {
    std::unique_ptr<Enki::Microphone> mics[sound::MICS];
    std::unique_ptr<Emitter> speaker;
};

class EnkiWorld : public physics::World {
public:
    explicit EnkiWorld(const physics::Scene &scene) : scene_(scene)
    {
        // Enki draws its wheel noise from one generator (Enki::random) and
        // its IR sensors' from C's rand(), seeded here
        std::srand((unsigned)scene.seed);
        const double *c = scene.wall_rgb;
        static const ground::Floor white;
        const ground::Floor &floor = scene.floor != nullptr ? *scene.floor : white;
        world_.reset(scene.walls ? new Enki::World(scene.width, scene.height,
                                                   Enki::Color(c[0], c[1], c[2]),
                                                   Enki::World::GroundTexture(
                                                       floor.texture_width(),
                                                       floor.texture_height(), floor.texture()))
                                 : new Enki::World());
        world_->setRandomSeed(scene.seed);
        contact_scene_.obstacles = &scene_.obstacles;
        contact_scene_.walls = scene.walls;
        contact_scene_.width = scene.width;
        contact_scene_.height = scene.height;
        for (const channel::Obstacle &o : scene.obstacles) {
            Enki::PhysicalObject *p = new Enki::PhysicalObject;
            if (o.box)
                p->setRectangular(o.a, o.b, o.h, -1);
            else
                p->setCylindric(o.a, o.h, -1);
            p->pos = Enki::Point(o.x, o.y);
            p->angle = o.angle;
            p->setColor(Enki::Color(o.rgb[0], o.rgb[1], o.rgb[2]));
            world_->addObject(p);
        }
        if (scene.sounds != nullptr)
            for (const sound::Source &src : scene.sounds->sources()) {
                sources_.emplace_back(new Emitter(scene.sounds->channels(), src.channel,
                                                  sound::amplitude_pa(src.db)));
                sources_.back()->pos = Enki::Point(src.x, src.y);
            }
    }

    void add(const physics::Placement &p) override
    {
        Body *b = new Body(p.camera);
        b->scene = &contact_scene_;
        b->setColor(Enki::Color(p.rgb[0], p.rgb[1], p.rgb[2]));
        b->pos = Enki::Point(p.x, p.y);
        b->angle = p.angle;
        b->setGeometry(5.3, 1000.0, scene_.noise);
        if (p.ground && scene_.walls) {     // open ground has no floor: the stub's white paper
            const double m = ground::response_m(), a = ground::response_a();
            for (int n = 0; n < ground::SENSORS; n++) {
                b->ground[n].reset(new Enki::GroundSensor(
                    b, Enki::Vector(ground::AHEAD_CM, ground::APART_CM * (1 - n)), ground::C,
                    ground::S, m, a, ground::SPOT_SD_CM, ground::NOISE_SD));
                b->addLocalInteraction(b->ground[n].get());
            }
        }
        if (scene_.sounds != nullptr) {
            const unsigned channels = scene_.sounds->channels();
            ears_.emplace_back();
            Ears &e = ears_.back();
            for (int m = 0; m < sound::MICS; m++)
                e.mics[m].reset(new Enki::Microphone(
                    b, Enki::Vector(sound::MIC_AT[m][0], sound::MIC_AT[m][1]), 0.0,
                    sound::spreading, channels));
            e.speaker.reset(new Emitter(channels, scene_.sounds->channel(sound::SPEAKER_HZ),
                                        sound::amplitude_pa(sound::SPEAKER_DB)));
        }
        world_->addObject(b);       // the world owns it
        bodies_.push_back(b);
        tof_.push_back(p.tof);
        poses_.push_back(channel::Pose{p.x, p.y, p.angle});
    }

    void drive(size_t i, double left, double right, double axle) override
    {
        Body *b = bodies_[i];
        b->setGeometry(axle, 1000.0, scene_.noise);
        b->leftSpeed = left;
        b->rightSpeed = right;
    }

    // one physics step, each robot's contacts in it counted
    void step(long now_ms) override
    {
        for (Body *b : bodies_) {
            b->now_ms = now_ms;
            b->contacts.begin_step();
        }
        world_->step(scene_.dt);
        for (Body *b : bodies_)
            b->contacts.end_step();
        for (size_t i = 0; i < bodies_.size(); i++)
            poses_[i] = channel::Pose{bodies_[i]->pos.x, bodies_[i]->pos.y, bodies_[i]->angle};
    }

    channel::Pose pose(size_t i) const override { return poses_[i]; }

    void hear(const sound::Playing &playing) override
    {
        playing_ = &playing;
        for (size_t i : playing.speakers)
            ears_[i].speaker->pos = bodies_[i]->pos;
    }

    void sense(size_t i, enki_robot_io &io) override
    {
        Body *b = bodies_[i];
        const Enki::IRSensor *ir[8] = {
            &b->infraredSensor0, &b->infraredSensor1, &b->infraredSensor2, &b->infraredSensor3,
            &b->infraredSensor4, &b->infraredSensor5, &b->infraredSensor6, &b->infraredSensor7,
        };
        for (int n = 0; n < 8; n++)
            io.prox[n] = physics::prox_reading(ir[n]->getValue());
        io.distance_mm = tof_[i] ? channel::tof_mm(poses_[i], scene_.obstacles, poses_,
                                                   scene_.walls, scene_.width, scene_.height)
                                 : channel::TOF_NONE_MM;
        if (io.camera_on) {
            double image[ENKI_CAMERA_PIXELS][3];
            for (int p = 0; p < ENKI_CAMERA_PIXELS; p++)
                for (int k = 0; k < 3; k++)
                    image[p][k] = b->camera.image[p][k];
            physics::store_camera(io, image);
        }
        if (io.ground_on)
            for (int n = 0; n < ground::SENSORS; n++)
                io.ground[n] = ground::reading(b->ground[n]->getValue());
        if (playing_ == nullptr || playing_->silent()) {
            std::memset(io.mic, 0, sizeof io.mic);
            return;
        }
        // Enki's microphones where the body is now, hearing what plays
        Ears &e = ears_[i];
        for (int m = 0; m < sound::MICS; m++) {
            Enki::Microphone &mic = *e.mics[m];
            mic.init();
            for (size_t k : playing_->sources)
                mic.objectStep(0.0, sources_[k].get(), world_.get());
            for (size_t k : playing_->speakers)
                mic.objectStep(0.0, ears_[k].speaker.get(), world_.get());
            const double *heard = mic.getAcquiredSound();
            double amplitude = 0;
            for (unsigned c = 0; c < scene_.sounds->channels(); c++)
                amplitude += heard[c];
            io.mic[m] = sound::volume_of(amplitude);
        }
    }

    // every other robot: Enki has no spatial index to ask
    void near(size_t i, double, std::vector<size_t> *out) override
    {
        out->clear();
        for (size_t k = 0; k < bodies_.size(); k++)
            if (k != i)
                out->push_back(k);
    }

    bool blocked(const channel::Pose &a, const channel::Pose &b) override
    {
        return channel::blocked(scene_.obstacles, a.x, a.y, b.x, b.y);
    }

    physics::Contacts contacts(size_t i) const override
    {
        const Body *b = bodies_[i];
        physics::Contacts c;
        c.walls = b->contacts.steps[contacts::WALL];
        c.objects = b->contacts.steps[contacts::OBJECT];
        c.robots = b->contacts.steps[contacts::ROBOT];
        c.steps = b->contacts.any_steps;
        c.first_ms = b->first_contact_ms;
        return c;
    }

private:
    physics::Scene scene_;
    contacts::Scene contact_scene_;         // its obstacles and walls, for contacts.h
    std::unique_ptr<Enki::World> world_;
    std::vector<Body *> bodies_;
    std::vector<bool> tof_;
    std::vector<channel::Pose> poses_;      // every robot's, after the last step
    std::vector<std::unique_ptr<Emitter>> sources_;     // the world's sound sources
    std::vector<Ears> ears_;                // each robot's (with a sound scene)
    const sound::Playing *playing_ = nullptr;
};

}  // namespace

namespace physics {

const char *const NAME = "enki";

std::unique_ptr<World> make(const Scene &scene, std::string *)
{
    return std::unique_ptr<World>(new EnkiWorld(scene));
}

}  // namespace physics

/*
 * world_runner.cpp - runs e-puck programs in an Enki world, in lockstep.
 *
 *   epuck-world SPEC RESULTS
 *
 * SPEC is the world as epuckc/sim/world.py resolved it (all lengths in cm,
 * angles in radians, one item per line):
 *
 *   arena square W H [R G B] | arena none
 *                                        walls of a W x H cm arena, corner (0,0),
 *                                        coloured R G B (0..1; default grey)
 *   seed N                               Enki's random generator (noise)
 *   noise F                              wheel speed noise, +-F (0.05 = 5 %)
 *   step_ms N                            ms of virtual time per world step
 *   messages RANGE LOSS EMIT RECV NOISE INTERVAL_MS
 *                                        the IR message channel (world_channel.h):
 *                                        range cm, loss 0..1, cone widths rad,
 *                                        range noise 0..1, a message's ms on the air
 *   box X Y L1 L2 ANGLE HEIGHT [R G B]   a static box centred at (X, Y)
 *   cylinder X Y R HEIGHT [R G B]        a static cylinder
 *   robot NAME X Y ANGLE                 an e-puck; the lines below belong to it
 *   lib PATH                             its program + runtime, a shared object
 *                                        (robots may name the same one)
 *   setting NAME VALUE                   what its getenv(NAME) returns
 *   colour R G B                         its body's colour (what cameras see)
 *   camera                               it has Enki's camera (its program reads it)
 *   tof                                  its ToF ray is cast (its program reads it)
 *
 * The robots of one `lib` share one loaded copy of it, each with its own
 * copy of its globals, swapped into the object's data pages while its code
 * runs (robot_loader.h; with thread-local storage, more than 8 KB of state,
 * or the environment's EPUCK_WORLD_COPIES set, each robot loads its own copy
 * of the file instead, in memory or beside the SPEC).  A robot's main()
 * runs as a coroutine (coroutine.h): it runs step_ms poll cycles, then
 * yields (robot_glue.c), and the world steps once.  Robots are
 * resumed in the order of the SPEC; nothing depends on wall-clock time, so
 * a run is reproducible byte for byte.
 *
 * Readable output: one robot writes to stdout as on the stub harness;
 * several robots' lines are collected per robot and printed after each
 * world step, prefixed with "NAME: ".
 * RESULTS gets one line per robot:
 *   NAME STATUS WALL_CONTACTS OBJECT_CONTACTS ROBOT_CONTACTS FIRST_CONTACT_MS
 * (contacts are counted in physics steps with a collision; first -1: none).
 * Exit status 0, or 4 with a message on stderr when the SPEC or a robot's
 * shared object cannot be used.
 */
#include <dlfcn.h>
#include <signal.h>
#include <sys/time.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>
#ifdef __GLIBC__
#include <stdio_ext.h>         // __fpending
#endif

#include <enki/PhysicalEngine.h>
#include <enki/robots/e-puck/EPuck.h>

#include "coroutine.h"
#include "enki_bridge.h"
#include "robot_loader.h"
#include "world_channel.h"

namespace {

const int EXIT_RUNNER = 4;

[[noreturn]] void die(const std::string &message)
{
    std::fprintf(stderr, "epuck-world: %s\n", message.c_str());
    std::exit(EXIT_RUNNER);
}

// Enki's e-puck with the program's wheel geometry and collision counters.
struct Body : public Enki::EPuck {
    long wall_contacts = 0, object_contacts = 0, robot_contacts = 0;
    long first_contact_ms = -1;
    long now_ms = 0;

    // Enki's EPuck(CAPABILITY_BASIC_SENSORS) also adds the scanner turret
    // (its test is `capabilities & CAPABILITY_SCANNER_TURRET`, and that
    // constant is 0x3), which costs most of a step and is never read here:
    // only the eight IR sensors are added.
    Body(bool with_camera) : Enki::EPuck(CAPABILITY_NONE)
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
    void collisionEvent(Enki::PhysicalObject *o) override
    {
        if (o == nullptr)
            wall_contacts++;
        else if (dynamic_cast<Body *>(o) != nullptr)
            robot_contacts++;
        else
            object_contacts++;
        if (first_contact_ms < 0)
            first_contact_ms = now_ms;
    }
};

struct Robot {
    std::string name, lib;
    double x = 0, y = 0, angle = 0;
    std::vector<std::string> settings;      // name, value, ...
    Enki::Color colour = Enki::Color::gray;
    bool camera = false, tof = false;
    enki_robot_io io;
    Body *body = nullptr;
    void *handle = nullptr;
    int (*main)(int, char **) = nullptr;
    void (*cmain_signal)(int wall) = nullptr;   // host/cmain.c's timers, this robot's
    coroutine::Coroutine run;               // its main, on its own stack
    // its own copy of its program's globals, when other robots share the
    // object (swapped in while its code runs)
    loader::Swapped state;
    FILE *out = nullptr;                    // several robots: collected output
    char *out_buf = nullptr;
    size_t out_size = 0, out_done = 0;
};

std::vector<Robot> robots;
std::map<void *, loader::State> states;     // of each program's object, by handle
Enki::World *world;
Robot *current;
Robot *volatile running_robot;      // the robot whose code runs now, else null

// The C main model's timers (host/cmain.c) are the process's: CPU time
// (a main that spins) and wall-clock time (the watchdog), each tick given
// to the robot that runs.  SA_NODEFER: a robot whose main spins is taken
// over inside the handler, which then never returns.
void on_timer(int sig)
{
    Robot *r = running_robot;
    if (r != nullptr && r->cmain_signal != nullptr)
        r->cmain_signal(sig == SIGALRM);
}

void start_timers()
{
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART | SA_NODEFER;
    sa.sa_handler = on_timer;
    sigaction(SIGVTALRM, &sa, nullptr);
    sigaction(SIGALRM, &sa, nullptr);
    struct itimerval every;
    every.it_interval.tv_sec = 0;
    every.it_interval.tv_usec = 10000;          // cmain.c's CPU_TICK_MS
    every.it_value = every.it_interval;
    setitimer(ITIMER_VIRTUAL, &every, nullptr);
    every.it_interval.tv_usec = 100000;         // cmain.c's WALL_TICK_MS
    every.it_value = every.it_interval;
    setitimer(ITIMER_REAL, &every, nullptr);
}

// robot -> world
void yield_robot(enki_robot_io *io)
{
    static_cast<Robot *>(io->runner)->run.yield();
}

void start_robot()
{
    static char arg0[] = "robot";
    static char *argv[] = { arg0, nullptr };
    Robot *r = current;
    int status = r->main(1, argv);
    r->io.status = status;
    r->io.finished = 1;
    yield_robot(&r->io);
    std::abort();
}

std::string rest(const char *line, const char *word)
{
    std::string s(line + std::strlen(word));
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r'))
        s.pop_back();
    if (!s.empty() && s[0] == ' ')
        s.erase(0, 1);
    return s;
}

double read_prox(Enki::IRSensor &s)
{
    double v = std::floor(s.getValue() + 0.5);
    return v < 0 ? 0 : v > 4095 ? 4095 : v;
}

std::vector<channel::Obstacle> obstacles;
channel::Settings messages;
bool walls = false;
double width = 0, height = 0;
std::vector<channel::Pose> poses;       // every robot's, after the last step

channel::Pose pose_of(const Robot &r)
{
    return channel::Pose{r.body->pos.x, r.body->pos.y, r.body->angle};
}

void sense(Robot &r)
{
    Enki::IRSensor *ir[8] = {
        &r.body->infraredSensor0, &r.body->infraredSensor1, &r.body->infraredSensor2,
        &r.body->infraredSensor3, &r.body->infraredSensor4, &r.body->infraredSensor5,
        &r.body->infraredSensor6, &r.body->infraredSensor7,
    };
    for (int n = 0; n < 8; n++)
        r.io.prox[n] = (int)read_prox(*ir[n]);
    r.io.x_mm = r.body->pos.x * 10.0;
    r.io.y_mm = r.body->pos.y * 10.0;
    r.io.heading_rad = r.body->angle;
    r.io.distance_mm = r.tof ? channel::tof_mm(pose_of(r), obstacles, poses, walls, width, height)
                             : channel::TOF_NONE_MM;
    if (r.camera) {
        // Enki's pixels go counter-clockwise, from the right; the camera's
        // line from the left
        for (int i = 0; i < ENKI_CAMERA_PIXELS; i++) {
            const Enki::Color &c = r.body->camera.image[ENKI_CAMERA_PIXELS - 1 - i];
            for (int k = 0; k < 3; k++) {
                double v = std::floor(c[k] * 255.0 + 0.5);
                r.io.camera[3 * i + k] = (unsigned char)(v < 0 ? 0 : v > 255 ? 255 : v);
            }
        }
    }
}

// The messages sent in the world step just ended, to every robot the
// channel lets hear them (in the SPEC's order: reproducible).
void exchange(channel::Random &random)
{
    for (Robot &s : robots) {
        for (int i = 0; i < s.io.n_sent; i++) {
            for (Robot &r : robots) {
                if (&r == &s || r.io.finished || r.io.n_inbox >= ENKI_MAX_INBOX)
                    continue;
                enki_message m;
                if (!channel::deliver(messages, obstacles, random, pose_of(s), pose_of(r),
                                      &m.sensor, &m.direction_rad, &m.distance_cm))
                    continue;
                m.value = s.io.sent[i];
                m.from = s.name.c_str();
                m.from_x_mm = s.body->pos.x * 10.0;
                m.from_y_mm = s.body->pos.y * 10.0;
                r.io.inbox[r.io.n_inbox++] = m;
            }
        }
        s.io.n_sent = 0;
    }
}

void flush_output(Robot &r, bool all)
{
    if (r.out == nullptr)
        return;
#ifdef __GLIBC__
    if (!all && __fpending(r.out) == 0 && r.out_size == r.out_done)
        return;                 // nothing written since the last step (most)
#endif
    std::fflush(r.out);
    size_t end = r.out_size;
    if (!all)
        while (end > r.out_done && r.out_buf[end - 1] != '\n')
            end--;
    size_t i = r.out_done;
    while (i < end) {
        size_t j = i;
        while (j < end && r.out_buf[j] != '\n')
            j++;
        std::printf("%s: %.*s\n", r.name.c_str(), (int)(j - i), r.out_buf + i);
        i = j + 1;
    }
    r.out_done = end < r.out_size ? end : r.out_size;
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc != 3)
        die("usage: epuck-world SPEC RESULTS");
    FILE *spec = std::fopen(argv[1], "r");
    if (spec == nullptr)
        die(std::string("cannot read ") + argv[1]);

    double noise = 0.05, wall_colour[3] = {0.5, 0.5, 0.5};
    unsigned long seed = 1;
    int step_ms = 10;
    using channel::Obstacle;
    robots.reserve(1024);

    char line[8192];
    int lineno = 0;
    while (std::fgets(line, sizeof line, spec) != nullptr) {
        lineno++;
        char name[256];
        double rgb[3];
        Obstacle o{};
        o.rgb[0] = o.rgb[1] = o.rgb[2] = 0.5;
        Robot r;
        if (std::sscanf(line, "arena square %lf %lf %lf %lf %lf", &width, &height, &wall_colour[0],
                        &wall_colour[1], &wall_colour[2]) >= 2)
            walls = true;
        else if (std::strncmp(line, "arena none", 10) == 0)
            walls = false;
        else if (std::sscanf(line, "seed %lu", &seed) == 1
                 || std::sscanf(line, "noise %lf", &noise) == 1
                 || std::sscanf(line, "step_ms %d", &step_ms) == 1
                 || std::sscanf(line, "messages %lf %lf %lf %lf %lf %d", &messages.range_cm,
                                &messages.loss, &messages.emitter_rad, &messages.receiver_rad,
                                &messages.range_noise, &messages.interval_ms) == 6)
            ;
        else if (std::sscanf(line, "box %lf %lf %lf %lf %lf %lf %lf %lf %lf", &o.x, &o.y, &o.a, &o.b,
                             &o.angle, &o.h, &o.rgb[0], &o.rgb[1], &o.rgb[2]) >= 6) {
            o.box = true;
            obstacles.push_back(o);
        } else if (std::sscanf(line, "cylinder %lf %lf %lf %lf %lf %lf %lf", &o.x, &o.y, &o.a, &o.h,
                               &o.rgb[0], &o.rgb[1], &o.rgb[2]) >= 4) {
            o.box = false;
            obstacles.push_back(o);
        } else if (std::sscanf(line, "robot %255s %lf %lf %lf", name, &r.x, &r.y, &r.angle) == 4) {
            r.name = name;
            robots.push_back(std::move(r));
        } else if (std::strncmp(line, "lib ", 4) == 0 && !robots.empty())
            robots.back().lib = rest(line, "lib");
        else if (!robots.empty() && std::sscanf(line, "colour %lf %lf %lf", &rgb[0], &rgb[1],
                                                &rgb[2]) == 3)
            robots.back().colour = Enki::Color(rgb[0], rgb[1], rgb[2]);
        else if (std::strncmp(line, "camera", 6) == 0 && !robots.empty())
            robots.back().camera = true;
        else if (std::strncmp(line, "tof", 3) == 0 && !robots.empty())
            robots.back().tof = true;
        else if (std::strncmp(line, "setting ", 8) == 0 && !robots.empty()) {
            std::string s = rest(line, "setting");
            size_t sp = s.find(' ');
            if (sp == std::string::npos)
                die(std::string(argv[1]) + ":" + std::to_string(lineno) + ": setting without a value");
            robots.back().settings.push_back(s.substr(0, sp));
            robots.back().settings.push_back(s.substr(sp + 1));
        } else if (line[0] != '#' && line[0] != '\n')
            die(std::string(argv[1]) + ":" + std::to_string(lineno) + ": cannot read this line");
    }
    std::fclose(spec);
    if (robots.empty())
        die("the world has no robot");
    if (step_ms < 1)
        die("step_ms must be at least 1");

    // Enki draws its noise from one generator (Enki::random); C's rand() is
    // seeded too in case a part of Enki uses it.
    std::srand((unsigned)seed);
    world = walls ? new Enki::World(width, height, Enki::Color(wall_colour[0], wall_colour[1],
                                                               wall_colour[2]))
                  : new Enki::World();
    world->setRandomSeed(seed);
    for (const Obstacle &o : obstacles) {
        Enki::PhysicalObject *p = new Enki::PhysicalObject;
        if (o.box)
            p->setRectangular(o.a, o.b, o.h, -1);
        else
            p->setCylindric(o.a, o.h, -1);
        p->pos = Enki::Point(o.x, o.y);
        p->angle = o.angle;
        p->setColor(Enki::Color(o.rgb[0], o.rgb[1], o.rgb[2]));
        world->addObject(p);
    }

    // the robots' copies go beside the SPEC where memory files are missing
    // (robot_loader.h)
    std::string folder(argv[1]);
    folder = folder.find('/') == std::string::npos ? "./" : folder.substr(0, folder.rfind('/') + 1);
    const bool several = robots.size() > 1;
    const char *copies_setting = std::getenv("EPUCK_WORLD_COPIES");
    const bool copies = copies_setting != nullptr && *copies_setting != '\0'
                        && std::strcmp(copies_setting, "0") != 0;
    for (Robot &r : robots) {
        std::memset(&r.io, 0, sizeof r.io);
        r.io.version = ENKI_BRIDGE_VERSION;
        r.io.yield = yield_robot;
        r.io.runner = &r;
        r.io.step_ms = step_ms;
        r.io.message_frame_ms = messages.interval_ms;
        r.io.camera_on = r.camera;
        if (r.settings.size() / 2 > ENKI_MAX_SETTINGS)
            die("too many settings for robot " + r.name);
        for (size_t i = 0; i < r.settings.size(); i++)
            r.io.settings[i] = r.settings[i].c_str();
        // the object of the first robot of its program, its own state
        // swapped in and out (robot_loader.h); else (thread-local storage,
        // more than 8 KB of state, or EPUCK_WORLD_COPIES for tests and
        // benches) its own copy of the file, the code shared with the first
        // robot's
        void *first = nullptr;
        for (Robot &o : robots) {
            if (&o == &r)
                break;
            if (o.lib == r.lib) {
                first = o.handle;
                break;
            }
        }
        std::string error;
        const std::string copy_path = folder + "robot" + std::to_string(&r - &robots[0]) + ".so";
        if (first == nullptr) {
            r.handle = loader::load(r.lib, nullptr, copy_path, &error);
            // the same file by another name is the object loaded already
            if (r.handle != nullptr && states.count(r.handle) != 0)
                first = r.handle;
            else if (r.handle != nullptr)
                states.emplace(r.handle, loader::state_of(r.handle));
        }
        if (first != nullptr)
            r.handle = !copies && states.at(first).swappable
                       ? first : loader::load(r.lib, first, copy_path, &error);
        if (r.handle == nullptr)
            die("cannot load robot " + r.name + ": " + error);
        auto attach = (int (*)(enki_robot_io *))dlsym(r.handle, "enki_robot_attach");
        r.main = (int (*)(int, char **))dlsym(r.handle, "main");
        r.cmain_signal = (void (*)(int))dlsym(r.handle, "epuck_cmain_signal");
        if (attach == nullptr || r.main == nullptr)
            die("robot " + r.name + ": " + r.lib + " is not a robot for this runner");
        // the default geometry until the program sets its own (epuckrt.h)
        r.io.mm_per_step = 128.805 / 1000.0;
        r.io.axle_mm = 53.0;
        r.body = new Body(r.camera);
        r.body->setColor(r.colour);
        r.body->pos = Enki::Point(r.x, r.y);
        r.body->angle = r.angle;
        r.body->setGeometry(r.io.axle_mm / 10.0, 1000.0, noise);
        world->addObject(r.body);
        if (several) {
            r.out = open_memstream(&r.out_buf, &r.out_size);
            if (r.out == nullptr)
                die("out of memory");
        }
    }
    loader::loaded();
    // the robots that share an object each start from its data as loaded
    // (its constructors have run, no robot's code yet)
    std::map<void *, int> sharing;
    for (const Robot &r : robots)
        sharing[r.handle]++;
    for (Robot &r : robots) {
        if (sharing[r.handle] < 2)
            continue;
        r.state.share(states.at(r.handle));
    }
    // readings for the first poll: the world as placed, nothing moving
    const double dt = step_ms / 1000.0;
    channel::Random random(seed);
    world->step(dt);
    for (Robot &r : robots)
        poses.push_back(pose_of(r));
    for (Robot &r : robots) {
        sense(r);
        auto attach = (int (*)(enki_robot_io *))dlsym(r.handle, "enki_robot_attach");
        r.state.swap_in();
        if (attach(&r.io) != 0)
            die("robot " + r.name + ": " + r.lib + " was built for another runner");
        r.state.swap_out();
        r.run.prepare(start_robot);
    }

    FILE *real_stdout = stdout;
    long now_ms = 0;
    start_timers();
    for (;;) {
        bool running = false;
        for (Robot &r : robots) {
            if (r.io.finished)
                continue;
            current = &r;
            if (r.out != nullptr)
                stdout = r.out;
            r.state.swap_in();
            running_robot = &r;
            r.run.resume();
            running_robot = nullptr;
            r.state.swap_out();
            stdout = real_stdout;
            running = running || !r.io.finished;
        }
        now_ms += step_ms;
        // the steps each robot made in this world step become its wheel
        // speeds; Enki moves the body by them in its next step
        for (Robot &r : robots) {
            double cm_per_step = r.io.mm_per_step / 10.0;
            r.body->setGeometry(r.io.axle_mm / 10.0, 1000.0, noise);
            r.body->leftSpeed = r.io.window_left * cm_per_step / dt;
            r.body->rightSpeed = r.io.window_right * cm_per_step / dt;
            r.body->now_ms = now_ms;
        }
        world->step(dt);
        for (size_t i = 0; i < robots.size(); i++)
            poses[i] = pose_of(robots[i]);
        exchange(random);
        for (Robot &r : robots) {
            r.io.pending_left = r.io.window_left;
            r.io.pending_right = r.io.window_right;
            r.io.window_left = r.io.window_right = 0;
            r.io.ms_in_window = 0;
            sense(r);
            flush_output(r, false);
        }
        if (!running)
            break;
    }
    std::fflush(stdout);

    FILE *results = std::fopen(argv[2], "w");
    if (results == nullptr)
        die(std::string("cannot write ") + argv[2]);
    for (Robot &r : robots) {
        flush_output(r, true);
        std::fprintf(results, "%s %d %ld %ld %ld %ld\n", r.name.c_str(), r.io.status,
                     r.body->wall_contacts, r.body->object_contacts, r.body->robot_contacts,
                     r.body->first_contact_ms);
    }
    std::fclose(results);
    std::fflush(stdout);
    // the robots' trace files are flushed at each record; exit() closes them
    return 0;
}

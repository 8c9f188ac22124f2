/*
 * world_runner.cpp - runs e-puck programs in a simulated world, in
 * lockstep: the runner's core, over a physics provider (physics.h; this
 * file is linked with physics_enki.cpp into epuck-world-enki and with
 * physics_chipmunk.cpp into epuck-world-chipmunk).
 *
 *   epuck-world-PHYSICS SPEC RESULTS
 *
 * SPEC is the world as epuckc/sim/world.py resolved it (all lengths in cm,
 * angles in radians, one item per line):
 *
 *   arena square W H [R G B] | arena none
 *                                        walls of a W x H cm arena, corner (0,0),
 *                                        coloured R G B (0..1; default grey)
 *   seed N                               the physics' random generators (noise)
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
 *   camera                               it has the camera (its program reads it)
 *   tof                                  its ToF ray is cast (its program reads it)
 *   ground                               it has the ground-sensor module (world_ground.h)
 *   floor W H PATH                       the floor's texture (world_ground.h)
 *   sound X Y HZ DB N ON OFF ...         a sound source (world_sound.h)
 *
 * The robots of one `lib` share one loaded copy of it, each with its own
 * copy of its globals, swapped into the object's data pages while its code
 * runs (robot_loader.h; with thread-local storage, more than 16 KB of state,
 * or the environment's EPUCK_WORLD_COPIES set, each robot loads its own copy
 * of the file instead, in memory or beside the SPEC).  A robot's main()
 * runs as a coroutine (coroutine.h): it runs step_ms poll cycles, then
 * yields (robot_glue.c), and the world steps once.  The robots' polls run
 * on EPUCK_WORLD_THREADS threads (default: one per CPU, at most one per
 * ROBOTS_PER_THREAD robots; workers.h), each thread with its own copy of
 * each program's object; the physics steps on the main thread in between.
 * Nothing depends on wall-clock time or on the threads, so a run is
 * reproducible byte for byte.
 *
 * Readable output: one robot writes to stdout as on the stub harness;
 * several robots' lines are collected per robot and printed after each
 * world step, prefixed with "NAME: ", in the SPEC's order.
 * RESULTS gets one line per robot:
 *   NAME STATUS WALL_CONTACTS OBJECT_CONTACTS ROBOT_CONTACTS FIRST_CONTACT_MS CONTACTS
 * (the physics steps in which the robot touched a wall, an obstacle,
 * another robot, each kind told apart by the provider (physics::Contacts),
 * and anything; first -1: none).
 * Exit status 0, or 4 with a message on stderr when the SPEC or a robot's
 * shared object cannot be used.
 */
#include <dlfcn.h>
#include <signal.h>
#include <sched.h>
#include <sys/resource.h>
#include <algorithm>
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

#include "coroutine.h"
#include "enki_bridge.h"
#include "physics.h"
#include "robot_loader.h"
#include "workers.h"
#include "world_channel.h"
#include "world_ground.h"
#include "world_sound.h"

namespace {

const int EXIT_RUNNER = 4;
// Fewer robots than this per thread are not worth a thread of their own
// (the wake-up of a thread costs about as much as ROBOTS_PER_THREAD polls;
// docs/performance.md, "Large worlds").
const size_t ROBOTS_PER_THREAD = 64;

[[noreturn]] void die(const std::string &message)
{
    std::fprintf(stderr, "epuck-world: %s\n", message.c_str());
    std::exit(EXIT_RUNNER);
}

struct Robot {
    std::string name, lib;
    physics::Placement placement;
    std::vector<std::string> settings;      // name, value, ...
    int thread = 0;                         // the one that resumes it (workers.h)
    enki_robot_io io;
    void *handle = nullptr;
    int (*main)(int, char **) = nullptr;
    void (*cmain_signal)(int wall) = nullptr;   // host/cmain.c's timers, this robot's
    coroutine::Coroutine run;               // its main, on its own stack
    // its own copy of its program's globals, when other robots share the
    // object (swapped in while its code runs)
    loader::Swapped state;
    std::string out;                        // several robots: its output not printed yet
};

std::vector<Robot> robots;
std::unique_ptr<physics::World> world;
std::map<void *, loader::State> states;     // of each program's object, by handle
thread_local Robot *current;                // the robot this thread resumes
thread_local Robot *volatile running_robot; // the robot whose code runs here now, else null
FILE *real_stdout;

// The C main model's timers (host/cmain.c), each thread's own (workers.h),
// each tick given to the robot that runs on that thread.
void on_timer(int sig)
{
    Robot *r = running_robot;
    if (r != nullptr && r->cmain_signal != nullptr)
        r->cmain_signal(sig == SIGALRM);
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
    r->run.entered();
    int status = r->main(1, argv);
    r->io.status = status;
    r->io.finished = 1;
    yield_robot(&r->io);
    std::abort();
}

// Several robots: stdout is this stream, unbuffered, whose every write
// goes to the output of the robot the writing thread runs (each printf
// reaches it whole, in the thread that called it).
ssize_t write_robot_output(void *, const char *buf, size_t size)
{
    Robot *r = running_robot;
    if (r != nullptr)
        r->out.append(buf, size);
    else
        std::fwrite(buf, 1, size, real_stdout);
    return (ssize_t)size;
}

FILE *robots_stdout()
{
    cookie_io_functions_t io;
    std::memset(&io, 0, sizeof io);
    io.write = write_robot_output;
    FILE *f = fopencookie(nullptr, "w", io);
    if (f == nullptr)
        die("out of memory");
    setvbuf(f, nullptr, _IONBF, 0);
    return f;
}

// The robot's whole lines written since the last call (all: the rest too),
// each prefixed with its name.
void flush_output(Robot &r, bool all)
{
    if (r.out.empty())
        return;
    size_t last = r.out.rfind('\n');
    size_t end = all ? r.out.size() : last == std::string::npos ? 0 : last + 1;
    if (end == 0)
        return;
    size_t i = 0;
    while (i < end) {
        size_t j = r.out.find('\n', i);
        if (j == std::string::npos || j > end)
            j = end;
        std::fprintf(real_stdout, "%s: %.*s\n", r.name.c_str(), (int)(j - i), r.out.data() + i);
        i = j + 1;
    }
    r.out.erase(0, end);
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

channel::Settings messages;
ground::Floor floor_texture;
sound::Scene sounds;
sound::Playing playing;                     // in the coming world step

// The samples the robots started playing in the step that began at
// `from_ms`, then what plays in the next one (from `now_ms`): what the
// robots' microphones hear before their next polls.
void take_sounds(long from_ms, long now_ms, int step_ms)
{
    for (size_t i = 0; i < robots.size(); i++) {
        enki_robot_io &io = robots[i].io;
        if (io.sound_started > 0)
            sounds.played(i, from_ms + io.sound_started - 1, io.sound_words);
        io.sound_started = 0;
    }
    sounds.playing(now_ms, now_ms + step_ms, &playing);
    world->hear(playing);
}

// The messages sent in the world step just ended, to every robot the
// channel lets hear them (in the SPEC's order: reproducible).
void exchange(channel::Random &random)
{
    std::vector<size_t> near;
    auto blocked = [](const channel::Pose &a, const channel::Pose &b) {
        return world->blocked(a, b);
    };
    for (size_t si = 0; si < robots.size(); si++) {
        Robot &s = robots[si];
        if (s.io.n_sent == 0)
            continue;
        world->near(si, messages.range_cm, &near);
        const channel::Pose from = world->pose(si);
        for (int i = 0; i < s.io.n_sent; i++) {
            for (size_t ri : near) {
                Robot &r = robots[ri];
                if (r.io.finished || r.io.n_inbox >= ENKI_MAX_INBOX)
                    continue;
                enki_message m;
                if (!channel::deliver(messages, blocked, random, from, world->pose(ri), &m.sensor,
                                      &m.direction_rad, &m.distance_cm))
                    continue;
                m.value = s.io.sent[i];
                m.from = s.name.c_str();
                m.from_x_mm = from.x * 10.0;
                m.from_y_mm = from.y * 10.0;
                r.io.inbox[r.io.n_inbox++] = m;
            }
        }
        s.io.n_sent = 0;
    }
}

// The world as the last step left it, in robot i's io.
void sense(size_t i)
{
    Robot &r = robots[i];
    const channel::Pose p = world->pose(i);
    r.io.x_mm = p.x * 10.0;
    r.io.y_mm = p.y * 10.0;
    r.io.heading_rad = p.angle;
    world->sense(i, r.io);
}

// Thread t's share of a world step: its robots' new readings (after the
// first step), then their polls, each robot in its own coroutine.
std::vector<std::vector<size_t>> shares;    // the robots of each thread, ascending
bool first_polls = true;

void poll_share(int t)
{
    const std::vector<size_t> &share = shares[t];
    for (size_t n = 0; n < share.size(); n++) {
        Robot &r = robots[share[n]];
        const size_t i = share[n];
        // the next robot's state and stack, on their way while this one runs
        if (n + 1 < share.size()) {
            const Robot &next = robots[share[n + 1]];
            next.state.prefetch();
            next.run.prefetch();
            __builtin_prefetch(&next.io);
        }
        if (r.io.finished)
            continue;
        if (!first_polls) {
            r.io.pending_left = r.io.window_left;
            r.io.pending_right = r.io.window_right;
            r.io.window_left = r.io.window_right = 0;
            r.io.ms_in_window = 0;
            sense(i);
        }
        current = &r;
        r.state.swap_in();
        running_robot = &r;
        r.run.resume();
        running_robot = nullptr;
        r.state.swap_out();
    }
}

// EPUCK_WORLD_THREADS, else one per CPU this process may run on, at most
// one per ROBOTS_PER_THREAD robots.
int thread_count()
{
    const char *setting = std::getenv("EPUCK_WORLD_THREADS");
    long wanted = setting != nullptr && *setting != '\0' ? std::atol(setting) : 0;
    if (wanted < 0 || wanted > 256)
        die("EPUCK_WORLD_THREADS is a number of threads from 1 to 256 (0 or unset: automatic)");
    if (wanted == 0) {
        cpu_set_t cpus;
        wanted = sched_getaffinity(0, sizeof cpus, &cpus) == 0 ? CPU_COUNT(&cpus) : 1;
        long most = (long)(robots.size() / ROBOTS_PER_THREAD);
        wanted = std::max(1L, std::min(wanted, most));
    }
    return (int)std::min<long>(wanted, (long)robots.size());
}

// Each robot's object: the file itself, for the first robot of its path;
// its copy for each other robot where the robots of a program cannot share
// one (thread-local storage, more than 16 KB of state, EPUCK_WORLD_COPIES);
// else one object per program and thread, the file itself for the first
// thread that runs it and copies for the others (robot_loader.h).
void load_robots(const std::string &folder, int threads)
{
    const char *copies_setting = std::getenv("EPUCK_WORLD_COPIES");
    const bool copies = copies_setting != nullptr && *copies_setting != '\0'
                        && std::strcmp(copies_setting, "0") != 0;
    std::map<std::string, void *> firsts;               // by path
    std::map<std::pair<void *, int>, void *> of_thread;  // (first, thread) -> its object
    std::string error;
    // the files first: which objects have thread-local storage, whose
    // robots all run on the main thread (the one their constructors ran on)
    for (size_t k = 0; k < robots.size(); k++) {
        Robot &r = robots[k];
        if (firsts.count(r.lib) != 0)
            continue;
        void *h = loader::load(r.lib, nullptr, folder + "robot" + std::to_string(k) + ".so", &error);
        if (h == nullptr)
            die("cannot load robot " + r.name + ": " + error);
        // the same file by another name is the object loaded already
        if (states.count(h) == 0)
            states.emplace(h, loader::state_of(h));
        firsts[r.lib] = h;
    }
    shares.assign(threads, {});
    for (size_t k = 0; k < robots.size(); k++) {
        Robot &r = robots[k];
        void *first = firsts.at(r.lib);
        r.thread = states.at(first).tls ? 0 : (int)(k * threads / robots.size());
        shares[r.thread].push_back(k);
        const std::string copy_path = folder + "robot" + std::to_string(k) + ".so";
        if (copies || !states.at(first).swappable) {
            bool taken = of_thread.count({first, -1}) != 0;
            r.handle = taken ? loader::load(r.lib, first, copy_path, &error) : first;
            of_thread[{first, -1}] = first;
        } else {
            auto found = of_thread.find({first, r.thread});
            if (found != of_thread.end()) {
                r.handle = found->second;
            } else {
                bool any = false;
                for (int t = 0; t < threads; t++)
                    any = any || of_thread.count({first, t}) != 0;
                r.handle = any ? loader::load(r.lib, first, copy_path, &error) : first;
                if (r.handle != nullptr && states.count(r.handle) == 0)
                    states.emplace(r.handle, loader::state_of(r.handle));
                of_thread[{first, r.thread}] = r.handle;
            }
        }
        if (r.handle == nullptr)
            die("cannot load robot " + r.name + ": " + error);
        // host/cmain.c's entry, where a reset starts main again (the robot
        // is linked with --wrap=main); a robot without it: its main
        r.main = (int (*)(int, char **))dlsym(r.handle, "__wrap_main");
        if (r.main == nullptr)
            r.main = (int (*)(int, char **))dlsym(r.handle, "main");
        r.cmain_signal = (void (*)(int))dlsym(r.handle, "epuck_cmain_signal");
        if (dlsym(r.handle, "enki_robot_attach") == nullptr || r.main == nullptr)
            die("robot " + r.name + ": " + r.lib + " is not a robot for this runner");
    }
    loader::loaded();
}

}  // namespace

int main(int argc, char **argv)
{
    if (argc != 3)
        die("usage: epuck-world SPEC RESULTS");
    // the robots' objects start their own timers as they load (host/cmain.c)
    workers::hold_timer_signals(true);
    FILE *spec = std::fopen(argv[1], "r");
    if (spec == nullptr)
        die(std::string("cannot read ") + argv[1]);

    physics::Scene scene;
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
        if (std::sscanf(line, "arena square %lf %lf %lf %lf %lf", &scene.width, &scene.height,
                        &scene.wall_rgb[0], &scene.wall_rgb[1], &scene.wall_rgb[2]) >= 2)
            scene.walls = true;
        else if (std::strncmp(line, "arena none", 10) == 0)
            scene.walls = false;
        else if (std::sscanf(line, "seed %lu", &scene.seed) == 1
                 || std::sscanf(line, "noise %lf", &scene.noise) == 1
                 || std::sscanf(line, "step_ms %d", &step_ms) == 1
                 || std::sscanf(line, "messages %lf %lf %lf %lf %lf %d", &messages.range_cm,
                                &messages.loss, &messages.emitter_rad, &messages.receiver_rad,
                                &messages.range_noise, &messages.interval_ms) == 6)
            ;
        else if (std::sscanf(line, "box %lf %lf %lf %lf %lf %lf %lf %lf %lf", &o.x, &o.y, &o.a, &o.b,
                             &o.angle, &o.h, &o.rgb[0], &o.rgb[1], &o.rgb[2]) >= 6) {
            o.box = true;
            scene.obstacles.push_back(o);
        } else if (std::sscanf(line, "cylinder %lf %lf %lf %lf %lf %lf %lf", &o.x, &o.y, &o.a, &o.h,
                               &o.rgb[0], &o.rgb[1], &o.rgb[2]) >= 4) {
            o.box = false;
            scene.obstacles.push_back(o);
        } else if (std::sscanf(line, "robot %255s %lf %lf %lf", name, &r.placement.x,
                               &r.placement.y, &r.placement.angle) == 4) {
            r.name = name;
            robots.push_back(std::move(r));
        } else if (std::strncmp(line, "lib ", 4) == 0 && !robots.empty())
            robots.back().lib = rest(line, "lib");
        else if (!robots.empty() && std::sscanf(line, "colour %lf %lf %lf", &rgb[0], &rgb[1],
                                                &rgb[2]) == 3)
            std::memcpy(robots.back().placement.rgb, rgb, sizeof rgb);
        else if (std::strncmp(line, "camera", 6) == 0 && !robots.empty())
            robots.back().placement.camera = true;
        else if (std::strncmp(line, "tof", 3) == 0 && !robots.empty())
            robots.back().placement.tof = true;
        else if (std::strncmp(line, "ground", 6) == 0 && !robots.empty())
            robots.back().placement.ground = true;
        else if (std::strncmp(line, "floor ", 6) == 0 || std::strncmp(line, "sound ", 6) == 0) {
            std::string error;
            if (!(line[0] == 'f' ? floor_texture.load(line, &error) : sounds.add_source(line, &error)))
                die(std::string(argv[1]) + ":" + std::to_string(lineno) + ": " + error);
        }
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
    scene.dt = step_ms / 1000.0;

    // a robot writing its own trace holds a file open: room for them all
    struct rlimit files;
    if (getrlimit(RLIMIT_NOFILE, &files) == 0 && files.rlim_cur < files.rlim_max) {
        files.rlim_cur = files.rlim_max;
        setrlimit(RLIMIT_NOFILE, &files);
    }

    sounds.listen(robots.size());
    scene.floor = &floor_texture;
    scene.sounds = &sounds;
    std::string error;
    world = physics::make(scene, &error);
    if (world == nullptr)
        die(error);

    // the robots' copies go beside the SPEC where memory files are missing
    // (robot_loader.h)
    std::string folder(argv[1]);
    folder = folder.find('/') == std::string::npos ? "./" : folder.substr(0, folder.rfind('/') + 1);
    const int threads = thread_count();
    load_robots(folder, threads);
    for (Robot &r : robots) {
        std::memset(&r.io, 0, sizeof r.io);
        r.io.version = ENKI_BRIDGE_VERSION;
        r.io.yield = yield_robot;
        r.io.runner = &r;
        r.io.step_ms = step_ms;
        r.io.message_frame_ms = messages.interval_ms;
        r.io.camera_on = r.placement.camera;
        r.io.ground_on = r.placement.ground && scene.walls;    // open ground: the stub's white paper
        if (r.settings.size() / 2 > ENKI_MAX_SETTINGS)
            die("too many settings for robot " + r.name);
        for (size_t i = 0; i < r.settings.size(); i++)
            r.io.settings[i] = r.settings[i].c_str();
        // the default geometry until the program sets its own (epuckrt.h)
        r.io.mm_per_step = 128.805 / 1000.0;
        r.io.axle_mm = 53.0;
        world->add(r.placement);
    }
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
    channel::Random random(scene.seed);
    world->step(0);
    take_sounds(0, 0, step_ms);
    for (size_t i = 0; i < robots.size(); i++) {
        Robot &r = robots[i];
        sense(i);
        auto attach = (int (*)(enki_robot_io *))dlsym(r.handle, "enki_robot_attach");
        r.state.swap_in();
        if (attach(&r.io) != 0)
            die("robot " + r.name + ": " + r.lib + " was built for another runner");
        r.state.swap_out();
        r.run.prepare(start_robot);
    }

    real_stdout = stdout;
    if (robots.size() > 1)
        stdout = robots_stdout();
    workers::install_handler(on_timer);
    workers::hold_timer_signals(false);
    workers::start_thread_timers();
    workers::Pool pool(threads, poll_share);
    const double dt = scene.dt;
    long now_ms = 0;
    for (;;) {
        pool.run();
        first_polls = false;
        bool running = false;
        for (Robot &r : robots) {
            flush_output(r, false);
            running = running || !r.io.finished;
        }
        const long from_ms = now_ms;
        now_ms += step_ms;
        // the steps each robot made in this world step become its wheel
        // speeds; the physics moves the body by them in its next step
        for (size_t i = 0; i < robots.size(); i++) {
            const Robot &r = robots[i];
            double cm_per_step = r.io.mm_per_step / 10.0;
            world->drive(i, r.io.window_left * cm_per_step / dt,
                         r.io.window_right * cm_per_step / dt, r.io.axle_mm / 10.0);
        }
        world->step(now_ms);
        exchange(random);
        take_sounds(from_ms, now_ms, step_ms);
        if (!running)
            break;
    }
    std::fflush(stdout);

    FILE *results = std::fopen(argv[2], "w");
    if (results == nullptr)
        die(std::string("cannot write ") + argv[2]);
    for (size_t i = 0; i < robots.size(); i++) {
        Robot &r = robots[i];
        flush_output(r, true);
        const physics::Contacts c = world->contacts(i);
        std::fprintf(results, "%s %d %ld %ld %ld %ld %ld\n", r.name.c_str(), r.io.status, c.walls,
                     c.objects, c.robots, c.first_ms, c.steps);
    }
    std::fclose(results);
    std::fflush(real_stdout);
    // the robots' trace files are flushed at each record; exit() closes
    // them (the physics is left as it is, nothing reads it any more; under
    // AddressSanitizer it is freed, so that LeakSanitizer finds nothing left)
#if defined(COROUTINE_ASAN)
    world.reset();
#else
    world.release();
#endif
    return 0;
}

/*
 * workers.h - the world runner's threads (world_runner.cpp): the robots'
 * polls (and their sensors' readings) spread over a few threads, the
 * physics step and the messages on the main thread in between.
 *
 * Each robot belongs to one thread for the whole run (robot k of N to
 * thread k * T / N, in the SPEC's order) and is resumed only there; in a
 * world step every thread resumes its robots in order, then all wait for
 * the slowest (Pool::run).  A robot reads only its own inputs and writes
 * only its own outputs and state during its poll, and the physics stands
 * still meanwhile, so nothing a robot does depends on which thread runs
 * it or when: the same world gives the same run with any number of
 * threads (tests/sim/test_chipmunk.py compares 1 and 3, on both physics).
 *
 * Each thread has its own timers of the C main model (host/cmain.c): a
 * tick every 10 ms of the thread's CPU time (SIGVTALRM, a main that spins)
 * and every 100 ms of wall-clock time (SIGALRM, the watchdog), each sent
 * to that thread (SIGEV_THREAD_ID) and given to the robot it runs.
 */
#ifndef WORLD_WORKERS_H
#define WORLD_WORKERS_H

#include <signal.h>
#include <sys/time.h>
#include <time.h>
#include <unistd.h>
#include <atomic>
#include <condition_variable>
#include <cstring>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace workers {

const long CPU_TICK_NS = 10 * 1000000L;     // host/cmain.c's CPU_TICK_MS
const long WALL_TICK_NS = 100 * 1000000L;   // host/cmain.c's WALL_TICK_MS

// The robots' objects start host/cmain.c's process timers when they are
// loaded; the runner's replace them.  Until its handlers are installed,
// their signals wait (blocked), so that no robot's handler runs while
// the robots load.
inline void hold_timer_signals(bool hold)
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGVTALRM);
    sigaddset(&set, SIGALRM);
    pthread_sigmask(hold ? SIG_BLOCK : SIG_UNBLOCK, &set, nullptr);
}

// The runner's handler for both signals (SA_NODEFER: a robot whose main
// spins is taken over inside the handler, which then never returns), and
// the loaded robots' process timers stopped.
inline void install_handler(void (*handler)(int))
{
    struct sigaction sa;
    std::memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART | SA_NODEFER;
    sa.sa_handler = handler;
    sigaction(SIGVTALRM, &sa, nullptr);
    sigaction(SIGALRM, &sa, nullptr);
    struct itimerval none;
    std::memset(&none, 0, sizeof none);
    setitimer(ITIMER_VIRTUAL, &none, nullptr);
    setitimer(ITIMER_REAL, &none, nullptr);
}

// This thread's own two timers (where Linux sends a timer's signal to one
// thread; elsewhere the process's, and the runner runs one thread).
inline bool start_thread_timers()
{
#if defined(__linux__) && defined(SIGEV_THREAD_ID)
    const struct { clockid_t clock; int signal; long ns; } timers[2] = {
        {CLOCK_THREAD_CPUTIME_ID, SIGVTALRM, CPU_TICK_NS},
        {CLOCK_MONOTONIC, SIGALRM, WALL_TICK_NS},
    };
    for (const auto &t : timers) {
        struct sigevent ev;
        std::memset(&ev, 0, sizeof ev);
        ev.sigev_notify = SIGEV_THREAD_ID;
        ev.sigev_signo = t.signal;
        ev._sigev_un._tid = gettid();
        timer_t id;
        if (timer_create(t.clock, &ev, &id) != 0)
            return false;
        struct itimerspec every;
        every.it_interval.tv_sec = 0;
        every.it_interval.tv_nsec = t.ns;
        every.it_value = every.it_interval;
        timer_settime(id, 0, &every, nullptr);
    }
    return true;
#else
    struct itimerval every;
    every.it_interval.tv_sec = 0;
    every.it_interval.tv_usec = CPU_TICK_NS / 1000;
    every.it_value = every.it_interval;
    setitimer(ITIMER_VIRTUAL, &every, nullptr);
    every.it_interval.tv_usec = WALL_TICK_NS / 1000;
    every.it_value = every.it_interval;
    setitimer(ITIMER_REAL, &every, nullptr);
    return false;
#endif
}

// Threads that each run work(t) once per run(), thread 0 being the
// caller's.  The others wait between runs, spinning a little first (a
// world step of many robots comes every few ms) and then asleep.
class Pool {
public:
    Pool(int threads, std::function<void(int)> work) : work_(std::move(work))
    {
        for (int t = 1; t < threads; t++)
            threads_.emplace_back([this, t] { serve(t); });
    }
    ~Pool()
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
            generation_++;
        }
        wake_.notify_all();
        for (std::thread &t : threads_)
            t.join();
    }
    int size() const { return (int)threads_.size() + 1; }

    // work(t) on every thread; returns when all are done
    void run()
    {
        if (threads_.empty()) {
            work_(0);
            return;
        }
        pending_.store((int)threads_.size(), std::memory_order_relaxed);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            generation_++;
            published_.store(generation_, std::memory_order_release);
        }
        wake_.notify_all();
        work_(0);
        for (int spin = 0; pending_.load(std::memory_order_acquire) != 0; spin++) {
            if (spin < SPINS)
                continue;
            std::unique_lock<std::mutex> lock(mutex_);
            done_.wait(lock, [this] { return pending_.load(std::memory_order_acquire) == 0; });
        }
    }

private:
    static const int SPINS = 20000;
    std::function<void(int)> work_;
    std::vector<std::thread> threads_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    unsigned long generation_ = 0;
    std::atomic<unsigned long> published_{0};
    std::atomic<int> pending_{0};
    bool stop_ = false;

    void serve(int t)
    {
        hold_timer_signals(false);
        start_thread_timers();
        unsigned long seen = 0;
        for (;;) {
            for (int spin = 0; published_.load(std::memory_order_acquire) == seen && spin < SPINS;
                 spin++)
                ;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [this, seen] { return generation_ != seen; });
                seen = generation_;
                if (stop_)
                    return;
            }
            work_(t);
            if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
                std::lock_guard<std::mutex> lock(mutex_);
                done_.notify_one();
            }
        }
    }
};

}  // namespace workers

#endif

/*
 * cmain.c - the C main model of the host harness (docs/runtime.md, "C
 * programs with their own main"): a program written against the e-puck
 * library runs its own main() on the simulated robot, deterministically.
 *
 * Main's clock.  Main runs on the process's (or, in an Enki world, the
 * robot's coroutine's) own stack, and owns a clock in dsPIC instruction
 * cycles (FCY 14.7456 MHz): every basic block of the user's C costs
 * CYCLES_PER_BLOCK (the user's C is compiled with
 * -fsanitize-coverage=trace-pc, which calls __sanitizer_cov_trace_pc at
 * each block), each library call what epuck_stub.h says, wait(n) n turns
 * of the library's busy loop.  Each time main's clock passes a millisecond,
 * the simulator takes that millisecond (rt_platform_idle: the wheels move,
 * the scenario applies, the agendas run: they preempt main there, as the
 * timer interrupt does on the robot) and main goes on.  Same program, world
 * and seed: the same trace.
 *
 * A main that spins without a block of its own (`while(1);` compiles to a
 * jump to itself, which gcc does not instrument) makes no progress on its
 * clock: after SPIN_CPU_MS of the process's CPU time without any, the
 * simulator takes over (from a signal handler on main's stack, which never
 * returns to it): simulated time runs on from main's clock, the agendas
 * running, until the time limit.  Main never runs again; it could only
 * have spun.
 *
 * The watchdog.  Code the simulator waits for (an extern action or event
 * of a rule program, an agenda, a main blocked in a system call) that has
 * not let simulated time advance for the watchdog's budget of wall-clock
 * time (EPUCK_WATCHDOG_MS, `epuckc run --watchdog`) ends the run: a
 * "watchdog" record closes the trace, stderr names the function and line
 * (the last block of the user's C that ran; addr2line), exit status
 * EXIT_WATCHDOG.
 *
 * Signals: SIGVTALRM (CPU time) for the spin, SIGALRM (wall clock) for the
 * watchdog, both from the process's start (a constructor).  In an Enki
 * world the runner installs its own after loading its robots (they share
 * one process), which calls epuck_cmain_signal of the robot running.
 *
 * The chip's instructions (host/dspic.c calls chip()): a reset starts main
 * again (the harness links the program with --wrap=main: __wrap_main keeps
 * where main starts and, before its first run, what the program's globals
 * hold; build/dspic_asm.py puts them in sections of their own), after the
 * library's simulation went back to its state at reset; sleep ends main
 * for good (the agendas and the motors stop, simulated time runs on);
 * idle waits for the next interrupt.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <setjmp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <unistd.h>

#include "rt_platform.h"
#include "epuck_stub.h"

#define EXIT_WATCHDOG 5
#define CYCLES_PER_BLOCK 5              /* a basic block of the user's C */
#define DECICYCLES_PER_MS 147456ULL     /* FCY 14.7456 MHz: 14745.6 cycles a ms */
#define SPIN_CPU_MS 50                  /* CPU time without progress: main spins */
#define CPU_TICK_MS 10
#define WALL_TICK_MS 100
#define DEFAULT_WATCHDOG_MS 5000L

enum { CTX_MAIN, CTX_LOOP, CTX_SIM };

static volatile sig_atomic_t ctx = CTX_MAIN;   /* who runs: main, mainloop, a step */
static int started;                 /* main's first call (or mainloop) initialised */
static unsigned long long main_cycles;     /* main's clock */
static long main_ms;                /* the simulator's steps taken from main */
static volatile unsigned long progress;    /* main's blocks and calls, every step */
static volatile sig_atomic_t taken_over;
static void *volatile last_pc;      /* the last block of the user's C that ran */
static long watchdog_ms = DEFAULT_WATCHDOG_MS;

static void read_budget(void);
static void take_over(void);

static unsigned long long boundary(long ms)
{
    return (unsigned long long)ms * DECICYCLES_PER_MS / 10ULL;
}

/* One simulated ms, main (or whoever called) preempted meanwhile. */
static void sim_step(void)
{
    sig_atomic_t was = ctx;
    ctx = CTX_SIM;
    rt_platform_idle();         /* exits at the time limit */
    progress++;
    ctx = was;
}

static void on_init(void)
{
    ctx = CTX_LOOP;             /* mainloop runs; main's first call puts CTX_MAIN back */
    if (!started) {
        started = 1;
        read_budget();
    }
}

/* Main's first block of C: the harness starts (the trace, the scenario,
 * the settings).  A generated rule program's main is not instrumented: it
 * starts the harness in mainloop, as before this model. */
static void start_main(void)
{
    started = 1;
    rt_platform_init();
    ctx = CTX_MAIN;
    read_budget();
}

/* Main spent `count` times `cycles_each` cycles: the simulator takes every
 * ms main's clock passed.  Nothing outside main (mainloop, a step), nor
 * before main's own C ran. */
static volatile sig_atomic_t reset_pending;    /* a reset from an agenda, for main */
static void reset_now(void);

static void charge(long count, int cycles_each)
{
    if (ctx != CTX_MAIN || !started)
        return;
    if (reset_pending)
        reset_now();
    progress++;
    main_cycles += (unsigned long long)count * (unsigned long long)cycles_each;
    while (ctx == CTX_MAIN && main_cycles >= boundary(main_ms + 1)) {
        main_ms++;
        sim_step();
    }
}

/* a call of the library: the LEDs as main left them (a pin it wrote) are
 * noted at main's clock before the call takes its time */
static void library_call(long count, int cycles_each)
{
    if (ctx == CTX_MAIN && started)
        stub_outputs_mark();
    charge(count, cycles_each);
}

void __sanitizer_cov_trace_pc(void);     /* gcc's and clang's name */
void __sanitizer_cov_trace_pc(void)
{
    last_pc = __builtin_return_address(0);
    if (ctx == CTX_MAIN) {
        if (!started)
            start_main();
        charge(1L, CYCLES_PER_BLOCK);
    }
}

/* ---- main's clock, for the library's devices (epuck_stub.h) ------------------ */

static unsigned long long now_cycles(void)
{
    return ctx == CTX_MAIN && started ? main_cycles : boundary(host_now_ms());
}

static unsigned long long mains_cycles(void)
{
    return main_cycles;
}

/* ---- the chip's instructions: reset, sleep, idle --------------------------------- */

static sigjmp_buf restart;
extern char __start_epuck_user_data[] __attribute__((weak));
extern char __stop_epuck_user_data[] __attribute__((weak));
extern char __start_epuck_user_bss[] __attribute__((weak));
extern char __stop_epuck_user_bss[] __attribute__((weak));
static char *user_data;             /* the program's globals before main first ran */

static size_t section_size(const char *start, const char *stop)
{
    return start != NULL && stop != NULL && stop > start ? (size_t)(stop - start) : 0;
}

/* Where main starts, and again after a reset. */
int __real_main(int argc, char **argv);
int __wrap_main(int argc, char **argv);
int __wrap_main(int argc, char **argv)
{
    size_t n = section_size(__start_epuck_user_data, __stop_epuck_user_data);
    int status;
    if (n > 0 && (user_data = malloc(n)) != NULL)
        memcpy(user_data, __start_epuck_user_data, n);
    sigsetjmp(restart, 1);
    status = __real_main(argc, argv);
    stub_outputs_end();         /* what the UARTs still had to say, the LEDs */
    return status;
}

static void reset_now(void)
{
    size_t n = section_size(__start_epuck_user_data, __stop_epuck_user_data);
    reset_pending = 0;
    host_record("reset", "reset", ", \"cause\": \"reset instruction\"",
                "reset     the reset instruction: main starts again");
    stub_reset_library();
    if (user_data != NULL)
        memcpy(__start_epuck_user_data, user_data, n);
    n = section_size(__start_epuck_user_bss, __stop_epuck_user_bss);
    if (n > 0)
        memset(__start_epuck_user_bss, 0, n);
    ctx = CTX_MAIN;
    siglongjmp(restart, 1);
}

/* The next interrupt after main's clock: the A/D scan's (1/16384 s) while
 * it runs, else the agendas' timer's (0.1 ms); 0: none. */
static unsigned long long next_interrupt(void)
{
    unsigned long long tick, per_s = stub_ad_scan_running() ? 16384ULL
                                     : stub_agendas_running() ? 10000ULL : 0ULL;
    if (per_s == 0)
        return 0;
    tick = (main_cycles * 10ULL * per_s) / (DECICYCLES_PER_MS * 1000ULL) + 1ULL;
    return (tick * DECICYCLES_PER_MS * 1000ULL + per_s * 10ULL - 1ULL) / (per_s * 10ULL);
}

static void chip(int instruction)
{
    if (instruction == STUB_INSN_RESET) {
        if (ctx == CTX_MAIN && started)
            reset_now();
        reset_pending = 1;          /* from an agenda: when main runs again */
        return;
    }
    if (ctx != CTX_MAIN || !started)
        return;
    if (instruction == STUB_INSN_IDLE) {
        unsigned long long wake = next_interrupt();
        if (wake > main_cycles) {
            charge((long)(wake - main_cycles), 1);
            return;
        }
    }
    /* sleep (or idle with nothing to wake it): main stops for good */
    host_record("sleep", "sleep", "", "sleep     main stops: nothing wakes the chip");
    stub_sleep_library();
    take_over();
}

/* ---- the spin and the watchdog ----------------------------------------------- */

/* `s` as the inside of a JSON string */
static void json_text(char *out, size_t size, const char *s)
{
    size_t used = 0;
    for (; *s != '\0' && used + 8 < size; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            used += (size_t)snprintf(out + used, size - used, "\\%c", c);
        else if (c < 0x20)
            used += (size_t)snprintf(out + used, size - used, "\\u%04x", c);
        else
            out[used++] = (char)c;
    }
    out[used] = '\0';
}

/* The function of the user's C that ran last, and its file:line when
 * addr2line finds them ("" if not). */
static void describe_pc(char *function, size_t fsize, char *where, size_t wsize)
{
    Dl_info info;
    char *pc = (char *)last_pc;
    char command[1400], exe[1024], out[256];
    const char *file;
    ssize_t n;
    FILE *p;

    snprintf(function, fsize, "the program's C");
    where[0] = '\0';
    if (pc == NULL || !dladdr(pc, &info) || info.dli_fname == NULL)
        return;
    if (info.dli_sname != NULL)
        snprintf(function, fsize, "%s", info.dli_sname);
    file = info.dli_fname;
    n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (file[0] != '/' && n > 0) {     /* the executable, as it was started */
        exe[n] = '\0';
        file = exe;
    }
    if (strchr(file, '\'') != NULL)
        return;
    snprintf(command, sizeof command, "addr2line -f -e '%s' %#lx 2>/dev/null", file,
             (unsigned long)(pc - 1 - (char *)info.dli_fbase));
    p = popen(command, "r");
    if (p == NULL)
        return;
    if (fgets(out, sizeof out, p) != NULL && strncmp(out, "??", 2) != 0) {
        out[strcspn(out, "\n")] = '\0';
        snprintf(function, fsize, "%s", out);
    }
    if (fgets(out, sizeof out, p) != NULL && strncmp(out, "??", 2) != 0) {
        out[strcspn(out, "\n (")] = '\0';
        snprintf(where, wsize, "%s", out);
    }
    pclose(p);
}

static void watchdog_fire(void)
{
    char function[512], where[512], line[1400], extra[1400], w_json[1100];
    const char *role = ctx == CTX_MAIN ? "main" : ctx == CTX_LOOP ? "an action or event"
                       : "an agenda (or an action it ran)";
    describe_pc(function, sizeof function, where, sizeof where);
    fprintf(stderr, "epuckc: the watchdog stopped the run: %s (%s%s%s) did not give the "
            "simulator back within %ld.%ld s of wall-clock time; simulated time stopped at "
            "%ld ms. Does it loop forever or wait for something that never comes? "
            "(--watchdog SECONDS sets the budget)\n", function, role, where[0] ? ", last at " : "",
            where, watchdog_ms / 1000, watchdog_ms % 1000 / 100, host_now_ms());
    json_text(w_json, sizeof w_json, where);
    stub_outputs_end();
    snprintf(extra, sizeof extra, ", \"where\": \"%s\", \"wall_ms\": %ld", w_json, watchdog_ms);
    snprintf(line, sizeof line, "watchdog  %s%s%s did not return within %ld ms of wall-clock time",
             function, where[0] ? " at " : "", where, watchdog_ms);
    host_record("watchdog", function, extra, line);
    fflush(stdout);
    exit(EXIT_WATCHDOG);
}

/* Main spins: the simulator runs on without it, to the time limit (a main
 * that spun before any block of its own, `int main(void) { for (;;); }`,
 * starts the harness here). */
static void take_over(void)
{
    taken_over = 1;
    if (!started)
        start_main();
    for (;;)
        sim_step();
}

static unsigned long cpu_seen;
static long wall_seen_ms = -1, wall_quiet_ms, cpu_quiet_ms;

/* A tick of the timers: wall 1 (SIGALRM, every WALL_TICK_MS of wall-clock
 * time: the watchdog, on simulated time), 0 (SIGVTALRM, every CPU_TICK_MS
 * of CPU time: the spin, on main's progress).  The Enki runner
 * calls it for the robot that runs. */
void epuck_cmain_signal(int wall)
{
    if (wall) {                 /* the watchdog: has simulated time advanced? */
        if (host_now_ms() != wall_seen_ms) {
            wall_seen_ms = host_now_ms();
            wall_quiet_ms = 0;
        } else if ((wall_quiet_ms += WALL_TICK_MS) >= watchdog_ms) {
            watchdog_fire();
        }
        return;
    }
    if (progress != cpu_seen) {
        cpu_seen = progress;
        cpu_quiet_ms = 0;
    } else if ((cpu_quiet_ms += CPU_TICK_MS) >= SPIN_CPU_MS && ctx == CTX_MAIN
               && !taken_over) {
        take_over();
    }
}

static void on_cpu_tick(int sig)
{
    (void)sig;
    epuck_cmain_signal(0);
}

static void on_wall_tick(int sig)
{
    (void)sig;
    epuck_cmain_signal(1);
}

static void read_budget(void)
{
    const char *budget = getenv("EPUCK_WATCHDOG_MS");
    if (budget != NULL && atol(budget) > 0)
        watchdog_ms = atol(budget);
}

/* From the start (a main may spin before any block of its own).  In an
 * Enki world the runner installs its own afterwards, which replace these. */
static void start_signals(void)
{
    struct sigaction sa;
    struct itimerval every;

    memset(&sa, 0, sizeof sa);
    sigemptyset(&sa.sa_mask);
    /* the take-over never returns from its handler: the signals stay open */
    sa.sa_flags = SA_RESTART | SA_NODEFER;
    sa.sa_handler = on_cpu_tick;
    sigaction(SIGVTALRM, &sa, NULL);
    sa.sa_handler = on_wall_tick;
    sigaction(SIGALRM, &sa, NULL);
    every.it_interval.tv_sec = 0;
    every.it_interval.tv_usec = CPU_TICK_MS * 1000;
    every.it_value = every.it_interval;
    setitimer(ITIMER_VIRTUAL, &every, NULL);
    every.it_interval.tv_usec = WALL_TICK_MS * 1000;
    every.it_value = every.it_interval;
    setitimer(ITIMER_REAL, &every, NULL);
}

__attribute__((constructor)) static void cmain_install(void)
{
    stub_cost_hook = library_call;
    stub_clock_hook = now_cycles;
    stub_main_hook = mains_cycles;
    stub_chip_hook = chip;
    host_init_hook = on_init;
    start_signals();
}

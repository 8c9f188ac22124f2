/*
 * coroutine.h - the robots' coroutines in the world runner
 * (world_runner.cpp): each robot's main() runs on its own stack, and the
 * runner resumes it for a world step; the robot yields back at the step's
 * end (robot_glue.c).
 *
 * On x86-64 a switch saves the callee-saved registers and swaps stacks (a
 * few ns); elsewhere ucontext's swapcontext, which also saves the signal
 * mask with a system call (about ten times slower; -DEPUCK_WORLD_UCONTEXT
 * chooses it on x86-64 too), with identical results.
 */
#ifndef ROBOT_COROUTINE_H
#define ROBOT_COROUTINE_H

#include <ucontext.h>
#include <cstddef>
#include <cstdint>
#include <memory>

// AddressSanitizer is told of each switch of stacks (its fibers' API), so
// that it knows which stack runs: a robot's, or the runner's
#if defined(__SANITIZE_ADDRESS__)
#define COROUTINE_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define COROUTINE_ASAN 1
#endif
#endif
#if defined(COROUTINE_ASAN)
#include <sanitizer/common_interface_defs.h>
#endif

namespace coroutine {

const size_t STACK_SIZE = 1 << 20;

#if defined(__x86_64__) && defined(__linux__) && !defined(EPUCK_WORLD_UCONTEXT)
#define FAST_SWITCH 1
extern "C" void epuck_switch_stack(void **save_sp, void *new_sp);
asm(R"(
    .text
    .globl epuck_switch_stack
    .type epuck_switch_stack, @function
epuck_switch_stack:
    pushq %rbp
    pushq %rbx
    pushq %r12
    pushq %r13
    pushq %r14
    pushq %r15
    movq %rsp, (%rdi)
    movq %rsi, %rsp
    popq %r15
    popq %r14
    popq %r13
    popq %r12
    popq %rbx
    popq %rbp
    ret
    .size epuck_switch_stack, .-epuck_switch_stack
    .section .note.GNU-stack,"",@progbits
    .text
)");
#else
#define FAST_SWITCH 0
#endif

struct Coroutine {
    std::unique_ptr<char[]> stack;          // not zeroed: the kernel commits it as used
#if FAST_SWITCH
    void *caller_sp = nullptr, *own_sp = nullptr;
#else
    ucontext_t caller_ctx, own_ctx;
#endif

    // `entry` runs on the coroutine's own stack at the first resume(); it
    // never returns (it yields for the last time instead)
    void prepare(void (*entry)())
    {
        stack.reset(new char[STACK_SIZE]);
#if FAST_SWITCH
        // the stack as epuck_switch_stack leaves it: six saved registers,
        // then the address it returns to (entry), then a dummy return
        // address for entry, with the stack 16-byte aligned at its call
        uintptr_t top = (reinterpret_cast<uintptr_t>(stack.get()) + STACK_SIZE) & ~uintptr_t(15);
        void **sp = reinterpret_cast<void **>(top);
        *--sp = nullptr;
        *--sp = reinterpret_cast<void *>(entry);
        for (int i = 0; i < 6; i++)
            *--sp = nullptr;
        own_sp = sp;
#else
        getcontext(&own_ctx);
        own_ctx.uc_stack.ss_sp = stack.get();
        own_ctx.uc_stack.ss_size = STACK_SIZE;
        own_ctx.uc_link = nullptr;
        makecontext(&own_ctx, entry, 0);
#endif
    }

    // Asks the processor for the top of the stack as it yielded, ahead of
    // the next resume().
    void prefetch() const
    {
#if FAST_SWITCH
        for (int i = 0; i < 8; i++)
            __builtin_prefetch(static_cast<char *>(own_sp) + 64 * i);
#endif
    }

#if defined(COROUTINE_ASAN)
    void *caller_fake = nullptr, *own_fake = nullptr;
    const void *caller_bottom = nullptr;
    size_t caller_size = 0;
#endif

    // the first thing `entry` does on the coroutine's stack
    void entered()
    {
#if defined(COROUTINE_ASAN)
        __sanitizer_finish_switch_fiber(nullptr, &caller_bottom, &caller_size);
#endif
    }

    // caller -> coroutine: returns when it yields
    void resume()
    {
#if defined(COROUTINE_ASAN)
        __sanitizer_start_switch_fiber(&caller_fake, stack.get(), STACK_SIZE);
#endif
#if FAST_SWITCH
        epuck_switch_stack(&caller_sp, own_sp);
#else
        swapcontext(&caller_ctx, &own_ctx);
#endif
#if defined(COROUTINE_ASAN)
        __sanitizer_finish_switch_fiber(caller_fake, nullptr, nullptr);
#endif
    }

    // coroutine -> caller: returns at the next resume()
    void yield()
    {
#if defined(COROUTINE_ASAN)
        __sanitizer_start_switch_fiber(&own_fake, caller_bottom, caller_size);
#endif
#if FAST_SWITCH
        epuck_switch_stack(&own_sp, caller_sp);
#else
        swapcontext(&own_ctx, &caller_ctx);
#endif
#if defined(COROUTINE_ASAN)
        __sanitizer_finish_switch_fiber(own_fake, &caller_bottom, &caller_size);
#endif
    }
};

}  // namespace coroutine

#endif

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

    // caller -> coroutine: returns when it yields
    void resume()
    {
#if FAST_SWITCH
        epuck_switch_stack(&caller_sp, own_sp);
#else
        swapcontext(&caller_ctx, &own_ctx);
#endif
    }

    // coroutine -> caller: returns at the next resume()
    void yield()
    {
#if FAST_SWITCH
        epuck_switch_stack(&own_sp, caller_sp);
#else
        swapcontext(&own_ctx, &caller_ctx);
#endif
    }
};

}  // namespace coroutine

#endif

/*
 * stack.c - the stack left to the calling thread (stack.h).
 *
 * The bounds of the thread's stack come from pthread_getattr_np (for the
 * main thread glibc derives them from RLIMIT_STACK and the process's
 * mappings), once per thread; the stack grows down, so what is left is the
 * distance from the current frame to the lowest address.
 */
#define _GNU_SOURCE /* pthread_getattr_np */
#include "base/stack.h"

#include <pthread.h>
#include <stdint.h>

/* per thread: the lowest address of its stack; known: 0 not asked yet,
 * 1 known, -1 unknown */
static _Thread_local const char *stack_lo;
static _Thread_local int known;

static void find_bounds(void)
{
    pthread_attr_t a;
    void *addr;
    size_t size;
    known = -1;
    if (pthread_getattr_np(pthread_self(), &a) != 0)
        return;
    if (pthread_attr_getstack(&a, &addr, &size) == 0 && addr != NULL) {
        stack_lo = addr;
        known = 1;
    }
    pthread_attr_destroy(&a);
}

size_t stack_left(void)
{
    if (known == 0)
        find_bounds();
    if (known < 0)
        return SIZE_MAX;
    const char *here = __builtin_frame_address(0);
    return here > stack_lo ? (size_t)(here - stack_lo) : 0;
}

int stack_low(void)
{
    return stack_left() < STACK_RESERVE;
}

/*
 * stack.h - how much stack the calling thread has left, for the passes
 * that recurse over expression trees (expand, sema, derive).
 *
 * Sema bounds an expression's height (SEMA_MAX_DEPTH), but a level of the
 * derivation takes about 1-2 KiB of stack (its exact values are
 * temporaries), so 2000 levels need more than a host's thread pool may
 * give a thread (1 or 2 MiB is common).  Each recursive step checks
 * stack_low() first and fails with a located error instead of running off
 * the end of the stack (docs/api.md, "Stack").
 */
#ifndef PC_STACK_H
#define PC_STACK_H

#include <stddef.h>

/* what a recursive step keeps free below itself: room for the work at the
 * bottom (FLINT and GMP put temporaries of up to 64 KiB on the stack,
 * printf, the out-of-memory handler's report) */
#define STACK_RESERVE ((size_t)192 * 1024)

/* the bytes of stack below the caller on this thread ((size_t)-1 when the
 * system does not say) */
size_t stack_left(void);

/* 1 when fewer than STACK_RESERVE bytes are left */
int stack_low(void);

/* the message of the passes that stop there */
#define STACK_MESSAGE                                                          \
    "expression nested too deeply for the stack of this thread: split it "     \
    "into several definitions (or give the thread more stack: docs/api.md)"

#endif

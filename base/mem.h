/*
 * mem.h - the one out-of-memory policy of the tree.
 *
 * pc_xmalloc & co. never return NULL, and every block they make is counted
 * (with its usable size) against one memory budget: free them with
 * pc_free, which takes the count off.  A block handed to someone who frees
 * it with pc_free() (the strings the C API returns) is disowned first
 * (mem_disown).  When memory cannot be had - the
 * system refuses it, or the memory budget (mem_set_limit) would be
 * exceeded - they call the out-of-memory path, which does not return: it calls
 * the handler (mem_set_oom_handler; pointcalc's own prints a located error
 * at the statement being derived and exits 1), and without one writes
 * "pointcalc: error: out of memory" to stderr and exits 1 with _exit (no
 * partial output is flushed).
 *
 * mem_use_for_gmp_flint() routes GMP's and FLINT's allocations through the
 * same policy and counts them too, so that the memory budget covers exact
 * arithmetic as well as the tree's own memory (names, printed text,
 * generated C, the arena).  It changes process-wide
 * settings: the command line calls it; a program using the library calls
 * it when it wants the budget and the policy for its own GMP use too.
 */
#ifndef PC_MEM_H
#define PC_MEM_H

#include <stddef.h>

void *pc_xmalloc(size_t n);
void *pc_xcalloc(size_t n, size_t size);
void *pc_xrealloc(void *p, size_t n);
/* a block aligned to align (a power of two, at least sizeof(void *)),
 * counted like the others: pc_free it */
void *pc_xaligned_alloc(size_t align, size_t n);
/* frees a block of pc_xmalloc & co. (or of a memory stream), taking it
 * off the count; NULL is nothing */
void pc_free(void *p);
/* takes p (a block of pc_xmalloc & co.) off the count and returns it: for
 * memory handed to a caller who releases it with pc_free() */
void *mem_disown(void *p);
char *pc_xstrdup(const char *s);
char *pc_xstrndup(const char *s, size_t n);
/* printf into a new string (names and integers: floating point goes
 * through numfmt.h, which does not depend on the locale) */
#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
char *
pc_xasprintf(const char *fmt, ...);

/* open_memstream and its fclose under the same policy: a stream the
 * system cannot make, or whose buffer it cannot grow, is out of memory,
 * never a NULL stream or a truncated text.  The buffer is counted as it
 * grows; *buf is the caller's after fclose, to release with pc_free. */
#include <stdio.h>
FILE *pc_xopen_memstream(char **buf, size_t *len);
void pc_xclose_memstream(FILE *f);

/* why the handler was called */
typedef enum MemFailure {
    MEM_SYSTEM, // the system refused the allocation
    MEM_BUDGET, // the memory budget would be exceeded
} MemFailure;

/* The handler must not return (it may _exit or longjmp at its own risk)
 * and must not allocate: it runs where an allocation just failed.  NULL
 * restores the default. */
typedef void (*MemOomHandler)(MemFailure why, void *arg);
void mem_set_oom_handler(MemOomHandler fn, void *arg);

/* Routes GMP's (mp_set_memory_functions) and FLINT's allocators through
 * this policy, with accounting.  Idempotent (pthread_once); call it before
 * other threads use GMP or FLINT. */
void mem_use_for_gmp_flint(void);
/* The memory budget in bytes (0: no budget) for everything counted: the
 * tree's allocators, and GMP's and FLINT's after mem_use_for_gmp_flint;
 * and the bytes counted now.
 * The counters are atomic and shared by all threads, and exact: what is
 * allocated after a reading and freed again leaves mem_in_use where it
 * was.  Threads allocating at once cannot together exceed the budget. */
void mem_set_limit(size_t bytes);
size_t mem_in_use(void);

#endif

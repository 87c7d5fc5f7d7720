/*
 * mem.c - the one out-of-memory policy (mem.h).
 *
 * Every allocation of the tree is counted: pc_xmalloc & co., the arena's
 * blocks (which come from pc_xmalloc), memory streams (a cookie stream
 * over a counted buffer) and, after mem_use_for_gmp_flint, GMP's and
 * FLINT's, all against one budget.  A reserve of 64 KiB is given back
 * just before the handler runs, so that it can still report.
 */
#define _GNU_SOURCE /* fopencookie */
#include "base/mem.h"

#include <gmp.h>
#include <malloc.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <flint/flint.h>

/* set before the threads (process-wide settings) */
static MemOomHandler handler;
static void *handler_arg;
/* the reserve: taken by one thread only (atomic exchange) */
static _Atomic(void *) reserve;
static _Atomic size_t limit;

void mem_set_oom_handler(MemOomHandler fn, void *arg)
{
    handler = fn;
    handler_arg = arg;
    void *r = malloc(64 * 1024), *none = NULL;
    if (!atomic_compare_exchange_strong(&reserve, &none, r))
        free(r);
}

/* the process is on its way out: a second failure (valgrind's
 * __libc_freeres flushes a memory stream's buffered text at _exit, which
 * asks for the memory again) exits without a second message */
static atomic_int reporting;

static _Noreturn void pc_out_of_memory(MemFailure why)
{
    static const char msg[] = "pointcalc: error: out of memory\n";
    static const char budget[] =
        "pointcalc: error: the memory budget ran out\n";
    if (atomic_exchange(&reporting, 1))
        _exit(1);
    free(atomic_exchange(&reserve, NULL));
    if (handler != NULL)
        handler(why, handler_arg);
    if (why == MEM_BUDGET) {
        if (write(2, budget, sizeof budget - 1) < 0)
            _exit(1);
    } else if (write(2, msg, sizeof msg - 1) < 0) {
        _exit(1);
    }
    _exit(1);
}

/* ---- the counted allocators (GMP, FLINT and the tree's own) ----------- */

/* The block sizes come from malloc_usable_size (glibc, valgrind and the
 * sanitizers all provide it), so the pointers handed out are malloc's own:
 * leak checkers see ordinary blocks.
 *
 * The counters are atomic: any thread may allocate.  A block is counted
 * with its usable size when it is made and the same size when it is
 * freed, so in_use returns exactly to where it was once everything made
 * since is freed.  (It used to saturate at 0 and was updated without
 * atomics: lost updates between threads, and a block of GMP's made before
 * mem_use_for_gmp_flint and freed after it clamping the count, left it
 * megabytes above what was in use, towards a spurious "memory budget ran
 * out".)  A block made before mem_use_for_gmp_flint and freed after it
 * takes its size off: in_use is signed and only ever too low then, which
 * mem_in_use shows as 0. */
static _Atomic long long in_use;

/* in_use += n (either sign) */
static void count(long long n)
{
    atomic_fetch_add_explicit(&in_use, n, memory_order_relaxed);
}

/* a refusal before the system is asked for n more bytes: beyond the
 * budget alone, or with what is counted now (plain loads: settle decides) */
static void precheck(size_t n)
{
    size_t lim = atomic_load_explicit(&limit, memory_order_relaxed);
    if (lim && (n > lim || atomic_load_explicit(&in_use, memory_order_relaxed) +
                                   (long long)n >
                               (long long)lim))
        pc_out_of_memory(MEM_BUDGET);
}

/* counts delta bytes of a block made (or grown) already; 1 when a growth
 * does not fit the budget (the count is then taken back): the check and
 * the count are one atomic step, so threads allocating at once cannot
 * together exceed the budget */
static int settle(long long delta)
{
    size_t lim = atomic_load_explicit(&limit, memory_order_relaxed);
    long long now =
        atomic_fetch_add_explicit(&in_use, delta, memory_order_relaxed) + delta;
    if (lim && delta > 0 && now > (long long)lim) {
        count(-delta);
        return 1;
    }
    return 0;
}

static void *c_alloc(size_t n)
{
    precheck(n);
    void *p = malloc(n ? n : 1);
    if (p == NULL)
        pc_out_of_memory(MEM_SYSTEM);
    if (settle((long long)malloc_usable_size(p))) {
        free(p);
        pc_out_of_memory(MEM_BUDGET);
    }
    return p;
}

static void c_free(void *p)
{
    if (p == NULL)
        return;
    count(-(long long)malloc_usable_size(p));
    free(p);
}

static void *c_realloc(void *p, size_t n)
{
    if (p == NULL)
        return c_alloc(n);
    size_t old = malloc_usable_size(p);
    precheck(n > old ? n - old : 0);
    void *q = realloc(p, n ? n : 1);
    if (q == NULL)
        pc_out_of_memory(MEM_SYSTEM);
    if (settle((long long)malloc_usable_size(q) - (long long)old))
        pc_out_of_memory(MEM_BUDGET); /* q stays counted as it was */
    return q;
}

static void *c_calloc(size_t n, size_t size)
{
    if (size != 0 && n > (size_t)-1 / size)
        pc_out_of_memory(MEM_SYSTEM);
    precheck(n * size);
    void *p = calloc(n ? n : 1, size ? size : 1);
    if (p == NULL)
        pc_out_of_memory(MEM_SYSTEM);
    if (settle((long long)malloc_usable_size(p))) {
        free(p);
        pc_out_of_memory(MEM_BUDGET);
    }
    return p;
}

static void *gmp_realloc(void *q, size_t old, size_t n)
{
    (void)old;
    return c_realloc(q, n);
}

static void gmp_free(void *q, size_t n)
{
    (void)n;
    c_free(q);
}

/* ---- the tree's allocators: the same counted blocks ---------------------- */

void *pc_xmalloc(size_t n)
{
    return c_alloc(n);
}

void *pc_xcalloc(size_t n, size_t size)
{
    return c_calloc(n, size);
}

void *pc_xrealloc(void *p, size_t n)
{
    return c_realloc(p, n);
}

void *pc_xaligned_alloc(size_t align, size_t n)
{
    precheck(n);
    void *p = NULL;
    if (posix_memalign(&p, align, n ? n : 1) != 0)
        pc_out_of_memory(MEM_SYSTEM);
    if (settle((long long)malloc_usable_size(p))) {
        free(p);
        pc_out_of_memory(MEM_BUDGET);
    }
    return p;
}

void pc_free(void *p)
{
    c_free(p);
}

void *mem_disown(void *p)
{
    if (p != NULL)
        count(-(long long)malloc_usable_size(p));
    return p;
}

char *pc_xstrndup(const char *s, size_t n)
{
    char *d = pc_xmalloc(n + 1);
    memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

char *pc_xstrdup(const char *s)
{
    return pc_xstrndup(s, strlen(s));
}

char *pc_xasprintf(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0)
        abort(); // an invalid format: a bug of the caller
    char *r = pc_xmalloc((size_t)n + 1);
    va_start(ap, fmt);
    vsnprintf(r, (size_t)n + 1, fmt, ap);
    va_end(ap);
    return r;
}

/* ---- memory streams over a counted buffer -------------------------------- */

/* open_memstream's contract (*buf and *len follow every write, *buf is
 * NUL-terminated and the caller's to pc_free after fclose), but the buffer
 * grows through pc_xrealloc: a text is counted against the budget while it
 * is written, not after (open_memstream's buffer is libc's, uncounted) */
typedef struct MemStream {
    char **buf;
    size_t *len, cap;
} MemStream;

static ssize_t ms_write(void *cookie, const char *s, size_t n)
{
    MemStream *m = cookie;
    size_t len = *m->len;
    if (n > (size_t)-1 / 2 - len)
        pc_out_of_memory(MEM_SYSTEM);
    if (len + n + 1 > m->cap) {
        size_t cap = m->cap ? m->cap : 256;
        while (cap < len + n + 1)
            cap *= 2;
        *m->buf = pc_xrealloc(*m->buf, cap);
        m->cap = cap;
    }
    memcpy(*m->buf + len, s, n);
    (*m->buf)[len + n] = '\0';
    *m->len = len + n;
    return (ssize_t)n;
}

static int ms_close(void *cookie)
{
    pc_free(cookie);
    return 0;
}

FILE *pc_xopen_memstream(char **buf, size_t *len)
{
    MemStream *m = pc_xmalloc(sizeof *m);
    m->buf = buf;
    m->len = len;
    m->cap = 16;
    *buf = pc_xmalloc(m->cap);
    **buf = '\0';
    *len = 0;
    cookie_io_functions_t io = {NULL, ms_write, NULL, ms_close};
    FILE *f = fopencookie(m, "w", io);
    if (!f)
        pc_out_of_memory(MEM_SYSTEM);
    return f;
}

void pc_xclose_memstream(FILE *f)
{
    /* a memory stream's only failure: growing its buffer (a write that
     * failed sets the error flag, flushed by fclose) */
    int bad = ferror(f);
    if (fclose(f) != 0 || bad)
        pc_out_of_memory(MEM_SYSTEM);
}

static void use_for_gmp_flint(void)
{
    void *r = malloc(64 * 1024), *none = NULL;
    if (!atomic_compare_exchange_strong(&reserve, &none, r))
        free(r);
    mp_set_memory_functions(c_alloc, gmp_realloc, gmp_free);
    __flint_set_memory_functions(c_alloc, c_calloc, c_realloc, c_free);
}

void mem_use_for_gmp_flint(void)
{
    static pthread_once_t once = PTHREAD_ONCE_INIT;
    pthread_once(&once, use_for_gmp_flint);
}

void mem_set_limit(size_t bytes)
{
    atomic_store_explicit(&limit, bytes, memory_order_relaxed);
}

size_t mem_in_use(void)
{
    long long n = atomic_load_explicit(&in_use, memory_order_relaxed);
    return n > 0 ? (size_t)n : 0;
}

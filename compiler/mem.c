/*
 * mem.c - the one out-of-memory policy (mem.h).
 *
 * A reserve of 64 KiB is given back just before the handler runs, so that
 * it can still report.
 */
#include "compiler/mem.h"

#include <gmp.h>
#include <malloc.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <flint/flint.h>

static MemOomHandler handler;
static void *handler_arg;
static void *reserve;
static size_t limit, in_use, peak;

void mem_set_oom_handler(MemOomHandler fn, void *arg)
{
    handler = fn;
    handler_arg = arg;
    if (reserve == NULL)
        reserve = malloc(64 * 1024);
}

_Noreturn void pc_out_of_memory(MemFailure why)
{
    static const char msg[] = "pointcalc: error: out of memory\n";
    static const char budget[] =
        "pointcalc: error: the memory budget ran out\n";
    free(reserve);
    reserve = NULL;
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

void *pc_xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (p == NULL)
        pc_out_of_memory(MEM_SYSTEM);
    return p;
}

void *pc_xcalloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size ? size : 1);
    if (p == NULL)
        pc_out_of_memory(MEM_SYSTEM);
    return p;
}

void *pc_xrealloc(void *p, size_t n)
{
    void *q = realloc(p, n ? n : 1);
    if (q == NULL)
        pc_out_of_memory(MEM_SYSTEM);
    return q;
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

FILE *pc_xopen_memstream(char **buf, size_t *len)
{
    FILE *f = open_memstream(buf, len);
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

/* ---- counted allocators for GMP and FLINT -------------------------------- */

/* The block sizes come from malloc_usable_size (glibc, valgrind and the
 * sanitizers all provide it), so the pointers handed out are malloc's own:
 * leak checkers see ordinary blocks. */

/* saturating: a block allocated before mem_use_for_gmp_flint and freed
 * after it was never counted */
static void count(size_t add, size_t sub)
{
    in_use = in_use + add > sub ? in_use + add - sub : 0;
    if (in_use > peak)
        peak = in_use;
}

static void *c_alloc(size_t n)
{
    if (limit && (n > limit || in_use > limit - n))
        pc_out_of_memory(MEM_BUDGET);
    void *p = malloc(n ? n : 1);
    if (p == NULL)
        pc_out_of_memory(MEM_SYSTEM);
    count(malloc_usable_size(p), 0);
    return p;
}

static void c_free(void *p)
{
    if (p == NULL)
        return;
    count(0, malloc_usable_size(p));
    free(p);
}

static void *c_realloc(void *p, size_t n)
{
    if (p == NULL)
        return c_alloc(n);
    size_t old = malloc_usable_size(p);
    if (limit && n > old && (n - old > limit || in_use > limit - (n - old)))
        pc_out_of_memory(MEM_BUDGET);
    void *q = realloc(p, n ? n : 1);
    if (q == NULL)
        pc_out_of_memory(MEM_SYSTEM);
    count(malloc_usable_size(q), old);
    return q;
}

static void *c_calloc(size_t n, size_t size)
{
    if (size != 0 && n > (size_t)-1 / size)
        pc_out_of_memory(MEM_SYSTEM);
    if (limit && (n * size > limit || in_use > limit - n * size))
        pc_out_of_memory(MEM_BUDGET);
    void *p = calloc(n ? n : 1, size ? size : 1);
    if (p == NULL)
        pc_out_of_memory(MEM_SYSTEM);
    count(malloc_usable_size(p), 0);
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

void mem_use_for_gmp_flint(void)
{
    static int done;
    if (done)
        return;
    done = 1;
    if (reserve == NULL)
        reserve = malloc(64 * 1024);
    mp_set_memory_functions(c_alloc, gmp_realloc, gmp_free);
    __flint_set_memory_functions(c_alloc, c_calloc, c_realloc, c_free);
}

void mem_set_limit(size_t bytes)
{
    limit = bytes;
}

size_t mem_limit(void)
{
    return limit;
}

size_t mem_in_use(void)
{
    return in_use;
}

size_t mem_peak(void)
{
    return peak;
}

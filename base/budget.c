/*
 * budget.c - the statement mark and the budget texts (budget.h).
 *
 * The current statement is kept in two slots and published by flipping an
 * index, so a signal handler never reads a half-written one.  Both are
 * per thread: threads deriving distinct schemes never share them, and the
 * out-of-memory handler (which runs on the allocating thread) reports the
 * statement of the derivation that ran out.
 */
#include "base/budget.h"

#include <signal.h>
#include <time.h>

#include "base/numfmt.h"

typedef struct Where {
    const Source *src;
    Span span;
} Where;

static _Thread_local Where slots[2];
static _Thread_local volatile sig_atomic_t cur = 0;

void budget_statement(const Source *src, Span span)
{
    int next = !cur;
    slots[next].src = src;
    slots[next].span = span;
    cur = next;
}

static _Thread_local const char *volatile phase_now;

void budget_phase(const char *phase)
{
    phase_now = phase;
}

const char *budget_phase_now(void)
{
    return phase_now;
}

void budget_where(const Source **src, Span *span)
{
    const Where *w = &slots[cur];
    *src = w->src;
    *span = w->span;
}

static _Thread_local double deadline_at, deadline_s, derive_at;

static double now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void budget_deadline_set(double seconds)
{
    deadline_s = seconds > 0 ? seconds : 0;
    deadline_at = seconds > 0 ? now_seconds() + seconds : 0;
}

int budget_late(void)
{
    if (deadline_at == 0 && derive_at == 0)
        return 0;
    double now = now_seconds();
    return (deadline_at > 0 && now > deadline_at) ||
           (derive_at > 0 && now > derive_at);
}

void budget_derive_until(double at)
{
    derive_at = at > 0 ? at : 0;
}

double budget_deadline_seconds(void)
{
    return deadline_s;
}

void budget_format_seconds(char *buf, size_t cap, double s)
{
    pc_snprintf(buf, cap, "%g s", s);
}

void budget_format_bytes(char *buf, size_t cap, size_t b)
{
    if (b >= ((size_t)1 << 30) && b % ((size_t)1 << 30) == 0)
        snprintf(buf, cap, "%zu GiB", b >> 30);
    else if (b >= ((size_t)1 << 20))
        snprintf(buf, cap, "%zu MiB", b >> 20);
    else
        snprintf(buf, cap, "%zu bytes", b);
}

/*
 * budget.c - the hard limits of the command line (budget.h): the options
 * every command takes, the timer and the memory handler.  Both handlers
 * report at the statement the library marked (base/budget.h).  The timer's
 * SIGALRM is the command line's: it reaches the command's thread (main.c
 * blocks it on the main thread, which only waits), whose mark it reads.
 */
#include "driver/cli/budget.h"

#include "compiler/expand.h"

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <unistd.h>

#include "base/check.h"
#include "base/diag.h"
#include "base/mem.h"
#include "base/numfmt.h"
#include "codegen/numsolve.h"

/* the messages, each around the phase: HEAD PHASE TAIL */
static char time_head[96], mem_head[96];
static const char oom_head[] = "out of memory while ";
static const char time_tail[] = "; raise it with --max-seconds";
static const char mem_tail[] = "; raise it with --max-memory";
static const char oom_tail[] = " (the system refused more)";

void budget_options_default(BudgetOptions *b)
{
    memset(b, 0, sizeof *b);
    b->max_seconds = BUDGET_DEFAULT_SECONDS;
    b->max_memory = BUDGET_DEFAULT_MEMORY;
    b->verbose = 0;
}

int budget_parse_option(BudgetOptions *b, int argc, char **argv, int i,
                        FILE *err)
{
    const char *a = argv[i];
    if (strcmp(a, "--verbose") == 0 || strcmp(a, "-v") == 0) {
        b->verbose = 1;
        return 1;
    }
    if (strcmp(a, "--keep-abs") == 0) {
        b->keep_abs = 1;
        return 1;
    }
    if (strncmp(a, "-D", 2) == 0) {
        const char *d = a[2] ? a + 2 : i + 1 < argc ? argv[i + 1] : NULL;
        if (!d) {
            fprintf(err, "pointcalc: -D needs NAME=INTEGER\n");
            return -1;
        }
        if (expand_check_define(d) != 0) {
            fprintf(err,
                    "pointcalc: -D '%s': expected NAME=INTEGER, e.g. -D "
                    "n=24 (a whole number below 2^40 in magnitude)\n",
                    d);
            return -1;
        }
        if (b->ndefines == BUDGET_MAX_DEFINES) {
            fprintf(err, "pointcalc: more than %d -D options\n",
                    BUDGET_MAX_DEFINES);
            return -1;
        }
        b->defines[b->ndefines++] = d;
        return a[2] ? 1 : 2;
    }
    int secs = strcmp(a, "--max-seconds") == 0;
    if (!secs && strcmp(a, "--max-memory") != 0)
        return 0;
    if (i + 1 >= argc) {
        fprintf(err, "pointcalc: %s needs a value\n", a);
        return -1;
    }
    const char *v = argv[i + 1];
    char *end;
    errno = 0;
    double x = pc_strtod(v, &end);
    if (end == v || errno != 0 || !(x >= 0) || (secs && x > 1e9)) {
        fprintf(err,
                "pointcalc: %s '%s': expected a number of %s from 0 (no "
                "budget) up\n",
                a, v, secs ? "seconds" : "bytes");
        return -1;
    }
    if (secs) {
        if (*end != '\0') {
            fprintf(err,
                    "pointcalc: --max-seconds '%s': expected a number of "
                    "seconds, e.g. 60 or 0.5 (0: no budget)\n",
                    v);
            return -1;
        }
        b->max_seconds = x;
        return 2;
    }
    double unit = 1;
    if (*end == 'K' || *end == 'k')
        unit = 1024.0, end++;
    else if (*end == 'M' || *end == 'm')
        unit = 1048576.0, end++;
    else if (*end == 'G' || *end == 'g')
        unit = 1073741824.0, end++;
    if (*end != '\0' || x * unit > 1e15) {
        fprintf(err,
                "pointcalc: --max-memory '%s': expected a size in bytes, or "
                "with K, M or G (KiB, MiB, GiB), e.g. 2G (0: no budget)\n",
                v);
        return -1;
    }
    b->max_memory = (size_t)(x * unit);
    return 2;
}

static void put_fd(void *ctx, const char *s, size_t n)
{
    pc_write_all(*(const int *)ctx, s, n);
}

/* "HEAD PHASE TAIL", located at what the pipeline marked
 * (base/budget.h): a statement ("FILE:LINE:COL: error: ...", then its line
 * and a caret), the whole file ("FILE: error: ...") or, with no mark,
 * "pointcalc: error: ..." */
static void report(const char *head, const char *tail)
{
    static const int fd = 2;
    DiagSink k = {put_fd, (void *)&fd};
    const Source *src;
    Span span;
    budget_where(&src, &span);
    const char *phase = budget_phase_now();
    if (src != NULL)
        diag_put_location(&k, src, span, "error");
    else
        put_fd((void *)&fd, "pointcalc: error: ", 18);
    put_fd((void *)&fd, head, strlen(head));
    phase = phase ? phase : "deriving this";
    put_fd((void *)&fd, phase, strlen(phase));
    put_fd((void *)&fd, tail, strlen(tail));
    put_fd((void *)&fd, "\n", 1);
    if (src != NULL && !DIAG_IS_WHOLE_FILE(span))
        diag_put_excerpt(&k, src, span);
}

static void on_alarm(int sig)
{
    (void)sig;
    report(time_head, time_tail);
    _exit(1);
}

static void on_oom(MemFailure why, void *arg)
{
    (void)arg;
    if (why == MEM_BUDGET)
        report(mem_head, mem_tail);
    else
        report(oom_head, oom_tail);
    _exit(1);
}

void budget_arm(double max_seconds, size_t max_memory)
{
    char amount[48];
    budget_format_seconds(amount, sizeof amount, max_seconds);
    snprintf(time_head, sizeof time_head,
             "the time budget of %s ran out while ", amount);
    budget_format_bytes(amount, sizeof amount, max_memory);
    snprintf(mem_head, sizeof mem_head,
             "the memory budget of %s ran out while ", amount);
    budget_phase(NULL); /* deriving */
    mem_set_limit(max_memory);
    mem_set_oom_handler(on_oom, NULL);
    if (max_seconds > 0) {
        struct sigaction sa;
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_alarm;
        sigemptyset(&sa.sa_mask);
        sigaction(SIGALRM, &sa, NULL);
        struct itimerval it = {{0, 0}, {0, 0}};
        /* a quarter second after the deadline that derive checks itself,
         * so that its message (at the exact expression) comes first
         * wherever it can */
        double t = max_seconds + 0.25;
        it.it_value.tv_sec = (time_t)t;
        it.it_value.tv_usec = (suseconds_t)((t - (double)(time_t)t) * 1e6);
        setitimer(ITIMER_REAL, &it, NULL);
    }
}

void budget_disarm(void)
{
    struct itimerval it = {{0, 0}, {0, 0}};
    setitimer(ITIMER_REAL, &it, NULL);
}

DeriveOptions derive_options_cli(const BudgetOptions *b, FILE *err,
                                 int *bad_define)
{
    DeriveOptions o = {.max_seconds = b->max_seconds,
                       .verbose = b->verbose ? err : NULL,
                       .defines = b->defines,
                       .ndefines = b->ndefines,
                       .bad_define = bad_define,
                       .keep_abs = b->keep_abs,
                       .numeric = numsolve_run};
    return o;
}

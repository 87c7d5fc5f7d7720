/*
 * main.c - the pointcalc command line (contract section 4; docs/ for the
 * rest).  Every command runs one pipeline, as far as it needs:
 *
 *   parse -> expand -> sema -> derive      cli_derive_file_steps (pipeline.c)
 *     |-> format (text, LaTeX, JSON)       derive  (derive.c)
 *     `-> lower to a Plan                  cli_plan_file (pipeline.c)
 *           |-> emit C                     emit-c  (emit_c.c)
 *           |-> interpret: CSV, JSON       eval    (eval.c, table.c)
 *           `-> sample and draw: SVG       plot    (plot.c)
 *     `-> find what the curves are       analyze (cmd_analyze.c)
 *
 * with the options every command shares in args.c.  This file only picks
 * the command, and runs it on a thread of CLI_STACK bytes of stack: the
 * passes recurse over expression trees, and the deepest the language
 * allows (2000 levels) need about 4 MiB (docs/api.md, "Stack"), whatever
 * `ulimit -s` says.  Exit status: 0 success, 1 an error in the scheme, 2 a
 * usage error; nothing reaches stdout when the scheme has an error.
 */
#include <errno.h>
#include <malloc.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include <flint/flint.h>

#include "base/mem.h"
#include "driver/cli/args.h"
#include "driver/cli/cli.h"
#include "driver/cli/fit.h"
#include "driver/cli/natural.h"

#define PC_VERSION "0.1.0"

typedef struct Command {
    const char *name;
    CliCommand *run;
} Command;

static const Command commands[] = {
    {"derive", cli_derive},   {"emit-c", cli_emit_c},   {"eval", cli_eval},
    {"help", cli_help},       {"plot", cli_plot},       {"fit", cli_fit},
    {"natural", cli_natural}, {"analyze", cli_analyze},
};

static const Command *find_command(const char *name)
{
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        if (strcmp(commands[i].name, name) == 0)
            return &commands[i];
    return NULL;
}

/* 1 when argv[1..] asks for help: -h or --help anywhere */
static int wants_help(int argc, char **argv)
{
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0)
            return 1;
    return 0;
}

/* pointcalc --help | --version, and nothing after them */
static int global_option(int argc, char **argv, FILE *out, FILE *err)
{
    int help = strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0;
    if (argc > 2) {
        fprintf(err, "pointcalc: %s takes no arguments, found '%s'\n", argv[1],
                argv[2]);
        return 2;
    }
    if (help)
        return fputs(cli_usage, out) < 0;
    return fprintf(out, "pointcalc %s\n", PC_VERSION) < 0;
}

static int run(int argc, char **argv)
{
    if (argc < 2) {
        fputs(cli_usage, stderr);
        return 2;
    }
    const char *name = argv[1];
    const Command *c = find_command(name);
    if (!c && (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0 ||
               strcmp(name, "--version") == 0))
        return global_option(argc, argv, stdout, stderr);
    if (!c)
        return args_usage_error(stderr, cli_usage, "unknown command '%s'",
                                name);
    if (wants_help(argc - 1, argv + 1))
        return fputs(help_text(name), stdout) < 0;
    return c->run(argc - 1, argv + 1, stdout, stderr);
}

/* the command's thread: 4 times what the deepest expression needs */
#define CLI_STACK ((size_t)16 << 20)

typedef struct Run {
    int argc;
    char **argv;
    int rc;
} Run;

static void *run_thread(void *arg)
{
    Run *r = arg;
    /* the budget's SIGALRM comes here, where the statement is marked */
    sigset_t alarm;
    sigemptyset(&alarm);
    sigaddset(&alarm, SIGALRM);
    pthread_sigmask(SIG_UNBLOCK, &alarm, NULL);
    r->rc = run(r->argc, r->argv);
    flint_cleanup(); /* this thread's caches */
    return NULL;
}

/* run() on a thread of CLI_STACK bytes (on this one if none can be made:
 * the passes then stop with a located error where the stack runs low) */
static int run_on_big_stack(int argc, char **argv)
{
    Run r = {argc, argv, 0};
    pthread_attr_t a;
    pthread_t th;
    sigset_t alarm, old;
    sigemptyset(&alarm);
    sigaddset(&alarm, SIGALRM);
    pthread_sigmask(SIG_BLOCK, &alarm, &old);
    /* one malloc arena: a thread's own would reserve 64 MiB of address
     * space, which a `ulimit -v` counts (the main thread only waits) */
    mallopt(M_ARENA_MAX, 1);
    int made = pthread_attr_init(&a) == 0;
    made = made && pthread_attr_setstacksize(&a, CLI_STACK) == 0 &&
           pthread_create(&th, &a, run_thread, &r) == 0;
    pthread_attr_destroy(&a);
    if (made)
        pthread_join(th, NULL);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    return made ? r.rc : run(argc, argv);
}

int main(int argc, char **argv)
{
    /* before anything allocates: GMP and FLINT under the one policy */
    mem_use_for_gmp_flint();
    int rc = run_on_big_stack(argc, argv);
    flint_cleanup_master();
    /* output that did not reach its file (a full disk, a closed pipe) is
     * an error too, never a silent exit 0 */
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "pointcalc: cannot write the output: %s\n",
                strerror(errno));
        if (rc == 0)
            rc = 1;
    }
    return rc;
}

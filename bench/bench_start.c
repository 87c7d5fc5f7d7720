/*
 * bench_start.c - process start: wall time of whole processes, spawned
 * (posix_spawn) and waited for, many times, interleaved:
 *
 *   /bin/true                           the floor of spawning a process
 *   pointcalc --version                 loading pointcalc and its libraries
 *   pointcalc derive desargues_arc.pcs  the main job as a build system
 *                                       calls it, once per scheme
 *
 * Median and spread (lowest and highest of the middle 80%) in ms.  Most of
 * pointcalc's start is the dynamic loader: libflint.so pulls in NTL,
 * libstdc++, gf2x, MPFR and GMP (about 10 000 relocations; LD_DEBUG=
 * statistics); Debian ships no static libflint.a, `make flint-static`
 * builds one from Debian's source package (.ci/flint-static) and the
 * Makefile then links pointcalc with it.  `bench_start BIN [OTHER]` runs a
 * second binary side by side (make bench: the static and the shared build
 * when both exist).
 */
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "bench/bench_util.h"

extern char **environ;

/* one run of argv with stdout and stderr to /dev/null; ms, or -1 */
static double run(char *const *argv)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", 1, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", 1, 0);
    pid_t pid;
    double t0 = bench_now_ms();
    int rc = posix_spawn(&pid, argv[0], &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0)
        return -1;
    int st;
    waitpid(pid, &st, 0);
    double t = bench_now_ms() - t0;
    return WIFEXITED(st) && WEXITSTATUS(st) == 0 ? t : -1;
}

int main(int argc, char **argv)
{
    /* argv[1]: the pointcalc to measure; argv[2]: another one run side by
     * side (e.g. the shared-library build against the static one) */
    const char *bins[2] = {argc > 1 ? argv[1] : "build/pointcalc",
                           argc > 2 ? argv[2] : NULL};
    int nb = bins[1] ? 2 : 1, nc = 1 + 2 * nb;
    char *cmds[5][4] = {{(char *)"/bin/true", NULL, NULL, NULL}};
    char names[5][160] = {"/bin/true (spawn floor)"};
    for (int b = 0; b < nb; b++) {
        char *v[4] = {(char *)bins[b], (char *)"--version", NULL, NULL};
        char *d[4] = {(char *)bins[b], (char *)"derive",
                      (char *)"examples/desargues_arc.pcs", NULL};
        memcpy(cmds[1 + 2 * b], v, sizeof v);
        memcpy(cmds[2 + 2 * b], d, sizeof d);
        snprintf(names[1 + 2 * b], sizeof names[0], "%s --version", bins[b]);
        snprintf(names[2 + 2 * b], sizeof names[0], "%s derive desargues_arc",
                 bins[b]);
    }
    enum { RUNS = 200 };
    static double t[5][RUNS];
    for (int r = 0; r < RUNS; r++)
        for (int j = 0; j < nc; j++) {
            int c = (j + r) % nc; /* interleaved, rotating */
            t[c][r] = run(cmds[c]);
            if (t[c][r] < 0) {
                fprintf(stderr, "bench_start: %s failed\n", names[c]);
                return 1;
            }
        }
    printf("bench_start: whole processes, %d runs each, interleaved; ms: "
           "median [10%%..90%%]\n",
           RUNS);
    double med[5];
    for (int c = 0; c < nc; c++) {
        qsort(t[c], RUNS, sizeof(double), bench_cmp_double);
        med[c] = t[c][RUNS / 2];
        printf("  %-52s %7.3f [%6.3f..%6.3f]\n", names[c], med[c],
               t[c][RUNS / 10], t[c][RUNS - 1 - RUNS / 10]);
    }
    for (int b = 0; b < nb; b++)
        printf("  %s over the spawn floor: --version %.3f ms, derive %.3f ms "
               "(goals: 1 and 2 ms)\n",
               bins[b], med[1 + 2 * b] - med[0], med[2 + 2 * b] - med[0]);
    return 0;
}

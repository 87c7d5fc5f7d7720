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
 * statistics); Debian ships no static libflint.a (docs/architecture.md).
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
    const char *bin = argc > 1 ? argv[1] : "build/pointcalc";
    char *cmds[3][4] = {
        {(char *)"/bin/true", NULL, NULL, NULL},
        {(char *)bin, (char *)"--version", NULL, NULL},
        {(char *)bin, (char *)"derive", (char *)"examples/desargues_arc.pcs",
         NULL}};
    static const char *const names[3] = {
        "/bin/true (spawn floor)", "pointcalc --version",
        "pointcalc derive desargues_arc.pcs"};
    enum { RUNS = 200 };
    static double t[3][RUNS];
    for (int r = 0; r < RUNS; r++)
        for (int j = 0; j < 3; j++) {
            int c = (j + r) % 3; /* interleaved, rotating */
            t[c][r] = run(cmds[c]);
            if (t[c][r] < 0) {
                fprintf(stderr, "bench_start: %s failed\n", names[c]);
                return 1;
            }
        }
    printf("bench_start: whole processes, %d runs each, interleaved; ms: "
           "median [10%%..90%%]\n",
           RUNS);
    double med[3];
    for (int c = 0; c < 3; c++) {
        qsort(t[c], RUNS, sizeof(double), bench_cmp_double);
        med[c] = t[c][RUNS / 2];
        printf("  %-36s %7.3f [%6.3f..%6.3f]\n", names[c], med[c],
               t[c][RUNS / 10], t[c][RUNS - 1 - RUNS / 10]);
    }
    printf("  over the spawn floor: --version %.3f ms, derive %.3f ms "
           "(goals: 1 and 2 ms as whole processes)\n",
           med[1] - med[0], med[2] - med[0]);
    return 0;
}

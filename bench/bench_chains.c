/*
 * bench_chains.c - derivation speed on chains of k nested meets, k = 1..8:
 * where exact derivation grows fastest.  Families (the scheme text is
 * generated below):
 *
 *   1p      one param t; both lines of each meet through the previous
 *           point: X_i = meet(line(A, along(X, B, t)), line(B, along(X, C,
 *           1 - t)))
 *   lin     2 params + 2 consts, both lines dependent, ratios u + k, v + h
 *   rat     the same with rational ratios (u + k)/(1 + h*v), (v + h)/(1 +
 *           k*u)
 *   one     2p2c, one line dependent, the base points rotating:
 *           X_i = meet(line(a, along(X, b, r1)), line(b, along(c, a, r2)))
 *   onerat  the same with the rational ratios
 *   vplane  2p2c, a line and a plane in 3-space (the V-theorem): X_i =
 *           meet(line(A, along(X, B, u + k)), plane(B, along(X, C, v + h),
 *           along(X, D, u + k)))
 *
 * Each case runs in a child process with a timeout (PC_CHAIN_TIMEOUT
 * seconds, default 30; a family stops growing at its first timeout):
 * in-process derive_source, repeated for about 0.3 s (at least 3 runs, one
 * when a run takes over 2 s); it reports the median, the lowest and the
 * highest run, and the size of the printed result.  "refused" is a size
 * limit's error (docs/language.md), reached in the time shown.
 *
 *   bench_chains [FAMILY|CASE ...]   only these families (vplane) or cases
 *                                    (vplane4)
 *   bench_chains --print CASE        the scheme text of one case (vplane4)
 *
 * The previous release's figures (commit b5e0642, the per-weight
 * representation, measured on this machine in the same way) are in the
 * table below; the last column is their ratio to today's median.
 */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <flint/flint.h>

#include "bench/bench_util.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"

typedef struct Base {
    const char *name;
    double seconds; // median; -1: over 150 s (timeout); 0: refused
} Base;

/* commit b5e0642 on this machine (2 cores, another process busy on the
 * second; medians of the same procedure; < 0.0001 s written as 0.00005):
 * 0 means that release refused the case too (a size limit), -1 that it
 * ran over 150 s */
static const Base baseline[] = {
    {"1p1", 0.00005},    {"1p2", 0.0001},     {"1p3", 0.0002},
    {"1p4", 0.0004},     {"1p5", 0.0011},     {"1p6", 0.0036},
    {"1p7", 0.0123},     {"1p8", 0.0580},     {"lin1", 0.0001},
    {"lin2", 0.0005},    {"lin3", 0.0054},    {"lin4", 0.2322},
    {"lin5", 97.1616},   {"lin6", 0},         {"lin7", 0},
    {"lin8", 0},         {"rat1", 0.0002},    {"rat2", 0.0055},
    {"rat3", 0.0930},    {"rat4", 6.0123},    {"rat5", -1},
    {"one1", 0.0001},    {"one2", 0.0002},    {"one3", 0.0006},
    {"one4", 0.0012},    {"one5", 0.0041},    {"one6", 0.0064},
    {"one7", 0.0172},    {"one8", 0.0241},    {"onerat1", 0.0002},
    {"onerat2", 0.0013}, {"onerat3", 0.0042}, {"onerat4", 0.0107},
    {"onerat5", 0.0248}, {"onerat6", 0.0818}, {"onerat7", 0.0898},
    {"onerat8", 0.1862}, {"vplane1", 0.0003}, {"vplane2", 0.0054},
    {"vplane3", 0.1075}, {"vplane4", 8.2364}, {"vplane5", -1},
};

/* the scheme of family fam at depth k (malloc'ed) */
static char *scheme(const char *fam, int k)
{
    static const char *const P[3] = {"A", "B", "C"};
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    const char *r1 = "u + k", *r2 = "v + h";
    int both = 1, plane = strcmp(fam, "vplane") == 0;
    if (strcmp(fam, "1p") == 0) {
        fputs("param t\n", f);
        r1 = "t";
        r2 = "1 - t";
    } else {
        fputs("param u, v\nconst k, h\n", f);
    }
    if (strcmp(fam, "rat") == 0 || strcmp(fam, "onerat") == 0) {
        r1 = "(u + k)/(1 + h*v)";
        r2 = "(v + h)/(1 + k*u)";
    }
    if (strncmp(fam, "one", 3) == 0)
        both = 0;
    if (plane)
        fputs("point A, B, C, D\nX0 = (A + 2*B + 4*C + 8*D)/15\n", f);
    else
        fputs("point A, B, C\nX0 = (A + 2*B + 4*C)/7\n", f);
    for (int i = 1; i <= k; i++) {
        const char *a = P[i % 3], *b = P[(i + 1) % 3], *c = P[(i + 2) % 3];
        if (plane)
            fprintf(
                f,
                "X%d = meet(line(A, along(X%d, B, %s)), plane(B, along(X%d, "
                "C, %s), along(X%d, D, %s)))\n",
                i, i - 1, r1, i - 1, r2, i - 1, r1);
        else if (both)
            fprintf(f,
                    "X%d = meet(line(A, along(X%d, B, %s)), line(B, along(X%d, "
                    "C, %s)))\n",
                    i, i - 1, r1, i - 1, r2);
        else
            fprintf(f,
                    "X%d = meet(line(%s, along(X%d, %s, %s)), line(%s, "
                    "along(%s, %s, %s)))\n",
                    i, a, i - 1, b, r1, b, c, a, r2);
    }
    fprintf(f, "output X%d\n", k);
    fclose(f);
    return text;
}

/* in the child: "MED LO HI BYTES" or "refused SECONDS" on fd */
static void run_case(const char *text, int fd)
{
    double t[200], total = 0;
    int n = 0;
    size_t bytes = 0;
    char line[128];
    for (;;) {
        double t0 = (bench_now_ms() / 1e3);
        Derived *d = derive_source("chain.pcs", text, strlen(text), NULL, NULL);
        t[n] = (bench_now_ms() / 1e3) - t0;
        if (!d) {
            snprintf(line, sizeof line, "refused %.4f\n", t[n]);
            if (write(fd, line, strlen(line)) < 0)
                _exit(1);
            _exit(0);
        }
        if (n == 0) {
            char *out = NULL;
            FILE *m = open_memstream(&out, &bytes);
            format_derived(m, d, FMT_TEXT, -1);
            fclose(m);
            free(out);
        }
        derived_free(d);
        total += t[n++];
        if (t[0] > 2 || n == 200 || (n >= 3 && total > 0.3))
            break;
    }
    qsort(t, (size_t)n, sizeof *t, bench_cmp_double);
    snprintf(line, sizeof line, "%.6f %.6f %.6f %zu\n", t[n / 2], t[0],
             t[n - 1], bytes);
    if (write(fd, line, strlen(line)) < 0)
        _exit(1);
    _exit(0);
}

static const Base *base_of(const char *name)
{
    for (size_t i = 0; i < sizeof baseline / sizeof *baseline; i++)
        if (strcmp(baseline[i].name, name) == 0)
            return &baseline[i];
    return NULL;
}

/* 1 when no filter is given or name (fam + k) matches one */
static int selected(int argc, char **argv, const char *fam, const char *name)
{
    if (argc < 2)
        return 1;
    for (int i = 1; i < argc; i++)
        if (strcmp(argv[i], fam) == 0 || strcmp(argv[i], name) == 0)
            return 1;
    return 0;
}

int main(int argc, char **argv)
{
    static const char *const fams[] = {"1p",  "lin",    "rat",
                                       "one", "onerat", "vplane"};
    if (argc == 3 && strcmp(argv[1], "--print") == 0) {
        for (size_t fi = 0; fi < sizeof fams / sizeof *fams; fi++) {
            size_t n = strlen(fams[fi]);
            if (strncmp(argv[2], fams[fi], n) == 0 && argv[2][n] >= '1' &&
                argv[2][n] <= '9' && argv[2][n + 1] == '\0') {
                char *text = scheme(fams[fi], argv[2][n] - '0');
                fputs(text, stdout);
                free(text);
                return 0;
            }
        }
        fprintf(stderr, "bench_chains: no case %s\n", argv[2]);
        return 2;
    }
    const char *to = getenv("PC_CHAIN_TIMEOUT");
    int timeout = to ? atoi(to) : 30;
    int quick = getenv("PC_BENCH_QUICK") != NULL;
    printf("bench_chains: chains of k meets, in-process derive_source, "
           "seconds: median [lowest..highest run]; timeout %d s\n",
           timeout);
    printf("%-9s %10s %22s %12s %12s %9s\n", "case", "median", "spread",
           "result", "b5e0642", "ratio");
    for (size_t fi = 0; fi < sizeof fams / sizeof *fams; fi++) {
        for (int k = 1; k <= (quick ? 4 : 8); k++) {
            char name[32], buf[128] = "";
            snprintf(name, sizeof name, "%s%d", fams[fi], k);
            if (!selected(argc, argv, fams[fi], name))
                continue;
            char *text = scheme(fams[fi], k);
            int pfd[2];
            if (pipe(pfd) != 0)
                return 1;
            fflush(stdout);
            pid_t pid = fork();
            if (pid == 0) {
                close(pfd[0]);
                alarm((unsigned)timeout);
                run_case(text, pfd[1]);
            }
            close(pfd[1]);
            ssize_t got = read(pfd[0], buf, sizeof buf - 1);
            close(pfd[0]);
            int status = 0;
            waitpid(pid, &status, 0);
            free(text);
            buf[got > 0 ? got : 0] = '\0';
            const Base *b = base_of(name);
            char was[32] = "-";
            if (b && b->seconds > 0)
                snprintf(was, sizeof was, "%.4f", b->seconds);
            else if (b && b->seconds < 0)
                snprintf(was, sizeof was, ">150");
            else if (b)
                snprintf(was, sizeof was, "refused");
            double med, lo, hi;
            size_t bytes;
            if (got <= 0) {
                printf("%-9s %10s %22s %12s %12s\n", name, "timeout", "", "",
                       was);
                break;
            }
            if (strncmp(buf, "refused", 7) == 0) {
                char in[48];
                snprintf(in, sizeof in, "(in %.4f s)", atof(buf + 8));
                printf("%-9s %10s %22s %12s %12s\n", name, "refused", in, "",
                       was);
                break;
            }
            if (sscanf(buf, "%lf %lf %lf %zu", &med, &lo, &hi, &bytes) != 4)
                break;
            char spread[48], ratio[16] = "";
            snprintf(spread, sizeof spread, "[%.4f..%.4f]", lo, hi);
            if (b && b->seconds > 0)
                snprintf(ratio, sizeof ratio, "%.1fx", b->seconds / med);
            else if (b && b->seconds < 0)
                snprintf(ratio, sizeof ratio, ">%.0fx", 150 / med);
            printf("%-9s %10.4f %22s %12zu %12s %9s\n", name, med, spread,
                   bytes, was, ratio);
        }
    }
    flint_cleanup_master();
    return 0;
}

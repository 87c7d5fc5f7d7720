/*
 * test_fuzz.c - robustness: mutated and truncated versions of every scheme
 * must produce either a derivation or a clean diagnostic, never a crash, a
 * hang or a leak; what derives then goes through every back end (format,
 * lower, emit-c, eval: tests/fuzz/exercise.h).  `make asan` runs this under
 * AddressSanitizer + UBSan, `make valgrind` under memcheck.
 *
 * The mutations are seeded: a failure is reproducible.  Each run samples
 * a different part of the mutation space (150 mutations of each file,
 * PC_FUZZ_MUTATIONS to change it) from a seed it prints; PC_FUZZ_SEED=N
 * repeats run N exactly.  Successive runs (every `make check`, every CI
 * run) so cover far more inputs than one fixed set of 1500 per file did,
 * at a tenth of the cost; `make fuzz` is the deep, coverage-guided search.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <flint/flint.h>

#include "base/check.h"
#include "compiler/derive.h"
#include "tests/fuzz/exercise.h"

static uint64_t rng_state;
static uint64_t run_seed; /* this run's sample of the mutations */

static uint32_t rnd(uint32_t n)
{
    /* xorshift64* */
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (uint32_t)((rng_state * 2685821657736338717ULL) >> 33) % n;
}

static const char *const tokens[] = {
    "(",           ")",           "[",
    "]",           ",",           "=",
    "+",           "-",           "*",
    "/",           "^",           "#",
    "\n",          "0",           "1",
    "2",           "0.5",         "1e3",
    ".",           "t",           "A",
    "B",           "k",           "M",
    "P",           "meet",        "line(",
    "plane(",      "along(",      "divide(",
    "subst(",      "diff(",       "bezier(",
    "point ",      "param ",      "const ",
    "output ",     "scheme ",     "in",
    "sin(",        "pi",          "unknown ",
    "solve ",      " for ",       "\t",
    "\xff",        "\0",          "$",
    "1/0",         "t^-3",        "A - A",
    "(t-t)",       "sqrt(",       "cos(",
    "exp(",        "ln(",         "^(1/2)",
    " > 0",        "dist(",       "dot(",
    "angle(",      " in (0, 1)",  " < 1",
    ">= 2",        "abs(",        "sign(",
    "coord(",      "natx(",       "naty(",
    ", 2)",        "def ",        "def P(t, a) = ",
    "sum(",        "prod(",       " for i in 1..3)",
    "..",          "piecewise(",  "join(",
    "smoothjoin(", "g[0..1]",     "-inf",
    "inf",         "check ",      "check M = A",
    " at t = 0",   " at t = 1, ", "on(",
    "parallel(",   "tangent(",    "contact(2, ",
    "C2(",         "G1(",         "line(A, B))",
};

/* The back ends of one derived scheme are exercised once per file and
 * token stream: a mutation or a cut inside a comment, or one that changes
 * only blanks, derives (always: the scanner must survive it) to the same
 * equations, and the back ends would walk the same paths again.  The key
 * is the text with comments dropped and blanks squeezed (FNV-1a). */
enum { SEEN_MAX = 4096 };
static uint64_t seen[SEEN_MAX];
static int nseen, nskipped;

static uint64_t token_key(const char *buf, size_t len)
{
    uint64_t h = 1469598103934665603ULL;
    int blank = 0;
    for (size_t i = 0; i < len; i++) {
        unsigned char c = (unsigned char)buf[i];
        if (c == '#') { /* to the end of the line */
            while (i + 1 < len && buf[i + 1] != '\n')
                i++;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\r') {
            blank = 1;
            continue;
        }
        if (blank) {
            h = (h ^ ' ') * 1099511628211ULL;
            blank = 0;
        }
        h = (h ^ c) * 1099511628211ULL;
    }
    return h;
}

/* 1 when the key was seen (for this file), else records it */
static int seen_before(uint64_t key)
{
    for (int i = 0; i < nseen; i++)
        if (seen[i] == key)
            return 1;
    if (nseen < SEEN_MAX)
        seen[nseen++] = key;
    return 0;
}

/* checks one input: success XOR errors, nothing else */
/* A watchdog: one FLINT call cannot be interrupted, so an input that
 * would run for hours (an unguarded size) would hang the suite.  Past
 * PROBE_SECONDS the run stops, saying which input of which seeded run did
 * it, so that PC_FUZZ_SEED repeats it. */
enum { PROBE_SECONDS = 120 };
static const char *probe_name;
static const char *probe_buf;
static size_t probe_len;

static void on_watchdog(int sig)
{
    (void)sig;
    static const char head[] = "\nfuzz: FAIL: one input of ";
    static const char mid[] = " ran past the watchdog (PC_FUZZ_SEED printed "
                              "above repeats the run); the input:\n";
    pc_write_all(2, head, sizeof head - 1);
    pc_write_all(2, probe_name, strlen(probe_name));
    pc_write_all(2, mid, sizeof mid - 1);
    pc_write_all(2, probe_buf, probe_len);
    pc_write_all(2, "\n", 1);
    _exit(1);
}

static int probe(const char *name, const char *buf, size_t len)
{
    int nerr = -1;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    probe_name = name;
    probe_buf = buf;
    probe_len = len;
    if (!getenv("PC_VALGRIND")) /* valgrind is ~30x slower: no watchdog */
        alarm(PROBE_SECONDS);
    Derived *d = derive_source(name, buf, len, NULL, &nerr);
    int ok = (d != NULL) == (nerr == 0);
    if (d && !seen_before(token_key(buf, len)))
        exercise_backends(d);
    else if (d)
        nskipped++;
    derived_free(d);
    alarm(0);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double sec = (double)(t1.tv_sec - t0.tv_sec) +
                 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    if (sec > 0.5 && getenv("PC_FUZZ_TIMES")) /* the slow inputs, to study */
        fprintf(stderr, "%s: %.2f s for\n%.*s\n----\n", name, sec, (int)len,
                buf);
    if (!ok)
        fprintf(stderr, "%s: inconsistent result (nerrors=%d)\n", name, nerr);
    return ok;
}

static char *mutate(const char *src, size_t len, size_t *outlen)
{
    size_t cap = len * 2 + 64;
    char *b = malloc(cap);
    memcpy(b, src, len);
    size_t n = len;
    int edits = 1 + (int)rnd(4);
    for (int e = 0; e < edits; e++) {
        size_t at = n ? rnd((uint32_t)n) : 0;
        switch (rnd(4)) {
        case 0: /* delete a short range */
            if (n) {
                size_t l = 1 + rnd(8);
                if (at + l > n)
                    l = n - at;
                memmove(b + at, b + at + l, n - at - l);
                n -= l;
            }
            break;
        case 1: /* replace a byte */
            if (n)
                b[at] = (char)rnd(256);
            break;
        default: { /* insert a token */
            const char *t = tokens[rnd(sizeof tokens / sizeof tokens[0])];
            size_t l = t[0] ? strlen(t) : 1;
            if (n + l >= cap)
                break;
            memmove(b + at + l, b + at, n - at);
            memcpy(b + at, t, l);
            n += l;
            break;
        }
        }
    }
    *outlen = n;
    return b;
}

static char *read_all(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *buf = malloc((size_t)n + 1);
    *len = fread(buf, 1, (size_t)n, f);
    fclose(f);
    return buf;
}

static int fuzz_dir(const char *dir, int mutations)
{
    DIR *d = opendir(dir);
    if (!d)
        return 0;
    int files = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t l = strlen(e->d_name);
        if (l < 5 || strcmp(e->d_name + l - 4, ".pcs") != 0)
            continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        size_t len = 0;
        char *text = read_all(path, &len);
        assert_non_null(text);
        files++;
        nseen = 0; /* the back ends once per token stream of this file */
        /* every truncation (stepping through long files: at most
         * PC_FUZZ_CUTS of them, 200 unless set; make valgrind sets fewer) */
        const char *ce = getenv("PC_FUZZ_CUTS");
        size_t cuts = ce && atoi(ce) > 0 ? (size_t)atoi(ce) : 200;
        size_t step = len / cuts + 1;
        for (size_t cut = 0; cut <= len; cut += step)
            assert_true(probe(path, text, cut));
        /* seeded random mutations */
        rng_state = (0x9e3779b97f4a7c15ULL ^ (uint64_t)len) +
                    run_seed * 0xbf58476d1ce4e5b9ULL;
        if (rng_state == 0) /* xorshift's one fixed point */
            rng_state = 1;
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        for (int m = 0; m < mutations; m++) {
            size_t ml;
            char *mut = mutate(text, len, &ml);
            assert_true(probe(path, mut, ml));
            free(mut);
        }
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double sec = (double)(t1.tv_sec - t0.tv_sec) +
                     1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
        if (getenv("PC_FUZZ_TIMES"))
            printf("  %s: %d mutations in %.2f s (back ends skipped for %d "
                   "repeated token streams so far)\n",
                   path, mutations, sec, nskipped);
        free(text);
    }
    closedir(d);
    return files;
}

static void test_fuzz_examples_never_crash(void **state)
{
    (void)state;
    const char *env = getenv("PC_FUZZ_MUTATIONS");
    int m = env ? atoi(env) : 150;
    const char *se = getenv("PC_FUZZ_SEED");
    run_seed = se ? strtoull(se, NULL, 10) : (uint64_t)time(NULL);
    printf("fuzz: seed %llu (PC_FUZZ_SEED=%llu repeats this run)\n",
           (unsigned long long)run_seed, (unsigned long long)run_seed);
    fflush(stdout); /* seen even if the watchdog ends the run */
    signal(SIGALRM, on_watchdog);
    int files = fuzz_dir("examples", m) + fuzz_dir("tests/schemes", m) +
                fuzz_dir("tests/errors", m);
    assert_true(files > 0);
}

static void test_fuzz_garbage_never_crashes(void **state)
{
    (void)state;
    rng_state = 42;
    for (int i = 0; i < 2000; i++) {
        char buf[64];
        size_t n = rnd(sizeof buf);
        for (size_t k = 0; k < n; k++)
            buf[k] = (char)rnd(256);
        assert_true(probe("garbage", buf, n));
    }
    /* pathological shapes */
    static const char *const cases[] = {
        "",
        "\n",
        "#",
        "point",
        "point A,",
        "M = ",
        "M = (",
        "M = )",
        "point A\nM = A\nM = A",
        "param t in [",
        "param t in [0, A]",
        "point A\nparam t\nM = A*t^1000000",
        "point A\nM = meet(A, A)",
        "point A, B\nparam t\nM = diff(A, t, 99)",
        "scheme\n",
        "output M\n",
        "point A\nM = A\noutput M, M\n",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        assert_true(probe("case", cases[i], strlen(cases[i])));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fuzz_examples_never_crash),
        cmocka_unit_test(test_fuzz_garbage_never_crashes),
    };
    int rc = cmocka_run_group_tests_name("fuzz", tests, NULL, NULL);
    flint_cleanup_master();
    return rc;
}

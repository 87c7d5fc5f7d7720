/*
 * test_threads.c - the library from several threads at once, on distinct
 * objects (docs/api.md, "Threads").
 *
 * Every example goes through the public pipeline (pc_scheme_parse_opts
 * with a time budget, pc_weight_str, pc_compile, pc_plan_dump, pc_eval,
 * pc_emit_c) on NTHREADS threads at once, each starting at another
 * example, then once on the main thread; every thread's texts and doubles
 * must be the main thread's, byte for byte.  The memory budget is on
 * (pc_use_memory_budget), and its counters must come back to where they
 * started once everything is freed.  `make tsan` runs this under
 * ThreadSanitizer, which fails on any data race (TSAN_OPTIONS=
 * halt_on_error=1): the process-wide state of the library is either
 * constant, made once (pthread_once), per thread (_Thread_local) or
 * atomic.
 */
#define _DEFAULT_SOURCE // signgam
#include <dirent.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <flint/flint.h>
#include <math.h>

#include "base/mem.h"
#include "base/strbuf.h"
#include "compiler/algebra/construct.h"
#include "libpointcalc.h"
#include "runtime/plan.h"

#define NTHREADS 4
#define MAXFILES 128
#define NSAMPLES 5
#define DIM 3

typedef struct Example {
    char *path;
    char *text;
    size_t len;
} Example;

static Example ex[MAXFILES];
static int nex;

static int by_path(const void *a, const void *b)
{
    return strcmp(((const Example *)a)->path, ((const Example *)b)->path);
}

static void load_examples(void)
{
    DIR *d = opendir("examples");
    assert_non_null(d);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t n = strlen(e->d_name);
        if (n < 5 || strcmp(e->d_name + n - 4, ".pcs") != 0)
            continue;
        assert_true(nex < MAXFILES);
        Example *x = &ex[nex++];
        x->path = pc_xasprintf("examples/%s", e->d_name);
        FILE *f = fopen(x->path, "rb");
        assert_non_null(f);
        char *buf = NULL;
        size_t cap = 0;
        FILE *m = open_memstream(&buf, &cap);
        assert_non_null(m);
        int c;
        while ((c = getc(f)) != EOF)
            putc(c, m);
        fclose(f);
        fclose(m);
        x->text = buf;
        x->len = cap;
    }
    closedir(d);
    qsort(ex, (size_t)nex, sizeof *ex, by_path);
    assert_true(nex >= 10);
}

static void appendf(StrBuf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    char tmp[512];
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n >= (int)sizeof tmp)
        n = (int)sizeof tmp - 1;
    sb_putn(b, tmp, (size_t)n);
}

static void append_owned(StrBuf *b, const char *what, char *s)
{
    appendf(b, "== %s\n", what);
    if (s != NULL)
        sb_putn(b, s, strlen(s));
    else
        sb_putn(b, "(null)", 6);
    sb_putn(b, "\n", 1);
    free(s);
}

/* everything the public API says about example i, as one text */
static char *run_example(int i)
{
    StrBuf b;
    memset(&b, 0, sizeof b);
    char *diag = NULL;
    pc_options o = {120, NULL, 0};
    pc_scheme *s =
        pc_scheme_parse_opts(ex[i].path, ex[i].text, ex[i].len, &o, &diag);
    if (s == NULL) {
        append_owned(&b, "parse error", diag);
        return sb_take(&b);
    }
    free(diag);
    appendf(&b, "%s: %d points, %d params, %d consts, %d outputs\n",
            pc_scheme_name(s), pc_npoints(s), pc_nparams(s), pc_nconsts(s),
            pc_noutputs(s));
    for (int k = 0; k < pc_noutputs(s); k++) {
        appendf(&b, "output %s kind %d line %d\n", pc_output_name(s, k),
                (int)pc_output_kind(s, k), pc_output_line(s, k));
        int np = pc_output_kind(s, k) == PC_SCALAR ? 1 : pc_npoints(s);
        for (int j = 0; j < np; j++)
            append_owned(&b, "weight", pc_weight_str(s, k, j));
    }
    diag = NULL;
    append_owned(&b, "emit-c", pc_emit_c(s, NULL, &diag));
    free(diag);
    diag = NULL;
    pc_plan *p = pc_compile(s, &diag);
    if (p == NULL) {
        append_owned(&b, "compile error", diag);
        pc_scheme_free(s);
        return sb_take(&b);
    }
    free(diag);
    append_owned(&b, "plan", pc_plan_dump(p));

    /* samples: params inside (0, 1), consts and coordinates fixed */
    int npar = pc_nparams(s), ncon = pc_nconsts(s), npt = pc_npoints(s);
    double *par = pc_xcalloc((size_t)(npar ? npar : 1) * NSAMPLES, sizeof *par);
    const double **parv = pc_xcalloc((size_t)(npar ? npar : 1), sizeof *parv);
    double *con = pc_xcalloc((size_t)(ncon ? ncon : 1), sizeof *con);
    double *pts = pc_xcalloc((size_t)(npt ? npt : 1) * DIM, sizeof *pts);
    const double **ptv = pc_xcalloc((size_t)(npt ? npt : 1), sizeof *ptv);
    for (int j = 0; j < npar; j++) {
        for (int n = 0; n < NSAMPLES; n++)
            par[j * NSAMPLES + n] = 0.1 + 0.17 * n + 0.013 * j;
        parv[j] = par + j * NSAMPLES;
    }
    for (int j = 0; j < ncon; j++)
        con[j] = 0.35 + 0.11 * j;
    for (int j = 0; j < npt; j++) {
        for (int d = 0; d < DIM; d++)
            pts[j * DIM + d] = (double)((j * 7 + d * 3) % 11) / 4.0 - 1.0 +
                               0.01 * (j + 1) * (d + 1);
        ptv[j] = pts + j * DIM;
    }
    for (int k = 0; k < pc_noutputs(s); k++) {
        double out[NSAMPLES * DIM];
        unsigned char status[NSAMPLES];
        size_t npoles = 0;
        int rc =
            pc_eval(p, k, NSAMPLES, parv, con, ptv, DIM, out, status, &npoles);
        appendf(&b, "eval %d: rc %d, %zu poles\n", k, rc, npoles);
        if (rc != PC_OK)
            continue;
        int w = pc_output_kind(s, k) == PC_SCALAR ? 1 : DIM;
        for (int n = 0; n < NSAMPLES; n++) {
            appendf(&b, " %d:", status[n]);
            for (int d = 0; d < w; d++)
                appendf(&b, " %a", out[n * w + d]);
            sb_putn(&b, "\n", 1);
        }
    }
    pc_free(par);
    pc_free(parv);
    pc_free(con);
    pc_free(pts);
    pc_free(ptv);
    pc_plan_free(p);
    pc_scheme_free(s);
    return sb_take(&b);
}

static char *expected[MAXFILES];

typedef struct Job {
    int first; // the example this thread starts at
    char *got[MAXFILES];
    slong fast_before, fast_after; // construct_meet_stats of the thread
} Job;

static void *worker(void *arg)
{
    Job *j = arg;
    slong red;
    construct_meet_stats(&j->fast_before, &red);
    for (int n = 0; n < nex; n++) {
        int i = (j->first + n) % nex;
        j->got[i] = run_example(i);
    }
    construct_meet_stats(&j->fast_after, &red);
    pc_thread_cleanup(); // this thread's FLINT caches
    return NULL;
}

static size_t mem_start;

/* NTHREADS threads at once, each from another example, then the
 * single-threaded reference: the same texts, and the memory counters back
 * where they were.  The threads come first, so that whatever the library
 * makes on first use is made by several threads at once. */
static void test_threads_agree(void **state)
{
    (void)state;
    /* valgrind runs one thread at a time: two are enough there */
    int nth = getenv("PC_VALGRIND") ? 2 : NTHREADS;
    Job jobs[NTHREADS];
    pthread_t th[NTHREADS];
    for (int t = 0; t < nth; t++) {
        memset(&jobs[t], 0, sizeof jobs[t]);
        jobs[t].first = t * nex / nth;
        assert_int_equal(pthread_create(&th[t], NULL, worker, &jobs[t]), 0);
    }
    for (int t = 0; t < nth; t++)
        assert_int_equal(pthread_join(th[t], NULL), 0);

    slong fast0, fast1, red;
    construct_meet_stats(&fast0, &red);
    signgam = 7; // lgamma would set it (to 1 or -1): the library uses lgamma_r
    for (int i = 0; i < nex; i++)
        expected[i] = run_example(i);
    assert_int_equal(signgam, 7);
    construct_meet_stats(&fast1, &red);
    assert_true(fast1 > fast0); // the examples meet fraction-free

    for (int t = 0; t < nth; t++) {
        /* the meet statistics are the thread's own: a new thread starts
         * at 0 whatever the others did */
        assert_int_equal(jobs[t].fast_before, 0);
        assert_int_equal(jobs[t].fast_after, fast1 - fast0);
        for (int i = 0; i < nex; i++) {
            if (strcmp(jobs[t].got[i], expected[i]) != 0)
                fail_msg("thread %d, %s: not the single-threaded result", t,
                         ex[i].path);
            pc_free(jobs[t].got[i]);
        }
    }
    for (int i = 0; i < nex; i++)
        pc_free(expected[i]);
    pc_thread_cleanup(); // the main thread's caches too
    /* every counted byte allocated since main began has been freed */
    assert_int_equal(mem_in_use(), mem_start);
}

/* plan_op_name is a constant table: it must agree with PLAN_OPS */
static void test_op_names(void **state)
{
    (void)state;
    static const char *const upper[] = {
#define NAME(name, nargs, cop) #name,
        PLAN_OPS(NAME)
#undef NAME
    };
    assert_int_equal(sizeof upper / sizeof *upper, PLAN_NOPS);
    for (int op = 0; op < PLAN_NOPS; op++) {
        const char *l = plan_op_name((PlanOp)op);
        assert_int_equal(strlen(l), strlen(upper[op]));
        for (size_t i = 0; upper[op][i]; i++) {
            char c = upper[op][i];
            assert_int_equal(l[i], c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
        }
    }
}

int main(void)
{
    pc_use_memory_budget((size_t)4 << 30);
    load_examples();
    mem_start = mem_in_use(); // the examples' paths stay to the end
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_threads_agree),
        cmocka_unit_test(test_op_names),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    for (int i = 0; i < nex; i++) {
        pc_free(ex[i].path);
        free(ex[i].text);
    }
    pc_cleanup();
    return rc;
}

/*
 * test_stack.c - the deepest expressions the language allows, on threads
 * with little stack (base/stack.h, docs/api.md "Stack").
 *
 * Sema allows 2000 levels; a level of the derivation takes 1-2 KiB of
 * stack, so 1999 nested along() (about 2.2 MiB) and 1997 nested sqrt()
 * (about 3.5 MiB) ran off the end of a 1 or 2 MiB thread stack (SIGSEGV).
 * On such a thread they now end in a located error; on a thread of the
 * documented 4 MiB the along() tower derives, and its weight of A is
 * checked against the closed form: 1999 times along(P, B, t) from A is
 * A*(1 - t)^1999 + B*(1 - (1 - t)^1999), (1 - t)^1999 expanded by FLINT.
 */
#define _DEFAULT_SOURCE /* MAP_ANONYMOUS, MAP_STACK */
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#include <cmocka.h>
#include <flint/fmpz_mpoly.h>

#include "base/mem.h"
#include "base/stack.h"
#include "libpointcalc.h"

/* sanitizers' frames are several times larger */
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define FRAME_SCALE 4
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define FRAME_SCALE 4
#endif
#endif
#ifndef FRAME_SCALE
#define FRAME_SCALE 1
#endif

typedef struct Job {
    const char *text;
    char *diag;      // the diagnostics (owned), NULL when derived
    char *weight;    // the weight of the first point (C API's string)
    size_t left_top; // stack_left() at the thread's start
} Job;

/* "point A, B / param t / M = along(along(... A ..., B, t), B, t)" */
static char *along_tower(int n)
{
    size_t cap = 64 + (size_t)n * 16;
    char *s = pc_xmalloc(cap), *p = s;
    p += sprintf(p, "point A, B\nparam t\nM = ");
    for (int i = 0; i < n; i++)
        p += sprintf(p, "along(");
    p += sprintf(p, "A");
    for (int i = 0; i < n; i++)
        p += sprintf(p, ", B, t)");
    sprintf(p, "\n");
    return s;
}

static char *sqrt_tower(int n)
{
    char *s = pc_xmalloc(32 + (size_t)n * 8), *p = s;
    p += sprintf(p, "param t\nx = ");
    for (int i = 0; i < n; i++)
        p += sprintf(p, "sqrt(");
    p += sprintf(p, "t");
    for (int i = 0; i < n; i++)
        p += sprintf(p, ")");
    sprintf(p, "\n");
    return s;
}

static void *derive_job(void *arg)
{
    Job *j = arg;
    j->left_top = stack_left();
    pc_options o = {.max_seconds = 120};
    pc_scheme *s = pc_scheme_parse_opts("deep.pcs", j->text, strlen(j->text),
                                        &o, &j->diag);
    if (s) {
        j->weight = pc_weight_str(s, 0, 0);
        pc_scheme_free(s);
    }
    pc_thread_cleanup();
    return NULL;
}

/* runs fn(arg) on a thread of exactly `stack` bytes: a stack of its own
 * (glibc would reuse a cached stack of an earlier thread up to 4 times
 * larger than asked) */
static void run_on_stack(void *(*fn)(void *), void *arg, size_t stack)
{
    pthread_attr_t a;
    pthread_t th;
    void *mem = mmap(NULL, stack, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS | MAP_STACK, -1, 0);
    assert_true(mem != MAP_FAILED);
    assert_int_equal(pthread_attr_init(&a), 0);
    assert_int_equal(pthread_attr_setstack(&a, mem, stack), 0);
    assert_int_equal(pthread_create(&th, &a, fn, arg), 0);
    assert_int_equal(pthread_join(th, NULL), 0);
    pthread_attr_destroy(&a);
    munmap(mem, stack);
}

static void run_with_stack(Job *j, size_t stack)
{
    run_on_stack(derive_job, j, stack);
}

/* the located error of the stack guard, at a column of the tower */
static void assert_stack_error(const char *diag, const char *line)
{
    assert_non_null(diag);
    assert_true(strncmp(diag, line, strlen(line)) == 0);
    const char *m = strstr(diag, ": error: ");
    assert_non_null(m);
    const char *want = ": error: " STACK_MESSAGE "\n";
    assert_true(strncmp(m, want, strlen(want)) == 0);
}

/* stack_left is the thread's: near its size at the start */
static void test_stack_left_measures(void **state)
{
    (void)state;
    Job j = {.text = "point A, B\nparam t\nM = along(A, B, t)\n"};
    run_with_stack(&j, (size_t)1 << 20);
    assert_null(j.diag);
    assert_string_equal(j.weight, "-t+1"); // the weight of A: 1 - t
    free(j.weight);
    assert_true(j.left_top <= ((size_t)1 << 20));
    assert_true(j.left_top > ((size_t)1 << 20) - 64 * 1024);
}

/* 1999 nested along: an error on 1 and 2 MiB, derived on 4 MiB */
static void test_along_1999(void **state)
{
    (void)state;
    char *text = along_tower(1999);
    for (size_t mib = 1; mib <= 2; mib++) {
        Job j = {.text = text};
        run_with_stack(&j, mib << 20);
        assert_stack_error(j.diag, "deep.pcs:3:");
        free(j.diag); // the C API's string
    }
    Job j = {.text = text};
    run_with_stack(&j, ((size_t)4 << 20) * FRAME_SCALE);
    if (j.diag)
        fail_msg("%s", j.diag);
    /* the weight of A: (1 - t)^1999, expanded by FLINT on its own */
    const char *vars[1] = {"t"};
    fmpz_mpoly_ctx_t ctx;
    fmpz_mpoly_t w;
    fmpz_mpoly_ctx_init(ctx, 1, ORD_LEX);
    fmpz_mpoly_init(w, ctx);
    fmpz_mpoly_set_str_pretty(w, "1 - t", vars, ctx);
    fmpz_mpoly_pow_ui(w, w, 1999, ctx);
    char *want = fmpz_mpoly_get_str_pretty(w, vars, ctx);
    assert_non_null(j.weight);
    assert_string_equal(j.weight, want);
    flint_free(want);
    free(j.weight);
    fmpz_mpoly_clear(w, ctx);
    fmpz_mpoly_ctx_clear(ctx);
    pc_free(text);
}

/* 1997 nested sqrt: an error on 1 MiB (not a crash) */
static void test_sqrt_1997(void **state)
{
    (void)state;
    char *text = sqrt_tower(1997);
    Job j = {.text = text};
    run_with_stack(&j, (size_t)1 << 20);
    assert_stack_error(j.diag, "deep.pcs:2:");
    free(j.diag);
    pc_free(text);
}

/* x0 = t, x1 = sin(x0), ..., xn = sin(x(n-1)): every definition is
 * shallow, so the derivation's guard never trips, but the value nests n
 * functions, and lowering it (kernel_reg, horner) and differentiating it
 * (kernel_derivative through kernel_dk) recurse n levels; `tail` follows */
static char *sin_chain(int n, const char *tail)
{
    size_t cap = 64 + (size_t)n * 32 + strlen(tail);
    char *s = pc_xmalloc(cap), *p = s;
    p += sprintf(p, "point A, B\nparam t in [1, 2]\nx0 = t\n");
    for (int i = 1; i <= n; i++)
        p += sprintf(p, "x%d = sin(x%d)\n", i, i - 1);
    sprintf(p, "%s", tail);
    return s;
}

typedef struct Lowering {
    const pc_scheme *s;
    pc_plan *plan;
    char *diag;
} Lowering;

static void *lower_job(void *arg)
{
    Lowering *l = arg;
    l->plan = pc_compile(l->s, &l->diag);
    pc_thread_cleanup();
    return NULL;
}

static void lower_with_stack(Lowering *l, size_t stack)
{
    run_on_stack(lower_job, l, stack);
}

/* sin nested 500 times by 500 definitions, derived on this thread, then
 * lowered on a thread of 256 KiB (a SIGSEGV before lowering had the
 * guard): the located error at the output; on 2 MiB it lowers, and the
 * plan evaluates to sin applied 500 times, computed here by libm */
static void test_lower_sin_chain(void **state)
{
    (void)state;
    char *text = sin_chain(500, "M = along(A, B, x500)\n");
    char *diag = NULL;
    pc_options o = {.max_seconds = 120};
    pc_scheme *s =
        pc_scheme_parse_opts("deep.pcs", text, strlen(text), &o, &diag);
    if (!s)
        fail_msg("%s", diag);
    Lowering l = {.s = s};
    lower_with_stack(&l, (size_t)256 << 10);
    assert_null(l.plan);
    assert_stack_error(l.diag, "deep.pcs:504:1:");
    free(l.diag);
    Lowering big = {.s = s};
    lower_with_stack(&big, ((size_t)2 << 20) * FRAME_SCALE);
    if (!big.plan)
        fail_msg("%s", big.diag);
    double t = 0.7, x = t, out[2];
    for (int i = 0; i < 500; i++)
        x = sin(x);
    const double *params[1] = {&t};
    const double a[2] = {0, 0}, b[2] = {1, 0};
    const double *points[2] = {a, b};
    assert_int_equal(
        pc_eval(big.plan, 0, 1, params, NULL, points, 2, out, NULL, NULL),
        PC_OK);
    assert_true(fabs(out[0] - x) < 1e-12); /* A + x*(B - A) = (x, 0) */
    assert_true(fabs(out[1]) < 1e-12);
    pc_plan_free(big.plan);
    pc_scheme_free(s);
    pc_free(text);
}

/* diff of the same chain on a thread of 384 KiB: the derivative recursed
 * 500 levels through kernel_dk and ran off the stack (SIGSEGV); now the
 * located error at the diff */
static void test_diff_sin_chain(void **state)
{
    (void)state;
    char *text = sin_chain(500, "y = diff(x500, t)\nM = along(A, B, y)\n");
    Job j = {.text = text};
    run_with_stack(&j, (size_t)384 << 10);
    assert_stack_error(j.diag, "deep.pcs:504:5:");
    free(j.diag);
    pc_free(text);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stack_left_measures),
        cmocka_unit_test(test_along_1999),
        cmocka_unit_test(test_sqrt_1997),
        cmocka_unit_test(test_lower_sin_chain),
        cmocka_unit_test(test_diff_sin_chain),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    pc_cleanup();
    return rc;
}

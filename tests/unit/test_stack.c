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
#include <pthread.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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

/* runs the job on a thread of `stack` bytes */
static void run_with_stack(Job *j, size_t stack)
{
    pthread_attr_t a;
    pthread_t th;
    assert_int_equal(pthread_attr_init(&a), 0);
    assert_int_equal(pthread_attr_setstacksize(&a, stack), 0);
    assert_int_equal(pthread_create(&th, &a, derive_job, j), 0);
    assert_int_equal(pthread_join(th, NULL), 0);
    pthread_attr_destroy(&a);
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stack_left_measures),
        cmocka_unit_test(test_along_1999),
        cmocka_unit_test(test_sqrt_1997),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    pc_cleanup();
    return rc;
}

/*
 * test_mem.c - the one allocator (base/mem.h): every block counted with
 * its usable size and taken off when freed, memory streams counted as they
 * grow (not after), a disowned block off the count, and the budget ending
 * the process with its message when the tree's own memory (not GMP's)
 * goes past it (issue 23 item 3).
 */
#include <malloc.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmocka.h>

#include "base/mem.h"

static void test_blocks_counted(void **state)
{
    (void)state;
    size_t before = mem_in_use();
    char *p = pc_xmalloc(100000);
    size_t u = malloc_usable_size(p);
    assert_true(u >= 100000);
    assert_int_equal(mem_in_use(), before + u);
    p = pc_xrealloc(p, 300000);
    assert_int_equal(mem_in_use(), before + malloc_usable_size(p));
    char *q = pc_xcalloc(1000, 100);
    assert_int_equal(mem_in_use(),
                     before + malloc_usable_size(p) + malloc_usable_size(q));
    pc_free(q);
    pc_free(p);
    assert_int_equal(mem_in_use(), before);
    double *a = pc_xaligned_alloc(64, 1000 * sizeof(double));
    assert_int_equal((uintptr_t)a % 64, 0);
    assert_int_equal(mem_in_use(), before + malloc_usable_size(a));
    pc_free(a);
    assert_int_equal(mem_in_use(), before);
}

/* the stream's text counts while it is written: a printed result can no
 * longer grow past the budget unseen */
static void test_memstream_counted_while_open(void **state)
{
    (void)state;
    size_t before = mem_in_use();
    char *buf = NULL;
    size_t len = 0;
    FILE *m = pc_xopen_memstream(&buf, &len);
    for (int i = 0; i < 100000; i++)
        fprintf(m, "%05d\n", i % 100000);
    fflush(m);
    assert_true(mem_in_use() >= before + 600000);
    assert_int_equal(len, 600000);
    pc_xclose_memstream(m);
    assert_int_equal(len, 600000);
    assert_int_equal(strlen(buf), 600000); // NUL-terminated
    assert_memory_equal(buf, "00000\n00001\n", 12);
    assert_memory_equal(buf + 599994, "99999\n", 6);
    assert_int_equal(mem_in_use(), before + malloc_usable_size(buf));
    pc_free(buf);
    assert_int_equal(mem_in_use(), before);
}

static void test_disown(void **state)
{
    (void)state;
    size_t before = mem_in_use();
    char *s = pc_xstrdup("handed over");
    assert_int_equal(mem_in_use(), before + malloc_usable_size(s));
    assert_ptr_equal(mem_disown(s), s);
    assert_int_equal(mem_in_use(), before);
    free(s); // the receiver's free(), as the C API's callers do
    assert_int_equal(mem_in_use(), before);
}

/* in a child: a budget of 1 MiB, then 2 MiB of the tree's own memory
 * (no GMP): exit 1 with the default handler's line */
static void test_budget_covers_own_memory(void **state)
{
    (void)state;
    int fd[2];
    assert_int_equal(pipe(fd), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        dup2(fd[1], 2);
        close(fd[0]);
        mem_set_limit((size_t)1 << 20);
        char *buf = NULL;
        size_t len = 0;
        FILE *m = pc_xopen_memstream(&buf, &len);
        for (int i = 0; i < (2 << 20) / 8; i++)
            fputs("12345678", m);
        pc_xclose_memstream(m);
        _exit(0); // not reached
    }
    close(fd[1]);
    char msg[256] = "";
    ssize_t n = read(fd[0], msg, sizeof msg - 1);
    msg[n > 0 ? n : 0] = '\0';
    close(fd[0]);
    int st = 0;
    waitpid(pid, &st, 0);
    assert_true(WIFEXITED(st));
    assert_int_equal(WEXITSTATUS(st), 1);
    assert_string_equal(msg, "pointcalc: error: the memory budget ran out\n");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_blocks_counted),
        cmocka_unit_test(test_memstream_counted_while_open),
        cmocka_unit_test(test_disown),
        cmocka_unit_test(test_budget_covers_own_memory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/*
 * test_checks_json.c - a derivation whose only errors are failed checks,
 * kept by a library caller (DeriveOptions.keep_failed_checks): its JSON
 * lists every verdict, the failed ones with their detail and orders.  The
 * command line never prints it (contract section 4: nothing on stdout
 * when a scheme has an error; tests/cli_test.sh).
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "base/mem.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"

static const char scheme[] = "point A, B, C\nparam t\nN = bezier(t, A, C, B)\n"
                             "check N = A at t = 0\n"
                             "check tangent(N at t = 0, line(A, B))\n"
                             "check C1(N at t = 1, along(B, C, t) at t = 0)\n";

static char *json_of(int keep, int *nerrors, int *kept)
{
    DeriveOptions o = {.max_seconds = 60, .keep_failed_checks = keep};
    FILE *null = fopen("/dev/null", "w");
    Derived *d =
        derive_source_ex("chk.pcs", scheme, strlen(scheme), null, nerrors, &o);
    fclose(null);
    *kept = d != NULL;
    if (!d)
        return NULL;
    char *out = NULL;
    size_t len = 0;
    FILE *f = pc_xopen_memstream(&out, &len);
    format_derived(f, d, FMT_JSON, -1);
    pc_xclose_memstream(f);
    derived_free(d);
    return out;
}

static void test_failed_checks_kept(void **state)
{
    (void)state;
    int nerr = 0, kept = 0;
    char *j = json_of(1, &nerr, &kept);
    assert_true(kept);
    assert_int_equal(nerr, 2);
    assert_non_null(
        strstr(j, "{\"line\": 4, \"kind\": \"equal\", \"verdict\": \"pass\"}"));
    const char *t = strstr(j, "{\"line\": 5, \"kind\": \"tangent\"");
    assert_non_null(t);
    assert_non_null(strstr(t, "\"verdict\": \"fail\""));
    assert_non_null(
        strstr(t, "\"detail\": \"the curve is not tangent to the line"));
    const char *c = strstr(j, "{\"line\": 6, \"kind\": \"C\"");
    assert_non_null(c);
    assert_non_null(strstr(c, "\"order\": 1"));
    assert_non_null(strstr(c, "\"found\": 0"));
    pc_free(j);
}

static void test_failed_checks_not_kept(void **state)
{
    (void)state;
    int nerr = 0, kept = 1;
    char *j = json_of(0, &nerr, &kept);
    assert_false(kept); /* the default: a failed check is an error */
    assert_null(j);
    assert_int_equal(nerr, 2);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_failed_checks_kept),
        cmocka_unit_test(test_failed_checks_not_kept),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

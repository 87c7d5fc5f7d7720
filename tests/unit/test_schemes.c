/*
 * test_schemes.c - the language tests as data (house style 26b).
 *
 * Every .pcs under examples/ and tests/schemes/ is derived in-process and
 * its expectation comments are checked:
 *
 *   # expect-weight NAME.POINT: EXPR   weight of POINT in NAME equals EXPR
 *                                      (symbolically; every base point with a
 *                                      nonzero weight must be listed)
 *   # expect-scalar NAME: EXPR         a scalar definition equals EXPR
 *   # expect-kind NAME: point|vector|scalar
 *
 * NAME must be an output of the scheme or any definition: the runner derives
 * a copy of the scheme with `output NAME` appended.  Every .pcs under
 * tests/errors/ must fail, and its `# expect-error: LINE:COL: MESSAGE` lines
 * must match the diagnostics, in order, exactly; each `# expect-note:
 * LINE:COL: MESSAGE` must be among the notes.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <flint/flint.h>

#include "codegen/numsolve.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"

/* derive_source with the numeric back end (numeric solves: `near`) */
static Derived *derive_text(const char *path, const char *text, size_t len,
                            FILE *err, int *nerrors)
{
    DeriveOptions opt = {.max_seconds = 60, .numeric = numsolve_run};
    return derive_source_ex(path, text, len, err, nerrors, &opt);
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
    size_t got = fread(buf, 1, (size_t)n, f);
    fclose(f);
    buf[got] = '\0';
    *len = got;
    return buf;
}

static int cmp_str(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

/* sorted list of the .pcs files in dir */
static char **list_pcs(const char *dir, int *n)
{
    DIR *d = opendir(dir);
    char **names = NULL;
    *n = 0;
    if (!d)
        return NULL;
    struct dirent *e;
    while ((e = readdir(d))) {
        size_t l = strlen(e->d_name);
        if (l > 4 && strcmp(e->d_name + l - 4, ".pcs") == 0) {
            names = realloc(names, sizeof(char *) * (size_t)(*n + 1));
            size_t sz = strlen(dir) + l + 2;
            names[*n] = malloc(sz);
            snprintf(names[*n], sz, "%s/%s", dir, e->d_name);
            (*n)++;
        }
    }
    closedir(d);
    qsort(names, (size_t)*n, sizeof(char *), cmp_str);
    return names;
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    char *e = s + strlen(s);
    while (e > s &&
           (e[-1] == ' ' || e[-1] == '\t' || e[-1] == '\r' || e[-1] == '\n'))
        *--e = '\0';
    return s;
}

static int failures;

#define CHECK(cond, ...)                                                       \
    do {                                                                       \
        if (!(cond)) {                                                         \
            fprintf(stderr, __VA_ARGS__);                                      \
            fputc('\n', stderr);                                               \
            failures++;                                                        \
        }                                                                      \
    } while (0)

/* derives text with "output NAME" appended */
static Derived *derive_with_output_ex(const char *path, const char *text,
                                      size_t len, const char *name,
                                      const char *want);

static Derived *derive_with_output(const char *path, const char *text,
                                   size_t len, const char *name)
{
    return derive_with_output_ex(path, text, len, name, NULL);
}

/* the same, with "expect__ = (want)" defined last and output second (an
 * expectation with functions: sin(phi), sqrt(...), which the test reads
 * with pointcalc's front end in the scheme's own ring) */
static Derived *derive_with_output_ex(const char *path, const char *text,
                                      size_t len, const char *name,
                                      const char *want)
{
    /* drop any existing output statement: replace "output" at line start */
    char *copy =
        malloc(len + strlen(name) + (want ? 2 * strlen(want) : 0) + 64);
    size_t k = 0;
    const char *p = text;
    while (p < text + len) {
        const char *eol = memchr(p, '\n', (size_t)(text + len - p));
        size_t l = eol ? (size_t)(eol - p + 1) : (size_t)(text + len - p);
        const char *q = p;
        while (q < p + l && (*q == ' ' || *q == '\t'))
            q++;
        if (strncmp(q, "output", 6) == 0 && (q[6] == ' ' || q[6] == '\t')) {
            copy[k++] = '#'; /* comment it out, keep columns */
        }
        memcpy(copy + k, p, l);
        k += l;
        p += l;
    }
    if (want)
        k += (size_t)sprintf(copy + k,
                             "\nexpect__ = (%s)\noutput %s, "
                             "expect__\n",
                             want, name);
    else
        k += (size_t)sprintf(copy + k, "\noutput %s\n", name);
    Derived *d = derive_text(path, copy, k, stderr, NULL);
    free(copy);
    return d;
}

static void check_expectations(const char *path)
{
    size_t len;
    char *text = read_all(path, &len);
    assert_non_null(text);
    int f0 = failures;

    /* the scheme itself must derive */
    int nerr = 0;
    Derived *whole = derive_text(path, text, len, stderr, &nerr);
    CHECK(whole != NULL, "%s: failed to derive (%d errors)", path, nerr);
    derived_free(whole);

    /* collect the names that have expectations */
    char *lines = strdup(text);
    int nexp = 0;
    for (char *save = NULL, *ln = strtok_r(lines, "\n", &save); ln;
         ln = strtok_r(NULL, "\n", &save)) {
        char *c = strstr(ln, "# expect-");
        if (!c)
            continue;
        c += 9;
        char kind[16] = {0}, name[128] = {0}, point[128] = {0};
        char *colon = strchr(c, ':');
        CHECK(colon != NULL, "%s: malformed expectation '%s'", path, ln);
        if (!colon)
            continue;
        size_t kl = strcspn(c, " ");
        if (kl >= sizeof kind)
            kl = sizeof kind - 1;
        memcpy(kind, c, kl);
        char *target_mem = strndup(c + kl, (size_t)(colon - c - (long)kl));
        char *target = trim(target_mem);
        char *want = trim(colon + 1);
        if (strcmp(kind, "weight") == 0) {
            char *dot = strchr(target, '.');
            CHECK(dot != NULL, "%s: expect-weight needs NAME.POINT", path);
            if (!dot) {
                free(target_mem);
                continue;
            }
            snprintf(name, sizeof name, "%.*s", (int)(dot - target), target);
            snprintf(point, sizeof point, "%s", dot + 1);
        } else {
            snprintf(name, sizeof name, "%s", target);
        }
        free(target_mem);
        nexp++;

        Derived *d = derive_with_output(path, text, len, name);
        CHECK(d != NULL, "%s: '%s' does not derive", path, name);
        if (!d)
            continue;
        const DerivedOutput *o = &d->outputs[0];
        const Ring *r = &d->ring;
        if (strcmp(kind, "kind") == 0) {
            const char *got = o->kind == KIND_POINT    ? "point"
                              : o->kind == KIND_VECTOR ? "vector"
                                                       : "scalar";
            CHECK(strcmp(got, want) == 0, "%s: kind of %s is %s, expected %s",
                  path, name, got, want);
        } else if (strcmp(kind, "weight") == 0 || strcmp(kind, "scalar") == 0) {
            RatFun exp, got;
            ratfun_init(exp, r);
            int rc = ratfun_set_str(exp, want, r);
            ratfun_clear(exp, r);
            int fallback = rc == RATFUN_ENAME || rc == RATFUN_ESYNTAX;
            if (fallback) {
                /* functions (sin(phi), sqrt(...)): read by the front end,
                 * in the scheme's own ring */
                derived_free(d);
                d = derive_with_output_ex(path, text, len, name, want);
                CHECK(d != NULL && d->noutputs == 2 &&
                          d->outputs[1].kind == KIND_SCALAR,
                      "%s: cannot derive expectation '%s'", path, want);
                if (!d || d->noutputs != 2) {
                    derived_free(d);
                    continue;
                }
                o = &d->outputs[0];
                r = &d->ring;
            }
            ratfun_init(exp, r);
            ratfun_init(got, r);
            if (fallback) {
                ratfun_set(exp, d->outputs[1].scalar, r);
                rc = 0;
            } else {
                rc = ratfun_set_str(exp, want, r);
            }
            CHECK(rc == 0, "%s: cannot parse expectation '%s' (%d)", path, want,
                  rc);
            if (strcmp(kind, "scalar") == 0) {
                CHECK(o->kind == KIND_SCALAR, "%s: %s is not a scalar", path,
                      name);
                ratfun_set(got, o->scalar, r);
            } else {
                slong pt = derived_find_point(d, point);
                CHECK(pt >= 0, "%s: unknown point '%s'", path, point);
                CHECK(o->kind != KIND_SCALAR, "%s: %s is a scalar", path, name);
                if (pt >= 0)
                    pteq_get_weight(got, o->eq, pt, r);
            }
            if (rc == 0 && !ratfun_equal(exp, got, r)) {
                char *g = ratfun_get_str(got, r);
                CHECK(0, "%s: %s%s%s is %s, expected %s", path, name,
                      point[0] ? "." : "", point, g, want);
                flint_free(g);
            }
            ratfun_clear(got, r);
            ratfun_clear(exp, r);
        } else {
            CHECK(0, "%s: unknown expectation kind '%s'", path, kind);
        }
        derived_free(d);
    }
    free(lines);

    /* every nonzero weight of a checked name must be listed */
    lines = strdup(text);
    for (char *save = NULL, *ln = strtok_r(lines, "\n", &save); ln;
         ln = strtok_r(NULL, "\n", &save)) {
        char *c = strstr(ln, "# expect-weight ");
        if (!c)
            continue;
        char name[128];
        if (sscanf(c + 16, "%127[^.]", name) != 1)
            continue;
        Derived *d = derive_with_output(path, text, len, name);
        if (!d)
            continue;
        for (slong k = 0; k < d->outputs[0].eq->len; k++) {
            char pat[300];
            snprintf(pat, sizeof pat, "# expect-weight %s.%s:", name,
                     d->points[d->outputs[0].eq->terms[k].point]);
            CHECK(strstr(text, pat) != NULL,
                  "%s: %s has a nonzero weight at %s that no expectation "
                  "lists",
                  path, name, d->points[d->outputs[0].eq->terms[k].point]);
        }
        derived_free(d);
    }
    free(lines);
    free(text);
    if (failures == f0)
        printf("  ok   %s (%d expectations)\n", path, nexp);
    else
        printf("  FAIL %s\n", path);
}

static void check_errors(const char *path)
{
    size_t len;
    char *text = read_all(path, &len);
    assert_non_null(text);
    char *out = NULL;
    size_t outlen = 0;
    FILE *mem = open_memstream(&out, &outlen);
    int nerr = 0;
    Derived *d = derive_text(path, text, len, mem, &nerr);
    fclose(mem);
    int f0 = failures;
    CHECK(d == NULL, "%s: derived although errors were expected", path);
    derived_free(d);

    /* expected "LINE:COL: MESSAGE" in order */
    char *lines = strdup(text);
    char *pos = out;
    int nexp = 0;
    for (char *save = NULL, *ln = strtok_r(lines, "\n", &save); ln;
         ln = strtok_r(NULL, "\n", &save)) {
        char *c = strstr(ln, "# expect-error:");
        if (!c)
            continue;
        nexp++;
        char want[1024];
        snprintf(want, sizeof want, "%s:%s", path, trim(c + 15));
        /* insert " error:" after LINE:COL: */
        char *p = want + strlen(path) + 1;
        p = strchr(p, ':');
        p = p ? strchr(p + 1, ':') : NULL;
        if (p) {
            char rest[1024];
            snprintf(rest, sizeof rest, "%s", p + 1);
            snprintf(p + 1, sizeof want - (size_t)(p + 1 - want), " error:%s",
                     rest);
        }
        char *hit = pos ? strstr(pos, want) : NULL;
        CHECK(hit != NULL, "%s: expected diagnostic\n  %s\ngot\n%s", path, want,
              out);
        if (hit)
            pos = hit + strlen(want);
    }
    /* expected notes "# expect-note: LINE:COL: MESSAGE", anywhere */
    free(lines);
    lines = strdup(text);
    for (char *save = NULL, *ln = strtok_r(lines, "\n", &save); ln;
         ln = strtok_r(NULL, "\n", &save)) {
        char *c = strstr(ln, "# expect-note:");
        if (!c)
            continue;
        char want[1024], *msg = trim(c + 14), *p = strchr(msg, ':');
        p = p ? strchr(p + 1, ':') : NULL;
        if (!p)
            continue;
        snprintf(want, sizeof want, "%s:%.*s: note:%s", path, (int)(p - msg),
                 msg, p + 1);
        CHECK(out && strstr(out, want), "%s: expected note\n  %s\ngot\n%s",
              path, want, out);
    }
    int reported = 0;
    for (char *q = out; q && (q = strstr(q, ": error: ")); q++)
        reported++;
    CHECK(reported == nexp, "%s: %d errors reported, %d expected:\n%s", path,
          reported, nexp, out);
    CHECK(nerr == nexp, "%s: error count %d, expected %d", path, nerr, nexp);
    if (failures == f0)
        printf("  ok   %s (%d errors)\n", path, nexp);
    free(lines);
    free(out);
    free(text);
}

static void run_dir(const char *dir, void (*fn)(const char *), int min)
{
    int n;
    char **names = list_pcs(dir, &n);
    assert_true(n >= min);
    for (int i = 0; i < n; i++) {
        fn(names[i]);
        free(names[i]);
    }
    free(names);
}

/* ---- the printed form read back ------------------------------------------ */

static int is_ident_char(char c)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
           (c >= '0' && c <= '9') || c == '_';
}

/* appends rhs to buf with every whole word `from` written `to` */
static void put_renamed(char **buf, size_t *len, size_t *cap, const char *rhs,
                        char *const *from, char *const *to, int n)
{
    for (const char *p = rhs; *p;) {
        int hit = -1;
        size_t fl = 0;
        if (is_ident_char(*p) && (p == rhs || !is_ident_char(p[-1])))
            for (int i = 0; i < n && hit < 0; i++) {
                fl = strlen(from[i]);
                if (strncmp(p, from[i], fl) == 0 && !is_ident_char(p[fl]))
                    hit = i;
            }
        const char *piece = hit >= 0 ? to[hit] : p;
        size_t pl = hit >= 0 ? strlen(to[hit]) : 1;
        if (*len + pl + 1 > *cap) {
            *cap = 2 * (*len + pl + 1);
            *buf = realloc(*buf, *cap);
        }
        memcpy(*buf + *len, piece, pl);
        *len += pl;
        (*buf)[*len] = '\0';
        p += hit >= 0 ? fl : 1;
    }
}

/* The text derive prints, read back by pointcalc's own front end: for every
 * output NAME = RHS, the scheme with `pb__K = (RHS) - (NAME)` added must
 * derive pb__K to exactly 0; both forms, over one denominator and relative
 * to the last base point (--origin).  (Family members print as M_1 and are read
 * as M[1].) */
static void check_print_back(const char *path)
{
    size_t len;
    char *text = read_all(path, &len);
    assert_non_null(text);
    Derived *d = derive_text(path, text, len, stderr, NULL);
    CHECK(d != NULL, "%s: does not derive", path);
    if (!d) {
        free(text);
        return;
    }
    char *out = NULL;
    size_t outlen = 0;
    FILE *mem = open_memstream(&out, &outlen);
    format_derived(mem, d, FMT_TEXT, -1);
    /* and relative to the last base point (derive --origin), whose
     * weights are printed (and un-rationalised) one by one */
    if (d->npoints > 0)
        format_derived(mem, d, FMT_TEXT, d->npoints - 1);
    fclose(mem);
    /* member names that the source spells NAME[k] */
    int nren = 0;
    char **from = calloc((size_t)d->npoints + 1, sizeof(char *));
    char **to = calloc((size_t)d->npoints + 1, sizeof(char *));
    for (slong i = 0; i < d->npoints; i++) {
        const char *u = strrchr(d->points[i], '_');
        if (!u || strstr(text, d->points[i]))
            continue;
        from[nren] = strdup(d->points[i]);
        to[nren] = malloc(strlen(d->points[i]) + 3);
        sprintf(to[nren], "%.*s[%s]", (int)(u - d->points[i]), d->points[i],
                u + 1);
        nren++;
    }
    size_t cap = len + 2 * outlen + 256, k = 0;
    char *copy = malloc(cap);
    for (size_t i = 0; i < len; i++) { /* comment out the output line */
        if ((i == 0 || text[i - 1] == '\n') &&
            strncmp(text + i, "output", 6) == 0 &&
            (text[i + 6] == ' ' || text[i + 6] == '\t'))
            copy[k++] = '#';
        copy[k++] = text[i];
    }
    copy[k] = '\0';
    int nout = 0;
    char *outs = strdup("");
    for (char *save = NULL, *ln = strtok_r(out, "\n", &save); ln;
         ln = strtok_r(NULL, "\n", &save)) {
        char *eq = strstr(ln, " = ");
        CHECK(eq != NULL, "%s: printed line without ' = ': %s", path, ln);
        if (!eq)
            continue;
        *eq = '\0';
        char *rhs = eq + 3;
        char *vec = strstr(rhs, "    (vector)");
        if (vec)
            *vec = '\0';
        if (strcmp(rhs, "0") == 0 && vec) {
            /* a zero vector: no expression of the language spells it */
            slong oi = derived_find_output(d, ln);
            CHECK(oi >= 0 && d->outputs[oi].eq->len == 0,
                  "%s: %s printed as 0 but is not", path, ln);
            continue;
        }
        char head[64];
        snprintf(head, sizeof head, "\npb__%d = (", ++nout);
        put_renamed(&copy, &k, &cap, head, NULL, NULL, 0);
        put_renamed(&copy, &k, &cap, rhs, from, to, nren);
        put_renamed(&copy, &k, &cap, ") - (", NULL, NULL, 0);
        put_renamed(&copy, &k, &cap, ln, NULL, NULL, 0);
        put_renamed(&copy, &k, &cap, ")", NULL, NULL, 0);
        size_t ol = strlen(outs);
        outs = realloc(outs, ol + 32);
        sprintf(outs + ol, "%spb__%d", nout > 1 ? ", " : "", nout);
    }
    put_renamed(&copy, &k, &cap, "\noutput ", NULL, NULL, 0);
    put_renamed(&copy, &k, &cap, outs, NULL, NULL, 0);
    put_renamed(&copy, &k, &cap, "\n", NULL, NULL, 0);
    Derived *b = derive_text(path, copy, k, stderr, NULL);
    CHECK(b != NULL, "%s: the printed form does not read back:\n%s", path,
          copy);
    int f0 = failures;
    for (slong i = 0; b && i < b->noutputs; i++) {
        const DerivedOutput *o = &b->outputs[i];
        int zero = o->kind == KIND_SCALAR
                       ? fmpz_mpoly_is_zero(o->scalar->num, b->ring.ctx)
                       : o->eq->len == 0;
        CHECK(zero, "%s: output %ld printed is not what was derived", path,
              (long)i + 1);
    }
    if (b && failures == f0)
        printf("  ok   %s (%d outputs read back)\n", path, nout);
    derived_free(b);
    derived_free(d);
    for (int i = 0; i < nren; i++) {
        free(from[i]);
        free(to[i]);
    }
    free(from);
    free(to);
    free(outs);
    free(copy);
    free(out);
    free(text);
}

static void test_printed_text_reads_back(void **state)
{
    (void)state;
    failures = 0;
    run_dir("examples", check_print_back, 10);
    run_dir("tests/schemes", check_print_back, 1);
    assert_int_equal(failures, 0);
}

static void test_examples_derive_to_expected(void **state)
{
    (void)state;
    failures = 0;
    run_dir("examples", check_expectations, 10);
    assert_int_equal(failures, 0);
}

static void test_schemes_derive_to_expected(void **state)
{
    (void)state;
    failures = 0;
    run_dir("tests/schemes", check_expectations, 1);
    assert_int_equal(failures, 0);
}

static void test_errors_are_reported_exactly(void **state)
{
    (void)state;
    failures = 0;
    run_dir("tests/errors", check_errors, 1);
    assert_int_equal(failures, 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_examples_derive_to_expected),
        cmocka_unit_test(test_printed_text_reads_back),
        cmocka_unit_test(test_schemes_derive_to_expected),
        cmocka_unit_test(test_errors_are_reported_exactly),
    };
    int rc = cmocka_run_group_tests_name("schemes", tests, NULL, NULL);
    flint_cleanup_master();
    return rc;
}

/*
 * test_locale.c - everything the library prints or reads is independent
 * of the caller's locale: with a comma-decimal locale in force
 * (setlocale(LC_ALL, "de_DE.UTF-8")), derive's text, LaTeX and JSON, the
 * generated C and header, the plan dump, eval's numbers, the sample specs
 * and the budget messages are byte for byte what they are in the C locale.
 *
 * The locale is made with localedef into a temporary LOCPATH when the
 * system has none with a decimal comma (Debian's `locales` package brings
 * the definitions; .ci/install-deps installs it).  Without localedef the
 * test fails: it must not pass by testing nothing.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h> /* after the four headers it needs */

#include <dirent.h>
#include <locale.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <flint/flint.h>

#include "codegen/emit_c.h"
#include "codegen/lower.h"
#include "codegen/numsolve.h"
#include "compiler/derive.h"
#include "compiler/print/format.h"
#include "driver/cli/budget.h"
#include "driver/cli/table.h"
#include "runtime/plan.h"
#include "runtime/plot.h"
#include "runtime/sample.h"

static char locpath[64];

/* a locale whose decimal point is a comma, or NULL */
static const char *comma_locale(void)
{
    static const char *const names[] = {"de_DE.UTF-8", "de_DE.utf8",
                                        "fr_FR.UTF-8", "ru_RU.UTF-8"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        if (setlocale(LC_ALL, names[i]) != NULL &&
            strcmp(localeconv()->decimal_point, ",") == 0) {
            setlocale(LC_ALL, "C");
            return names[i];
        }
    }
    setlocale(LC_ALL, "C");
    return NULL;
}

static int setup(void **state)
{
    (void)state;
    if (comma_locale() != NULL)
        return 0;
    /* make one: localedef -i de_DE -f UTF-8 DIR/de_DE.UTF-8 */
    strcpy(locpath, "/tmp/pc_localeXXXXXX");
    if (mkdtemp(locpath) == NULL)
        return -1;
    char cmd[256];
    snprintf(cmd, sizeof cmd,
             "localedef -i de_DE -f UTF-8 %s/de_DE.UTF-8 >/dev/null 2>&1",
             locpath);
    if (system(cmd) != 0)
        fprintf(stderr, "test_locale: localedef failed (is the `locales` "
                        "package installed?)\n");
    setenv("LOCPATH", locpath, 1);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    if (locpath[0] != '\0') {
        char cmd[128];
        snprintf(cmd, sizeof cmd, "rm -rf %s", locpath);
        if (system(cmd) != 0)
            return -1;
    }
    return 0;
}

/* the SVG of the point outputs over [0, 1] of the first param, points at
 * (i, i^2/3), consts 0.75, the other params 0.5 */
static void plot_points(FILE *m, const Plan *p)
{
    int *curves = calloc((size_t)p->noutputs + 1, sizeof *curves);
    double *xy = calloc(2 * (size_t)p->npoints + 1, sizeof *xy);
    const double **pts = calloc((size_t)p->npoints + 1, sizeof *pts);
    double *pv = calloc((size_t)p->nparams + 1, sizeof *pv);
    double *cv = calloc((size_t)p->nconsts + 1, sizeof *cv);
    int nc = 0;
    for (int o = 0; o < p->noutputs && p->nparams > 0; o++)
        if (p->outputs[o].kind == KIND_POINT)
            curves[nc++] = o;
    for (int i = 0; i < p->npoints; i++) {
        xy[2 * i] = i;
        xy[2 * i + 1] = i * i / 3.0;
        pts[i] = xy + 2 * i;
    }
    for (int i = 0; i < p->nparams; i++)
        pv[i] = 0.5;
    for (int i = 0; i < p->nconsts; i++)
        cv[i] = 0.75;
    if (nc > 0) {
        PlotSpec s;
        plot_spec_default(&s);
        s.env.plan = p;
        s.env.params = pv;
        s.env.consts = cv;
        s.env.points = pts;
        s.env.dim = 2;
        s.curves = curves;
        s.ncurves = nc;
        s.lo = 0;
        s.hi = 1;
        s.lim.max_samples = 200;
        s.tangents = pv;
        s.ntangents = 1;
        s.comb = 10;
        plot_svg(m, &s, NULL);
    }
    free(curves);
    free(xy);
    free(pts);
    free(pv);
    free(cv);
}

/* everything printed about one scheme, as one string */
static char *outputs(const char *path)
{
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    DeriveOptions opt = {.max_seconds = 60, .numeric = numsolve_run};
    Derived *d = derive_file_ex(path, m, NULL, &opt);
    if (d != NULL) {
        format_derived(m, d, FMT_TEXT, -1);
        format_derived(m, d, FMT_LATEX, -1);
        format_derived(m, d, FMT_JSON, -1);
        Plan *p = lower_derived(d, m);
        if (p != NULL) {
            emit_c(m, p, NULL, path);
            emit_c_header(m, p, NULL, path);
            plan_dump(m, p);
            plot_points(m, p);
            plan_free(p);
        }
        derived_free(d);
    }
    fclose(m);
    return text;
}

/* numbers printed and read outside derive */
static char *numbers(void)
{
    static const double v[] = {0.5, -1.25e-7, 3.0, 1e300, 0.1};
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
        table_number(m, v[i], TABLE_CSV);
        fputc(' ', m);
    }
    Spec s;
    char msg[128], buf[64];
    if (sample_parse(&s, "0.25:0.75:3", msg, sizeof msg) == 0) {
        for (size_t k = 0; k < s.n; k++)
            table_number(m, sample_value(&s, k), TABLE_JSON);
        sample_clear(&s);
    } else {
        fputs(msg, m);
    }
    budget_format_seconds(buf, sizeof buf, 0.5);
    fputs(buf, m);
    fclose(m);
    return text;
}

static void test_outputs_do_not_depend_on_the_locale(void **state)
{
    (void)state;
    const char *loc = comma_locale();
    if (loc == NULL)
        fail_msg("no comma-decimal locale could be made (localedef and the "
                 "`locales` package are needed for this test)");
    static const char *const dirs[] = {"examples", "tests/schemes"};
    int n = 0;
    for (size_t di = 0; di < 2; di++) {
        DIR *dir = opendir(dirs[di]);
        assert_non_null(dir);
        struct dirent *e;
        while ((e = readdir(dir)) != NULL) {
            size_t l = strlen(e->d_name);
            if (l < 5 || strcmp(e->d_name + l - 4, ".pcs") != 0)
                continue;
            char path[512];
            snprintf(path, sizeof path, "%s/%s", dirs[di], e->d_name);
            setlocale(LC_ALL, "C");
            char *c = outputs(path);
            assert_non_null(setlocale(LC_ALL, loc));
            assert_string_equal(localeconv()->decimal_point, ",");
            char *comma = outputs(path);
            setlocale(LC_ALL, "C");
            if (strcmp(c, comma) != 0)
                fail_msg("%s prints differently under %s", path, loc);
            free(c);
            free(comma);
            n++;
        }
        closedir(dir);
    }
    assert_true(n >= 10);
    char *c = numbers();
    assert_non_null(setlocale(LC_ALL, loc));
    char *comma = numbers();
    setlocale(LC_ALL, "C");
    assert_string_equal(c, comma);
    assert_string_equal(c,
                        "0.5 -1.2499999999999999e-07 3 1.0000000000000001e+300 "
                        "0.10000000000000001 0.250.50.750.5 s");
    free(c);
    free(comma);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_outputs_do_not_depend_on_the_locale),
    };
    int fails = cmocka_run_group_tests(tests, setup, teardown);
    flint_cleanup_master();
    return fails;
}

/*
 * test_eval.c - `pointcalc eval` and `pointcalc emit-c` through the binary
 * ($PC_BIN, default build/pointcalc): the CSV/JSON shapes of contract
 * section 4, grids, scalar columns, poles, and every usage error (exit 2,
 * a message on stderr, nothing on stdout).  Also the library API.
 */
/* cmocka.h needs these first, in this order */
// clang-format off
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
// clang-format on

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "libpointcalc.h"

static char tmpdir[64];
static const char *bin;

static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return calloc(1, 1);
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    int c;
    while ((c = fgetc(f)) != EOF)
        fputc(c, m);
    fclose(m);
    fclose(f);
    return buf;
}

typedef struct Run {
    int rc;
    char *out, *err;
} Run;

/* runs `pointcalc ARGS` (a shell fragment) */
static Run run(const char *args)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s %s >%s/out 2>%s/err", bin, args, tmpdir,
             tmpdir);
    int st = system(cmd);
    Run r;
    r.rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    snprintf(cmd, sizeof cmd, "%s/out", tmpdir);
    r.out = slurp(cmd);
    snprintf(cmd, sizeof cmd, "%s/err", tmpdir);
    r.err = slurp(cmd);
    return r;
}

static void run_free(Run *r)
{
    free(r->out);
    free(r->err);
}

static void write_scheme(const char *name, const char *text)
{
    char path[128];
    snprintf(path, sizeof path, "%s/%s", tmpdir, name);
    FILE *f = fopen(path, "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
}

#define DA "examples/desargues_arc.pcs --output M "
#define PTS "--at A=0,0,0 --at B=1,0,0 --at C=0,1,0 --at D=0,0,1 "

static void test_eval_csv_desargues(void **state)
{
    (void)state;
    Run r = run("eval " DA PTS "--param t=0:1:5");
    assert_int_equal(r.rc, 0);
    assert_string_equal(r.err, "");
    assert_string_equal(r.out, "t,M.1,M.2,M.3\n"
                               "0,0,0,0\n"
                               "0.25,0.075000000000000011,0.22500000000000001,"
                               "0.025000000000000001\n"
                               "0.5,0.25,0.25,0.25\n"
                               "0.75,0.22500000000000001,0.075000000000000011,"
                               "0.67500000000000004\n"
                               "1,0,0,1\n");
    run_free(&r);
    /* a list, and a single value: the centroid at t = 1/2 */
    r = run("eval " DA PTS "--param t=0.5");
    assert_string_equal(r.out, "t,M.1,M.2,M.3\n0.5,0.25,0.25,0.25\n");
    run_free(&r);
    r = run("eval " DA PTS "--param t=1,0");
    assert_string_equal(r.out, "t,M.1,M.2,M.3\n1,0,0,1\n0,0,0,0\n");
    run_free(&r);
}

static void usage_error(const char *args, const char *expect);

/* numbers at the edges of double: -0 prints as 0, a subnormal param is a
 * value, and a range over the whole double line has no inf in it */
static void test_eval_number_edges(void **state)
{
    (void)state;
    write_scheme("neg.pcs", "param t\ns = -t/2\n");
    char args[512];
    snprintf(args, sizeof args, "eval %s/neg.pcs --param t=0,1e-310", tmpdir);
    Run r = run(args);
    assert_int_equal(r.rc, 0);
    assert_string_equal(r.out, "t,s\n0,0\n9.9999999999999694e-311,"
                               "-5.0000000000002318e-311\n");
    run_free(&r);
    snprintf(args, sizeof args, "eval %s/neg.pcs --param t=-1e308:1e308:3",
             tmpdir);
    r = run(args);
    assert_int_equal(r.rc, 0);
    assert_string_equal(r.out, "t,s\n-1e+308,5.0000000000000001e+307\n0,0\n"
                               "1e+308,-5.0000000000000001e+307\n");
    run_free(&r);
    snprintf(args, sizeof args, "eval %s/neg.pcs --param t=1e-400", tmpdir);
    usage_error(args, "malformed value list");
}

static void test_eval_all_outputs_and_json(void **state)
{
    (void)state;
    Run r =
        run("eval examples/desargues_arc.pcs " PTS "--param t=0 --format json");
    assert_int_equal(r.rc, 0);
    assert_non_null(strstr(r.out, "\"scheme\": \"desargues_arc\""));
    assert_non_null(strstr(r.out, "{\"params\": {\"t\": 0}, \"consts\": {}, "
                                  "\"values\": {\"M\": [0, 0, 0], "));
    assert_non_null(strstr(r.out, "\"dM\": [0, 1, 0]")); // C - A
    run_free(&r);
    r = run("eval examples/desargues_arc.pcs --at A=0 --at B=1 --at C=2 "
            "--at D=3 --param t=1");
    assert_int_equal(r.rc, 0);
    assert_string_equal(r.out, "t,M.1,M_CB.1,M_AD.1,dM.1,d2M.1\n"
                               "1,3,3,3,2,-2\n"); // d2M(1) = 2C - 2D
    run_free(&r);
}

static void test_eval_grid_last_param_fastest(void **state)
{
    (void)state;
    write_scheme("grid.pcs", "point A, B\nparam u, v\nconst k\n"
                             "s = u*10 + v*k\nM = along(A, B, s)\n"
                             "output s, M\n");
    char args[512];
    snprintf(args, sizeof args,
             "eval %s/grid.pcs --at A=0 --at B=1 --set k=2 "
             "--param u=0,1 --param v=0:1:3",
             tmpdir);
    Run r = run(args);
    assert_int_equal(r.rc, 0);
    assert_string_equal(r.out, "u,v,s,M.1\n"
                               "0,0,0,0\n0,0.5,1,1\n0,1,2,2\n"
                               "1,0,10,10\n1,0.5,11,11\n1,1,12,12\n");
    run_free(&r);
}

static void test_eval_pole_prints_nan_and_exits_1(void **state)
{
    (void)state;
    write_scheme("pole.pcs", "point A, B\nparam t\nM = A + (B - A)/t\n");
    char args[512];
    snprintf(args, sizeof args,
             "eval %s/pole.pcs --at A=0,0 --at B=1,2 --param t=-1,0,1", tmpdir);
    Run r = run(args);
    assert_int_equal(r.rc, 1);
    assert_string_equal(r.out, "t,M.1,M.2\n-1,-1,-2\n0,nan,nan\n1,1,2\n");
    assert_non_null(strstr(r.err, "pole of M at t=0"));
    run_free(&r);
    snprintf(args, sizeof args,
             "eval %s/pole.pcs --at A=0,0 --at B=1,2 --param t=0 "
             "--format json",
             tmpdir);
    r = run(args);
    assert_int_equal(r.rc, 1);
    assert_non_null(strstr(r.out, "{\"params\": {\"t\": 0}, \"consts\": {}, "
                                  "\"values\": {\"M\": [null, null]}, "
                                  "\"poles\": [\"M\"]}"));
    run_free(&r);
}

/* a value too large for double precision in the terms of a finite curve
 * point (t^3 overflows at t = 1e103): every row printed, the sample
 * reported, exit 1 - exit 0 means every number is finite */
static void test_eval_overflow_is_reported(void **state)
{
    (void)state;
    Run r = run("eval " DA PTS "--param t=0.5,1e103");
    assert_int_equal(r.rc, 1);
    assert_string_equal(r.out, "t,M.1,M.2,M.3\n0.5,0.25,0.25,0.25\n"
                               "1e+103,nan,nan,nan\n");
    assert_non_null(strstr(r.err, "pointcalc: eval: M at t=1e+103 is not "
                                  "finite in double precision"));
    assert_null(strstr(r.err, "pole"));
    run_free(&r);
    r = run("eval " DA PTS "--param t=1e103 --format json");
    assert_int_equal(r.rc, 1);
    assert_non_null(strstr(r.out, "\"M\": [null, null, null]}, "
                                  "\"nonfinite\": [\"M\"]}"));
    run_free(&r);
    /* a scheme without params: no " at" */
    write_scheme("nopar.pcs", "point A, B\nM = A + (B - A)*10^300\n");
    char args[512];
    snprintf(args, sizeof args, "eval %s/nopar.pcs --at A=0 --at B=1e10",
             tmpdir);
    r = run(args);
    assert_int_equal(r.rc, 1);
    assert_string_equal(r.out, "M.1\ninf\n");
    assert_non_null(strstr(r.err, "pointcalc: eval: M is not finite"));
    run_free(&r);
}

/* usage errors: exit 2, stderr says what, stdout stays empty */
static void usage_error(const char *args, const char *expect)
{
    Run r = run(args);
    if (r.rc != 2 || r.out[0] || !strstr(r.err, expect)) {
        fprintf(stderr, "pointcalc %s\n  rc %d\n  out: %s\n  err: %s\n", args,
                r.rc, r.out, r.err);
        fail();
    }
    run_free(&r);
}

static void test_eval_usage_errors(void **state)
{
    (void)state;
    usage_error("eval", "needs a scheme FILE");
    usage_error("eval " DA PTS "--param t=0 --bogus", "unknown or incomplete");
    usage_error("eval " DA PTS "--param", "unknown or incomplete");
    usage_error("eval " DA PTS "--param t=0 --format yaml",
                "unknown format 'yaml'");
    usage_error("eval " DA PTS "--param t=0 x.pcs", "one FILE");
    usage_error("eval " DA "--at A=0,0,0 --at B=1,0,0 --at C=0,1,0 --param t=0",
                "missing --at D=");
    usage_error("eval " DA PTS "--at E=1,1,1 --param t=0",
                "'E' is not a base point");
    usage_error("eval " DA PTS "--at A=1,1,1 --param t=0",
                "--at A given twice");
    usage_error("eval " DA "--at A=0,0,0 --at B=1,0 --at C=0,1,0 --at D=0,0,1 "
                "--param t=0",
                "same dimension");
    usage_error("eval " DA "--at A=0,x,0 --at B=1,0,0 --at C=0,1,0 "
                "--at D=0,0,1 --param t=0",
                "malformed coordinates");
    usage_error("eval " DA "--at A=0,,0 --at B=1,0,0 --at C=0,1,0 "
                "--at D=0,0,1 --param t=0",
                "malformed coordinates");
    usage_error("eval " DA "--at A --param t=0", "expects NAME=VALUE");
    usage_error("eval " DA PTS, "missing --param t=SPEC");
    usage_error("eval " DA PTS "--param s=0", "'s' is not a param");
    usage_error("eval " DA PTS "--param t=0 --param t=1", "given twice");
    usage_error("eval " DA PTS "--param t=0:1", "malformed range");
    usage_error("eval " DA PTS "--param t=0:1:0", "count must be");
    usage_error("eval " DA PTS "--param t=0:1:1", "count must be at least 2");
    usage_error("eval " DA PTS "--param t=0:1:x", "count must be");
    usage_error("eval " DA PTS "--param t=1e999", "malformed value list");
    usage_error("eval " DA PTS "--param t=nan", "malformed value list");
    usage_error("eval " DA PTS "--param t=0.5x", "malformed value list");
    usage_error("eval " DA PTS "--param t=0 --set k=1", "not a const");
    usage_error("eval " DA PTS "--param t=0 --set t=1", "'t' is a param");
    usage_error("eval examples/desargues_arc.pcs " PTS "--param t=0 "
                "--output Q",
                "'Q' is not an output");
    usage_error("eval examples/conic_ceva.pcs --at A1=0 --at A2=1 --at A3=2 "
                "--param t=0",
                "missing --set k=VALUE");
    usage_error("eval examples/conic_ceva.pcs --at A1=0 --at A2=1 --at A3=2 "
                "--param t=0 --set k=1/2",
                "malformed number");
    usage_error("eval examples/conic_ceva.pcs --at A1=0 --at A2=1 --at A3=2 "
                "--param k=0 --set k=1",
                "'k' is a const");
}

static void test_eval_scheme_errors_exit_1(void **state)
{
    (void)state;
    /* the zero vector has no dimension of its own */
    write_scheme("zero.pcs", "point A\nparam t\nZ = A - A\n");
    char zargs[512];
    snprintf(zargs, sizeof zargs, "eval %s/zero.pcs --param t=1", tmpdir);
    usage_error(zargs, "output Z is the zero vector");
    /* emit-c: two outputs that would make the same C function */
    write_scheme("fnclash.pcs",
                 "scheme f\npoint A, B\nparam t\n"
                 "M = along(A, B, t)\n"
                 "M_batch = along(B, A, t)\noutput M, M_batch\n");
    snprintf(zargs, sizeof zargs, "emit-c %s/fnclash.pcs", tmpdir);
    Run z = run(zargs);
    assert_int_equal(z.rc, 1);
    assert_string_equal(z.out, "");
    assert_non_null(strstr(z.err, "fnclash.pcs:5:1: error: emit-c would write "
                                  "the C function f_M_batch for both M (line "
                                  "4) and M_batch; rename one of them\n"
                                  "M_batch = along(B, A, t)\n^~~~~~~\n"));
    run_free(&z);
    write_scheme("bad.pcs", "point A, B\nparam t\nM = along(A, X, t)\n");
    char args[512];
    snprintf(args, sizeof args, "eval %s/bad.pcs --at A=0 --param t=0", tmpdir);
    Run r = run(args);
    assert_int_equal(r.rc, 1);
    assert_string_equal(r.out, "");
    assert_non_null(strstr(r.err, "bad.pcs:3:14: error: undefined name 'X'"));
    run_free(&r);
    snprintf(args, sizeof args, "emit-c %s/bad.pcs", tmpdir);
    r = run(args);
    assert_int_equal(r.rc, 1);
    assert_string_equal(r.out, "");
    run_free(&r);
    r = run("eval /nonexistent.pcs --param t=0");
    assert_int_equal(r.rc, 1);
    run_free(&r);
}

static void test_emit_c_options(void **state)
{
    (void)state;
    char args[512], path[128];
    usage_error("emit-c", "needs a scheme FILE");
    usage_error("emit-c examples/desargues_arc.pcs --prefix 9x",
                "not a usable C identifier");
    usage_error("emit-c examples/desargues_arc.pcs --prefix int",
                "not a usable C identifier");
    usage_error("emit-c examples/desargues_arc.pcs -q", "unknown");
    snprintf(args, sizeof args,
             "emit-c examples/desargues_arc.pcs -o %s/g.c --header %s/g.h "
             "--prefix arc",
             tmpdir, tmpdir);
    Run r = run(args);
    assert_int_equal(r.rc, 0);
    assert_string_equal(r.out, "");
    run_free(&r);
    snprintf(path, sizeof path, "%s/g.h", tmpdir);
    char *h = slurp(path);
    assert_non_null(strstr(h, "void arc_M(double t, const double *A"));
    assert_non_null(strstr(h, "size_t arc_M_batch_checked(size_t n"));
    free(h);
    snprintf(path, sizeof path, "%s/g.c", tmpdir);
    char *c = slurp(path);
    assert_non_null(strstr(c, "#include <math.h>\n#include <stddef.h>\n"));
    free(c);
    r = run("emit-c examples/desargues_arc.pcs -o /nonexistent/dir/x.c");
    assert_int_equal(r.rc, 1);
    assert_non_null(strstr(r.err, "cannot write"));
    run_free(&r);
    r = run("emit-c examples/desargues_arc.pcs --dump-plan");
    assert_int_equal(r.rc, 0);
    assert_non_null(strstr(r.out, "plan desargues_arc: params t;"));
    run_free(&r);
}

/* libpointcalc.h: parse, weights as text, compile, evaluate */
/* pc_eval of an output that reads coordinate k (coord(P, k)): dim >= k,
 * PC_EINVAL below, and nothing written */
static void test_api_coord_needs_dim(void **state)
{
    (void)state;
    static const char text[] = "point A, B\nparam t\n"
                               "x = coord(along(A, B, t), 3)\n";
    char *diag = NULL;
    pc_scheme *s = pc_scheme_parse("c.pcs", text, strlen(text), &diag);
    assert_non_null(s);
    pc_plan *p = pc_compile(s, &diag);
    assert_non_null(p);
    double ts[2] = {0, 0.25}, out[2] = {7, 7};
    double A[3] = {1, 2, 3}, B[3] = {5, 6, 11};
    const double *prm[1] = {ts}, *pts[2] = {A, B};
    assert_int_equal(pc_eval(p, 0, 2, prm, NULL, pts, 2, out, NULL, NULL),
                     PC_EINVAL);
    assert_true(out[0] == 7 && out[1] == 7);
    assert_int_equal(pc_eval(p, 0, 2, prm, NULL, pts, 3, out, NULL, NULL),
                     PC_OK);
    assert_true(out[0] == 3 && out[1] == 5);
    /* n = 0: nothing to do, as the generated batch (issue 23 item 9) */
    size_t np = 9;
    assert_int_equal(pc_eval(p, 0, 0, NULL, NULL, NULL, 0, NULL, NULL, &np),
                     PC_OK);
    assert_true(np == 0);
    assert_int_equal(pc_eval(p, 1, 0, NULL, NULL, NULL, 0, NULL, NULL, NULL),
                     PC_EINVAL);
    pc_plan_free(p);
    pc_scheme_free(s);
}

static void test_api_roundtrip(void **state)
{
    (void)state;
    char *diag = NULL;
    pc_scheme *bad = pc_scheme_parse("x.pcs", "point A\nM = B\n", 14, &diag);
    assert_null(bad);
    assert_non_null(diag);
    assert_non_null(strstr(diag, "x.pcs:2:5: error:"));
    free(diag);
    pc_scheme *s = pc_scheme_load("examples/desargues_arc.pcs", &diag);
    assert_non_null(s);
    assert_null(diag);
    assert_string_equal(pc_scheme_name(s), "desargues_arc");
    assert_int_equal(pc_npoints(s), 4);
    assert_string_equal(pc_param_name(s, 0), "t");
    int o = pc_find_output(s, "M");
    assert_int_equal(o, 0);
    assert_int_equal(pc_output_kind(s, o), PC_POINT);
    char *w = pc_weight_str(s, o, 3);
    assert_non_null(strstr(w, "t^3"));
    free(w);
    assert_int_equal(pc_output_kind(s, 7), PC_NOKIND);
    assert_int_equal(pc_output_line(s, -1), -1);
    pc_plan *p = pc_compile(s, &diag);
    assert_non_null(p);
    assert_null(diag);
    double ts[3] = {0, 0.5, 1}, out[9];
    double A[3] = {0, 0, 0}, B[3] = {4, 0, 0}, C[3] = {0, 4, 0},
           D[3] = {0, 0, 4};
    const double *prm[1] = {ts}, *pts[4] = {A, B, C, D};
    size_t np = 9;
    assert_int_equal(pc_eval(p, o, 3, prm, NULL, pts, 3, out, NULL, &np),
                     PC_OK);
    assert_int_equal(np, 0);
    assert_true(out[3] == 1 && out[4] == 1 && out[5] == 1);
    assert_int_equal(pc_eval(p, 99, 3, prm, NULL, pts, 3, out, NULL, NULL),
                     PC_EINVAL);
    pts[1] = NULL;
    assert_int_equal(pc_eval(p, o, 3, prm, NULL, pts, 3, out, NULL, NULL),
                     PC_EINVAL);
    char *dump = pc_plan_dump(p);
    assert_non_null(strstr(dump, "output M point"));
    free(dump);
    char *src = pc_emit_c(s, "arc", &diag);
    assert_non_null(strstr(src, "void arc_M_batch("));
    assert_null(diag);
    free(src);
    assert_null(pc_emit_c(s, "1x", &diag));
    assert_non_null(strstr(diag, "prefix '1x'"));
    free(diag);
    pc_plan_free(p);
    pc_scheme_free(s);
    /* what cannot become a double comes back as a diagnostic */
    static const char big[] = "point A, B\nparam t\nM = A + (B - A)*10^400*t\n";
    s = pc_scheme_parse("big.pcs", big, strlen(big), &diag);
    assert_non_null(s);
    assert_null(pc_compile(s, &diag));
    assert_non_null(strstr(diag, "big.pcs:3:1: error: M cannot be evaluated "
                                 "in double precision"));
    free(diag);
    assert_null(pc_emit_c(s, NULL, NULL)); // diagnostics are optional
    pc_scheme_free(s);
    /* two outputs that make one C function name */
    static const char two[] = "scheme f\npoint A, B\nparam t\n"
                              "M = along(A, B, t)\nM_batch = along(B, A, t)\n"
                              "output M, M_batch\n";
    s = pc_scheme_parse("two.pcs", two, strlen(two), NULL);
    assert_null(pc_emit_c(s, NULL, &diag));
    assert_non_null(strstr(diag, "two.pcs:5:1: error: emit-c would write the "
                                 "C function f_M_batch for both M (line 4) "
                                 "and M_batch"));
    free(diag);
    pc_scheme_free(s);
}

static int setup(void **state)
{
    (void)state;
    bin = getenv("PC_BIN");
    if (!bin)
        bin = "build/pointcalc";
    strcpy(tmpdir, "/tmp/pc_eval_XXXXXX");
    return mkdtemp(tmpdir) ? 0 : -1;
}

static int teardown(void **state)
{
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmpdir);
    int rc = system(cmd);
    pc_cleanup();
    return rc;
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_eval_csv_desargues),
        cmocka_unit_test(test_eval_number_edges),
        cmocka_unit_test(test_eval_all_outputs_and_json),
        cmocka_unit_test(test_eval_grid_last_param_fastest),
        cmocka_unit_test(test_eval_pole_prints_nan_and_exits_1),
        cmocka_unit_test(test_eval_overflow_is_reported),
        cmocka_unit_test(test_eval_usage_errors),
        cmocka_unit_test(test_eval_scheme_errors_exit_1),
        cmocka_unit_test(test_emit_c_options),
        cmocka_unit_test(test_api_roundtrip),
        cmocka_unit_test(test_api_coord_needs_dim),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}

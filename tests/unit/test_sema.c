/*
 * test_sema.c - compiler/sema.c: a scheme is parsed, expanded and checked
 * by sema_check, and the SemaInfo is inspected: the points, params,
 * consts, unknowns and definitions with each Sym's kind and index, the
 * steps in source order, the outputs (listed, or the last definition),
 * Node.is_point of expressions, the builtin resolved for every call (pi
 * as a name included) and the coord index folded to one literal.  Then
 * every error sema reports, each with its exact text, line, column and
 * caret: undefined and built-in names, redefinitions with their notes,
 * functions used as names, unknown functions, wrong arity, a point where
 * a scalar is expected and the reverse, the operators' kind errors,
 * meet/line/plane, subst, diff, coord, the metric calls, bezier, ranges
 * and bounds, solve (equations, unknowns, counts), output, a second
 * scheme or output statement, and expressions nested too deeply.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/arena.h"
#include "base/diag.h"
#include "compiler/expand.h"
#include "compiler/sema.h"
#include "grammar/ast.h"
#include "grammar/parse.h"

/* One checked scheme: its arena holds the AST and the SemaInfo. */
typedef struct Checked {
    Arena a;
    Source src;
    Diag d;
    FILE *mem;
    char *out; // the diagnostics, after checked_end
    size_t len;
    Scheme *s;
    SemaInfo *I;
} Checked;

/* parses (no error allowed), expands (no error allowed) and checks text */
static void check(Checked *c, const char *text)
{
    c->out = NULL;
    c->len = 0;
    c->mem = open_memstream(&c->out, &c->len);
    arena_init(&c->a);
    source_init(&c->src, "x.pcs", text, strlen(text));
    diag_init(&c->d, &c->src, c->mem);
    c->s = parse_scheme(&c->src, &c->a, &c->d);
    assert_int_equal(c->d.nerrors, 0);
    assert_int_equal(expand_scheme(c->s, &c->a, &c->d, NULL, 0, NULL), 0);
    c->I = sema_check(c->s, &c->a, &c->d);
    assert_non_null(c->I);
    fflush(c->mem);
}

static void checked_free(Checked *c)
{
    fclose(c->mem);
    source_clear(&c->src);
    arena_reset(&c->a);
    free(c->out);
}

/* the diagnostics of checking text; *nerrors their count (caller frees) */
static char *sema_errors(const char *text, int *nerrors)
{
    Checked c;
    check(&c, text);
    fclose(c.mem);
    *nerrors = c.d.nerrors;
    source_clear(&c.src);
    arena_reset(&c.a);
    return c.out;
}

/* ---- expected diagnostics ---------------------------------------------- */

/* Appends to w the diagnostic "x.pcs:LN:COL: WHAT: MSG", the source line
 * and a caret under span, which must be the text at column col of line
 * (a check on the hand-counted column) */
static void diag_at(char *w, size_t cap, const char *what, int ln,
                    const char *line, int col, const char *span,
                    const char *msg)
{
    assert_true(strncmp(line + col - 1, span, strlen(span)) == 0);
    size_t k = strlen(w);
    int n = snprintf(w + k, cap - k, "x.pcs:%d:%d: %s: %s\n%s\n%*s^", ln, col,
                     what, msg, line, col - 1, "");
    assert_true(n > 0 && (size_t)n < cap - k);
    k += (size_t)n;
    for (size_t i = 1; i < strlen(span); i++)
        w[k++] = '~';
    w[k++] = '\n';
    w[k] = '\0';
    assert_true(k < cap);
}

enum { CAP = 8192 };

/* text has exactly one error, at line ln (whose text is line), column col
 * over span, with message msg */
static void one_error(const char *text, int ln, const char *line, int col,
                      const char *span, const char *msg)
{
    char want[CAP] = "";
    diag_at(want, CAP, "error", ln, line, col, span, msg);
    int n;
    char *s = sema_errors(text, &n);
    assert_string_equal(s, want);
    assert_int_equal(n, 1);
    free(s);
}

/* ---- the SemaInfo ------------------------------------------------------ */

static const char *const demo = "scheme demo\n"
                                "point A, B, C\n"
                                "param t in [0, 1]\n"
                                "const k\n"
                                "param u\n"
                                "const e in (0, 1)\n"
                                "unknown X\n"
                                "unknown scalar s\n"
                                "M = along(A, B, t)\n"
                                "solve X = along(A, C, s), s*2 = k for X, s\n"
                                "v = t*k\n"
                                "N = M + (B - A)*v\n"
                                "output N, X, M\n";

static void test_info_declarations(void **state)
{
    (void)state;
    Checked c;
    check(&c, demo);
    SemaInfo *I = c.I;
    assert_int_equal(c.d.nerrors, 0);
    assert_int_equal(c.len, 0);
    assert_string_equal(I->scheme_name, "demo");

    /* points in declaration order */
    assert_int_equal(I->npoints, 3);
    const char *pts[] = {"A", "B", "C"};
    for (int i = 0; i < 3; i++) {
        assert_string_equal(I->points[i]->name, pts[i]);
        assert_int_equal(I->points[i]->kind, SYM_POINT);
        assert_int_equal(I->points[i]->index, i);
        assert_int_equal(I->points[i]->is_point, 1);
    }
    /* params and consts numbered apart, whatever their interleaving */
    assert_int_equal(I->nparams, 2);
    assert_string_equal(I->params[0]->name, "t");
    assert_string_equal(I->params[1]->name, "u");
    assert_int_equal(I->params[0]->kind, SYM_PARAM);
    assert_int_equal(I->params[0]->index, 0);
    assert_int_equal(I->params[1]->index, 1);
    assert_int_equal(I->params[0]->is_point, 0);
    /* the declaring statement, with its range */
    assert_int_equal(I->params[0]->decl->kind, ST_PARAM);
    assert_non_null(I->params[0]->decl->lo);
    assert_null(I->params[1]->decl->lo);
    assert_int_equal(I->nconsts, 2);
    assert_string_equal(I->consts[0]->name, "k");
    assert_string_equal(I->consts[1]->name, "e");
    assert_int_equal(I->consts[0]->kind, SYM_CONST);
    assert_int_equal(I->consts[0]->index, 0);
    assert_int_equal(I->consts[1]->index, 1);
    assert_int_equal(I->consts[1]->decl->lo_open, 1);
    assert_int_equal(I->consts[1]->decl->bad, 0);

    /* unknowns: a point and a scalar, both solved by the solve */
    assert_int_equal(I->nunknowns, 2);
    Sym *X = I->unknowns[0], *s = I->unknowns[1];
    assert_string_equal(X->name, "X");
    assert_string_equal(s->name, "s");
    assert_int_equal(X->kind, SYM_UNKNOWN);
    assert_int_equal(s->kind, SYM_UNKNOWN);
    assert_int_equal(X->index, 0);
    assert_int_equal(s->index, 1);
    assert_int_equal(X->is_point, 1);
    assert_int_equal(s->is_point, 0);
    assert_non_null(X->solved_by);
    assert_ptr_equal(X->solved_by, s->solved_by);
    assert_int_equal(X->solved_by->kind, ST_SOLVE);
    assert_int_equal(X->solved_by->bad, 0);

    /* the definitions, and the steps in source order */
    assert_int_equal(I->ndefs, 3);
    const char *defs[] = {"M", "v", "N"};
    const int defpoint[] = {1, 0, 1};
    for (int i = 0; i < 3; i++) {
        Sym *d = I->defs[i];
        assert_string_equal(d->name, defs[i]);
        assert_int_equal(d->kind, SYM_DEF);
        assert_int_equal(d->index, i);
        assert_int_equal(d->is_point, defpoint[i]);
        assert_int_equal(d->bad, 0);
        assert_ptr_equal(d->def->sym, d);
    }
    assert_int_equal(I->nsteps, 4);
    assert_ptr_equal(I->steps[0], I->defs[0]->def);
    assert_ptr_equal(I->steps[1], X->solved_by);
    assert_ptr_equal(I->steps[2], I->defs[1]->def);
    assert_ptr_equal(I->steps[3], I->defs[2]->def);

    /* the outputs as listed */
    assert_int_equal(I->noutputs, 3);
    assert_ptr_equal(I->outputs[0], I->defs[2]);
    assert_ptr_equal(I->outputs[1], X);
    assert_ptr_equal(I->outputs[2], I->defs[0]);
    checked_free(&c);
}

static void test_info_expression_kinds(void **state)
{
    (void)state;
    Checked c;
    check(&c, demo);
    SemaInfo *I = c.I;
    /* M = along(A, B, t) */
    Node *m = I->defs[0]->def->expr;
    assert_int_equal(m->kind, ND_CALL);
    assert_int_equal(m->builtin, BI_ALONG);
    assert_int_equal(m->is_point, 1);
    Node *a = m->args, *b = a->next, *t = b->next;
    assert_ptr_equal(a->sym, I->points[0]);
    assert_ptr_equal(b->sym, I->points[1]);
    assert_ptr_equal(t->sym, I->params[0]);
    assert_int_equal(a->is_point, 1);
    assert_int_equal(t->is_point, 0);
    /* v = t*k: a scalar */
    Node *v = I->defs[1]->def->expr;
    assert_int_equal(v->kind, ND_MUL);
    assert_int_equal(v->is_point, 0);
    assert_ptr_equal(v->rhs->sym, I->consts[0]);
    /* N = M + (B - A)*v: the sum, the product and the difference are
     * combinations of points; the name M means the definition */
    Node *n = I->defs[2]->def->expr;
    assert_int_equal(n->kind, ND_ADD);
    assert_int_equal(n->is_point, 1);
    assert_ptr_equal(n->lhs->sym, I->defs[0]);
    assert_int_equal(n->lhs->is_point, 1);
    assert_int_equal(n->rhs->kind, ND_MUL);
    assert_int_equal(n->rhs->is_point, 1);
    assert_int_equal(n->rhs->lhs->kind, ND_SUB);
    assert_int_equal(n->rhs->lhs->is_point, 1);
    assert_int_equal(n->rhs->rhs->is_point, 0);
    assert_ptr_equal(n->rhs->rhs->sym, I->defs[1]);
    /* the solve: X = along(A, C, s) is a point equation, s*2 = k scalar;
     * the unknown scalar s is a scalar before it is solved */
    Equation *e = I->steps[1]->eqs;
    assert_int_equal(e->lhs->is_point, 1);
    assert_ptr_equal(e->lhs->sym, I->unknowns[0]);
    assert_int_equal(e->rhs->is_point, 1);
    assert_int_equal(e->next->lhs->is_point, 0);
    assert_ptr_equal(e->next->lhs->lhs->sym, I->unknowns[1]);
    checked_free(&c);
}

/* the expression of definition i */
static Node *def_expr(const SemaInfo *I, int i)
{
    return I->defs[i]->def->expr;
}

static void test_builtins_resolved(void **state)
{
    (void)state;
    Checked c;
    check(&c, "point A, B, C, D\nparam t\nconst k\n"
              "P = meet(line(A, B), line(C, D))\n"          /* 0 */
              "Q = meet(line(A, B), plane(B, C, D))\n"      /* 1 */
              "x = sqrt(t) + sin(t)*cos(k) + atan2(t, k)\n" /* 2 */
              "y = pi\n"                                    /* 3 */
              "R = subst(P, A, B)\n"                        /* 4 */
              "z = diff(x, t, 2)\n"                         /* 5 */
              "S = bezier(t, A, B, C)\n"                    /* 6 */
              "V = diff(S, t)\n"                            /* 7 */
              "w = dot(B - A, C - A) + dist(A, B)\n"        /* 8 */
              "g = angle(A, B, C)\n"                        /* 9 */
              "h = coord(A, 2*2 - 1)\n"                     /* 10 */
              "T = divide(A, B, k)\n"                       /* 11 */
              "f = tan(t) + abs(k)\n"                       /* 12 */
              "r = subst(x, t, k + 1)\n");                  /* 13 */
    SemaInfo *I = c.I;
    assert_int_equal(c.d.nerrors, 0);
    assert_int_equal(I->ndefs, 14);

    Node *n = def_expr(I, 0);
    assert_int_equal(n->builtin, BI_MEET);
    assert_int_equal(n->is_point, 1);
    assert_int_equal(n->args->builtin, BI_LINE);
    assert_int_equal(n->args->next->builtin, BI_LINE);
    n = def_expr(I, 1);
    assert_int_equal(n->args->next->builtin, BI_PLANE);

    /* x = sqrt(t) + sin(t)*cos(k) + atan2(t, k): ((sqrt + (sin*cos)) +
     * atan2) */
    n = def_expr(I, 2);
    assert_int_equal(n->is_point, 0);
    assert_int_equal(n->rhs->builtin, BI_ATAN2);
    assert_int_equal(n->lhs->lhs->builtin, BI_SQRT);
    assert_int_equal(n->lhs->rhs->lhs->builtin, BI_SIN);
    assert_int_equal(n->lhs->rhs->rhs->builtin, BI_COS);

    /* pi as a name: a call of no arguments */
    n = def_expr(I, 3);
    assert_int_equal(n->kind, ND_CALL);
    assert_int_equal(n->builtin, BI_PI);
    assert_int_equal(n->nargs, 0);
    assert_null(n->args);
    assert_int_equal(n->is_point, 0);

    /* subst and diff take the kind of their first argument */
    n = def_expr(I, 4);
    assert_int_equal(n->builtin, BI_SUBST);
    assert_int_equal(n->is_point, 1);
    assert_ptr_equal(n->args->next->sym, I->points[0]);
    n = def_expr(I, 5);
    assert_int_equal(n->builtin, BI_DIFF);
    assert_int_equal(n->is_point, 0);
    assert_ptr_equal(n->args->next->sym, I->params[0]);
    assert_int_equal(def_expr(I, 6)->builtin, BI_BEZIER);
    assert_int_equal(def_expr(I, 6)->is_point, 1);
    assert_int_equal(def_expr(I, 7)->is_point, 1);
    assert_int_equal(I->defs[7]->is_point, 1);

    /* the metric calls are scalars of points */
    n = def_expr(I, 8);
    assert_int_equal(n->lhs->builtin, BI_DOT);
    assert_int_equal(n->rhs->builtin, BI_DIST);
    assert_int_equal(n->is_point, 0);
    assert_int_equal(def_expr(I, 9)->builtin, BI_ANGLE);

    /* coord's index folded to one literal */
    n = def_expr(I, 10);
    assert_int_equal(n->builtin, BI_COORD);
    assert_int_equal(n->is_point, 0);
    assert_int_equal(n->args->next->kind, ND_NUM);
    assert_string_equal(n->args->next->text, "3");
    assert_null(n->args->next->lhs);

    assert_int_equal(def_expr(I, 11)->builtin, BI_DIVIDE);
    assert_int_equal(def_expr(I, 11)->is_point, 1);
    n = def_expr(I, 12);
    assert_int_equal(n->lhs->builtin, BI_TAN);
    assert_int_equal(n->rhs->builtin, BI_ABS);
    n = def_expr(I, 13);
    assert_int_equal(n->is_point, 0);
    assert_ptr_equal(n->args->next->sym, I->params[0]);

    /* no output statement: the last definition */
    assert_int_equal(I->noutputs, 1);
    assert_ptr_equal(I->outputs[0], I->defs[13]);
    assert_null(I->scheme_name);
    checked_free(&c);
}

static void test_outputs_may_name_later_definitions(void **state)
{
    (void)state;
    Checked c;
    check(&c, "point A, B\noutput N, M\nM = A\nN = B\nL = A\n");
    assert_int_equal(c.d.nerrors, 0);
    assert_int_equal(c.I->noutputs, 2);
    assert_string_equal(c.I->outputs[0]->name, "N");
    assert_string_equal(c.I->outputs[1]->name, "M");
    checked_free(&c);
}

static void test_families_reach_sema_as_members(void **state)
{
    (void)state;
    Checked c;
    check(&c, "int n = 3\npoint M[1..n]\nparam t\n"
              "X = bezier(t, M[1..n])\n");
    assert_int_equal(c.d.nerrors, 0);
    assert_int_equal(c.I->npoints, 3);
    assert_string_equal(c.I->points[2]->name, "M_3");
    assert_int_equal(c.I->points[2]->index, 2);
    Node *x = def_expr(c.I, 0);
    assert_int_equal(x->nargs, 4);
    assert_ptr_equal(x->args->next->next->sym, c.I->points[1]);
    checked_free(&c);
}

/* ---- names ------------------------------------------------------------- */

static void test_undefined_names(void **state)
{
    (void)state;
    one_error("point A, B\nM = along(A, Q, 1/2)\n", 2, "M = along(A, Q, 1/2)",
              14, "Q",
              "undefined name 'Q'; expected a declared point, parameter, "
              "constant or an earlier definition");
    /* a definition is known only after it */
    one_error("point A\nM = N\nN = A\n", 2, "M = N", 5, "N",
              "undefined name 'N'; expected a declared point, parameter, "
              "constant or an earlier definition");
}

static void test_bad_definition_not_reported_again(void **state)
{
    (void)state;
    Checked c;
    check(&c, "point A\nM = Q\nN = M + A\nL = A\n");
    assert_int_equal(c.d.nerrors, 1);
    assert_int_equal(c.I->ndefs, 3);
    assert_int_equal(c.I->defs[0]->bad, 1);
    assert_int_equal(c.I->defs[1]->bad, 1); /* uses the bad M */
    assert_int_equal(c.I->defs[2]->bad, 0);
    checked_free(&c);
}

/* the diagnostics of a redefinition at (ln2, line2, col2) of one first
 * declared at (ln1, line1, col1) as what */
static void redefinition(const char *text, int ln2, const char *line2, int col2,
                         int ln1, const char *line1, int col1, const char *name,
                         const char *as)
{
    char want[CAP] = "", msg[256];
    snprintf(msg, sizeof msg, "redefinition of '%s'", name);
    diag_at(want, CAP, "error", ln2, line2, col2, name, msg);
    snprintf(msg, sizeof msg, "'%s' was first declared here as %s", name, as);
    diag_at(want, CAP, "note", ln1, line1, col1, name, msg);
    int n;
    char *s = sema_errors(text, &n);
    assert_int_equal(n, 1);
    assert_string_equal(s, want);
    free(s);
}

static void test_redefinitions(void **state)
{
    (void)state;
    redefinition("point A\nconst k\nk = A\n", 3, "k = A", 1, 2, "const k", 7,
                 "k", "a constant");
    redefinition("point A\nM = A\nM = A*2 - A\n", 3, "M = A*2 - A", 1, 2,
                 "M = A", 1, "M", "a definition");
    redefinition("unknown X\npoint A, X\nM = A\n", 2, "point A, X", 10, 1,
                 "unknown X", 9, "X", "an unknown");
    redefinition("param t\nconst t\npoint A\nM = A\n", 2, "const t", 7, 1,
                 "param t", 7, "t", "a parameter");
    redefinition("point A, B, A\nM = A\n", 1, "point A, B, A", 13, 1,
                 "point A, B, A", 7, "A", "a base point");
}

static void test_built_in_names(void **state)
{
    (void)state;
    one_error("point A, sin\nM = A\n", 1, "point A, sin", 10, "sin",
              "'sin' is a built-in name; choose another name");
    one_error("param pi\npoint A\nM = A\n", 1, "param pi", 7, "pi",
              "'pi' is a built-in name; choose another name");
    one_error("point A\nalong = A\nM = A\n", 2, "along = A", 1, "along",
              "'along' is a built-in name; choose another name");
    one_error("point A\nconst coord\nM = A\n", 2, "const coord", 7, "coord",
              "'coord' is a built-in name; choose another name");
}

static void test_functions_as_names(void **state)
{
    (void)state;
    one_error("point A, B\nM = along\n", 2, "M = along", 5, "along",
              "'along' is a function; expected 'along(' with its arguments");
    one_error("point A\nx = sin + 1\n", 2, "x = sin + 1", 5, "sin",
              "'sin' is a function; expected 'sin(' with its arguments");
    one_error("point A\nx = pi(1)\n", 2, "x = pi(1)", 5, "pi",
              "'pi' is a constant, not a function; write pi without "
              "parentheses");
    one_error("point A\nx = foo(1)\n", 2, "x = foo(1)", 5, "foo",
              "unknown function 'foo'; expected along, divide, meet, subst, "
              "diff, bezier or a scalar function");
    one_error("point A\nx = A(1)\n", 2, "x = A(1)", 5, "A",
              "'A' is a base point, not a function");
    one_error("point A\nparam t\nx = t(1)\n", 3, "x = t(1)", 5, "t",
              "'t' is a parameter, not a function");
}

/* ---- arity ------------------------------------------------------------- */

static void test_arity(void **state)
{
    (void)state;
    one_error("point A, B\nM = along(A, B)\n", 2, "M = along(A, B)", 5,
              "along(A, B)", "along() takes 3 arguments, found 2");
    one_error("point A, B\nx = sqrt(1, 2)\n", 2, "x = sqrt(1, 2)", 5,
              "sqrt(1, 2)", "sqrt() takes 1 argument, found 2");
    one_error("point A\nx = atan2(1)\n", 2, "x = atan2(1)", 5, "atan2(1)",
              "atan2() takes 2 arguments, found 1");
    one_error("point A\nparam t\nx = diff(t)\n", 3, "x = diff(t)", 5, "diff(t)",
              "diff() takes 2 to 3 arguments, found 1");
    one_error("point A\nparam t\nx = diff(t, t, 1, 1)\n", 3,
              "x = diff(t, t, 1, 1)", 5, "diff(t, t, 1, 1)",
              "diff() takes 2 to 3 arguments, found 4");
    one_error("point A\nparam t\nX = bezier(t, A)\n", 3, "X = bezier(t, A)", 5,
              "bezier(t, A)", "bezier() takes at least 3 arguments, found 2");
    one_error("point A, B\nM = meet(line(A, B))\n", 2, "M = meet(line(A, B))",
              5, "meet(line(A, B))", "meet() takes 2 arguments, found 1");
}

/* ---- kinds ------------------------------------------------------------- */

static void test_point_where_scalar_expected(void **state)
{
    (void)state;
    one_error("point A, B\nx = sin(A)\n", 2, "x = sin(A)", 9, "A",
              "expected a scalar as the argument of sin(), but 'A' is a base "
              "point");
    one_error("point A, B\nx = sin(A + B)\n", 2, "x = sin(A + B)", 9, "A + B",
              "expected a scalar as the argument of sin(), found a point or "
              "vector");
    one_error("point A, B\nM = along(A, B, A)\n", 2, "M = along(A, B, A)", 17,
              "A", "expected a scalar as the ratio, but 'A' is a base point");
    one_error("point A, B\nM = divide(A, B, B - A)\n", 2,
              "M = divide(A, B, B - A)", 18, "B - A",
              "expected a scalar as the simple ratio, found a point or "
              "vector");
    one_error("point A, B\nM = bezier(A, A, B)\n", 2, "M = bezier(A, A, B)", 12,
              "A",
              "expected a scalar as the parameter of bezier(), but 'A' is a "
              "base point");
    one_error("point A, B\nx = 2^A\n", 2, "x = 2^A", 7, "A",
              "expected a scalar exponent");
    one_error("point A, B\nM = A/B\n", 2, "M = A/B", 7, "B",
              "cannot divide by a point or vector; expected a scalar divisor");
    one_error("point A, B\nM = A^2\n", 2, "M = A^2", 5, "A",
              "cannot raise a point or vector to a power; expected a scalar "
              "base");
}

static void test_scalar_where_point_expected(void **state)
{
    (void)state;
    one_error("point A, B\nparam t\nM = along(t, B, 1)\n", 3,
              "M = along(t, B, 1)", 11, "t",
              "expected a point or vector as the first point, but 't' is a "
              "parameter");
    one_error("point A, B\nconst k\nM = divide(A, 2*k, k)\n", 3,
              "M = divide(A, 2*k, k)", 15, "2*k",
              "expected a point or vector as the second point, found a "
              "scalar");
    one_error("point A, B\nparam t\nX = bezier(t, A, t)\n", 3,
              "X = bezier(t, A, t)", 18, "t",
              "expected a point or vector as a control point, but 't' is a "
              "parameter");
    one_error("point A, B\nparam t\nx = dot(B - A, t)\n", 3,
              "x = dot(B - A, t)", 16, "t",
              "expected a point or vector as argument 2 of dot(), but 't' is "
              "a parameter");
    one_error("point A, B\nx = angle(A, 1, B)\n", 2, "x = angle(A, 1, B)", 14,
              "1",
              "expected a point or vector as argument 2 of angle(), found a "
              "scalar");
    one_error("point A, B\nparam t\nx = coord(t, 1)\n", 3, "x = coord(t, 1)",
              11, "t",
              "expected a point or vector as the first argument of coord(), "
              "but 't' is a parameter");
}

static void test_operator_kinds(void **state)
{
    (void)state;
    one_error("point A\nparam t\nM = A + t\n", 3, "M = A + t", 5, "A + t",
              "cannot add a scalar and a point: expected both sides to be "
              "scalars or both points/vectors");
    one_error("point A\nparam t\nM = t - A\n", 3, "M = t - A", 5, "t - A",
              "cannot subtract a scalar and a point: expected both sides to "
              "be scalars or both points/vectors");
    one_error("point A, B\nM = A*B\n", 2, "M = A*B", 5, "A*B",
              "cannot multiply two points or vectors; expected a scalar on "
              "one side");
    /* the errors of both sides are all reported */
    int n;
    char *s = sema_errors("point A, B\nx = sin(A) + cos(B)\n", &n);
    assert_int_equal(n, 2);
    char want[CAP] = "";
    diag_at(want, CAP, "error", 2, "x = sin(A) + cos(B)", 9, "A",
            "expected a scalar as the argument of sin(), but 'A' is a base "
            "point");
    diag_at(want, CAP, "error", 2, "x = sin(A) + cos(B)", 18, "B",
            "expected a scalar as the argument of cos(), but 'B' is a base "
            "point");
    assert_string_equal(s, want);
    free(s);
}

/* ---- meet, subst, diff, coord ------------------------------------------ */

static void test_meet_and_flats(void **state)
{
    (void)state;
    one_error("point A, B, C\nM = meet(A, line(B, C))\n", 2,
              "M = meet(A, line(B, C))", 10, "A",
              "expected 'line(P, Q)' as the first argument of meet()");
    one_error("point A, B, C\nM = meet(plane(A, B, C), line(A, B))\n", 2,
              "M = meet(plane(A, B, C), line(A, B))", 10, "plane(A, B, C)",
              "expected 'line(P, Q)' as the first argument of meet(); write "
              "the plane second: meet(line(P, Q), plane(R, S, U))");
    one_error("point A, B, C\nM = meet(line(A, B), C)\n", 2,
              "M = meet(line(A, B), C)", 22, "C",
              "expected 'line(P, Q)' or 'plane(R, S, U)' as the second "
              "argument of meet()");
    one_error("point A, B, C\nM = meet(line(A), line(B, C))\n", 2,
              "M = meet(line(A), line(B, C))", 10, "line(A)",
              "line() takes 2 points, found 1");
    one_error("point A, B, C\nM = meet(line(A, B), plane(A, B))\n", 2,
              "M = meet(line(A, B), plane(A, B))", 22, "plane(A, B)",
              "plane() takes 3 points, found 2");
    one_error("point A, B, C\nparam t\nM = meet(line(A, t), line(B, C))\n", 3,
              "M = meet(line(A, t), line(B, C))", 18, "t",
              "expected a point or vector as a point of the line, but 't' is "
              "a parameter");
    one_error("point A, B, C\nM = meet(line(A, B), plane(A, B, 1))\n", 2,
              "M = meet(line(A, B), plane(A, B, 1))", 34, "1",
              "expected a point or vector as a point of the plane, found a "
              "scalar");
    one_error("point A, B\nM = line(A, B)\n", 2, "M = line(A, B)", 5,
              "line(A, B)",
              "line() is only meaningful inside meet(); expected "
              "meet(line(P, Q), line(R, S))");
    one_error("point A, B, C\nM = plane(A, B, C)\n", 2, "M = plane(A, B, C)", 5,
              "plane(A, B, C)",
              "plane() is only meaningful inside meet(); expected "
              "meet(line(P, Q), line(R, S))");
}

static void test_subst_errors(void **state)
{
    (void)state;
    one_error("point A\nparam t\nx = subst(t, 2, 1)\n", 3, "x = subst(t, 2, 1)",
              14, "2",
              "expected the name of a parameter, constant or base point to "
              "replace");
    one_error("point A\nparam t\nx = subst(t, q, 1)\n", 3, "x = subst(t, q, 1)",
              14, "q", "undefined name 'q'");
    one_error("point A, B\nparam t\nM = subst(A, A, t)\n", 3,
              "M = subst(A, A, t)", 17, "t",
              "expected a point or vector as the replacement of a base "
              "point, but 't' is a parameter");
    one_error("point A, B\nparam t\nx = subst(t, t, A)\n", 3,
              "x = subst(t, t, A)", 17, "A",
              "expected a scalar as the value substituted, but 'A' is a base "
              "point");
    one_error("point A, B\nM = A\nN = subst(M, M, B)\n", 3,
              "N = subst(M, M, B)", 14, "M",
              "subst() replaces a parameter, a constant, a base point or an "
              "unknown, but 'M' is a definition");
}

static void test_diff_errors(void **state)
{
    (void)state;
    one_error("point A\nparam t\nx = diff(t, A)\n", 3, "x = diff(t, A)", 13,
              "A",
              "expected the name of a parameter or constant to differentiate "
              "by");
    one_error("point A\nparam t\nx = diff(t, 2*t)\n", 3, "x = diff(t, 2*t)", 13,
              "2*t",
              "expected the name of a parameter or constant to differentiate "
              "by");
    one_error("point A\nparam t\nx = diff(t, t, 31)\n", 3, "x = diff(t, t, 31)",
              16, "31",
              "expected the order of the derivative as a whole number from 0 "
              "to 30");
    one_error("point A\nparam t\nx = diff(t, t, 1.5)\n", 3,
              "x = diff(t, t, 1.5)", 16, "1.5",
              "expected the order of the derivative as a whole number from 0 "
              "to 30");
    one_error("point A\nparam t\nx = diff(t, t, 100)\n", 3,
              "x = diff(t, t, 100)", 16, "100",
              "expected the order of the derivative as a whole number from 0 "
              "to 30");
    /* the bounds themselves are fine */
    int n;
    char *s = sema_errors("point A\nparam t\nconst k\nx = diff(t, t, 30)\n"
                          "y = diff(t, k, 0)\n",
                          &n);
    assert_int_equal(n, 0);
    assert_string_equal(s, "");
    free(s);
}

static void test_coord_errors(void **state)
{
    (void)state;
    one_error("point A\nx = coord(A, 0)\n", 2, "x = coord(A, 0)", 14, "0",
              "coordinates are numbered from 1 (coord(P, 1) is the first), "
              "so there is no coordinate 0");
    one_error("point A\nx = coord(A, 2 - 5)\n", 2, "x = coord(A, 2 - 5)", 14,
              "2 - 5",
              "coordinates are numbered from 1 (coord(P, 1) is the first), "
              "so there is no coordinate -3");
    one_error("point A\nparam t\nx = coord(A, t)\n", 3, "x = coord(A, t)", 14,
              "t",
              "expected the number of a coordinate: a whole number from 1 to "
              "1000000, of literals and int constants");
    one_error("point A\nx = coord(A, 1000001)\n", 2, "x = coord(A, 1000001)",
              14, "1000001",
              "expected the number of a coordinate: a whole number from 1 to "
              "1000000, of literals and int constants");
    one_error("point A\nx = coord(A, 1.5)\n", 2, "x = coord(A, 1.5)", 14, "1.5",
              "expected the number of a coordinate: a whole number from 1 to "
              "1000000, of literals and int constants");
    /* the largest coordinate is fine, and so is an int constant */
    int n;
    char *s = sema_errors("int d = 1000000\npoint A\nx = coord(A, d)\n", &n);
    assert_int_equal(n, 0);
    free(s);
}

/* ---- declarations' ranges and bounds ----------------------------------- */

static void test_range_and_bound_errors(void **state)
{
    (void)state;
    Checked c;
    check(&c, "point A\nparam t in [A, 1]\nM = A\n");
    assert_int_equal(c.d.nerrors, 1);
    assert_int_equal(c.s->stmts->next->bad, 1);
    checked_free(&c);
    one_error("point A\nparam t in [A, 1]\nM = A\n", 2, "param t in [A, 1]", 13,
              "A",
              "expected a scalar as the lower end of the range, but 'A' is a "
              "base point");
    one_error("point A\nparam t in [0, A]\nM = A\n", 2, "param t in [0, A]", 16,
              "A",
              "expected a scalar as the upper end of the range, but 'A' is a "
              "base point");
    one_error("point A\nconst k > A\nM = A\n", 2, "const k > A", 11, "A",
              "expected a scalar as the lower bound, but 'A' is a base point");
    one_error("point A\nconst k < A\nM = A\n", 2, "const k < A", 11, "A",
              "expected a scalar as the upper bound, but 'A' is a base point");
    one_error("point A\nconst k in (0, q)\nM = A\n", 2, "const k in (0, q)", 16,
              "q",
              "undefined name 'q'; expected a declared point, parameter, "
              "constant or an earlier definition");
}

/* ---- solve ------------------------------------------------------------- */

static void test_solve_errors(void **state)
{
    (void)state;
    one_error("point A\nparam t\nunknown X\nsolve X = t for X\n", 4,
              "solve X = t for X", 7, "X = t",
              "cannot equate a point or vector and a scalar; expected both "
              "sides to be points or vectors");
    one_error("point A\nparam t\nunknown X\nsolve t = 1 for X\n", 4,
              "solve t = 1 for X", 7, "t = 1",
              "a scalar equation cannot determine unknown points; expected an "
              "equation between points or vectors, or an unknown scalar "
              "(unknown scalar k) to solve for");
    one_error("point A\nunknown X\nsolve X = A for Y\n", 3, "solve X = A for Y",
              17, "Y",
              "undefined name 'Y' after 'for'; expected an unknown declared "
              "with 'unknown Y'");
    one_error("point A\nunknown X\nsolve X = A for A\n", 3, "solve X = A for A",
              17, "A",
              "'A' is a base point; expected an unknown (declared with "
              "'unknown') after 'for'");
    one_error("point A, B\nunknown X\nsolve X = A, X = B for X, X\n", 3,
              "solve X = A, X = B for X, X", 27, "X", "'X' is listed twice");
    one_error("point A, B\nunknown X, Y\nsolve X = A for X, Y\n", 3,
              "solve X = A for X, Y", 1, "solve X = A for X, Y",
              "1 equation for 2 unknowns: the system is underdetermined; "
              "expected one point equation per unknown point");
    one_error("point A, B\nunknown X\nsolve X = A, X = B for X\n", 3,
              "solve X = A, X = B for X", 1, "solve X = A, X = B for X",
              "2 equations for 1 unknown: the system is over-determined; "
              "expected one point equation per unknown point");
    /* with an unknown scalar, the counts are left to the rank */
    int n;
    char *s = sema_errors("point A, B\nunknown X\nunknown scalar k\n"
                          "solve X = A, X = along(A, B, k) for X, k\n"
                          "output X\n",
                          &n);
    assert_int_equal(n, 0);
    free(s);
}

static void test_solved_twice(void **state)
{
    (void)state;
    const char *text = "point A, B\nunknown X\nsolve X = A for X\n"
                       "solve X = B for X\noutput X\n";
    char want[CAP] = "";
    diag_at(want, CAP, "error", 4, "solve X = B for X", 17, "X",
            "the unknown 'X' is solved twice");
    diag_at(want, CAP, "note", 3, "solve X = A for X", 1, "solve X = A for X",
            "'X' was first solved here");
    Checked c;
    check(&c, text);
    fclose(c.mem);
    c.mem = NULL;
    assert_int_equal(c.d.nerrors, 1);
    assert_string_equal(c.out, want);
    /* the first solve stands, the second is bad */
    Stmt *first = c.I->steps[0], *second = c.I->steps[1];
    assert_int_equal(first->bad, 0);
    assert_int_equal(second->bad, 1);
    assert_ptr_equal(c.I->unknowns[0]->solved_by, first);
    source_clear(&c.src);
    arena_reset(&c.a);
    free(c.out);
}

static void test_bad_solve_solves_nothing(void **state)
{
    (void)state;
    const char *text = "point A\nparam t\nunknown X\nsolve X = t for X\n"
                       "output X\n";
    char want[CAP] = "";
    diag_at(want, CAP, "error", 4, "solve X = t for X", 7, "X = t",
            "cannot equate a point or vector and a scalar; expected both "
            "sides to be points or vectors");
    diag_at(want, CAP, "error", 5, "output X", 8, "X",
            "the unknown 'X' is never solved; expected 'solve ... for X' "
            "before it is output");
    int n;
    char *s = sema_errors(text, &n);
    assert_int_equal(n, 2);
    assert_string_equal(s, want);
    free(s);
}

/* ---- output, scheme ---------------------------------------------------- */

static void test_output_errors(void **state)
{
    (void)state;
    one_error("point A\nM = A\noutput Q\n", 3, "output Q", 8, "Q",
              "undefined name 'Q' in output; expected a definition");
    one_error("point A\nM = A\noutput A\n", 3, "output A", 8, "A",
              "'A' is a base point; expected a definition (NAME = EXPR) or a "
              "solved unknown in output");
    one_error("point A\nparam t\nM = A\noutput M, t\n", 4, "output M, t", 11,
              "t",
              "'t' is a parameter; expected a definition (NAME = EXPR) or a "
              "solved unknown in output");
    one_error("point A\nunknown X\nM = A\noutput X\n", 4, "output X", 8, "X",
              "the unknown 'X' is never solved; expected 'solve ... for X' "
              "before it is output");
    one_error("point A\nM = A\noutput M, M\n", 3, "output M, M", 11, "M",
              "'M' is listed twice");
    one_error("point A\nM = A\noutput M\noutput M\n", 4, "output M", 1,
              "output M",
              "a second 'output' statement; expected one 'output' listing "
              "every name");
}

static void test_defines_nothing(void **state)
{
    (void)state;
    /* at the end of the last statement */
    one_error("point A, B\n", 1, "point A, B", 11, "",
              "the scheme defines nothing; expected a definition 'NAME = "
              "EXPR' to output");
    one_error("point A, B\nparam t\n\n", 2, "param t", 8, "",
              "the scheme defines nothing; expected a definition 'NAME = "
              "EXPR' to output");
    /* not when another error was reported */
    int n;
    char *s = sema_errors("point A, A\n", &n);
    assert_int_equal(n, 1);
    assert_null(strstr(s, "defines nothing"));
    free(s);
}

static void test_second_scheme(void **state)
{
    (void)state;
    char want[CAP] = "";
    diag_at(want, CAP, "error", 2, "scheme b", 1, "scheme b",
            "a second 'scheme' statement");
    diag_at(want, CAP, "note", 1, "scheme a", 1, "scheme a",
            "the scheme was named here");
    Checked c;
    check(&c, "scheme a\nscheme b\npoint A\nM = A\n");
    fclose(c.mem);
    assert_int_equal(c.d.nerrors, 1);
    assert_string_equal(c.out, want);
    assert_string_equal(c.I->scheme_name, "a");
    source_clear(&c.src);
    arena_reset(&c.a);
    free(c.out);
}

/* ---- depth ------------------------------------------------------------- */

/* "point A\nx = 1+1+...+1\n" with n ones: a left-deep tree of height n */
static char *sum_of_ones(int n)
{
    char *t = malloc((size_t)(2 * n + 32));
    strcpy(t, "point A\nx = 1");
    size_t k = strlen(t);
    for (int i = 1; i < n; i++) {
        t[k++] = '+';
        t[k++] = '1';
    }
    strcpy(t + k, "\n");
    return t;
}

static void test_depth_bound(void **state)
{
    (void)state;
    char *t = sum_of_ones(SEMA_MAX_DEPTH);
    int n;
    char *s = sema_errors(t, &n);
    assert_int_equal(n, 0);
    free(s);
    free(t);

    t = sum_of_ones(SEMA_MAX_DEPTH + 1);
    s = sema_errors(t, &n);
    assert_int_equal(n, 1);
    const char *head = "x.pcs:2:5: error: expression nested too deeply (2001 "
                       "levels; at most 2000): split it into several "
                       "definitions\n";
    assert_true(strncmp(s, head, strlen(head)) == 0);
    free(s);
    free(t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_info_declarations),
        cmocka_unit_test(test_info_expression_kinds),
        cmocka_unit_test(test_builtins_resolved),
        cmocka_unit_test(test_outputs_may_name_later_definitions),
        cmocka_unit_test(test_families_reach_sema_as_members),
        cmocka_unit_test(test_undefined_names),
        cmocka_unit_test(test_bad_definition_not_reported_again),
        cmocka_unit_test(test_redefinitions),
        cmocka_unit_test(test_built_in_names),
        cmocka_unit_test(test_functions_as_names),
        cmocka_unit_test(test_arity),
        cmocka_unit_test(test_point_where_scalar_expected),
        cmocka_unit_test(test_scalar_where_point_expected),
        cmocka_unit_test(test_operator_kinds),
        cmocka_unit_test(test_meet_and_flats),
        cmocka_unit_test(test_subst_errors),
        cmocka_unit_test(test_diff_errors),
        cmocka_unit_test(test_coord_errors),
        cmocka_unit_test(test_range_and_bound_errors),
        cmocka_unit_test(test_solve_errors),
        cmocka_unit_test(test_solved_twice),
        cmocka_unit_test(test_bad_solve_solves_nothing),
        cmocka_unit_test(test_output_errors),
        cmocka_unit_test(test_defines_nothing),
        cmocka_unit_test(test_second_scheme),
        cmocka_unit_test(test_depth_bound),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

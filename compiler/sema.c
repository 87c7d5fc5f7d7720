/*
 * sema.c - names, kinds and arity.
 *
 * Kinds here are static: an expression is either a scalar (a rational
 * function of the params and consts) or a combination of points (a point
 * equation, whatever its weight sum).  Whether a combination is a point, a
 * vector or an error depends on its weight sum, which compiler/derive/
 * computes.
 */
#include "compiler/sema.h"

#include <stdio.h>

#include <stdlib.h>
#include <string.h>

#include "base/check.h"
#include "base/stack.h"
#include "compiler/check.h"

typedef struct Builtin_info {
    const char *name;
    int min_args, max_args;
    int result; // 1 combination, 0 scalar, -1 as its first argument
} BuiltinInfo;

static const BuiltinInfo builtins[BI_COUNT] = {
#define X(id, name, lo, hi, res) [id] = {name, lo, hi, res},
    PC_BUILTINS(X)
#undef X
#define PC_FUNCTION(ID, name, ar, lang, k, p, c, latex, dom)                   \
    PC_WHEN(lang)([BI_##ID] = {name, ar, ar, 0}, )
#include "base/functions.def"
#undef PC_FUNCTION
};

enum { NBUCKETS = 64 };

typedef struct Sema {
    Arena *arena;
    Diag *diag;
    Sym *table[NBUCKETS];
    SemaInfo *info;
    int cap_points, cap_params, cap_consts, cap_defs, cap_unknowns, cap_steps;
} Sema;

static unsigned hash(const char *s)
{
    unsigned h = 5381;
    while (*s)
        h = h * 33 + (unsigned char)*s++;
    return h % NBUCKETS;
}

static Sym *lookup(Sema *S, const char *name)
{
    for (Sym *s = S->table[hash(name)]; s; s = s->next)
        if (strcmp(s->name, name) == 0)
            return s;
    return NULL;
}

static const char *sym_kind_word(SymKind k)
{
    switch (k) {
    case SYM_POINT:
        return "a base point";
    case SYM_PARAM:
        return "a parameter";
    case SYM_CONST:
        return "a constant";
    case SYM_UNKNOWN:
        return "an unknown";
    case SYM_DEF:
        return "a definition";
    }
    return "?";
}

/* grows an arena array of Sym * (old contents are copied; the arena keeps
 * the old block, which is fine for the sizes of a scheme) */
static void push(Sema *S, Sym ***arr, int *n, int *cap, Sym *s)
{
    if (*n == *cap) {
        int nc = *cap ? 2 * *cap : 8;
        Sym **na = arena_alloc(S->arena, sizeof(Sym *) * (size_t)nc);
        if (*n)
            memcpy(na, *arr, sizeof(Sym *) * (size_t)*n);
        *arr = na;
        *cap = nc;
    }
    (*arr)[(*n)++] = s;
}

int sema_is_builtin(const char *name)
{
    for (int b = 0; b < BI_COUNT; b++)
        if (strcmp(builtins[b].name, name) == 0)
            return 1;
    return 0;
}

/* the step blocks (ramp, step, rayr, rayl: docs/language.md "Step
 * functions") are functions only in the call form: a scheme may still
 * name a point or a definition `step` or `ramp` */
static int is_soft_builtin(int b)
{
    return b == BI_RAMP || b == BI_STEP || b == BI_RAYR || b == BI_RAYL;
}

static int is_reserved(const char *name)
{
    if (strcmp(name, "pi") == 0)
        return 1;
    for (int b = 0; b < BI_COUNT; b++)
        if (!is_soft_builtin(b) && strcmp(builtins[b].name, name) == 0)
            return 1;
    return 0;
}

static Sym *declare(Sema *S, const char *name, Span span, SymKind kind)
{
    Sym *old = lookup(S, name);
    if (old) {
        diag_error(S->diag, span, "redefinition of '%s'", name);
        diag_note(S->diag, old->span, "'%s' was first declared here as %s",
                  name, sym_kind_word(old->kind));
        return NULL;
    }
    if (is_reserved(name)) {
        diag_error(S->diag, span,
                   "'%s' is a built-in name; choose another name", name);
        return NULL;
    }
    Sym *s = arena_new(S->arena, Sym);
    s->name = name;
    s->kind = kind;
    s->span = span;
    unsigned h = hash(name);
    s->next = S->table[h];
    S->table[h] = s;
    return s;
}

static int check_expr(Sema *S, Node *n);

/* a definition or a solve, in source order */
static void push_step(Sema *S, Stmt *st)
{
    SemaInfo *I = S->info;
    if (I->nsteps == S->cap_steps) {
        int nc = S->cap_steps ? 2 * S->cap_steps : 8;
        Stmt **na = arena_alloc(S->arena, sizeof(Stmt *) * (size_t)nc);
        if (I->nsteps)
            memcpy(na, I->steps, sizeof(Stmt *) * (size_t)I->nsteps);
        I->steps = na;
        S->cap_steps = nc;
    }
    I->steps[I->nsteps++] = st;
}

/* the kind of a name used in an expression: 1 point, 0 scalar, -1 error */
static int check_name(Sema *S, Node *n)
{
    Sym *s = lookup(S, n->text);
    if (!s && strcmp(n->text, "pi") == 0) {
        /* the constant pi (a built-in name: no scheme declares its own) */
        n->kind = ND_CALL;
        n->builtin = BI_PI;
        n->args = NULL;
        n->nargs = 0;
        n->name_span = n->span;
        return 0;
    }
    if (!s) {
        for (int b = 0; b < BI_COUNT; b++)
            if (strcmp(builtins[b].name, n->text) == 0) {
                diag_error(S->diag, n->span,
                           "'%s' is a function; expected '%s(' with its "
                           "arguments",
                           n->text, n->text);
                return -1;
            }
        diag_error(S->diag, n->span,
                   "undefined name '%s'; expected a declared point, "
                   "parameter, constant or an earlier definition",
                   n->text);
        return -1;
    }
    n->sym = s;
    switch (s->kind) {
    case SYM_POINT:
        return 1;
    case SYM_PARAM:
    case SYM_CONST:
        return 0;
    case SYM_UNKNOWN: /* free until its solve, then its solution */
        return s->is_point;
    case SYM_DEF:
        return s->bad ? -1 : s->is_point;
    }
    return -1;
}

static const char *kind_word(int k)
{
    return k ? "a point or vector" : "a scalar";
}

/* expects kind `want` (1 combination, 0 scalar) of argument n */
static int expect(Sema *S, Node *n, int want, const char *what)
{
    int k = check_expr(S, n);
    if (k < 0)
        return -1;
    if (k != want) {
        if (n->kind == ND_NAME && n->sym)
            diag_error(S->diag, n->span, "expected %s as %s, but '%s' is %s",
                       kind_word(want), what, n->text,
                       sym_kind_word(n->sym->kind));
        else
            diag_error(S->diag, n->span, "expected %s as %s, found %s",
                       kind_word(want), what, kind_word(k));
        return -1;
    }
    return k;
}

/* the Nth argument (0-based) */
static Node *arg(Node *call, int i)
{
    Node *a = call->args;
    while (a && i-- > 0)
        a = a->next;
    return a;
}

/* a flat inside meet(): line(P, Q) or plane(R, S, U) */
static int check_flat(Sema *S, Node *n, int allow_plane)
{
    if (n->kind != ND_CALL ||
        (strcmp(n->text, "line") != 0 && strcmp(n->text, "plane") != 0)) {
        diag_error(S->diag, n->span,
                   allow_plane ? "expected 'line(P, Q)' or 'plane(R, S, U)' "
                                 "as the second argument of meet()"
                               : "expected 'line(P, Q)' as the first "
                                 "argument of meet()");
        return -1;
    }
    int is_line = strcmp(n->text, "line") == 0;
    if (!is_line && !allow_plane) {
        diag_error(S->diag, n->span,
                   "expected 'line(P, Q)' as the first argument of meet(); "
                   "write the plane second: meet(line(P, Q), plane(R, S, U))");
        return -1;
    }
    n->builtin = is_line ? BI_LINE : BI_PLANE;
    int want = is_line ? 2 : 3;
    if (n->nargs != want) {
        diag_error(S->diag, n->span, "%s() takes %d points, found %d", n->text,
                   want, n->nargs);
        return -1;
    }
    int ok = 0;
    for (Node *a = n->args; a; a = a->next)
        if (expect(S, a, 1,
                   is_line ? "a point of the line" : "a point of the plane") <
            0)
            ok = -1;
    n->is_point = 1;
    return ok;
}

/* *v = the value of n, a whole-number expression: literals (int
 * constants and comprehension variables are literals after expand.c),
 * unary minus, + - *; 0 when it is not one or leaves [-2^40, 2^40] */
/* n, a whole-number expression of value v, made the literal v: derive
 * reads the coordinate of coord() and the smoothness of step() as one */
static void fold_literal(Sema *S, Node *n, long long v)
{
    if (n->kind == ND_NUM)
        return;
    char buf[24];
    snprintf(buf, sizeof buf, "%lld", v);
    n->kind = ND_NUM;
    n->text = arena_strdup(S->arena, buf);
    n->lhs = n->rhs = NULL;
}

static int whole_number(const Node *n, long long *v)
{
    const long long lim = 1LL << 40;
    long long a, b;
    switch (n->kind) {
    case ND_NUM:
        if (strspn(n->text, "0123456789") != strlen(n->text) ||
            strlen(n->text) > 12)
            return 0;
        *v = atoll(n->text);
        break;
    case ND_NEG:
        if (!whole_number(n->lhs, &a))
            return 0;
        *v = -a;
        break;
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
        if (!whole_number(n->lhs, &a) || !whole_number(n->rhs, &b))
            return 0;
        if (n->kind == ND_MUL && a != 0 && llabs(b) > lim / llabs(a))
            return 0; /* |a*b| > 2^40, and it could overflow */
        *v = n->kind == ND_ADD ? a + b : n->kind == ND_SUB ? a - b : a * b;
        break;
    default:
        return 0;
    }
    return *v >= -lim && *v <= lim;
}

/* coord(P, k): P a point or vector, k a whole number 1 .. SEMA_MAX_COORD
 * (a whole-number expression of literals and int constants); sema leaves
 * k as one literal, the number derive reads */
static int check_coord(Sema *S, Node *n)
{
    int ok = expect(S, arg(n, 0), 1, "the first argument of coord()");
    Node *k = arg(n, 1);
    long long v = 0;
    int whole = whole_number(k, &v);
    if (whole && v < 1) {
        diag_error(S->diag, k->span,
                   "coordinates are numbered from 1 (coord(P, 1) is the "
                   "first), so there is no coordinate %lld",
                   v);
        return -1;
    }
    if (!whole || v > SEMA_MAX_COORD) {
        diag_error(S->diag, k->span,
                   "expected the number of a coordinate: a whole number "
                   "from 1 to %d, of literals and int constants",
                   SEMA_MAX_COORD);
        return -1;
    }
    fold_literal(S, k, v); /* coord(P[i], i + 1) in a comprehension */
    return ok < 0 ? -1 : 0;
}

/* the builtin that call n names, and its arity checked (n->builtin set):
 * the builtin, or -1 reported */
static int find_builtin(Sema *S, Node *n)
{
    int b;
    for (b = 0; b < BI_COUNT; b++)
        if (strcmp(builtins[b].name, n->text) == 0)
            break;
    if (b == BI_COUNT) {
        Sym *s = lookup(S, n->text);
        if (s)
            diag_error(S->diag, n->name_span, "'%s' is %s, not a function",
                       n->text, sym_kind_word(s->kind));
        else
            diag_error(S->diag, n->name_span,
                       "unknown function '%s'; expected along, divide, meet, "
                       "subst, diff, bezier or a scalar function",
                       n->text);
        return -1;
    }
    if (b == BI_PI && n->builtin != BI_PI) { /* (not a pi typed before) */
        diag_error(S->diag, n->name_span,
                   "'pi' is a constant, not a function; write pi without "
                   "parentheses");
        return -1;
    }
    n->builtin = b;
    const BuiltinInfo *bi = &builtins[b];
    if (n->nargs < bi->min_args ||
        (bi->max_args >= 0 && n->nargs > bi->max_args)) {
        if (bi->max_args < 0)
            diag_error(S->diag, n->span,
                       "%s() takes at least %d arguments, found %d", bi->name,
                       bi->min_args, n->nargs);
        else if (bi->min_args == bi->max_args)
            diag_error(S->diag, n->span, "%s() takes %d argument%s, found %d",
                       bi->name, bi->min_args, bi->min_args == 1 ? "" : "s",
                       n->nargs);
        else
            diag_error(S->diag, n->span,
                       "%s() takes %d to %d arguments, found %d", bi->name,
                       bi->min_args, bi->max_args, n->nargs);
        return -1;
    }
    return b;
}

/* subst(E, x, by): x a param, const, base point or unknown, by of its
 * kind; the kind of E, or -1 reported */
static int check_subst(Sema *S, Node *n)
{
    int k = check_expr(S, arg(n, 0));
    Node *x = arg(n, 1);
    if (x->kind != ND_NAME) {
        diag_error(S->diag, x->span,
                   "expected the name of a parameter, constant or base "
                   "point to replace");
        return -1;
    }
    Sym *s = lookup(S, x->text);
    if (!s) {
        diag_error(S->diag, x->span, "undefined name '%s'", x->text);
        return -1;
    }
    x->sym = s;
    if (s->kind == SYM_POINT || (s->kind == SYM_UNKNOWN && s->is_point)) {
        if (expect(S, arg(n, 2), 1, "the replacement of a base point") < 0)
            return -1;
    } else if (s->kind == SYM_PARAM || s->kind == SYM_CONST ||
               s->kind == SYM_UNKNOWN) {
        if (expect(S, arg(n, 2), 0, "the value substituted") < 0)
            return -1;
    } else {
        diag_error(S->diag, x->span,
                   "subst() replaces a parameter, a constant, a base "
                   "point or an unknown, but '%s' is %s",
                   x->text, sym_kind_word(s->kind));
        return -1;
    }
    return k;
}

/* diff(E, t[, n]): t a param or const, n a whole number from 0 to 30;
 * the kind of E, or -1 reported */
static int check_diff(Sema *S, Node *n)
{
    int k = check_expr(S, arg(n, 0));
    Node *x = arg(n, 1);
    if (x->kind != ND_NAME || !lookup(S, x->text) ||
        (lookup(S, x->text)->kind != SYM_PARAM &&
         lookup(S, x->text)->kind != SYM_CONST)) {
        diag_error(S->diag, x->span,
                   "expected the name of a parameter or constant to "
                   "differentiate by");
        return -1;
    }
    x->sym = lookup(S, x->text);
    Node *order = arg(n, 2);
    if (order) {
        int okn = order->kind == ND_NUM;
        for (const char *c = okn ? order->text : ""; *c; c++)
            if (*c < '0' || *c > '9')
                okn = 0;
        if (!okn || strlen(order->text) > 2 || atoi(order->text) > 30) {
            diag_error(S->diag, order->span,
                       "expected the order of the derivative as a whole "
                       "number from 0 to 30");
            return -1;
        }
    }
    return k;
}

static int check_call(Sema *S, Node *n)
{
    int b = find_builtin(S, n);
    if (b < 0)
        return -1;
    const BuiltinInfo *bi = &builtins[b];
    int ok = 0;
    switch ((Builtin)b) {
    case BI_ALONG:
    case BI_DIVIDE:
        if (expect(S, arg(n, 0), 1, "the first point") < 0)
            ok = -1;
        if (expect(S, arg(n, 1), 1, "the second point") < 0)
            ok = -1;
        if (expect(S, arg(n, 2), 0,
                   b == BI_ALONG ? "the ratio" : "the simple ratio") < 0)
            ok = -1;
        return ok < 0 ? -1 : 1;
    case BI_MEET:
        if (check_flat(S, arg(n, 0), 0) < 0)
            ok = -1;
        if (check_flat(S, arg(n, 1), 1) < 0)
            ok = -1;
        return ok < 0 ? -1 : 1;
    case BI_LINE:
    case BI_PLANE:
        diag_error(S->diag, n->span,
                   "%s() is only meaningful inside meet(); expected "
                   "meet(line(P, Q), line(R, S))",
                   bi->name);
        return -1;
    case BI_SUBST:
        return check_subst(S, n);
    case BI_DIFF:
        return check_diff(S, n);
    case BI_BEZIER: {
        if (expect(S, arg(n, 0), 0, "the parameter of bezier()") < 0)
            ok = -1;
        for (Node *a = arg(n, 1); a; a = a->next)
            if (expect(S, a, 1, "a control point") < 0)
                ok = -1;
        return ok < 0 ? -1 : 1;
    }
    case BI_DOT:
    case BI_DIST:
    case BI_ANGLE: { /* metric scalars of points and vectors */
        char what[64];
        int i = 0;
        for (Node *a = n->args; a; a = a->next, i++) {
            snprintf(what, sizeof what, "argument %d of %s()", i + 1, bi->name);
            if (expect(S, a, 1, what) < 0)
                ok = -1;
        }
        return ok < 0 ? -1 : 0;
    }
    case BI_COORD:
        return check_coord(S, n);
    case BI_STEP: { /* step(t, a, w, m): m a whole number 0 .. 10 */
        for (int i = 0; i < 3; i++)
            if (expect(S, arg(n, i), 0,
                       i == 0   ? "the argument of step()"
                       : i == 1 ? "the start of step()"
                                : "the width of step()") < 0)
                ok = -1;
        Node *m = arg(n, 3);
        long long v = 0;
        if (!whole_number(m, &v) || v < 0 || v > SEMA_MAX_STEP_ORDER) {
            diag_error(S->diag, m->span,
                       "expected the smoothness of step() as a whole number "
                       "from 0 to %d (of literals and int constants): "
                       "step(t, a, w, m) is C^m",
                       SEMA_MAX_STEP_ORDER);
            return -1;
        }
        fold_literal(S, m, v); /* derive reads one literal */
        return ok < 0 ? -1 : 0;
    }
    default: { /* the scalar functions */
        char what[64];
        for (Node *a = n->args; a; a = a->next) {
            snprintf(what, sizeof what, "the argument of %s()", bi->name);
            if (expect(S, a, 0, what) < 0)
                ok = -1;
        }
        return ok < 0 ? -1 : 0;
    }
    }
    return -1;
}

static int check_node(Sema *S, Node *n);

/* returns 1 combination, 0 scalar, -1 error (already reported); the
 * errors inside a user function's expansion are followed by a note at its
 * call */
static int check_expr(Sema *S, Node *n)
{
    if (!n->call_site)
        return check_node(S, n);
    diag_push_context(S->diag, n->call_site->span, n->call_site->text);
    int k = check_node(S, n);
    diag_pop_context(S->diag);
    return k;
}

static int check_node(Sema *S, Node *n)
{
    int k = -1;
    if (stack_low()) {
        diag_error(S->diag, n->span, STACK_MESSAGE);
        return -1;
    }
    /* every later pass recurses over the tree: bound its height here, at
     * the root, before any recursion (a sum of 20000 terms is a left-deep
     * tree of that height) */
    if (n->depth > SEMA_MAX_DEPTH) {
        diag_error(S->diag, n->span,
                   "expression nested too deeply (%d levels; at most %d): "
                   "split it into several definitions",
                   n->depth, SEMA_MAX_DEPTH);
        return -1;
    }
    switch (n->kind) {
    case ND_NUM:
        k = 0;
        break;
    case ND_NAME:
        k = check_name(S, n);
        break;
    case ND_NEG:
        k = check_expr(S, n->lhs);
        break;
    case ND_ADD:
    case ND_SUB: {
        int a = check_expr(S, n->lhs), b = check_expr(S, n->rhs);
        if (a < 0 || b < 0)
            break;
        if (a != b) {
            diag_error(S->diag, n->span,
                       "cannot %s a scalar and a point: expected both sides "
                       "to be scalars or both points/vectors",
                       n->kind == ND_ADD ? "add" : "subtract");
            break;
        }
        k = a;
        break;
    }
    case ND_MUL: {
        int a = check_expr(S, n->lhs), b = check_expr(S, n->rhs);
        if (a < 0 || b < 0)
            break;
        if (a && b) {
            diag_error(S->diag, n->span,
                       "cannot multiply two points or vectors; expected a "
                       "scalar on one side");
            break;
        }
        k = a || b;
        break;
    }
    case ND_DIV: {
        int a = check_expr(S, n->lhs), b = check_expr(S, n->rhs);
        if (a < 0 || b < 0)
            break;
        if (b) {
            diag_error(S->diag, n->rhs->span,
                       "cannot divide by a point or vector; expected a "
                       "scalar divisor");
            break;
        }
        k = a;
        break;
    }
    case ND_POW: {
        int a = check_expr(S, n->lhs), b = check_expr(S, n->rhs);
        if (a < 0 || b < 0)
            break;
        if (a) {
            diag_error(S->diag, n->lhs->span,
                       "cannot raise a point or vector to a power; expected "
                       "a scalar base");
            break;
        }
        if (b) {
            diag_error(S->diag, n->rhs->span, "expected a scalar exponent");
            break;
        }
        k = 0;
        break;
    }
    case ND_CALL:
        k = check_call(S, n);
        break;
    case ND_INDEX: /* expand.c replaced every one */
    case ND_COMPR:
        PC_UNREACHABLE("an index or a comprehension left by expand");
    }
    n->is_point = k > 0;
    return k;
}

static void declare_list(Sema *S, Stmt *st, SymKind kind)
{
    SemaInfo *I = S->info;
    for (Name *nm = st->names; nm; nm = nm->next) {
        Sym *s = declare(S, nm->text, nm->span, kind);
        if (!s)
            continue;
        s->decl = st;
        switch (kind) {
        case SYM_POINT:
            s->is_point = 1;
            s->index = I->npoints;
            push(S, &I->points, &I->npoints, &S->cap_points, s);
            break;
        case SYM_PARAM:
            s->index = I->nparams;
            push(S, &I->params, &I->nparams, &S->cap_params, s);
            break;
        case SYM_CONST:
            s->index = I->nconsts;
            push(S, &I->consts, &I->nconsts, &S->cap_consts, s);
            break;
        case SYM_UNKNOWN:
            s->is_point = !st->scalar;
            s->index = I->nunknowns;
            push(S, &I->unknowns, &I->nunknowns, &S->cap_unknowns, s);
            break;
        default:
            break;
        }
    }
}

/* `solve EQ, ... for X, ...`: both sides of every equation combinations of
 * points, every name after `for` an unknown not solved before, as many
 * equations as unknowns.  Marks the statement bad on any error. */
static void check_solve(Sema *S, Stmt *st)
{
    int neq = 0, nunk = 0, nscalar = 0, errors0 = S->diag->nerrors;
    for (Name *nm = st->names; nm; nm = nm->next) {
        Sym *s = lookup(S, nm->text);
        nscalar += s && s->kind == SYM_UNKNOWN && !s->is_point;
    }
    for (Equation *e = st->eqs; e; e = e->next, neq++) {
        int kl = check_expr(S, e->lhs), kr = check_expr(S, e->rhs);
        if (kl < 0 || kr < 0)
            continue;
        if (kl != kr)
            diag_error(S->diag, e->span,
                       "cannot equate %s and %s; expected both sides to be "
                       "points or vectors",
                       kind_word(kl), kind_word(kr));
        else if (kl == 0 && nscalar == 0)
            diag_error(S->diag, e->span,
                       "a scalar equation cannot determine unknown points; "
                       "expected an equation between points or vectors, "
                       "or an unknown scalar (unknown scalar k) to solve "
                       "for");
    }
    for (Name *nm = st->names; nm; nm = nm->next, nunk++) {
        Sym *s = lookup(S, nm->text);
        if (!s) {
            diag_error(S->diag, nm->span,
                       "undefined name '%s' after 'for'; expected an unknown "
                       "declared with 'unknown %s'",
                       nm->text, nm->text);
            continue;
        }
        if (s->kind != SYM_UNKNOWN) {
            diag_error(S->diag, nm->span,
                       "'%s' is %s; expected an unknown (declared with "
                       "'unknown') after 'for'",
                       nm->text, sym_kind_word(s->kind));
            continue;
        }
        if (s->solved_by == st) {
            diag_error(S->diag, nm->span, "'%s' is listed twice", nm->text);
            continue;
        }
        if (s->solved_by) {
            diag_error(S->diag, nm->span, "the unknown '%s' is solved twice",
                       nm->text);
            diag_note(S->diag, s->solved_by->span, "'%s' was first solved here",
                      nm->text);
            continue;
        }
        s->solved_by = st;
    }
    /* with unknown scalars a point equation holds one scalar equation per
     * base point: the rank decides (derive/solve_stmt.c) */
    if (neq != nunk && nscalar == 0)
        diag_error(S->diag, st->span,
                   "%d equation%s for %d unknown%s: the system is %s; "
                   "expected one point equation per unknown point",
                   neq, neq == 1 ? "" : "s", nunk, nunk == 1 ? "" : "s",
                   neq < nunk ? "underdetermined" : "over-determined");
    st->bad = S->diag->nerrors != errors0;
    if (st->bad) /* a solve with an error solves nothing */
        for (Name *nm = st->names; nm; nm = nm->next) {
            Sym *s = lookup(S, nm->text);
            if (s && s->solved_by == st)
                s->solved_by = NULL;
        }
}

/* a number written with literals and + - * / only (a fit's interval) */
static int constant_number(const Node *n)
{
    switch (n->kind) {
    case ND_NUM:
        return 1;
    case ND_NEG:
        return constant_number(n->lhs);
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
    case ND_DIV:
        return constant_number(n->lhs) && constant_number(n->rhs);
    default:
        return 0;
    }
}

/* `fit X to f on [lo, hi] [samples m]` (docs/fit.md): X an earlier point
 * definition (the curve), f an earlier scalar one (the target), lo and hi
 * numbers, m a whole number >= 1; derive ignores the statement */
static void check_fit(Sema *S, Stmt *st)
{
    static const char *const role[2] = {"a point definition (the curve)",
                                        "a scalar definition (the target)"};
    int i = 0, want = st->data ? 1 : 2; /* X, or X and f */
    long long m;
    for (Name *nm = st->names; nm; nm = nm->next, i++) {
        Sym *s = lookup(S, nm->text);
        if (i >= want) {
            diag_error(S->diag, nm->span,
                       "fit names one curve and one target; expected 'fit X "
                       "to f', found more names");
            break;
        }
        if (!s)
            diag_error(S->diag, nm->span,
                       "undefined name '%s' in fit; expected %s defined "
                       "before it",
                       nm->text, role[i]);
        else if (s->kind != SYM_DEF || (!s->bad && s->is_point != (i == 0)))
            diag_error(S->diag, nm->span, "'%s' is %s; expected %s in fit",
                       nm->text,
                       s->kind != SYM_DEF ? sym_kind_word(s->kind)
                       : s->is_point      ? "a point definition"
                                          : "a scalar definition",
                       role[i]);
    }
    if (i < want && st->names)
        diag_error(S->diag, st->span,
                   "fit names one curve and one target; expected 'fit X "
                   "to f'");
    if (!constant_number(st->lo))
        diag_error(S->diag, st->lo->span,
                   "expected a number as the lower end of the fit's "
                   "interval");
    else if (!constant_number(st->hi))
        diag_error(S->diag, st->hi->span,
                   "expected a number as the upper end of the fit's "
                   "interval");
    if (st->expr && (!whole_number(st->expr, &m) || m < 1))
        diag_error(S->diag, st->expr->span,
                   "expected a whole number >= 1 of samples");
}

/* sema's typing of an expression, for check_resolve (check.h) */
static int type_expr(void *S, Node *n)
{
    return check_expr(S, n);
}

/* The `output` list (output_stmt, or NULL: the last definition): each a
 * definition or a solved unknown, listed once.  Outputs are resolved last:
 * they may name definitions that follow. */
static void resolve_outputs(Sema *S, const Stmt *output_stmt,
                            const Scheme *scheme, int errors0)
{
    SemaInfo *I = S->info;
    Diag *diag = S->diag;
    int cap = 0;
    if (output_stmt) {
        for (Name *nm = output_stmt->names; nm; nm = nm->next) {
            Sym *s = lookup(S, nm->text);
            if (!s) {
                diag_error(diag, nm->span,
                           "undefined name '%s' in output; expected a "
                           "definition",
                           nm->text);
                continue;
            }
            if (s->kind != SYM_DEF && s->kind != SYM_UNKNOWN) {
                diag_error(diag, nm->span,
                           "'%s' is %s; expected a definition (NAME = EXPR) "
                           "or a solved unknown in output",
                           nm->text, sym_kind_word(s->kind));
                continue;
            }
            if (s->kind == SYM_UNKNOWN && !s->solved_by) {
                diag_error(diag, nm->span,
                           "the unknown '%s' is never solved; expected "
                           "'solve ... for %s' before it is output",
                           nm->text, nm->text);
                continue;
            }
            for (int i = 0; i < I->noutputs; i++)
                if (I->outputs[i] == s) {
                    diag_error(diag, nm->span, "'%s' is listed twice",
                               nm->text);
                    s = NULL;
                    break;
                }
            if (s)
                push(S, &I->outputs, &I->noutputs, &cap, s);
        }
    } else if (I->ndefs > 0) {
        push(S, &I->outputs, &I->noutputs, &cap, I->defs[I->ndefs - 1]);
    } else if (diag->nerrors == errors0) {
        int end = 0;
        for (Stmt *st = scheme->stmts; st; st = st->next)
            end = st->span.end;
        diag_error(diag, (Span){end, end},
                   "the scheme defines nothing; expected a definition "
                   "'NAME = EXPR' to output");
    }
}

SemaInfo *sema_check(Scheme *scheme, Arena *a, Diag *diag)
{
    Sema S = {.arena = a, .diag = diag};
    SemaInfo *I = arena_new(a, SemaInfo);
    S.info = I;
    int errors0 = diag->nerrors;
    Stmt *output_stmt = NULL;
    Span scheme_span = {0, 0};

    for (Stmt *st = scheme->stmts; st; st = st->next) {
        switch (st->kind) {
        case ST_INT: /* expand.c has substituted its value */
            break;
        case ST_SCHEME:
            if (I->scheme_name) {
                diag_error(diag, st->span, "a second 'scheme' statement");
                diag_note(diag, scheme_span, "the scheme was named here");
            } else {
                I->scheme_name = st->name->text;
                scheme_span = st->span;
            }
            break;
        case ST_POINT:
            declare_list(&S, st, SYM_POINT);
            break;
        case ST_PARAM:
            declare_list(&S, st, SYM_PARAM);
            if (st->lo) {
                /* bad: derive does not read a range with an error */
                if (expect(&S, st->lo, 0, "the lower end of the range") < 0)
                    st->bad = 1;
                else if (expect(&S, st->hi, 0, "the upper end of the range") <
                         0)
                    st->bad = 1;
            }
            break;
        case ST_CONST:
            declare_list(&S, st, SYM_CONST);
            /* bounds: scalars (derive checks that they are numbers);
             * bad: derive does not read a bound with an error */
            if (st->lo && expect(&S, st->lo, 0, "the lower bound") < 0)
                st->bad = 1;
            else if (st->hi && expect(&S, st->hi, 0, "the upper bound") < 0)
                st->bad = 1;
            break;
        case ST_UNKNOWN:
            declare_list(&S, st, SYM_UNKNOWN);
            break;
        case ST_SOLVE:
            check_solve(&S, st);
            push_step(&S, st);
            break;
        case ST_FUNC: /* expand.c expanded every call */
            break;
        case ST_DEF: {
            int k = check_expr(&S, st->expr);
            for (Equation *e = st->joints; e; e = e->next)
                if (check_expr(&S, e->lhs) < 0 || check_expr(&S, e->rhs) < 0)
                    k = -1;
            Sym *s = declare(&S, st->name->text, st->name->span, SYM_DEF);
            if (!s)
                break;
            s->def = st;
            st->sym = s;
            push_step(&S, st);
            s->bad = k < 0;
            s->is_point = k > 0;
            s->index = I->ndefs;
            push(&S, &I->defs, &I->ndefs, &S.cap_defs, s);
            break;
        }
        case ST_FIT:
            check_fit(&S, st);
            break;
        case ST_CHECK: /* after every definition: compiler/derive/check.c */
            check_resolve(I, st, a, diag, type_expr, &S);
            break;
        case ST_OUTPUT:
            if (output_stmt) {
                diag_error(diag, st->span,
                           "a second 'output' statement; expected one "
                           "'output' listing every name");
                break;
            }
            output_stmt = st;
            break;
        }
    }

    /* outputs are resolved last: they may name definitions that follow */
    resolve_outputs(&S, output_stmt, scheme, errors0);
    /* with errors too: derive then reduces the definitions that are fine
     * (s->bad marks the others) and reports their errors as well */
    return I;
}

/*
 * check_sema.c - a `check` statement resolved into plain expressions
 * (check.h): the claim's name and arguments checked, the `at` bindings
 * substituted into every value, the jets of curves written as
 * subst(diff(M, t, j), t, v).  Sema (sema.c) calls check_resolve for every
 * check with its own expression typing; derive (compiler/derive/check.c)
 * evaluates the expressions in source order, after every definition and
 * solve.
 */
#include "compiler/check.h"

#include <stdlib.h>
#include <string.h>

#include "compiler/sema.h"

const char *check_kind_name(CheckKind k)
{
    static const char *const names[] = {
#define X(k, s) s,
        PC_CHECK_KINDS(X)
#undef X
    };
    return names[k];
}

typedef struct Resolver {
    Stmt *st;
    Arena *a;
    Diag *d;
    int (*type)(void *, Node *);
    void *ctx;
    Node *ops[2 * (CHECK_MAX_ORDER + 2) + 2];
    int nops;
} Resolver;

static const char *const claims =
    "expected a claim after 'check': 'L = R', 'on(P, line(A, B))', "
    "'parallel(U, V)', 'tangent(M at t = v, line(A, B))', 'contact(k, M at "
    "t = a, N at u = b)', 'Ck(M at t = a, N at u = b)', 'Gk(...)' or "
    "'order(M, t) = N' "
    "(docs/language.md, Checks)";

static Node *nth(Node *call, int i)
{
    Node *x = call->args;
    while (x && i-- > 0)
        x = x->next;
    return x;
}

/* a new call name(args...) at span, args linked here */
static Node *call3(Arena *a, const char *name, Node *x, Node *y, Node *z,
                   Span span)
{
    x->next = y;
    y->next = z;
    z->next = NULL;
    return ast_new_call(a, name, span, x, span);
}

/* a copy of a leaf (a name or a number): leaves are linked by next in
 * argument lists, so every use needs its own */
static Node *leaf(Arena *a, const Node *n)
{
    Node *c = n->kind == ND_NUM ? ast_new_num(a, n->text, n->span)
                                : ast_new_name(a, n->text, n->span);
    return c;
}

/* e with every binding of the statement's `at` substituted, innermost
 * first: subst(subst(e, t, v), u, w) */
static Node *wrap(Resolver *R, Node *e)
{
    for (Equation *b = R->st->eqs; b; b = b->next)
        e = call3(R->a, "subst", e, leaf(R->a, b->lhs), b->rhs, e->span);
    return e;
}

/* a shallow copy of n whose next is free (a subtree used twice keeps its
 * children; only the root is linked into a new argument list) */
static Node *root_copy(Arena *a, const Node *n)
{
    Node *c = arena_new(a, Node);
    *c = *n;
    c->next = NULL;
    return c;
}

static int add_op(Resolver *R, Node *e)
{
    R->ops[R->nops++] = e;
    return 0;
}

/* the name n (ND_NAME, typed) is a param: 1, else reported, 0 */
static int is_param(Resolver *R, const Node *n, const char *what)
{
    if (n->kind == ND_NAME && n->sym && n->sym->kind == SYM_PARAM)
        return 1;
    diag_error(R->d, n->span, "expected a param in %s, found '%s'", what,
               n->kind == ND_NAME ? n->text : "an expression");
    return 0;
}

/* The jet of a curve at its point, len values: arg is `M at t = v`
 * (subst(M, t, v)), or M alone when the statement's `at` binds one param.
 * Returns 0, or -1 (reported). */
static int add_jet(Resolver *R, Node *arg, int len, Node **mvv)
{
    Node *m = arg, *var = NULL, *val = NULL;
    if (arg->kind == ND_CALL && strcmp(arg->text, "subst") == 0 &&
        arg->nargs == 3) {
        m = nth(arg, 0);
        var = nth(arg, 1);
        val = nth(arg, 2);
    } else if (R->st->eqs && !R->st->eqs->next) {
        var = R->st->eqs->lhs;
        val = R->st->eqs->rhs;
    } else {
        diag_error(R->d, arg->span,
                   "expected a curve at its point, 'M at t = VALUE' (or one "
                   "'at t = VALUE' after the claim)");
        return -1;
    }
    int k = R->type(R->ctx, m);
    if (k < 0 || R->type(R->ctx, var) < 0 || R->type(R->ctx, val) < 0)
        return -1;
    if (!is_param(R, var, "a curve's point 'M at t = VALUE'"))
        return -1;
    if (k == 0) {
        diag_error(R->d, m->span,
                   "expected a curve (a point or vector), found a scalar");
        return -1;
    }
    if (mvv) /* M, t and v themselves */
        mvv[0] = m, mvv[1] = var, mvv[2] = val;
    static const char *const digit[] = {"0", "1", "2", "3", "4",
                                        "5", "6", "7", "8", "9"};
    for (int j = 0; j < len; j++) {
        Node *d = call3(R->a, "diff", root_copy(R->a, m), leaf(R->a, var),
                        ast_new_num(R->a, digit[j], arg->span), arg->span);
        add_op(R, wrap(R, call3(R->a, "subst", d, leaf(R->a, var),
                                root_copy(R->a, val), arg->span)));
    }
    return 0;
}

/* Ck(M at t = a) of one curve: ops NULL for the jets, then M and a */
static int add_knot(Resolver *R, CheckInfo *c, Node *arg)
{
    Node *mvv[3];
    if (add_jet(R, arg, 1, mvv) < 0)
        return -1;
    R->nops = 0;
    for (int i = 0; i < 2 * c->jetlen; i++)
        add_op(R, NULL);
    add_op(R, wrap(R, root_copy(R->a, mvv[0])));
    add_op(R, wrap(R, root_copy(R->a, mvv[2])));
    c->knot_var = mvv[1]->sym->index;
    c->what[0] = c->what[1] = arg->span;
    return 0;
}

/* the arguments of line(A, B) (n = 2) or plane(A, B, C) (n = 3), as ops;
 * *n receives how many, 0 when x is neither (not reported) */
static void add_flat(Resolver *R, Node *x, int *n)
{
    *n = 0;
    if (x->kind != ND_CALL)
        return;
    if (strcmp(x->text, "line") == 0 && x->nargs == 2)
        *n = 2;
    else if (strcmp(x->text, "plane") == 0 && x->nargs == 3)
        *n = 3;
    for (int i = 0; i < *n; i++)
        add_op(R, wrap(R, root_copy(R->a, nth(x, i))));
}

/* `Ck`, `Gk`: k from 0 to CHECK_MAX_ORDER, else -1 */
static int order_of(const char *name)
{
    if ((name[0] != 'C' && name[0] != 'G') || !name[1] || strlen(name) > 2)
        return -1;
    int k = name[1] - '0';
    return k >= 0 && k <= CHECK_MAX_ORDER ? k : -1;
}

static int arity(Resolver *R, Node *call, int n, const char *form)
{
    if (call->nargs == n)
        return 0;
    diag_error(R->d, call->span, "%s() takes %d arguments, found %d: %s",
               call->text, n, call->nargs, form);
    return -1;
}

/* a whole number of literals, + - * and unary minus (ints are literals
 * after expand.c: `order(X, t) = n + 1`) into *v; 0 when n is not one */
static int whole(const Node *n, long *v)
{
    long a, b;
    char *end;
    switch (n->kind) {
    case ND_NUM:
        *v = strtol(n->text, &end, 10);
        return *end == '\0' && *v >= 0 && *v <= 100000;
    case ND_NEG:
        return whole(n->lhs, &a) && (*v = -a, 1);
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
        if (!whole(n->lhs, &a) || !whole(n->rhs, &b))
            return 0;
        *v = n->kind == ND_ADD ? a + b : n->kind == ND_SUB ? a - b : a * b;
        return *v >= -100000 && *v <= 100000;
    default:
        return 0;
    }
}

/* contact(k, M at t = a, N at u = b): k a whole number 1..CHECK_MAX_ORDER
 * - 1 */
static int contact_order(Resolver *R, Node *k)
{
    long v;
    if (whole(k, &v) && v >= 1 && v < CHECK_MAX_ORDER)
        return (int)v;
    diag_error(R->d, k->span,
               "expected the order of contact, a whole number from 1 to %d",
               CHECK_MAX_ORDER - 1);
    return -1;
}

/* the predicates; returns 0 or -1 (reported) */
static int resolve_claim(Resolver *R, CheckInfo *c, Node *call)
{
    const char *f = call->text;
    int n;
    if (strcmp(f, "on") == 0) {
        if (arity(R, call, 2, "on(P, line(A, B)) or on(P, plane(A, B, C))"))
            return -1;
        add_op(R, wrap(R, root_copy(R->a, nth(call, 0))));
        add_flat(R, nth(call, 1), &n);
        if (!n) {
            diag_error(R->d, nth(call, 1)->span,
                       "expected line(A, B) or plane(A, B, C) as the second "
                       "argument of on()");
            return -1;
        }
        c->kind = n == 2 ? CK_ON_LINE : CK_ON_PLANE;
        return 0;
    }
    if (strcmp(f, "parallel") == 0) {
        if (arity(R, call, 2, "parallel(U, V) of two vectors"))
            return -1;
        c->kind = CK_PARALLEL;
        add_op(R, wrap(R, root_copy(R->a, nth(call, 0))));
        add_op(R, wrap(R, root_copy(R->a, nth(call, 1))));
        return 0;
    }
    if (strcmp(f, "tangent") == 0) {
        if (arity(R, call, 2, "tangent(M at t = VALUE, line(A, B))"))
            return -1;
        add_flat(R, nth(call, 1), &n);
        if (n != 2) {
            diag_error(R->d, nth(call, 1)->span,
                       "expected line(A, B) as the second argument of "
                       "tangent()");
            return -1;
        }
        c->kind = CK_TANGENT;
        c->order = CHECK_MAX_ORDER;
        c->jet0 = 2;
        c->jetlen = CHECK_MAX_ORDER + 1;
        c->what[0] = nth(call, 0)->span;
        return add_jet(R, nth(call, 0), c->jetlen, NULL);
    }
    int k = order_of(f);
    int contact = strcmp(f, "contact") == 0;
    if (k < 0 && !contact) {
        diag_error(R->d, call->name_span, "unknown claim '%s(...)'; %s", f,
                   claims);
        return -1;
    }
    if (contact) {
        if (arity(R, call, 3, "contact(k, M at t = a, N at u = b)") ||
            (k = contact_order(R, nth(call, 0))) < 0)
            return -1;
    } else if (call->nargs != 1 &&
               arity(R, call, 2,
                     "Ck(M at t = a, N at u = b) or Ck(M at t = a)")) {
        return -1;
    }
    if (contact) { /* contact(k, M at t = a, line(A, B)) */
        add_flat(R, nth(call, 2), &n);
        if (n == 2) {
            c->kind = CK_CONTACT_LINE;
            c->order = k;
            c->jet0 = 2;
            c->jetlen = k + 2;
            c->what[0] = nth(call, 1)->span;
            return add_jet(R, nth(call, 1), c->jetlen, NULL);
        }
        R->nops = 0; /* plane(...): no line, the ops it added dropped */
    }
    c->kind = contact ? CK_CONTACT : f[0] == 'C' ? CK_C : CK_G;
    c->order = k;
    c->jetlen = k + 1 + contact;
    if (call->nargs == 1)
        return add_knot(R, c, nth(call, 0));
    for (int i = 0; i < 2; i++) {
        Node *arg = nth(call, i + contact);
        c->what[i] = arg->span;
        if (add_jet(R, arg, c->jetlen, NULL) < 0)
            return -1;
    }
    return 0;
}

/* order(M, t) = n: M a curve, t a param, n a whole number */
static int resolve_order(Resolver *R, CheckInfo *c, Node *call, Node *n)
{
    long v;
    if (arity(R, call, 2, "order(M, t) = N"))
        return -1;
    if (!whole(n, &v) || v < 0) {
        diag_error(R->d, n->span,
                   "expected the order, a whole number, after 'order(M, t) "
                   "='");
        return -1;
    }
    Node *var = nth(call, 1);
    if (R->type(R->ctx, var) < 0 || !is_param(R, var, "order(M, t)"))
        return -1;
    c->kind = CK_ORDER;
    c->order = (int)v;
    c->knot_var = var->sym->index;
    c->what[0] = nth(call, 0)->span;
    add_op(R, wrap(R, root_copy(R->a, nth(call, 0))));
    return 0;
}

/* the bindings of `at`: each a param or const, bound once, to a scalar */
static int check_bindings(Resolver *R)
{
    for (Equation *b = R->st->eqs; b; b = b->next) {
        if (R->type(R->ctx, b->lhs) < 0 || R->type(R->ctx, b->rhs) < 0)
            return -1;
        if (!b->lhs->sym || (b->lhs->sym->kind != SYM_PARAM &&
                             b->lhs->sym->kind != SYM_CONST)) {
            diag_error(R->d, b->lhs->span,
                       "expected a param or const after 'at', found '%s'",
                       b->lhs->text);
            return -1;
        }
        if (b->rhs->is_point) {
            diag_error(R->d, b->rhs->span,
                       "expected a scalar value for '%s', found a point or "
                       "vector",
                       b->lhs->text);
            return -1;
        }
        for (Equation *o = R->st->eqs; o != b; o = o->next)
            if (strcmp(o->lhs->text, b->lhs->text) == 0) {
                diag_error(R->d, b->lhs->span, "'%s' is bound twice",
                           b->lhs->text);
                return -1;
            }
    }
    return 0;
}

/* every op typed; their kinds as each claim needs them */
static int type_ops(Resolver *R, CheckInfo *c)
{
    int kinds[sizeof R->ops / sizeof R->ops[0]];
    for (int i = 0; i < R->nops; i++)
        if ((kinds[i] = R->ops[i] ? R->type(R->ctx, R->ops[i]) : 1) < 0)
            return -1;
    if (c->kind == CK_EQUAL && kinds[0] != kinds[1]) {
        diag_error(R->d, R->st->span,
                   "cannot compare a scalar and a point or vector; expected "
                   "both sides to be scalars or both points/vectors");
        return -1;
    }
    if (c->kind == CK_EQUAL)
        return 0;
    for (int i = 0; i < R->nops - (c->knot_var >= 0); i++)
        if (!kinds[i]) {
            diag_error(R->d, R->ops[i]->span,
                       "expected a point or vector in %s(), found a scalar",
                       check_kind_name(c->kind));
            return -1;
        }
    return 0;
}

/* st appended to I->checks (arena, capacity the next power of two) */
static void push_check(SemaInfo *I, Stmt *st, Arena *a)
{
    int n = I->nchecks;
    if ((n & (n - 1)) == 0) { /* 0, 1, 2, 4, ...: full */
        Stmt **na = arena_alloc(a, sizeof(Stmt *) * (size_t)(n ? 2 * n : 1));
        if (n)
            memcpy(na, I->checks, sizeof(Stmt *) * (size_t)n);
        I->checks = na;
    }
    I->checks[I->nchecks++] = st;
}

int check_resolve(SemaInfo *I, Stmt *st, Arena *a, Diag *d,
                  int (*type)(void *, Node *), void *ctx)
{
    if (st->bad) /* its expansion failed (reported), or the template of
                    `check ... for i in a..b` (expand.c: its instances
                    follow it) */
        return -1;
    Resolver R = {.st = st, .a = a, .d = d, .type = type, .ctx = ctx};
    CheckInfo *c = arena_new(a, CheckInfo);
    c->knot_var = -1;
    int rc = check_bindings(&R);
    if (rc == 0 && st->rhs && st->expr->kind == ND_CALL &&
        strcmp(st->expr->text, "order") == 0) {
        rc = resolve_order(&R, c, st->expr, st->rhs);
    } else if (rc == 0 && st->rhs) {
        c->kind = CK_EQUAL;
        if (type(ctx, st->expr) < 0 || type(ctx, st->rhs) < 0)
            rc = -1;
        add_op(&R, wrap(&R, st->expr));
        add_op(&R, wrap(&R, st->rhs));
    } else if (rc == 0 && st->expr->kind != ND_CALL) {
        diag_error(d, st->expr->span, "%s", claims);
        rc = -1;
    } else if (rc == 0) {
        rc = resolve_claim(&R, c, st->expr);
    }
    if (rc == 0)
        rc = type_ops(&R, c);
    c->ops = arena_alloc(a, sizeof(Node *) * (size_t)(R.nops ? R.nops : 1));
    memcpy(c->ops, R.ops, sizeof(Node *) * (size_t)R.nops);
    c->nops = R.nops;
    st->check = c;
    st->bad = rc < 0;
    if (rc == 0)
        push_check(I, st, a);
    return rc;
}

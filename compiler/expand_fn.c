/*
 * expand_fn.c - user functions, sums and products over an index, and the
 * composite-curve constructions piecewise() and join() (Dolya, ch. 2).
 *
 *   def P(t, a, w) = (w + abs(t - a) - abs(t - a - w))/(2*w)
 *   R = sum(P(t, i, 1)*(A[i+1] - A[i]) for i in 0..n-1)
 *   p = piecewise(t, p1, t1, p2, t2, p3)
 *   R = join(t, 0, g1[0..1], 1, g2[0..pi/2], 2)
 *
 * All of them are unrolled here, on the syntax tree, into the expressions
 * sema and derive already know: a call of a user function is a copy of its
 * body with each parameter replaced by the (expanded) argument, a sum is a
 * balanced tree of additions, piecewise and join are the formulas of the
 * text.  A function may call only the functions defined before it, so no
 * expansion recurses; the node budget of expand.c bounds the copies.
 */
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>

#include "base/mem.h"
#include "compiler/algebra/ratfun.h"
#include "compiler/expand.h"
#include "compiler/expand_int.h"
#include "compiler/sema.h"

/* ---- bindings and functions --------------------------------------------- */

static Func *ex_find_func(Expander *E, const char *name)
{
    for (int i = 0; i < E->nfuncs; i++)
        if (strcmp(E->funcs[i].name, name) == 0)
            return &E->funcs[i];
    return NULL;
}

const Binding *ex_find_binding(const Expander *E, const char *name)
{
    for (int i = E->nbinds - 1; i >= E->frame; i--)
        if (strcmp(E->binds[i].name, name) == 0)
            return &E->binds[i];
    return NULL;
}

const Binding *ex_index_binding(const Expander *E)
{
    for (int i = E->nbinds - 1; i >= E->frame; i--)
        if (!E->binds[i].arg)
            return &E->binds[i];
    return NULL;
}

void ex_bind(Expander *E, const char *name, const Node *arg, slong value)
{
    if (E->nbinds == E->capbinds) {
        E->capbinds = E->capbinds ? 2 * E->capbinds : 16;
        E->binds = pc_xrealloc(E->binds, sizeof(Binding) * (size_t)E->capbinds);
    }
    E->binds[E->nbinds++] = (Binding){name, arg, value};
}

/* the calls this pass unrolls itself (they are not sema's builtins) */
static int is_expander_call(const char *name)
{
    return strcmp(name, "sum") == 0 || strcmp(name, "prod") == 0 ||
           strcmp(name, "piecewise") == 0 || strcmp(name, "join") == 0 ||
           strcmp(name, "smoothjoin") == 0;
}

typedef struct Scope {
    const char *name;
    const struct Scope *up;
} Scope;

static int in_scope(const Scope *s, const char *name)
{
    for (; s; s = s->up)
        if (strcmp(s->name, name) == 0)
            return 1;
    return 0;
}

/* every name of a function's body is a parameter, an index of a sum in
 * it, or declared before the function; every call is of a builtin or of a
 * function defined before it */
static int check_body(Expander *E, const Func *F, const Node *n,
                      const Scope *sc)
{
    int st = 0;
    if (ex_too_deep(n))
        return 0; /* sema refuses it at the call */
    switch (n->kind) {
    case ND_NUM:
        return 0;
    case ND_NAME:
        if (in_scope(sc, n->text) || ex_find_int(E, n->text) ||
            ex_find_name(E, n->text) >= 0 || ex_find_family(E, n->text) ||
            strcmp(n->text, "pi") == 0 ||
            (strcmp(n->text, "inf") == 0)) /* a join's infinite end */
            return 0;
        diag_error(E->d, n->span,
                   "'%s' is not a parameter of %s() and is not declared "
                   "before it; expected one of its parameters or an earlier "
                   "name",
                   n->text, F->name);
        return -1;
    case ND_INDEX:
        if (!ex_find_family(E, n->text) && !ex_find_func(E, n->text) &&
            strcmp(n->text, F->name) != 0) {
            diag_error(E->d, n->name_span,
                       "'%s' is not a family declared before %s(); expected "
                       "NAME[i] of a family declared as NAME[lo..hi]",
                       n->text, F->name);
            st = -1;
        } else if (strcmp(n->text, F->name) == 0) {
            diag_error(E->d, n->name_span,
                       "%s() uses itself; a function cannot be recursive",
                       F->name);
            st = -1;
        }
        if (check_body(E, F, n->lhs, sc) < 0 ||
            (n->rhs && check_body(E, F, n->rhs, sc) < 0))
            st = -1;
        return st;
    case ND_COMPR: {
        Scope inner = {n->var, sc};
        if (check_body(E, F, n->args, sc) < 0 ||
            check_body(E, F, n->args->next, sc) < 0 ||
            check_body(E, F, n->lhs, &inner) < 0)
            st = -1;
        return st;
    }
    case ND_CALL:
        if (strcmp(n->text, F->name) == 0) {
            diag_error(E->d, n->name_span,
                       "%s() calls itself; a function cannot be recursive",
                       F->name);
            st = -1;
        } else if (!ex_find_func(E, n->text) && !is_expander_call(n->text) &&
                   !sema_is_builtin(n->text)) {
            diag_error(E->d, n->name_span,
                       "unknown function '%s'; a function may call the "
                       "built-in functions and the functions defined before "
                       "it",
                       n->text);
            st = -1;
        }
        for (const Node *a = n->args; a; a = a->next)
            if (check_body(E, F, a, sc) < 0)
                st = -1;
        return st;
    case ND_NEG:
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
    case ND_DIV:
    case ND_POW:
        st = check_body(E, F, n->lhs, sc);
        if (n->rhs && check_body(E, F, n->rhs, sc) < 0)
            st = -1;
        return st;
    }
    return 0;
}

void ex_define_func(Expander *E, Stmt *st)
{
    const char *name = st->name->text;
    Span span = st->name->span;
    Func F = {name, span, st->names, 0, st->expr, 0};
    Func *old = ex_find_func(E, name);
    if (old) {
        diag_error(E->d, span, "redefinition of the function '%s'", name);
        diag_note(E->d, old->span, "'%s' was first defined here", name);
        return;
    }
    if (sema_is_builtin(name) || is_expander_call(name)) {
        diag_error(E->d, span,
                   "'%s' is a built-in function; choose another name", name);
        F.bad = 1;
    } else if (ex_check_free(E, name, span, 1) < 0) {
        F.bad = 1;
    }
    Scope scopes[64], *sc = NULL;
    for (Name *p = st->names; p; p = p->next) {
        for (Name *q = st->names; q != p; q = q->next)
            if (strcmp(q->text, p->text) == 0) {
                diag_error(E->d, p->span,
                           "the parameter '%s' of %s() is repeated; expected "
                           "distinct names",
                           p->text, name);
                F.bad = 1;
            }
        if (F.nparams == 64) {
            diag_error(E->d, p->span,
                       "%s() has more than 64 parameters; expected at most "
                       "64",
                       name);
            F.bad = 1;
            break;
        }
        scopes[F.nparams] = (Scope){p->text, sc};
        sc = &scopes[F.nparams++];
    }
    if (check_body(E, &F, st->expr, sc) < 0)
        F.bad = 1;
    if (E->nfuncs == E->capfuncs) {
        E->capfuncs = E->capfuncs ? 2 * E->capfuncs : 8;
        E->funcs = pc_xrealloc(E->funcs, sizeof(Func) * (size_t)E->capfuncs);
    }
    E->funcs[E->nfuncs++] = F;
}

/* the expansion of node (a copy of a function's body, a formula) replaces
 * the call at *slot */
static void replace(Node **slot, Node *with)
{
    with->next = (*slot)->next;
    *slot = with;
}

static int call_func(Expander *E, Func *F, Node **slot)
{
    Node *n = *slot;
    if (F->bad)
        return -1;
    if (ex_rewrite_args(E, n) < 0)
        return -1;
    if (n->nargs != F->nparams) {
        diag_error(E->d, n->span, "%s() takes %d argument%s, found %d", F->name,
                   F->nparams, F->nparams == 1 ? "" : "s", n->nargs);
        diag_note(E->d, F->span, "%s() is defined here", F->name);
        return -1;
    }
    if (E->call_depth >= EXPAND_MAX_CALL_DEPTH) {
        diag_error(E->d, n->span,
                   "functions call functions more than %d levels deep",
                   EXPAND_MAX_CALL_DEPTH);
        return -1;
    }
    if (ex_budget_nodes(E, n, ex_count_nodes(F->body)) < 0)
        return -1;
    Node *body = ex_clone(E, F->body);
    int frame = E->frame, nb = E->nbinds;
    E->frame = E->nbinds;
    int k = 0;
    for (Node *a = n->args; a; a = a->next, k++) {
        Name *p = F->params;
        for (int j = 0; j < k; j++)
            p = p->next;
        ex_bind(E, p->text, a, 0);
    }
    E->call_depth++;
    diag_push_context(E->d, n->span, F->name);
    int st = ex_rewrite(E, &body);
    diag_pop_context(E->d);
    E->call_depth--;
    E->nbinds = nb;
    E->frame = frame;
    if (st < 0)
        return -1;
    body->call_site = n;
    replace(slot, body);
    return 0;
}

/* ---- building expressions -------------------------------------------------
 */

/* (NULL when an operand is: a copy ran over the node budget) */
static Node *bin(Expander *E, NodeKind k, Node *a, Node *b, Span span)
{
    return a && b ? ast_new_binary(E->a, k, a, b, span) : NULL;
}

static Node *num(Expander *E, const char *text, Span span)
{
    return ast_new_num(E->a, text, span);
}

static Node *call1(Expander *E, const char *name, Node *arg, Span span)
{
    return arg ? ast_new_call(E->a, name, span, arg, span) : NULL;
}

/* the terms t[0..n) joined by op into a balanced tree (depth log n) */
static Node *balanced(Expander *E, NodeKind op, Node **t, slong n, Span span)
{
    if (n == 1)
        return t[0];
    slong h = n / 2;
    return bin(E, op, balanced(E, op, t, h, span),
               balanced(E, op, t + h, n - h, span), span);
}

/* a copy of n for one more use, counted */
static Node *use(Expander *E, const Node *n)
{
    if (ex_budget_nodes(E, n, ex_count_nodes(n)) < 0)
        return NULL;
    return ex_clone(E, n);
}

/* ---- sum and prod -----------------------------------------------------------
 */

static int compr_bounds(Expander *E, const Node *n, slong *lo, slong *hi)
{
    if (strcmp(n->text, "sum") != 0 && strcmp(n->text, "prod") != 0) {
        diag_error(E->d, n->name_span,
                   "'%s' takes no comprehension; expected sum(EXPR for i in "
                   "a..b) or prod(EXPR for i in a..b)",
                   n->text);
        return -1;
    }
    if (ex_find_binding(E, n->var)) {
        diag_error(E->d, n->var_span,
                   "'%s' is already bound here; expected another name for "
                   "the index",
                   n->var);
        return -1;
    }
    if (ex_check_free(E, n->var, n->var_span, 1) < 0)
        return -1;
    if (ex_eval_int(E, n->args, lo) < 0 ||
        ex_eval_int(E, n->args->next, hi) < 0)
        return -1;
    return 0;
}

int ex_expand_compr(Expander *E, Node **slot)
{
    Node *n = *slot;
    slong lo, hi;
    int prod = strcmp(n->text, "prod") == 0;
    if (compr_bounds(E, n, &lo, &hi) < 0)
        return -1;
    slong count = hi >= lo ? hi - lo + 1 : 0;
    if (count == 0) { /* the empty sum is 0, the empty product 1 */
        replace(slot, num(E, prod ? "1" : "0", n->span));
        return 0;
    }
    if (ex_budget_nodes(E, n, count * ex_count_nodes(n->lhs)) < 0)
        return -1;
    Node **terms = pc_xmalloc(sizeof(Node *) * (size_t)count);
    int st = 0;
    for (slong k = 0; k < count && st == 0; k++) {
        terms[k] = ex_clone(E, n->lhs);
        ex_bind(E, n->var, NULL, lo + k);
        st = ex_rewrite(E, &terms[k]);
        E->nbinds--;
    }
    if (st == 0)
        replace(slot,
                balanced(E, prod ? ND_MUL : ND_ADD, terms, count, n->span));
    pc_free(terms);
    return st;
}

int ex_eval_int_compr(Expander *E, const Node *n, slong *out)
{
    slong lo, hi;
    int prod = strcmp(n->text, "prod") == 0;
    if (compr_bounds(E, n, &lo, &hi) < 0)
        return -1;
    if (ex_budget_nodes(E, n, hi >= lo ? hi - lo + 1 : 0) < 0)
        return -1;
    slong acc = prod ? 1 : 0;
    for (slong k = lo; k <= hi; k++) {
        slong v;
        ex_bind(E, n->var, NULL, k);
        int st = ex_eval_int(E, n->lhs, &v);
        E->nbinds--;
        if (st < 0 || ex_int_range(E, n->span,
                                   prod ? (__int128)acc * v : (__int128)acc + v,
                                   &acc) < 0)
            return -1;
    }
    *out = acc;
    return 0;
}

/* ---- knots ----------------------------------------------------------------
 */

/* q = the value of a knot made of numbers, ints and indices with + - * /;
 * -1 (nothing reported) for any other knot: its order is not checked */
static int knot_value(Expander *E, const Node *n, fmpq_t q)
{
    fmpq_t b;
    int st = 0;
    if (ex_too_deep(n))
        return -1;
    switch (n->kind) {
    case ND_NUM:
        return ratfun_literal_fmpq(q, n->text);
    case ND_NAME: {
        const Binding *bd = ex_find_binding(E, n->text);
        const IntSym *is = ex_find_int(E, n->text);
        if (bd && bd->arg)
            return knot_value(E, bd->arg, q);
        if (bd || (is && !is->bad)) {
            fmpq_set_si(q, bd ? bd->value : is->value, 1);
            return 0;
        }
        return -1;
    }
    case ND_NEG:
        if (knot_value(E, n->lhs, q) < 0)
            return -1;
        fmpq_neg(q, q);
        return 0;
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
    case ND_DIV:
        fmpq_init(b);
        if (knot_value(E, n->lhs, q) < 0 || knot_value(E, n->rhs, b) < 0 ||
            (n->kind == ND_DIV && fmpq_is_zero(b)))
            st = -1;
        else if (n->kind == ND_ADD)
            fmpq_add(q, q, b);
        else if (n->kind == ND_SUB)
            fmpq_sub(q, q, b);
        else if (n->kind == ND_MUL)
            fmpq_mul(q, q, b);
        else
            fmpq_div(q, q, b);
        fmpq_clear(b);
        return st;
    default:
        return -1;
    }
}

/* the knots knots[0..n) must increase where their values are numbers */
static int check_knots(Expander *E, Node **knots, int n)
{
    fmpq_t a, b;
    int st = 0, have = 0;
    fmpq_init(a);
    fmpq_init(b);
    for (int k = 0; k < n && st == 0; k++) {
        if (knot_value(E, knots[k], b) < 0) {
            have = 0;
            continue;
        }
        if (have && fmpq_cmp(b, a) <= 0) {
            char *sa = fmpq_get_str(NULL, 10, a),
                 *sb = fmpq_get_str(NULL, 10, b);
            diag_error(E->d, knots[k]->span,
                       "the knots must increase: this one is %s, after %s", sb,
                       sa);
            flint_free(sa);
            flint_free(sb);
            st = -1;
        }
        fmpq_swap(a, b);
        have = 1;
    }
    fmpq_clear(a);
    fmpq_clear(b);
    return st;
}

/* ---- piecewise -------------------------------------------------------------
 */

/* piecewise(t, p1, t1, p2, ..., pn) =
 *   (p1 + pn)/2 + sum_k (p_{k+1} - p_k)/2 * sign(t - t_k)
 * (Dolya 2.3.1, Theorem 1): p1 before t1, p_k between t_{k-1} and t_k, pn
 * after; at a knot the mean of its two pieces (their common value when the
 * curve is continuous there).  a[0] is t, a[2k-1] piece k, a[2k] knot k. */
static int piecewise_formula(Expander *E, Node **slot, Node **a, int na)
{
    Span sp = (*slot)->span;
    int npieces = na / 2, st = -1;
    Node **knots = pc_xmalloc(sizeof(Node *) * (size_t)npieces);
    Node **terms = pc_xmalloc(sizeof(Node *) * (size_t)npieces);
    for (int k = 1; k < npieces; k++)
        knots[k - 1] = a[2 * k];
    if (check_knots(E, knots, npieces - 1) < 0)
        goto done;
    if (npieces == 1)
        terms[0] = use(E, a[1]);
    else
        terms[0] =
            bin(E, ND_DIV, bin(E, ND_ADD, use(E, a[1]), use(E, a[na - 1]), sp),
                num(E, "2", sp), sp);
    if (!terms[0])
        goto done;
    for (int k = 1; k < npieces; k++) {
        Node *jump =
            bin(E, ND_DIV,
                bin(E, ND_SUB, use(E, a[2 * k + 1]), use(E, a[2 * k - 1]), sp),
                num(E, "2", sp), sp);
        Node *side = bin(E, ND_SUB, use(E, a[0]), use(E, a[2 * k]), sp);
        terms[k] = bin(E, ND_MUL, jump, call1(E, "sign", side, sp), sp);
        if (!terms[k])
            goto done;
    }
    Node *f = balanced(E, ND_ADD, terms, npieces, sp);
    st = ex_rewrite(E, &f);
    if (st == 0)
        replace(slot, f);
done:
    pc_free(knots);
    pc_free(terms);
    return st;
}

static int expand_piecewise(Expander *E, Node **slot)
{
    Node *n = *slot;
    int na = n->nargs;
    if (na < 2 || na % 2) {
        diag_error(E->d, n->span,
                   "piecewise() takes the param, then pieces and knots in "
                   "turn: piecewise(t, p1, t1, p2, ..., pn); found %d "
                   "argument%s",
                   na, na == 1 ? "" : "s");
        return -1;
    }
    Node **a = pc_xmalloc(sizeof(Node *) * (size_t)na);
    na = 0;
    for (Node *x = n->args; x; x = x->next)
        a[na++] = x;
    int st = piecewise_formula(E, slot, a, na);
    pc_free(a);
    return st;
}

/* ---- join ------------------------------------------------------------------
 */

/* one argument of join(): a knot, or a segment g[lo..hi] (lo may be -inf
 * for the first, hi inf for the last) */
typedef struct JoinArg {
    Node *node;
    Func *seg; // a segment's function; NULL for a knot
    Node *lo, *hi;
    int lo_inf, hi_inf;
} JoinArg;

/* a segment's interval [lo, hi] must not be empty where its ends are
 * numbers */
static int check_segment(Expander *E, const JoinArg *j)
{
    fmpq_t lo, hi;
    int st = 0;
    fmpq_init(lo);
    fmpq_init(hi);
    if (knot_value(E, j->lo, lo) == 0 && knot_value(E, j->hi, hi) == 0 &&
        fmpq_cmp(lo, hi) >= 0) {
        char *sl = fmpq_get_str(NULL, 10, lo), *sh = fmpq_get_str(NULL, 10, hi);
        diag_error(E->d, j->node->span,
                   "the segment %s[%s..%s] is empty; expected an interval "
                   "lo..hi with lo < hi (the segment is traced from lo to hi)",
                   j->node->text, sl, sh);
        flint_free(sl);
        flint_free(sh);
        st = -1;
    }
    fmpq_clear(lo);
    fmpq_clear(hi);
    return st;
}

static int is_inf(Expander *E, const Node *n, int neg)
{
    if (neg)
        return n->kind == ND_NEG && is_inf(E, n->lhs, 0);
    return n->kind == ND_NAME && strcmp(n->text, "inf") == 0 &&
           !ex_find_int(E, "inf") && ex_find_name(E, "inf") < 0;
}

static int join_arg(Expander *E, Node *x, JoinArg *j)
{
    *j = (JoinArg){x, NULL, NULL, NULL, 0, 0};
    if (x->kind != ND_INDEX || !x->rhs)
        return 0;
    j->seg = ex_find_func(E, x->text);
    if (!j->seg) {
        diag_error(E->d, x->name_span,
                   "'%s' is not a function; expected a segment g[lo..hi] of "
                   "a function g(u) defined with def",
                   x->text);
        return -1;
    }
    if (j->seg->nparams != 1) {
        diag_error(E->d, x->name_span,
                   "the segment function %s() takes %d parameters; expected "
                   "a function of one parameter",
                   x->text, j->seg->nparams);
        diag_note(E->d, j->seg->span, "%s() is defined here", x->text);
        return -1;
    }
    j->lo = x->lhs;
    j->hi = x->rhs;
    j->lo_inf = is_inf(E, x->lhs, 1);
    j->hi_inf = is_inf(E, x->rhs, 0);
    return j->lo_inf || j->hi_inf ? 0 : check_segment(E, j);
}

/* g(arg) as a call, expanded later with the formula */
static Node *seg_at(Expander *E, const JoinArg *g, Node *arg, Span sp)
{
    if (!arg)
        return NULL;
    return call1(E, g->seg->name, arg, sp);
}

/* a call of a step built-in (ramp, step, rayr, rayl: their formulas live
 * in compiler/derive/functions.c) with the arguments args[0..n) */
static Node *builtin_call(Expander *E, const char *name, Node **args, int n,
                          Span sp)
{
    for (int i = 0; i < n; i++)
        if (!args[i])
            return NULL;
    for (int i = 0; i + 1 < n; i++)
        args[i]->next = args[i + 1];
    return ast_new_call(E->a, name, sp, args[0], sp);
}

/* the blending function on [a, a + w]: ramp(t, a, w) (Theorem 1), or the
 * C^m step(t, a, w, m) (Theorem 2) */
static Node *blend(Expander *E, Node *m, Node *t, Node *a, Node *w, Span sp)
{
    Node *args[4] = {t, a, w, m ? use(E, m) : NULL};
    return builtin_call(E, m ? "step" : "ramp", args, m ? 4 : 3, sp);
}

/* rayl(t, a) = min(t - a, 0) before the first knot, rayr(t, a) = max(t - a,
 * 0) after the last (Theorem 3); times (a - t)^m = (-1)^m (t - a)^m or
 * (t - a)^m for a C^m join (the text's remark after Theorem 3) */
static Node *ray(Expander *E, Node *m, Node *t, Node *a, int right, Span sp)
{
    Node *t2 = m ? use(E, t) : NULL, *a2 = m ? use(E, a) : NULL;
    Node *args[2] = {t, a};
    Node *r = builtin_call(E, right ? "rayr" : "rayl", args, 2, sp);
    if (!m || !r)
        return r;
    Node *d = right ? bin(E, ND_SUB, t2, a2, sp) : bin(E, ND_SUB, a2, t2, sp);
    return bin(E, ND_MUL, bin(E, ND_POW, d, use(E, m), sp), r, sp);
}

/* the joints: g_k(hi_k) = g_{k+1}(lo_{k+1}) at every inner knot, checked
 * by derive after the definition (stmt->joints) */
static void add_joint(Expander *E, const JoinArg *g, const JoinArg *h,
                      const JoinArg *knot)
{
    if (!E->stmt || E->stmt->kind != ST_DEF || E->call_depth > 0)
        return;
    Span sp = knot->node->span;
    Node *l = seg_at(E, g, use(E, g->hi), sp);
    Node *r = seg_at(E, h, use(E, h->lo), sp);
    if (!l || !r || ex_rewrite(E, &l) < 0 || ex_rewrite(E, &r) < 0)
        return;
    Equation *q = ast_new_equation(E->a, l, r, sp);
    char *what =
        arena_alloc(E->a, strlen(g->seg->name) + strlen(h->seg->name) + 8);
    sprintf(what, "%s %s", g->seg->name, h->seg->name);
    q->what = what;
    E->stmt->joints = ast_append_equation(E->stmt->joints, q);
}

/* a join() call, its arguments read and checked */
typedef struct Join {
    const char *fn; // "join" or "smoothjoin"
    Node *m, *t;    // the smoothness (NULL: the ramp) and the param
    JoinArg *a;     // the arguments after t
    int na;
    int head, tail; // an infinite first (a[0]) or last (a[na-1]) branch
    int first;      // a[first] is the first knot
    Node **knots;
    int nknots, nseg;
} Join;

/* the pattern: [g0[-inf..b]] knot (segment knot)+ [g[a..inf]], or two
 * infinite branches around one knot */
static int join_pattern(Expander *E, Join *J, Span sp)
{
    JoinArg *a = J->a;
    int last = J->na - 1;
    J->head = J->na > 0 && a[0].seg && a[0].lo_inf;
    J->tail = J->na > 0 && a[last].seg && a[last].hi_inf;
    J->first = J->head;
    last -= J->tail;
    for (int k = J->first; k <= last; k++) {
        int want_knot = (k - J->first) % 2 == 0;
        const JoinArg *j = &a[k];
        if (want_knot != !j->seg || (j->seg && (j->lo_inf || j->hi_inf)) ||
            (!want_knot && k == last)) {
            diag_error(E->d, j->node->span,
                       "expected %s here: %s() takes knots and segments in "
                       "turn, t0, g1[a..b], t1, ..., the first and the last "
                       "segment may be infinite (g0[-inf..b], g[a..inf])",
                       want_knot ? "a knot" : "a finite segment g[a..b]",
                       J->fn);
            return -1;
        }
        if (want_knot)
            J->knots[J->nknots++] = j->node;
        else
            J->nseg++;
    }
    if (J->nknots == 0 || (J->nseg == 0 && !(J->head && J->tail))) {
        diag_error(E->d, sp,
                   "%s() needs at least one segment between two knots, or "
                   "two infinite branches at one knot",
                   J->fn);
        return -1;
    }
    return check_knots(E, J->knots, J->nknots);
}

/* the terms of formula (2), (4) or (8) of 2.1 into terms (at most nseg +
 * 2); their number, or -1 when a copy ran over the budget */
static int join_terms(Expander *E, const Join *J, Node **terms, Span sp)
{
    const JoinArg *a = J->a;
    Node *m = J->m, *t = J->t;
    int nt = 0;
    if (J->head) /* R0(b0 + Ql(t, t0)) */
        terms[nt++] =
            seg_at(E, &a[0],
                   bin(E, ND_ADD, use(E, a[0].hi),
                       ray(E, m, use(E, t), use(E, J->knots[0]), 0, sp), sp),
                   sp);
    else /* R1(tau_1^0) */
        terms[nt++] = seg_at(E, &a[1], use(E, a[1].lo), sp);
    for (int k = 0; k < J->nseg; k++) {
        const JoinArg *g = &a[J->first + 1 + 2 * k];
        Node *ta = J->knots[k], *tb = J->knots[k + 1];
        Node *w = bin(E, ND_SUB, use(E, tb), use(E, ta), sp);
        Node *al = blend(E, m, use(E, t), use(E, ta), w, sp);
        Node *dt = bin(E, ND_SUB, use(E, g->hi), use(E, g->lo), sp);
        Node *arg =
            bin(E, ND_ADD, use(E, g->lo), bin(E, ND_MUL, dt, al, sp), sp);
        terms[nt++] = bin(E, ND_SUB, seg_at(E, g, arg, sp),
                          seg_at(E, g, use(E, g->lo), sp), sp);
    }
    if (J->tail) { /* R_{n+1}(a + Q(t, tn)) - R_{n+1}(a) */
        const JoinArg *g = &a[J->na - 1];
        Node *tn = J->knots[J->nknots - 1];
        Node *arg = bin(E, ND_ADD, use(E, g->lo),
                        ray(E, m, use(E, t), use(E, tn), 1, sp), sp);
        terms[nt++] = bin(E, ND_SUB, seg_at(E, g, arg, sp),
                          seg_at(E, g, use(E, g->lo), sp), sp);
    }
    for (int k = 0; k < nt; k++)
        if (!terms[k])
            return -1;
    return nt;
}

/* the joints, where consecutive segments must meet */
static void join_joints(Expander *E, const Join *J)
{
    const JoinArg *a = J->a, *prev = J->head ? &a[0] : NULL;
    for (int k = 0; k < J->nseg; k++) {
        const JoinArg *g = &a[J->first + 1 + 2 * k];
        if (prev)
            add_joint(E, prev, g, &a[J->first + 2 * k]);
        prev = g;
    }
    if (J->tail && prev)
        add_joint(E, prev, &a[J->na - 1], &a[J->na - 2]);
}

/* join(t, [g0[-inf..b],] t0, g1[a..b], t1, ..., gn[a..b], tn [, g[a..inf]])
 * (Dolya 2.1, Theorems 1-3); smoothjoin(m, t, ...) blends with the C^m
 * step instead of the ramp (Theorem 2). */
static int expand_join(Expander *E, Node **slot, int smooth)
{
    Node *n = *slot, *x = n->args;
    Span sp = n->span;
    Join J = {smooth ? "smoothjoin" : "join",
              NULL,
              NULL,
              NULL,
              0,
              0,
              0,
              0,
              NULL,
              0,
              0};
    if (smooth) {
        J.m = x;
        x = x ? x->next : NULL;
    }
    J.t = x;
    if (!J.t) {
        diag_error(E->d, sp,
                   "%s() takes %sthe param, then knots and segments in turn: "
                   "%s(%st, t0, g1[a..b], t1, ...)",
                   J.fn, smooth ? "the smoothness m, " : "", J.fn,
                   smooth ? "m, " : "");
        return -1;
    }
    int st = 0;
    J.a = pc_xmalloc(sizeof(JoinArg) * (size_t)(n->nargs + 1));
    J.knots = pc_xmalloc(sizeof(Node *) * (size_t)(n->nargs + 1));
    Node **terms = pc_xmalloc(sizeof(Node *) * (size_t)(n->nargs + 3));
    for (x = J.t->next; x; x = x->next)
        if (join_arg(E, x, &J.a[J.na++]) < 0)
            st = -1;
    int nt = -1;
    if (st == 0 && join_pattern(E, &J, sp) == 0)
        nt = join_terms(E, &J, terms, sp);
    if (nt > 0) {
        join_joints(E, &J);
        Node *f = balanced(E, ND_ADD, terms, nt, sp);
        st = ex_rewrite(E, &f);
        if (st == 0)
            replace(slot, f);
    } else {
        st = -1;
    }
    pc_free(J.a);
    pc_free(J.knots);
    pc_free(terms);
    return st;
}

int ex_expand_call(Expander *E, Node **slot, int *st)
{
    Node *n = *slot;
    Func *F = ex_find_func(E, n->text);
    if (F) {
        *st = call_func(E, F, slot);
        return 1;
    }
    if (strcmp(n->text, "sum") == 0 || strcmp(n->text, "prod") == 0) {
        diag_error(E->d, n->span,
                   "%s() takes one comprehension: %s(EXPR for i in a..b)",
                   n->text, n->text);
        *st = -1;
        return 1;
    }
    if (strcmp(n->text, "piecewise") == 0) {
        *st = expand_piecewise(E, slot);
        return 1;
    }
    if (strcmp(n->text, "join") == 0 || strcmp(n->text, "smoothjoin") == 0) {
        *st = expand_join(E, slot, n->text[0] == 's');
        return 1;
    }
    return 0;
}

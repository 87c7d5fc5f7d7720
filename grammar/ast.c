/*
 * ast.c - the AST's constructors (arena-allocated nodes, statements, name
 * lists and equations, each with its byte span) for the parser's actions,
 * and ast_dump, the deterministic S-expression form the front end's golden
 * tests compare (tests/unit/test_front.c).
 */
#include "grammar/ast.h"

#include <stdio.h>

Node *ast_new_num(Arena *a, const char *text, Span span)
{
    Node *n = arena_new(a, Node);
    n->kind = ND_NUM;
    n->text = text;
    n->span = span;
    n->depth = 1;
    return n;
}

Node *ast_new_name(Arena *a, const char *text, Span span)
{
    Node *n = arena_new(a, Node);
    n->kind = ND_NAME;
    n->text = text;
    n->span = span;
    n->name_span = span;
    n->depth = 1;
    return n;
}

Node *ast_new_unary(Arena *a, NodeKind kind, Node *lhs, Span span)
{
    Node *n = arena_new(a, Node);
    n->kind = kind;
    n->lhs = lhs;
    n->span = span;
    n->depth = lhs->depth + 1;
    return n;
}

Node *ast_new_binary(Arena *a, NodeKind kind, Node *lhs, Node *rhs, Span span)
{
    Node *n = arena_new(a, Node);
    n->kind = kind;
    n->lhs = lhs;
    n->rhs = rhs;
    n->span = span;
    n->depth = (lhs->depth > rhs->depth ? lhs->depth : rhs->depth) + 1;
    return n;
}

Node *ast_new_call(Arena *a, const char *name, Span name_span, Node *args,
                   Span span)
{
    Node *n = arena_new(a, Node);
    n->kind = ND_CALL;
    n->text = name;
    n->name_span = name_span;
    n->args = args;
    n->depth = 1;
    for (Node *x = args; x; x = x->next) {
        n->nargs++;
        if (x->depth + 1 > n->depth)
            n->depth = x->depth + 1;
    }
    n->span = span;
    return n;
}

Node *ast_new_compr(Arena *a, const char *name, Span name_span, Node *body,
                    const char *var, Span var_span, Node *lo, Node *hi,
                    Span span)
{
    Node *n = arena_new(a, Node);
    n->kind = ND_COMPR;
    n->text = name;
    n->name_span = name_span;
    n->lhs = body;
    n->var = var;
    n->var_span = var_span;
    lo->next = hi;
    n->args = lo;
    n->nargs = 2;
    n->span = span;
    n->depth = body->depth;
    if (lo->depth > n->depth)
        n->depth = lo->depth;
    if (hi->depth > n->depth)
        n->depth = hi->depth;
    n->depth++;
    return n;
}

Node *ast_new_index(Arena *a, const char *name, Span name_span, Node *lo,
                    Node *hi, Span span)
{
    Node *n = arena_new(a, Node);
    n->kind = ND_INDEX;
    n->text = name;
    n->name_span = name_span;
    n->lhs = lo;
    n->rhs = hi;
    n->span = span;
    n->depth = lo->depth + 1;
    if (hi && hi->depth + 1 > n->depth)
        n->depth = hi->depth + 1;
    return n;
}

Node *ast_append(Node *list, Node *item)
{
    if (!list)
        return item;
    Node *x = list;
    while (x->next)
        x = x->next;
    x->next = item;
    return list;
}

Name *ast_new_namelist(Arena *a, const char *text, Span span)
{
    Name *n = arena_new(a, Name);
    n->text = text;
    n->span = span;
    return n;
}

Name *ast_append_name(Name *list, Name *item)
{
    if (!list)
        return item;
    Name *x = list;
    while (x->next)
        x = x->next;
    x->next = item;
    return list;
}

Equation *ast_new_equation(Arena *a, Node *lhs, Node *rhs, Span span)
{
    Equation *e = arena_new(a, Equation);
    e->lhs = lhs;
    e->rhs = rhs;
    e->span = span;
    return e;
}

Equation *ast_append_equation(Equation *list, Equation *item)
{
    if (!list)
        return item;
    Equation *x = list;
    while (x->next)
        x = x->next;
    x->next = item;
    return list;
}

Stmt *ast_new_stmt(Arena *a, StmtKind kind, Span span)
{
    Stmt *s = arena_new(a, Stmt);
    s->kind = kind;
    s->span = span;
    return s;
}

static const char *ast_node_kind_name(NodeKind k)
{
    static const char *const names[] = {
#define X(k, s) s,
        PC_NODE_KINDS(X)
#undef X
    };
    return names[k];
}

static const char *ast_stmt_kind_name(StmtKind k)
{
    static const char *const names[] = {
#define X(k, s) s,
        PC_STMT_KINDS(X)
#undef X
    };
    return names[k];
}

static void dump_node(FILE *out, const Node *n)
{
    switch (n->kind) {
    case ND_NUM:
    case ND_NAME:
        fputs(n->text, out);
        return;
    case ND_NEG:
        fputs("(neg ", out);
        dump_node(out, n->lhs);
        fputc(')', out);
        return;
    case ND_INDEX:
        fprintf(out, "(%s ", n->text);
        dump_node(out, n->lhs);
        if (n->rhs) {
            fputs(" .. ", out);
            dump_node(out, n->rhs);
        }
        fputc(')', out);
        return;
    case ND_COMPR:
        fprintf(out, "(%s ", n->text);
        dump_node(out, n->lhs);
        fprintf(out, " (for %s ", n->var);
        dump_node(out, n->args);
        fputc(' ', out);
        dump_node(out, n->args->next);
        fputs("))", out);
        return;
    case ND_CALL:
        fprintf(out, "(%s", n->text);
        for (const Node *a = n->args; a; a = a->next) {
            fputc(' ', out);
            dump_node(out, a);
        }
        fputc(')', out);
        return;
    default:
        fprintf(out, "(%s ", ast_node_kind_name(n->kind));
        dump_node(out, n->lhs);
        fputc(' ', out);
        dump_node(out, n->rhs);
        fputc(')', out);
        return;
    }
}

static void dump_names(FILE *out, const Name *n)
{
    for (; n; n = n->next) {
        fprintf(out, " %s", n->text);
        if (n->index || n->lo) {
            fputc('[', out);
            dump_node(out, n->index ? n->index : n->lo);
            if (n->hi) {
                fputs("..", out);
                dump_node(out, n->hi);
            }
            fputc(']', out);
        }
    }
}

void ast_dump(FILE *out, const Scheme *s)
{
    for (const Stmt *st = s->stmts; st; st = st->next) {
        fprintf(out, "(%s", ast_stmt_kind_name(st->kind));
        if (st->scalar)
            fputs(" scalar", out);
        if (st->name)
            fprintf(out, " %s", st->name->text);
        dump_names(out, st->names);
        if (st->expr) {
            fputc(' ', out);
            dump_node(out, st->expr);
        }
        if (st->rhs) { /* check L = R */
            fputs(" (is ", out);
            dump_node(out, st->rhs);
            fputc(')', out);
        }
        if (st->lo && st->hi) { /* a range: its open ends named */
            fputs(" (in ", out);
            dump_node(out, st->lo);
            fputc(' ', out);
            dump_node(out, st->hi);
            fputs(st->lo_open ? " lo-open" : "", out);
            fputs(st->hi_open ? " hi-open" : "", out);
            fputc(')', out);
        } else if (st->lo || st->hi) { /* a const's one-sided bound */
            fprintf(out, " (%s ",
                    st->lo ? (st->lo_open ? ">" : ">=")
                           : (st->hi_open ? "<" : "<="));
            dump_node(out, st->lo ? st->lo : st->hi);
            fputc(')', out);
        }
        for (const Equation *e = st->eqs; e; e = e->next) {
            fputs(" (= ", out);
            dump_node(out, e->lhs);
            fputc(' ', out);
            dump_node(out, e->rhs);
            if (e->var) {
                fprintf(out, " (for %s ", e->var);
                dump_node(out, e->lo);
                fputc(' ', out);
                dump_node(out, e->hi);
                fputc(')', out);
            }
            fputc(')', out);
        }
        for (const Equation *e = st->start; e; e = e->next) {
            fputs(" (near ", out);
            dump_node(out, e->lhs);
            fputc(' ', out);
            dump_node(out, e->rhs);
            fputc(')', out);
        }
        fputs(")\n", out);
    }
}

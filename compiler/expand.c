/*
 * expand.c - families, int constants and comprehensions (see expand.h).
 *
 * One walk over the statements in source order.  Names known here: the int
 * constants, the families, and every plain name declared so far (to refuse
 * a comprehension variable or a member name that would hide one).  Every
 * other name is left for sema.
 */
#include "compiler/expand.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/mem.h"
#include "base/stack.h"
#include "compiler/check.h"
#include "compiler/expand_int.h"
#include "compiler/sema.h"

IntSym *ex_find_int(Expander *E, const char *name)
{
    for (int i = 0; i < E->nints; i++)
        if (strcmp(E->ints[i].name, name) == 0)
            return &E->ints[i];
    return NULL;
}

Family *ex_find_family(Expander *E, const char *name)
{
    for (int i = 0; i < E->nfams; i++)
        if (strcmp(E->fams[i].name, name) == 0)
            return &E->fams[i];
    return NULL;
}

int ex_find_name(Expander *E, const char *name)
{
    for (int i = 0; i < E->nnames; i++)
        if (strcmp(E->names[i], name) == 0)
            return i;
    return -1;
}

/* 1 when name has the form of a member's name, BASE_k (k without leading
 * zeros, at most 12 digits): *baselen = strlen(BASE), *k = k */
static int member_form(const char *name, size_t *baselen, slong *k)
{
    const char *us = strrchr(name, '_');
    if (!us || us == name || !us[1] || strlen(us + 1) > 12 ||
        strspn(us + 1, "0123456789") != strlen(us + 1) ||
        (us[1] == '0' && us[2]))
        return 0;
    *baselen = (size_t)(us - name);
    *k = strtol(us + 1, NULL, 10);
    return 1;
}

/* 1 when name is the name of member lo..hi of the family called base */
static int is_member_name(const char *name, const char *base, slong lo,
                          slong hi, slong *k)
{
    size_t bl;
    return member_form(name, &bl, k) && strlen(base) == bl &&
           strncmp(base, name, bl) == 0 && *k >= lo && *k <= hi;
}

/* the family member a plain name would denote ("M_3" with M[1..5]), or
 * NULL */
static Family *member_of(Expander *E, const char *name, slong *index)
{
    for (int i = 0; i < E->nfams; i++) {
        Family *f = &E->fams[i];
        if (is_member_name(name, f->name, f->lo, f->hi, index))
            return f;
    }
    return NULL;
}

/* 0, or -1 after reporting that name is taken by an int, a family or a
 * family member, or (plain_too) by a plain name: sema reports two plain
 * declarations of one name itself */
int ex_check_free(Expander *E, const char *name, Span span, int plain_too)
{
    IntSym *is = ex_find_int(E, name);
    Family *f = ex_find_family(E, name);
    int k = plain_too ? ex_find_name(E, name) : -1;
    slong idx;
    if (is || f || k >= 0) {
        diag_error(E->d, span, "redefinition of '%s'", name);
        diag_note(E->d,
                  is  ? is->span
                  : f ? f->span
                      : E->spans[k],
                  "'%s' was first declared here", name);
        return -1;
    }
    if ((f = member_of(E, name, &idx)) != NULL) {
        diag_error(E->d, span,
                   "'%s' is the name of the family member %s[%ld]; choose "
                   "another name",
                   name, f->name, (long)idx);
        diag_note(E->d, f->span, "the family %s is declared here", f->name);
        return -1;
    }
    return 0;
}

static void add_name(Expander *E, const char *name, Span span)
{
    if (E->nnames == E->capnames) {
        E->capnames = E->capnames ? 2 * E->capnames : 32;
        E->names = pc_xrealloc(E->names, sizeof(char *) * (size_t)E->capnames);
        E->spans = pc_xrealloc(E->spans, sizeof(Span) * (size_t)E->capnames);
    }
    E->names[E->nnames] = name;
    E->spans[E->nnames++] = span;
}

static const char *ex_member_name(Expander *E, const char *base, slong k)
{
    char buf[32];
    size_t n = strlen(base);
    snprintf(buf, sizeof buf, "_%ld", (long)k);
    char *s = arena_alloc(E->a, n + strlen(buf) + 1);
    memcpy(s, base, n);
    strcpy(s + n, buf);
    return s;
}

/* ---- integer expressions ------------------------------------------------ */

int ex_int_range(Expander *E, Span span, __int128 v, slong *out)
{
    if (v >= EXPAND_MAX_INT || v <= -EXPAND_MAX_INT) {
        diag_error(E->d, span,
                   "integer too large: the integers of a scheme stay below "
                   "2^40 in magnitude");
        return -1;
    }
    *out = (slong)v;
    return 0;
}

/* n as a whole number: numbers, int constants, the comprehension variable,
 * + - * / ^ (an exact division, a non-negative exponent) */

int ex_eval_int(Expander *E, const Node *n, slong *out)
{
    slong a, b;
    if (ex_too_deep(n)) {
        diag_error(E->d, n->span,
                   "expression nested too deeply (%d levels; at most %d)",
                   n->depth, SEMA_MAX_DEPTH);
        return -1;
    }
    switch (n->kind) {
    case ND_NUM: {
        const char *c = n->text;
        for (; *c; c++)
            if (!isdigit((unsigned char)*c))
                break;
        if (*c || strlen(n->text) > 13) {
            if (*c)
                diag_error(E->d, n->span,
                           "expected a whole number here, found '%s'", n->text);
            else
                diag_error(E->d, n->span,
                           "integer too large: the integers of a scheme stay "
                           "below 2^40 in magnitude");
            return -1;
        }
        return ex_int_range(E, n->span, (__int128)strtoll(n->text, NULL, 10),
                            out);
    }
    case ND_NAME: {
        const Binding *bd = ex_find_binding(E, n->text);
        if (bd && !bd->arg) {
            *out = bd->value;
            return 0;
        }
        if (bd) /* a parameter: its argument, expanded at the call */
            return ex_eval_int(E, bd->arg, out);
        IntSym *is = ex_find_int(E, n->text);
        if (is) {
            *out = is->value;
            return is->bad ? -1 : 0;
        }
        diag_error(E->d, n->span,
                   "'%s' is not an integer; expected whole numbers, 'int' "
                   "constants and comprehension variables here",
                   n->text);
        return -1;
    }
    case ND_NEG:
        if (ex_eval_int(E, n->lhs, &a) < 0)
            return -1;
        *out = -a;
        return 0;
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
    case ND_DIV:
    case ND_POW:
        if (ex_eval_int(E, n->lhs, &a) < 0 || ex_eval_int(E, n->rhs, &b) < 0)
            return -1;
        switch (n->kind) {
        case ND_ADD:
            return ex_int_range(E, n->span, (__int128)a + b, out);
        case ND_SUB:
            return ex_int_range(E, n->span, (__int128)a - b, out);
        case ND_MUL:
            return ex_int_range(E, n->span, (__int128)a * b, out);
        case ND_DIV:
            if (b == 0) {
                diag_error(E->d, n->rhs->span, "division by zero");
                return -1;
            }
            if (a % b != 0) {
                diag_error(E->d, n->span,
                           "%ld/%ld is not a whole number; expected an exact "
                           "division here",
                           (long)a, (long)b);
                return -1;
            }
            *out = a / b;
            return 0;
        default: {
            if (b < 0) {
                diag_error(E->d, n->rhs->span,
                           "expected a non-negative exponent here, found %ld",
                           (long)b);
                return -1;
            }
            __int128 p = 1;
            for (slong k = 0; k < b; k++) {
                p *= a;
                if (p >= EXPAND_MAX_INT || p <= -EXPAND_MAX_INT)
                    return ex_int_range(E, n->span, p, out);
                if (p == 0 || p == 1)
                    break;
            }
            if (p == 1 && a == -1 && b % 2)
                p = -1;
            return ex_int_range(E, n->span, p, out);
        }
        }
    case ND_COMPR:
        return ex_eval_int_compr(E, n, out);
    case ND_CALL:
    case ND_INDEX:
        break;
    }
    diag_error(E->d, n->span,
               "expected a whole number here (numbers, 'int' constants, "
               "comprehension variables, + - * / ^)");
    return -1;
}

/* ---- expressions -------------------------------------------------------- */

int ex_budget_nodes(Expander *E, const Node *n, long k)
{
    E->nodes += k;
    if (E->nodes <= EXPAND_MAX_NODES)
        return 0;
    if (!E->over)
        diag_error(E->d, n->span,
                   "the scheme unrolls to more than %d expression nodes; "
                   "expected smaller families or comprehensions",
                   EXPAND_MAX_NODES);
    E->over = 1;
    return -1;
}

static int budget_members(Expander *E, Span span, slong k)
{
    if (k > 0)
        E->members += (long)k;
    if (E->members <= EXPAND_MAX_MEMBERS)
        return 0;
    if (!E->over)
        diag_error(E->d, span,
                   "the scheme unrolls to more than %d family members and "
                   "equations; expected smaller families or comprehensions",
                   EXPAND_MAX_MEMBERS);
    E->over = 1;
    return -1;
}

Node *ex_clone(Expander *E, const Node *n)
{
    if (!n)
        return NULL;
    Node *c = arena_new(E->a, Node);
    *c = *n;
    c->lhs = ex_clone(E, n->lhs);
    c->rhs = ex_clone(E, n->rhs);
    c->next = NULL;
    c->args = NULL;
    Node **tail = &c->args;
    for (const Node *x = n->args; x; x = x->next) {
        *tail = ex_clone(E, x);
        tail = &(*tail)->next;
    }
    return c;
}

long ex_count_nodes(const Node *n)
{
    long k = 0;
    for (; n; n = n->next)
        k += 1 + ex_count_nodes(n->lhs) + ex_count_nodes(n->rhs) +
             ex_count_nodes(n->args);
    return k;
}

/* the number v as an expression (a negative one as -|v|) at span */
static Node *ex_number(Expander *E, slong v, Span span)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%ld", (long)(v < 0 ? -v : v));
    Node *n = ast_new_num(E->a, arena_strdup(E->a, buf), span);
    return v < 0 ? ast_new_unary(E->a, ND_NEG, n, span) : n;
}

/* the member index of family f that n's index denotes, checked */
static int member_index(Expander *E, const Family *f, const Node *ix, slong *k)
{
    if (ex_eval_int(E, ix, k) < 0)
        return -1;
    if (*k < f->lo || *k > f->hi) {
        if (f->lo > f->hi)
            diag_error(E->d, ix->span,
                       "index %ld is out of range: the family %s is empty",
                       (long)*k, f->name);
        else if (ex_index_binding(E))
            diag_error(E->d, ix->span,
                       "index %ld (at %s = %ld) is out of range: %s has the "
                       "members %s[%ld..%ld]",
                       (long)*k, ex_index_binding(E)->name,
                       (long)ex_index_binding(E)->value, f->name, f->name,
                       (long)f->lo, (long)f->hi);
        else
            diag_error(E->d, ix->span,
                       "index %ld is out of range: %s has the members "
                       "%s[%ld..%ld]",
                       (long)*k, f->name, f->name, (long)f->lo, (long)f->hi);
        return -1;
    }
    return 0;
}

static Family *family_of(Expander *E, const char *name, Span span)
{
    Family *f = ex_find_family(E, name);
    if (!f)
        diag_error(E->d, span,
                   "'%s' is not a family; expected NAME[i] of a family "
                   "declared as NAME[lo..hi]",
                   name);
    return f;
}

/* a call's argument list with every range NAME[a..b] replaced by its
 * members */
int ex_rewrite_args(Expander *E, Node *call)
{
    int st = 0;
    Node *out = NULL, **tail = &out;
    int nargs = 0, depth = 1;
    for (Node *x = call->args, *next; x; x = next) {
        next = x->next;
        x->next = NULL;
        if (x->kind == ND_INDEX && x->rhs) {
            Family *f = family_of(E, x->text, x->name_span);
            slong lo, hi;
            if (!f || ex_eval_int(E, x->lhs, &lo) < 0 ||
                ex_eval_int(E, x->rhs, &hi) < 0) {
                st = -1;
                continue;
            }
            if (lo <= hi && (lo < f->lo || hi > f->hi)) {
                slong bad = lo < f->lo ? lo : hi;
                diag_error(E->d, lo < f->lo ? x->lhs->span : x->rhs->span,
                           "index %ld is out of range: %s has the members "
                           "%s[%ld..%ld]",
                           (long)bad, f->name, f->name, (long)f->lo,
                           (long)f->hi);
                st = -1;
                continue;
            }
            if (ex_budget_nodes(E, x, hi - lo + 1) < 0)
                return -1;
            for (slong k = lo; k <= hi; k++) {
                *tail =
                    ast_new_name(E->a, ex_member_name(E, f->name, k), x->span);
                tail = &(*tail)->next;
                nargs++;
            }
            continue;
        }
        if (ex_rewrite(E, &x) < 0)
            st = -1;
        *tail = x;
        tail = &x->next;
        nargs++;
        if (x->depth + 1 > depth)
            depth = x->depth + 1;
    }
    call->args = out;
    call->nargs = nargs;
    call->depth = depth;
    return st;
}

/* An expression deeper than sema accepts is left alone: sema refuses it at
 * its root before recursing, and so must every pass before it (the
 * recursion below would otherwise run as deep as the parser allows). */
int ex_too_deep(const Node *n)
{
    return n->depth > SEMA_MAX_DEPTH;
}

int ex_rewrite(Expander *E, Node **slot)
{
    Node *n = *slot;
    if (ex_too_deep(n))
        return 0;
    if (stack_low()) {
        diag_error(E->d, n->span, STACK_MESSAGE);
        return -1;
    }
    switch (n->kind) {
    case ND_NUM:
        return 0;
    case ND_NAME: {
        slong v;
        const Binding *b = ex_find_binding(E, n->text);
        if (b && b->arg) { /* a parameter: a copy of its argument */
            if (ex_budget_nodes(E, n, ex_count_nodes(b->arg)) < 0)
                return -1;
            Node *c = ex_clone(E, b->arg);
            c->next = n->next;
            *slot = c;
            return 0;
        }
        if (b || ex_find_int(E, n->text)) {
            if (ex_eval_int(E, n, &v) < 0)
                return -1;
            Node *num = ex_number(E, v, n->span);
            num->next = n->next;
            *slot = num;
            return 0;
        }
        Family *f = ex_find_family(E, n->text);
        if (f) {
            diag_error(E->d, n->span,
                       "'%s' is a family of %s; expected a member %s[i] or "
                       "a range %s[a..b] among a function's arguments",
                       n->text, f->what, n->text, n->text);
            return -1;
        }
        return 0;
    }
    case ND_INDEX: {
        slong k;
        if (n->rhs) {
            diag_error(E->d, n->span,
                       "a range %s[a..b] stands for several points; expected "
                       "it among the arguments of a function such as "
                       "bezier()",
                       n->text);
            return -1;
        }
        Family *f = family_of(E, n->text, n->name_span);
        if (!f || member_index(E, f, n->lhs, &k) < 0)
            return -1;
        Node *m = ast_new_name(E->a, ex_member_name(E, f->name, k), n->span);
        m->next = n->next;
        *slot = m;
        return 0;
    }
    case ND_CALL: {
        int st;
        if (ex_expand_call(E, slot, &st))
            return st;
        return ex_rewrite_args(E, n);
    }
    case ND_COMPR:
        return ex_expand_compr(E, slot);
    case ND_NEG:
    case ND_ADD:
    case ND_SUB:
    case ND_MUL:
    case ND_DIV:
    case ND_POW: {
        int st = ex_rewrite(E, &n->lhs);
        if (n->rhs && ex_rewrite(E, &n->rhs) < 0)
            st = -1;
        n->depth = n->lhs->depth + 1;
        if (n->rhs && n->rhs->depth + 1 > n->depth)
            n->depth = n->rhs->depth + 1;
        return st;
    }
    }
    return 0;
}

/* ---- name lists --------------------------------------------------------- */

/* a declaration list: plain names and families NAME[lo..hi] */
static Name *declare_names(Expander *E, Name *list, const char *what,
                           int allow_family)
{
    Name *out = NULL, **tail = &out;
    for (Name *nm = list, *next; nm; nm = next) {
        next = nm->next;
        nm->next = NULL;
        if (nm->index || (nm->lo && !allow_family)) {
            diag_error(E->d, nm->span,
                       allow_family ? "expected a name or a family "
                                      "NAME[lo..hi] in a declaration"
                                    : "expected a plain name; families of "
                                      "parameters and constants are not "
                                      "supported");
            continue;
        }
        if (ex_check_free(E, nm->text, nm->span, nm->lo != NULL) < 0)
            continue;
        if (!nm->lo) {
            add_name(E, nm->text, nm->span);
            *tail = nm;
            tail = &nm->next;
            continue;
        }
        slong lo, hi;
        if (ex_eval_int(E, nm->lo, &lo) < 0 || ex_eval_int(E, nm->hi, &hi) < 0)
            continue;
        if (lo < 0) {
            diag_error(E->d, nm->lo->span,
                       "a family's indices start at 0 or above, found %ld",
                       (long)lo);
            continue;
        }
        /* no earlier plain name may be one of its members */
        int clash = 0;
        for (int i = 0; i < E->nnames && !clash; i++) {
            slong k;
            if (!is_member_name(E->names[i], nm->text, lo, hi, &k))
                continue;
            diag_error(E->d, nm->span,
                       "the family member %s[%ld] would be named '%s', which "
                       "is declared already",
                       nm->text, (long)k, E->names[i]);
            diag_note(E->d, E->spans[i], "'%s' was declared here", E->names[i]);
            clash = 1;
        }
        if (clash || budget_members(E, nm->span, hi - lo + 1) < 0)
            continue;
        if (E->nfams == E->capfams) {
            E->capfams = E->capfams ? 2 * E->capfams : 8;
            E->fams = pc_xrealloc(E->fams, sizeof(Family) * (size_t)E->capfams);
        }
        E->fams[E->nfams++] = (Family){nm->text, lo, hi, nm->span, what};
        for (slong k = lo; k <= hi; k++) {
            Name *m = ast_new_namelist(E->a, ex_member_name(E, nm->text, k),
                                       nm->span);
            *tail = m;
            tail = &m->next;
        }
    }
    return out;
}

/* a list that refers to names (for X, ...; output ...): plain names,
 * members NAME[i] and ranges NAME[a..b] */
static Name *refer_names(Expander *E, Name *list)
{
    Name *out = NULL, **tail = &out;
    for (Name *nm = list, *next; nm; nm = next) {
        next = nm->next;
        nm->next = NULL;
        if (!nm->index && !nm->lo) {
            Family *f = ex_find_family(E, nm->text);
            if (f) { /* the whole family */
                for (slong k = f->lo; k <= f->hi; k++) {
                    Name *m = ast_new_namelist(
                        E->a, ex_member_name(E, f->name, k), nm->span);
                    *tail = m;
                    tail = &m->next;
                }
                continue;
            }
            *tail = nm;
            tail = &nm->next;
            continue;
        }
        Family *f = family_of(E, nm->text, nm->span);
        slong lo, hi;
        if (!f)
            continue;
        if (nm->index) {
            if (member_index(E, f, nm->index, &lo) < 0)
                continue;
            hi = lo;
        } else {
            if (ex_eval_int(E, nm->lo, &lo) < 0 ||
                ex_eval_int(E, nm->hi, &hi) < 0)
                continue;
            if (lo <= hi && (lo < f->lo || hi > f->hi)) {
                const Node *bad = lo < f->lo ? nm->lo : nm->hi;
                diag_error(E->d, bad->span,
                           "index %ld is out of range: %s has the members "
                           "%s[%ld..%ld]",
                           (long)(lo < f->lo ? lo : hi), f->name, f->name,
                           (long)f->lo, (long)f->hi);
                continue;
            }
        }
        for (slong k = lo; k <= hi; k++) {
            Name *m =
                ast_new_namelist(E->a, ex_member_name(E, f->name, k), nm->span);
            *tail = m;
            tail = &m->next;
        }
    }
    return out;
}

/* ---- statements --------------------------------------------------------- */

static int parse_define(const char *text, char *name, size_t cap, slong *v)
{
    const char *eq = strchr(text, '=');
    if (!eq || eq == text || (size_t)(eq - text) >= cap)
        return -1;
    if (!(isalpha((unsigned char)text[0]) || text[0] == '_'))
        return -1;
    for (const char *c = text; c < eq; c++)
        if (!(isalnum((unsigned char)*c) || *c == '_'))
            return -1;
    const char *d = eq + 1;
    if (*d == '-' || *d == '+')
        d++;
    if (!*d || strlen(d) > 13 || strspn(d, "0123456789") != strlen(d))
        return -1;
    long long x = strtoll(eq + 1, NULL, 10);
    if (x >= EXPAND_MAX_INT || x <= -EXPAND_MAX_INT)
        return -1;
    memcpy(name, text, (size_t)(eq - text));
    name[eq - text] = '\0';
    *v = (slong)x;
    return 0;
}

int expand_check_define(const char *text)
{
    char name[128];
    slong v;
    return parse_define(text, name, sizeof name, &v);
}

static void expand_int(Expander *E, Stmt *st, const char *const *defines,
                       int ndefines, char *used)
{
    slong v = 0;
    const char *name = st->name->text;
    int bad;
    if (ex_check_free(E, name, st->name->span, 1) < 0)
        return;
    bad = ex_eval_int(E, st->expr, &v) < 0;
    for (int k = 0; k < ndefines; k++) {
        char dn[128];
        slong dv;
        if (parse_define(defines[k], dn, sizeof dn, &dv) == 0 &&
            strcmp(dn, name) == 0) {
            v = dv;
            bad = 0;
            used[k] = 1;
        }
    }
    if (E->nints == E->capints) {
        E->capints = E->capints ? 2 * E->capints : 8;
        E->ints = pc_xrealloc(E->ints, sizeof(IntSym) * (size_t)E->capints);
    }
    E->ints[E->nints++] = (IntSym){name, bad ? 0 : v, st->name->span, bad};
}

static void expand_solve(Expander *E, Stmt *st)
{
    Equation *out = NULL, **tail = &out;
    for (Equation *e = st->eqs, *next; e; e = next) {
        next = e->next;
        e->next = NULL;
        if (!e->var || ex_too_deep(e->lhs) || ex_too_deep(e->rhs)) {
            if (ex_rewrite(E, &e->lhs) < 0 || ex_rewrite(E, &e->rhs) < 0) {
                st->bad = 1;
                continue;
            }
            *tail = e;
            tail = &e->next;
            continue;
        }
        slong lo, hi;
        if (ex_check_free(E, e->var, e->var_span, 1) < 0 ||
            ex_eval_int(E, e->lo, &lo) < 0 || ex_eval_int(E, e->hi, &hi) < 0 ||
            budget_members(E, e->span, hi - lo + 1) < 0) {
            st->bad = 1;
            continue;
        }
        long size = ex_count_nodes(e->lhs) + ex_count_nodes(e->rhs);
        for (slong k = lo; k <= hi; k++) {
            if (ex_budget_nodes(E, e->lhs, size) < 0) {
                st->bad = 1;
                break;
            }
            Equation *c = ast_new_equation(E->a, ex_clone(E, e->lhs),
                                           ex_clone(E, e->rhs), e->span);
            ex_bind(E, e->var, NULL, k);
            int bad = ex_rewrite(E, &c->lhs) < 0 || ex_rewrite(E, &c->rhs) < 0;
            E->nbinds--;
            if (bad) { /* one report is enough: stop at the first value */
                st->bad = 1;
                break;
            }
            *tail = c;
            tail = &c->next;
        }
    }
    st->eqs = out;
    st->names = refer_names(E, st->names);
    for (Equation *b = st->start; b; b = b->next) /* `near k = n/2` */
        if (ex_rewrite(E, &b->rhs) < 0)
            st->bad = 1;
}

/* `check Ck(...)`, `Gk(...)` with k an int (or a comprehension's index):
 * the claim renamed C3, G2 ...; 0, or -1 after an error */
static int check_order_name(Expander *E, Node *call)
{
    const char *f = call->text;
    if ((f[0] != 'C' && f[0] != 'G') || !isalpha((unsigned char)f[1]) ||
        (!ex_find_binding(E, f + 1) && !ex_find_int(E, f + 1)))
        return 0;
    Node k = {.kind = ND_NAME, .text = f + 1, .span = call->name_span};
    k.span.start++;
    slong v;
    if (ex_eval_int(E, &k, &v) < 0)
        return -1;
    if (v < 0 || v > CHECK_MAX_ORDER) {
        diag_error(E->d, call->name_span,
                   "%s is %c%ld: the order of continuity goes from 0 to %d", f,
                   f[0], (long)v, CHECK_MAX_ORDER);
        return -1;
    }
    char name[32];
    snprintf(name, sizeof name, "%c%ld", f[0], (long)v);
    call->text = arena_strdup(E->a, name);
    return 0;
}

/* a check (compiler/check.h): its values, the claim's arguments but not
 * the claim itself (a user function called on() does not replace the
 * claim on()), and the values of its `at` bindings */
static void expand_claim(Expander *E, Stmt *st)
{
    int bad = 0;
    if (st->rhs)
        bad = ex_rewrite(E, &st->expr) < 0 || ex_rewrite(E, &st->rhs) < 0;
    else if (st->expr->kind == ND_CALL && !ex_too_deep(st->expr))
        bad = check_order_name(E, st->expr) < 0 ||
              ex_rewrite_args(E, st->expr) < 0;
    for (Equation *b = st->eqs; b; b = b->next)
        bad |= ex_rewrite(E, &b->rhs) < 0;
    st->bad = bad;
}

/* an instance of a check's comprehension: a copy of st, with i = k told
 * in its name (for the messages) */
static Stmt *check_instance(Expander *E, const Stmt *st, const char *var,
                            slong k)
{
    Stmt *c = ast_new_stmt(E->a, ST_CHECK, st->span);
    c->expr = ex_clone(E, st->expr);
    c->rhs = st->rhs ? ex_clone(E, st->rhs) : NULL;
    Equation **tail = &c->eqs;
    for (const Equation *b = st->eqs; b; b = b->next) {
        *tail = ast_new_equation(E->a, ex_clone(E, b->lhs), ex_clone(E, b->rhs),
                                 b->span);
        tail = &(*tail)->next;
    }
    char text[64];
    snprintf(text, sizeof text, "%s = %ld", var, (long)k);
    c->name = ast_new_namelist(E->a, arena_strdup(E->a, text), st->span);
    return c;
}

/* a check, or `check ... for i in a..b`: one claim per i, in order, each
 * after the one before (sum's index semantics: a..b inclusive, none when
 * b < a).  Returns the last statement it leaves in the list. */
static Stmt *expand_check(Expander *E, Stmt *st)
{
    Equation *f = st->eqs, **link = &st->eqs;
    while (f && f->lhs)
        link = &f->next, f = f->next;
    if (!f) {
        expand_claim(E, st);
        return st;
    }
    *link = NULL; /* the comprehension: the last "binding" */
    slong lo, hi;
    if (ex_check_free(E, f->var, f->var_span, 1) < 0 ||
        ex_eval_int(E, f->lo, &lo) < 0 || ex_eval_int(E, f->hi, &hi) < 0 ||
        budget_members(E, f->span, hi - lo + 1) < 0) {
        st->bad = 1;
        return st;
    }
    Stmt *last = st, *next = st->next;
    for (slong k = lo; k <= hi; k++) {
        Stmt *c = check_instance(E, st, f->var, k);
        ex_bind(E, f->var, NULL, k);
        expand_claim(E, c);
        E->nbinds--;
        last->next = c;
        last = c;
    }
    last->next = next;
    st->bad = 1; /* the template itself is no claim: skipped, silently */
    return last;
}

int expand_scheme(Scheme *s, Arena *a, Diag *diag, const char *const *defines,
                  int ndefines, char *used)
{
    Expander E = {.a = a, .d = diag};
    int errors0 = diag->nerrors;
    for (int k = 0; k < ndefines; k++)
        used[k] = 0;
    for (Stmt *st = s->stmts; st && !E.over; st = st->next) {
        E.stmt = st;
        budget_statement(diag->src, st->span); /* blamed if out of memory */
        switch (st->kind) {
        case ST_SCHEME:
            break;
        case ST_INT:
            expand_int(&E, st, defines, ndefines, used);
            break;
        case ST_POINT:
            st->names = declare_names(&E, st->names, "points", 1);
            break;
        case ST_UNKNOWN:
            st->names = declare_names(&E, st->names, "unknowns", 1);
            break;
        case ST_PARAM:
        case ST_CONST:
            st->names = declare_names(
                &E, st->names, st->kind == ST_PARAM ? "params" : "consts", 0);
            if (st->lo)
                ex_rewrite(&E, &st->lo);
            if (st->hi)
                ex_rewrite(&E, &st->hi);
            break;
        case ST_FUNC:
            ex_define_func(&E, st);
            break;
        case ST_DEF:
            if (ex_check_free(&E, st->name->text, st->name->span, 0) == 0)
                add_name(&E, st->name->text, st->name->span);
            ex_rewrite(&E, &st->expr);
            break;
        case ST_SOLVE:
            expand_solve(&E, st);
            break;
        case ST_OUTPUT:
            st->names = refer_names(&E, st->names);
            break;
        case ST_CHECK:
            st = expand_check(&E, st);
            break;
        case ST_FIT: /* its names may be members: fit M[2] to f ... */
            st->names = refer_names(&E, st->names);
            ex_rewrite(&E, &st->lo);
            ex_rewrite(&E, &st->hi);
            if (st->expr)
                ex_rewrite(&E, &st->expr);
            break;
        }
    }
    pc_free(E.ints);
    pc_free(E.fams);
    pc_free(E.funcs);
    pc_free(E.binds);
    pc_free(E.names);
    pc_free(E.spans);
    return diag->nerrors - errors0;
}

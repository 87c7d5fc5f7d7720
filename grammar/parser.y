/*
 * parser.y - the pure, located bison grammar of .pcs schemes.
 *
 * One statement per line; `error NEWLINE` resynchronises at the end of a
 * bad line so every syntax error of a file is reported.  Actions only call
 * ast_new_* builders (house style 12); names, kinds, arity and weight sums are
 * checked in compiler/sema.c.
 */
%define api.pure full
%define api.prefix {pc_yy}
%define api.location.type {Span}
%define parse.error detailed
%locations
%param {yyscan_t scanner}
%parse-param {Parser *p}
%expect 0
%define api.value.type union

%code requires {
#include "base/arena.h"
#include "base/diag.h"
#include "base/source.h"
#include "grammar/ast.h"

#ifndef YY_TYPEDEF_YY_SCANNER_T
#define YY_TYPEDEF_YY_SCANNER_T
typedef void *yyscan_t;
#endif

/* scanner state (yyextra) */
typedef struct LexState {
    Arena *arena;  // where identifier and number texts are copied
    Diag *diag;    // lexical errors
    int offset;    // byte offset of the next token
    int eof_nl;    // the synthetic final NEWLINE was returned
    int line_bad;  // a bad character was reported on this line: the
                   // rest of its bad characters are not (no cascade)
} LexState;

/* parser state */
typedef struct Parser {
    Arena *arena;
    Diag *diag;
    Scheme *scheme;
    Stmt *tail; // last statement, for appending
    Equation *seqs; // the solve being parsed: its equations so far
    Name *snames;   // ... and its unknowns
    Equation *sstart; // ... and the starts of a numeric solve (`near`)
} Parser;

/* a span from the first to the last right-hand-side symbol (jq's rule) */
#define YYLLOC_DEFAULT(Cur, Rhs, N)                                            \
    do {                                                                       \
        if (N) {                                                               \
            (Cur).start = YYRHSLOC(Rhs, 1).start;                              \
            (Cur).end = YYRHSLOC(Rhs, N).end;                                  \
        } else {                                                               \
            (Cur).start = (Cur).end = YYRHSLOC(Rhs, 0).end;                    \
        }                                                                      \
    } while (0)
}

%code provides {
#define YYSTYPE PC_YYSTYPE
#define YYLTYPE PC_YYLTYPE
#define YY_DECL int pc_yylex(PC_YYSTYPE *yylval_param, PC_YYLTYPE *yylloc_param, yyscan_t yyscanner)
YY_DECL;
}

%code {
#include <string.h>

#define PARSER_MAX_DEPTH 10000 /* bison's default YYMAXDEPTH, made explicit */
#define YYMAXDEPTH PARSER_MAX_DEPTH

static void pc_yyerror(Span *loc, yyscan_t scanner, Parser *p, const char *msg)
{
    (void)scanner;
    if (strcmp(msg, "memory exhausted") == 0) /* the parser's stack limit */
        diag_error(p->diag, *loc,
                   "expression nested too deeply for the parser (%d levels "
                   "of parentheses or operators at most)",
                   PARSER_MAX_DEPTH);
    else
        diag_error(p->diag, *loc, "%s", msg);
}

static void add_stmt(Parser *p, Stmt *s)
{
    if (!s)
        return;
    if (p->tail)
        p->tail->next = s;
    else
        p->scheme->stmts = s;
    p->tail = s;
}

static Stmt *stmt_names(Parser *p, StmtKind k, Name *names, Span span)
{
    Stmt *s = ast_new_stmt(p->arena, k, span);
    s->names = names;
    return s;
}

/* a name of a fit (X, f): NAME or a member NAME[i] written as an
 * expression; anything else is reported (NULL) */
static Name *fit_name(Parser *p, const Node *n)
{
    if (n->kind == ND_NAME)
        return ast_new_namelist(p->arena, n->text, n->span);
    if (n->kind == ND_INDEX) {
        Name *nm = ast_new_namelist(p->arena, n->text, n->span);
        if (n->rhs) {
            nm->lo = n->lhs;
            nm->hi = n->rhs;
        } else {
            nm->index = n->lhs;
        }
        return nm;
    }
    diag_error(p->diag, n->span,
               "expected a name in 'fit X to f on [LO, HI]' (docs/fit.md)");
    return NULL;
}

/* `fit X to f on [lo, hi]`: fit, to and on are keywords only here; the
 * first of them that is not the word expected is reported */
static Stmt *stmt_fit(Parser *p, const char *const *kw, const Span *kws,
                      Node *xn, Node *fn, Span span)
{
    static const char *const want[3] = {"fit", "to", "on"};
    for (int i = 0; i < 3; i++)
        if (strcmp(kw[i], want[i]) != 0) {
            diag_error(p->diag, kws[i],
                       "unexpected '%s'; expected 'fit X to f on [LO, HI]' "
                       "(a curve fitted to a function, docs/fit.md)",
                       kw[i]);
            return NULL;
        }
    Name *x = fit_name(p, xn), *f = x ? fit_name(p, fn) : NULL;
    if (!f)
        return NULL;
    Stmt *s = stmt_names(p, ST_FIT, x, span);
    x->next = f;
    return s;
}

/* `fit X to data "FILE.csv" on [lo, hi]`: the target is data (data is a
 * keyword only here) */
static Stmt *stmt_fit_data(Parser *p, const char *const *kw, const Span *kws,
                           Node *xn, const char *file, Span span)
{
    static const char *const want[4] = {"fit", "to", "data", "on"};
    for (int i = 0; i < 4; i++)
        if (strcmp(kw[i], want[i]) != 0) {
            diag_error(p->diag, kws[i],
                       "unexpected '%s'; expected 'fit X to data \"FILE.csv\" "
                       "on [LO, HI]' (a curve fitted to data, docs/fit.md)",
                       kw[i]);
            return NULL;
        }
    Name *x = fit_name(p, xn);
    if (!x)
        return NULL;
    Stmt *s = stmt_names(p, ST_FIT, x, span);
    s->data = file;
    return s;
}

/* `def NAME(a, b) = ...`: the call's arguments must be plain names */
static Stmt *stmt_func(Parser *p, Node *call, Node *body, Span span)
{
    Name *params = NULL;
    for (Node *a = call->args; a; a = a->next) {
        if (a->kind != ND_NAME) {
            diag_error(p->diag, a->span,
                       "expected a parameter name in 'def %s(NAME, ...) = "
                       "...'",
                       call->text);
            return NULL;
        }
        params =
            ast_append_name(params, ast_new_namelist(p->arena, a->text, a->span));
    }
    Stmt *s = ast_new_stmt(p->arena, ST_FUNC, span);
    s->name = ast_new_namelist(p->arena, call->text, call->name_span);
    s->names = params;
    s->expr = body;
    return s;
}

/* A statement that starts with a word other than a keyword: `int n = 12`,
 * `def f(t) = ...` and `check L = R [at t = 0]`, `check on(P, line(A, B))`
 * (int, def and check are keywords only here, so that older schemes may
 * still call a point int, def or check).  lhs = rhs when rhs is not NULL,
 * else lhs alone; at: the bindings of `at`, or NULL. */
static Stmt *stmt_word(Parser *p, const char *w, Span ws, Node *lhs, Node *rhs,
                       Equation *at, Span span)
{
    if (strcmp(w, "check") == 0) {
        Stmt *s = ast_new_stmt(p->arena, ST_CHECK, span);
        s->expr = lhs;
        s->rhs = rhs;
        s->eqs = at;
        return s;
    }
    int is_int = strcmp(w, "int") == 0, is_def = strcmp(w, "def") == 0;
    if (rhs && at && (is_int || is_def)) {
        diag_error(p->diag, at->span,
                   at->lhs ? "unexpected 'at' after '%s %s': 'at' belongs to "
                             "a check"
                           : "unexpected 'for' after '%s %s': 'for i in "
                             "a..b' after a statement belongs to a check",
                   w, lhs->text ? lhs->text : "...");
        return NULL;
    }
    if (rhs && lhs->kind == ND_NAME) {
        if (!is_int) {
            diag_error(p->diag, ws,
                       "unexpected '%s' before the name '%s'; expected 'int "
                       "%s = ...' or '%s = ...'",
                       w, lhs->text, lhs->text, lhs->text);
            return NULL;
        }
        Stmt *s = ast_new_stmt(p->arena, ST_INT, span);
        s->name = ast_new_namelist(p->arena, lhs->text, lhs->span);
        s->expr = rhs;
        return s;
    }
    if (rhs && lhs->kind == ND_CALL) {
        if (!is_def) {
            diag_error(p->diag, ws,
                       "unexpected '%s' before '%s(...)'; expected 'def "
                       "%s(NAME, ...) = ...' (a function)",
                       w, lhs->text, lhs->text);
            return NULL;
        }
        return stmt_func(p, lhs, rhs, span);
    }
    diag_error(p->diag, ws,
               "unexpected '%s'; expected a statement: 'check CLAIM', 'int "
               "NAME = ...', 'def NAME(...) = ...' or 'NAME = ...'",
               w);
    return NULL;
}

/* `at t = 0, u = 1`: at is a keyword only here */
static Equation *at_clause(Parser *p, const char *w, Span ws, Equation *binds)
{
    if (strcmp(w, "at") == 0)
        return binds;
    diag_error(p->diag, ws,
               "unexpected '%s'; expected 'at NAME = VALUE' or the end of "
               "the line",
               w);
    return NULL;
}

/* a numeric solve's `near a = 1, b = 0` (near is a keyword only here) */
static Equation *near_clause(Parser *p, const char *w, Span ws,
                             Equation *starts)
{
    if (strcmp(w, "near") == 0)
        return starts;
    diag_error(p->diag, ws,
               "unexpected '%s'; expected 'near NAME = VALUE, ...' (the "
               "start of a numeric solve) or the end of the line",
               w);
    return NULL;
}

/* `E at t = v` among a call's arguments: subst(E, t, v) (at is a keyword
 * only here) */
static Node *arg_at(Parser *p, Node *e, const char *w, Span ws, Node *var,
                    Node *val, Span span)
{
    if (strcmp(w, "at") != 0) {
        diag_error(p->diag, ws,
                   "unexpected '%s'; expected 'EXPR at NAME = VALUE', ',' "
                   "or ')'",
                   w);
        return e;
    }
    e->next = var;
    var->next = val;
    return ast_new_call(p->arena, "subst", ws, e, span);
}
}

%token <const char *> IDENT "identifier"
%token <const char *> NUMBER "number"
%token <const char *> STRING "string"
%token NEWLINE "end of line"
%token SCHEME "'scheme'" POINT "'point'" PARAM "'param'" CONST "'const'"
%token UNKNOWN "'unknown'" SOLVE "'solve'" FOR "'for'" OUTPUT "'output'"
%token IN "'in'" DOTDOT "'..'" LE "'<='" GE "'>='"

%left '+' '-'
%left '*' '/'
%precedence UMINUS
%right '^'

%type <Node *> expr args arg fit_samples
%type <Name *> names name
%type <Equation *> at_opt bindings check_for near_opt
%type <Stmt *> stmt
%type <int> lbr rbr

%%

/* scheme = line* */
scheme:
  %empty
| scheme line
;

/* line = NEWLINE | stmt NEWLINE | error NEWLINE */
line:
  NEWLINE
| stmt NEWLINE      { add_stmt(p, $1); }
| error NEWLINE     { yyerrok; }
;

stmt:
  SCHEME IDENT      { $$ = ast_new_stmt(p->arena, ST_SCHEME, @$);
                      $$->name = ast_new_namelist(p->arena, $2, @2); }
| POINT names       { $$ = stmt_names(p, ST_POINT, $2, @$); }
| PARAM names       { $$ = stmt_names(p, ST_PARAM, $2, @$); }
| PARAM names IN lbr expr ',' expr rbr
                    { $$ = stmt_names(p, ST_PARAM, $2, @$); $$->lo = $5; $$->hi = $7;
                      $$->lo_open = $4; $$->hi_open = $8; }
| CONST names       { $$ = stmt_names(p, ST_CONST, $2, @$); }
| CONST names IN lbr expr ',' expr rbr /* `const e in (0, 1)` */
                    { $$ = stmt_names(p, ST_CONST, $2, @$); $$->lo = $5; $$->hi = $7;
                      $$->lo_open = $4; $$->hi_open = $8; }
| CONST names '>' expr /* `const a, b > 0`: positive constants */
                    { $$ = stmt_names(p, ST_CONST, $2, @$); $$->lo = $4; $$->lo_open = 1; }
| CONST names GE expr
                    { $$ = stmt_names(p, ST_CONST, $2, @$); $$->lo = $4; }
| CONST names '<' expr
                    { $$ = stmt_names(p, ST_CONST, $2, @$); $$->hi = $4; $$->hi_open = 1; }
| CONST names LE expr
                    { $$ = stmt_names(p, ST_CONST, $2, @$); $$->hi = $4; }
| UNKNOWN names     { $$ = stmt_names(p, ST_UNKNOWN, $2, @$); }
| UNKNOWN IDENT names /* `unknown scalar k`: scalar is a keyword only here */
                    { if (strcmp($2, "scalar") != 0) {
                          diag_error(p->diag, @2,
                                     "unexpected '%s'; expected 'unknown "
                                     "NAME, ...' (points) or 'unknown scalar "
                                     "NAME, ...'",
                                     $2);
                          $$ = NULL;
                      } else {
                          $$ = stmt_names(p, ST_UNKNOWN, $3, @$);
                          $$->scalar = 1;
                      } }
| OUTPUT names      { $$ = stmt_names(p, ST_OUTPUT, $2, @$); }
| IDENT '=' expr    { $$ = ast_new_stmt(p->arena, ST_DEF, @$);
                      $$->name = ast_new_namelist(p->arena, $1, @1); $$->expr = $3; }
| IDENT expr '=' expr at_opt /* `int n = 12`, `def f(t) = ...`, `check L =
                         R [at t = 0]`: int, def, check and at are keywords
                         only here, so that older schemes may still call a
                         point int or def */
                    { $$ = stmt_word(p, $1, @1, $2, $4, $5, @$); }
| IDENT expr at_opt /* `check on(P, line(A, B))` */
                    { $$ = stmt_word(p, $1, @1, $2, NULL, $3, @$); }
| IDENT expr IDENT expr IDENT '[' expr ',' expr ']' fit_samples
                    /* `fit X to f on [-1, 1] samples 100` (docs/fit.md) */
                    { const char *kw[3] = {$1, $3, $5};
                      Span kws[3] = {@1, @3, @5};
                      $$ = stmt_fit(p, kw, kws, $2, $4, @$);
                      if ($$) {
                          $$->lo = $7;
                          $$->hi = $9;
                          $$->expr = $11;
                      } }
| IDENT expr IDENT IDENT STRING IDENT '[' expr ',' expr ']' fit_samples
                    /* `fit X to data "FILE.csv" on [-1, 1]` (docs/fit.md) */
                    { const char *kw[4] = {$1, $3, $4, $6};
                      Span kws[4] = {@1, @3, @4, @6};
                      $$ = stmt_fit_data(p, kw, kws, $2, $5, @$);
                      if ($$) {
                          $$->lo = $8;
                          $$->hi = $10;
                          $$->expr = $12;
                      } }
| SOLVE             { p->seqs = NULL; p->snames = NULL; p->sstart = NULL; }
  solve_eqs         { $$ = stmt_names(p, ST_SOLVE, p->snames, @$); $$->eqs = p->seqs;
                      $$->start = p->sstart;
                      p->seqs = NULL; p->snames = NULL; p->sstart = NULL; }
;

/* a check's `at t = 0, u = 1`, or nothing; then `for i in a..b` (a
 * comprehension: one claim per i), kept as a last binding without sides */
at_opt:
  %empty            { $$ = NULL; }
| IDENT bindings    { $$ = at_clause(p, $1, @1, $2); }
| check_for         { $$ = $1; }
| IDENT bindings check_for
                    { $$ = at_clause(p, $1, @1, $2);
                      if ($$)
                          $$ = ast_append_equation($$, $3); }
;

check_for:
  FOR IDENT IN expr DOTDOT expr
                    { $$ = ast_new_equation(p->arena, NULL, NULL, @$);
                      $$->var = $2; $$->var_span = @2; $$->lo = $4; $$->hi = $6; }
;

bindings:
  IDENT '=' expr    { $$ = ast_new_equation(p->arena, ast_new_name(p->arena, $1, @1), $3, @$); }
| bindings ',' IDENT '=' expr
                    { $$ = ast_append_equation($1, ast_new_equation(p->arena,
                          ast_new_name(p->arena, $3, @3), $5, (Span){@3.start, @5.end})); }
;

/* a fit's optional `samples M` */
fit_samples:
  %empty            { $$ = NULL; }
| IDENT expr        { $$ = $2;
                      if (strcmp($1, "samples") != 0)
                          diag_error(p->diag, @1,
                                     "unexpected '%s'; expected 'samples M' "
                                     "or the end of the fit statement",
                                     $1); }
;

/* the ends of an interval: '[' and ']' include them, '(' and ')' do not */
lbr:
  '['               { $$ = 0; }
| '('               { $$ = 1; }
;

rbr:
  ']'               { $$ = 0; }
| ')'               { $$ = 1; }
;

/* NAME, a family NAME[lo..hi], or one member NAME[i] */
name:
  IDENT             { $$ = ast_new_namelist(p->arena, $1, @1); }
| IDENT '[' expr ']'
                    { $$ = ast_new_namelist(p->arena, $1, @$); $$->index = $3; }
| IDENT '[' expr DOTDOT expr ']'
                    { $$ = ast_new_namelist(p->arena, $1, @$); $$->lo = $3; $$->hi = $5; }
;

names:
  name              { $$ = $1; }
| names ',' name    { $$ = ast_append_name($1, $3); }
;

/* solve EQ [for i in a..b], ... for X, ...: right-recursive, so that after
 * an equation `for i in` (a comprehension) and `for X` (the unknowns) are
 * told apart by the token after the name; the equations are collected in
 * the parser, in source order */
solve_eqs:
  equation solve_tail
;

solve_tail:
  FOR names near_opt { p->snames = $2; p->sstart = $3; }
| ',' solve_eqs
| compr solve_tail2
;

solve_tail2:
  FOR names near_opt { p->snames = $2; p->sstart = $3; }
| ',' solve_eqs
;

/* a numeric solve's starts, `near a = 1, b = 0`, or nothing (an exact
 * solve) */
near_opt:
  %empty            { $$ = NULL; }
| IDENT bindings    { $$ = near_clause(p, $1, @1, $2); }
;

equation:
  expr '=' expr     { p->seqs = ast_append_equation(p->seqs,
                          ast_new_equation(p->arena, $1, $3, @$)); }
;

compr:
  FOR IDENT IN expr DOTDOT expr
                    { Equation *e = p->seqs;
                      while (e->next)
                          e = e->next;
                      e->var = $2; e->var_span = @2; e->lo = $4; e->hi = $6;
                      e->span.end = @6.end; }
;

expr:
  NUMBER            { $$ = ast_new_num(p->arena, $1, @$); }
| IDENT             { $$ = ast_new_name(p->arena, $1, @$); }
| IDENT '(' args ')' { $$ = ast_new_call(p->arena, $1, @1, $3, @$); }
| IDENT '(' expr FOR IDENT IN expr DOTDOT expr ')' /* sum(E for i in a..b) */
                    { $$ = ast_new_compr(p->arena, $1, @1, $3, $5, @5, $7, $9, @$); }
| IDENT '[' expr ']' { $$ = ast_new_index(p->arena, $1, @1, $3, NULL, @$); }
| IDENT '[' expr DOTDOT expr ']'
                    { $$ = ast_new_index(p->arena, $1, @1, $3, $5, @$); }
| '(' expr ')'      { $$ = $2; $$->span = @$; }
| '-' expr %prec UMINUS { $$ = ast_new_unary(p->arena, ND_NEG, $2, @$); }
| '+' expr %prec UMINUS { $$ = $2; }
| expr '+' expr     { $$ = ast_new_binary(p->arena, ND_ADD, $1, $3, @$); }
| expr '-' expr     { $$ = ast_new_binary(p->arena, ND_SUB, $1, $3, @$); }
| expr '*' expr     { $$ = ast_new_binary(p->arena, ND_MUL, $1, $3, @$); }
| expr '/' expr     { $$ = ast_new_binary(p->arena, ND_DIV, $1, $3, @$); }
| expr '^' expr     { $$ = ast_new_binary(p->arena, ND_POW, $1, $3, @$); }
;

args:
  arg               { $$ = $1; }
| args ',' arg      { $$ = ast_append($1, $3); }
;

/* an argument; `E at t = v` is subst(E, t, v) (in a check: the curve E at
 * its point t = v) */
arg:
  expr              { $$ = $1; }
| expr IDENT IDENT '=' expr
                    { $$ = arg_at(p, $1, $2, @2, ast_new_name(p->arena, $3, @3), $5, @$); }
;

%%

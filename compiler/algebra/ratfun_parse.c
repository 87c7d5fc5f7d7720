/*
 * ratfun_parse.c - ratfun_set_str: a rational function from its text
 * (ratfun.h), the inverse of ratfun_get_str.
 *
 * A small recursive-descent reader over the ring's variable names, with
 * exact decimals; the unit tests write their expectations with it
 * (test_ratfun, test_steps).  The language's own parser is grammar/.
 */
#include "compiler/algebra/ratfun.h"

#include <stdlib.h>
#include <string.h>

#include "base/mem.h"

/* Recursive descent over
 *   expr   = ['+'|'-'] term (('+'|'-') term)*     (sign handled in unary)
 *   term   = unary (('*'|'/') unary)*
 *   unary  = ('+'|'-') unary | power
 *   power  = atom ['^' expo]
 *   expo   = ['+'|'-'] INT | '(' ['+'|'-'] INT ')'
 *   atom   = NUMBER | NAME | '(' expr ')'
 * so -x^2 = -(x^2) and a/b*c = (a/b)*c, as in the language. */
typedef struct StrParser {
    const char *s; // cursor
    const Ring *r;
    int depth; // nesting of '(' and unary signs, bounded: no stack blow-up
} StrParser;

#define STR_MAX_DEPTH 1000

static int parse_expr(RatFun res, StrParser *p);

static void skip_blanks(StrParser *p)
{
    while (*p->s == ' ' || *p->s == '\t' || *p->s == '\n' || *p->s == '\r')
        p->s++;
}

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

static int is_name_char(char c, int first)
{
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_' ||
           (!first && is_digit(c));
}

/* [+-] digits, capped at RATFUN_STR_MAX_EXP */
static int parse_small_int(slong *e, StrParser *p)
{
    int neg = 0;
    slong v = 0;

    skip_blanks(p);
    if (*p->s == '+' || *p->s == '-') {
        neg = *p->s == '-';
        p->s++;
        skip_blanks(p);
    }
    if (!is_digit(*p->s))
        return RATFUN_ESYNTAX;
    while (is_digit(*p->s)) {
        v = 10 * v + (*p->s - '0');
        if (v > RATFUN_STR_MAX_EXP)
            return RATFUN_EOVERFLOW;
        p->s++;
    }
    *e = neg ? -v : v;
    return RATFUN_OK;
}

/* NUMBER = (digits ['.' digits*] | '.' digits) [('e'|'E') ['+'|'-'] digits],
 * read exactly: mantissa m with f fraction digits and exponent x gives
 * m * 10^(x - f). */
static int parse_number(RatFun res, StrParser *p)
{
    int st = RATFUN_OK;
    slong frac = 0, ex = 0;
    fmpz_t m, ten;
    fmpq_t q;

    fmpz_init(m);
    fmpz_init(ten);
    fmpq_init(q);
    if (!is_digit(*p->s) && !(*p->s == '.' && is_digit(p->s[1]))) {
        st = RATFUN_ESYNTAX;
        goto cleanup;
    }
    while (is_digit(*p->s)) {
        fmpz_mul_ui(m, m, 10);
        fmpz_add_ui(m, m, (ulong)(*p->s++ - '0'));
    }
    if (*p->s == '.') {
        p->s++;
        while (is_digit(*p->s)) {
            fmpz_mul_ui(m, m, 10);
            fmpz_add_ui(m, m, (ulong)(*p->s++ - '0'));
            frac++;
        }
    }
    if ((*p->s == 'e' || *p->s == 'E') &&
        (is_digit(p->s[1]) ||
         ((p->s[1] == '+' || p->s[1] == '-') && is_digit(p->s[2])))) {
        p->s++;
        st = parse_small_int(&ex, p);
        if (st != RATFUN_OK)
            goto cleanup;
    }
    /* |ex| <= RATFUN_STR_MAX_EXP + (digits in the text): no blow-up */
    ex -= frac;
    fmpz_set_ui(ten, 10);
    fmpz_pow_ui(ten, ten, (ulong)(ex >= 0 ? ex : -ex));
    if (ex >= 0) {
        fmpz_mul(fmpq_numref(q), m, ten);
        fmpz_one(fmpq_denref(q));
    } else {
        fmpq_set_fmpz_frac(q, m, ten);
    }
    ratfun_set_fmpq(res, q, p->r);
cleanup:
    fmpq_clear(q);
    fmpz_clear(ten);
    fmpz_clear(m);
    return st;
}

static int parse_atom(RatFun res, StrParser *p)
{
    int st;

    skip_blanks(p);
    if (*p->s == '(') {
        p->s++;
        if (++p->depth > STR_MAX_DEPTH)
            return RATFUN_ESYNTAX;
        st = parse_expr(res, p);
        p->depth--;
        if (st != RATFUN_OK)
            return st;
        skip_blanks(p);
        if (*p->s != ')')
            return RATFUN_ESYNTAX;
        p->s++;
        return RATFUN_OK;
    }
    if (is_name_char(*p->s, 1)) {
        const char *start = p->s;
        size_t len;
        while (is_name_char(*p->s, 0))
            p->s++;
        len = (size_t)(p->s - start);
        for (slong i = 0; i < p->r->nvars; i++) {
            if (strlen(p->r->names[i]) == len &&
                memcmp(p->r->names[i], start, len) == 0) {
                ratfun_gen(res, i, p->r);
                return RATFUN_OK;
            }
        }
        return RATFUN_ENAME;
    }
    return parse_number(res, p);
}

static int parse_power(RatFun res, StrParser *p)
{
    int st;
    slong e;

    st = parse_atom(res, p);
    if (st != RATFUN_OK)
        return st;
    skip_blanks(p);
    if (*p->s != '^')
        return RATFUN_OK;
    p->s++;
    skip_blanks(p);
    if (*p->s == '(') {
        p->s++;
        st = parse_small_int(&e, p);
        if (st != RATFUN_OK)
            return st;
        skip_blanks(p);
        if (*p->s != ')')
            return RATFUN_ESYNTAX;
        p->s++;
    } else {
        st = parse_small_int(&e, p);
        if (st != RATFUN_OK)
            return st;
    }
    return ratfun_pow_si(res, res, e, p->r);
}

static int parse_unary(RatFun res, StrParser *p)
{
    int st;

    skip_blanks(p);
    if (*p->s == '-' || *p->s == '+') {
        int neg = *p->s == '-';
        p->s++;
        if (++p->depth > STR_MAX_DEPTH)
            return RATFUN_ESYNTAX;
        st = parse_unary(res, p);
        p->depth--;
        if (st == RATFUN_OK && neg)
            ratfun_neg(res, res, p->r);
        return st;
    }
    return parse_power(res, p);
}

static int parse_term(RatFun res, StrParser *p)
{
    int st;
    RatFun rhs;

    ratfun_init(rhs, p->r);
    st = parse_unary(res, p);
    while (st == RATFUN_OK) {
        char op;
        skip_blanks(p);
        op = *p->s;
        if (op != '*' && op != '/')
            break;
        p->s++;
        st = parse_unary(rhs, p);
        if (st != RATFUN_OK)
            break;
        if (op == '*')
            ratfun_mul(res, res, rhs, p->r);
        else
            st = ratfun_div(res, res, rhs, p->r);
    }
    ratfun_clear(rhs, p->r);
    return st;
}

static int parse_expr(RatFun res, StrParser *p)
{
    int st;
    RatFun rhs;

    ratfun_init(rhs, p->r);
    st = parse_term(res, p);
    while (st == RATFUN_OK) {
        char op;
        skip_blanks(p);
        op = *p->s;
        if (op != '+' && op != '-')
            break;
        p->s++;
        st = parse_term(rhs, p);
        if (st != RATFUN_OK)
            break;
        if (op == '+')
            ratfun_add(res, res, rhs, p->r);
        else
            ratfun_sub(res, res, rhs, p->r);
    }
    ratfun_clear(rhs, p->r);
    return st;
}

int ratfun_set_str(RatFun res, const char *s, const Ring *r)
{
    int st;
    StrParser p = {s, r, 0};
    RatFun t;

    ratfun_init(t, r);
    st = parse_expr(t, &p);
    if (st == RATFUN_OK) {
        skip_blanks(&p);
        if (*p.s != '\0')
            st = RATFUN_ESYNTAX;
    }
    if (st == RATFUN_OK)
        ratfun_swap(res, t, r);
    ratfun_clear(t, r);
    return st;
}

/* (ratfun.h) */
int ratfun_literal_fmpq(fmpq_t q, const char *text)
{
    size_t n = strlen(text);
    char *digits = pc_xmalloc(n + 2);
    size_t k = 0;
    long frac = 0, exp10 = 0;
    int in_frac = 0;
    const char *c = text;
    for (; *c && *c != 'e' && *c != 'E'; c++) {
        if (*c == '.') {
            in_frac = 1;
            continue;
        }
        digits[k++] = *c;
        frac += in_frac;
    }
    if (k == 0)
        digits[k++] = '0';
    digits[k] = '\0';
    if (*c == 'e' || *c == 'E') {
        exp10 = strtol(c + 1, NULL, 10);
        if (exp10 > 1000 || exp10 < -1000) {
            pc_free(digits);
            return -1;
        }
    }
    fmpz_set_str(fmpq_numref(q), digits, 10);
    fmpz_one(fmpq_denref(q));
    pc_free(digits);
    long e = exp10 - frac;
    fmpz_t p;
    fmpz_init(p);
    fmpz_set_ui(p, 10);
    fmpz_pow_ui(p, p, (ulong)(e < 0 ? -e : e));
    if (e < 0)
        fmpz_set(fmpq_denref(q), p);
    else
        fmpz_mul(fmpq_numref(q), fmpq_numref(q), p);
    fmpz_clear(p);
    fmpq_canonicalise(q);
    return 0;
}

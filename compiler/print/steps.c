/*
 * steps.c - `pointcalc derive --steps`: the derivation as the book prints
 * it, one step per definition in source order.
 *
 * Every value is printed by format_output_rhs (format.c), so a step reads
 * exactly like derive's own output; scalars (a meet's parameters and
 * determinant, the ratio of along) go through the same printer as scalar
 * outputs.  A meet is shown the way the monograph solves it (1.3.5, and
 * the Desargues-arc article): the point W of the second flat written in
 * the simplex of the first line and the other points, the determinant
 * that makes the moving triangle (tetrahedron) vanish, the parameter
 * lambda = b/(a + b) it gives, and a + b, which is zero exactly when the
 * flats are parallel (derive.h, DerivedStep).
 */
#include "compiler/print/steps.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "base/budget.h"
#include "base/json.h"
#include "base/mem.h"
#include "compiler/print/book.h"
#include "compiler/print/latexbreak.h"

/* the value x printed like a scalar output (malloc'd) */
static char *scalar_str(const Derived *d, const RatFun x, FormatStyle st)
{
    DerivedOutput o;
    memset(&o, 0, sizeof o);
    o.kind = KIND_SCALAR;
    o.scalar[0] = x[0]; /* a read-only view */
    return format_output_rhs(d, &o, st, -1);
}

/* 1 when s is a plain identifier (no parentheses needed around it) */
static int is_identifier(const char *s)
{
    if (!*s || isdigit((unsigned char)*s))
        return 0;
    for (; *s; s++)
        if (!isalnum((unsigned char)*s) && *s != '_')
            return 0;
    return 1;
}

/* ---- text ---------------------------------------------------------------- */

/* a name in a product: "P", "(A + B)" */
static void text_factor(FILE *out, const char *name)
{
    fprintf(out, is_identifier(name) ? "%s" : "(%s)", name);
}

static void text_value(FILE *out, const Derived *d, const DerivedOutput *o,
                       slong origin)
{
    char *v = format_output_rhs(d, o, FMT_TEXT, origin);
    fputs(v, out);
    pc_free(v);
    if (o->kind == KIND_VECTOR)
        fputs("    (vector)", out);
}

/* the coordinate names: a, b, then c (a line) or c1, c2 (a plane) */
static void coord_name(char *buf, size_t cap, slong k, slong n)
{
    if (k < 2)
        snprintf(buf, cap, "%c", (int)('a' + k));
    else if (n == 3)
        snprintf(buf, cap, "c");
    else
        snprintf(buf, cap, "c%ld", (long)(k - 1));
}

/* the first point (not a direction) of args[lo..hi-1]: the flat's origin */
static slong flat_origin(const DerivedStep *s, slong lo, slong hi)
{
    for (slong j = lo; j < hi; j++)
        if (s->args[j].kind != KIND_VECTOR)
            return j;
    return lo;
}

/* vertex j of the simplex: the point itself, or origin + j for a direction */
static void text_vertex(FILE *out, const DerivedStep *s, slong j)
{
    slong lo = j < s->nfirst ? 0 : s->nfirst;
    slong hi = j < s->nfirst ? s->nfirst : s->nargs;
    if (s->args[j].kind == KIND_VECTOR)
        fprintf(out, "(%s + %s)", s->args[flat_origin(s, lo, hi)].name,
                s->args[j].name);
    else
        text_factor(out, s->args[j].name);
}

/* the direction of args[j] from origin o: "(Q - P)", or a direction itself */
static void text_direction(FILE *out, const DerivedStep *s, slong j, slong o)
{
    if (s->args[j].kind == KIND_VECTOR)
        text_factor(out, s->args[j].name);
    else
        fprintf(out, "(%s - %s)", s->args[j].name, s->args[o].name);
}

/* the parameter names: lambda on the first line; mu, or mu1 and mu2 */
static const char *param_name(const DerivedStep *s, slong j, FormatStyle st)
{
    if (j == 0)
        return st == FMT_LATEX ? "\\lambda" : "lambda";
    if (s->nparams == 2)
        return st == FMT_LATEX ? "\\mu" : "mu";
    if (j == 1)
        return st == FMT_LATEX ? "\\mu_1" : "mu1";
    return st == FMT_LATEX ? "\\mu_2" : "mu2";
}

static void text_meet(FILE *out, const Derived *d, const DerivedStep *s)
{
    const char *M = s->value.name;
    slong nb = s->nargs - s->nfirst, n = nb + 1;
    char cn[32];
    if (s->has_sv) {
        fprintf(out, "    %s-theorem in the simplex ", nb == 2 ? "S" : "V");
        for (slong j = 0, k = 0; j < s->nargs; j++)
            if (j != s->sv_w) {
                fputs(k++ ? ", " : "", out);
                text_vertex(out, s, j);
            }
        fputs(":  ", out);
        text_vertex(out, s, s->sv_w);
        fputs(" = ", out);
        for (slong k = 0, j = 0; k < n; k++, j++) {
            if (j == s->sv_w)
                j++;
            coord_name(cn, sizeof cn, k, n);
            fprintf(out, "%s%s*", k ? " + " : "", cn);
            text_vertex(out, s, j);
        }
        fputs("\n       ", out);
        for (slong k = 0; k < n; k++) {
            char *v = scalar_str(d, s->sv_coord + k, FMT_TEXT);
            coord_name(cn, sizeof cn, k, n);
            fprintf(out, "%s %s = %s", k ? "," : "", cn, v);
            pc_free(v);
        }
        /* det[a, b, c..; 1 - lambda, lambda, 0..; unit rows] */
        fputs("\n    det[", out);
        for (slong k = 0; k < n; k++) {
            coord_name(cn, sizeof cn, k, n);
            fprintf(out, "%s%s", k ? ", " : "", cn);
        }
        fputs("; 1 - lambda, lambda", out);
        for (slong k = 2; k < n; k++)
            fputs(", 0", out);
        for (slong r = 2; r < n; r++) {
            fputs(";", out);
            for (slong k = 0; k < n; k++)
                fprintf(out, "%s%d", k ? ", " : " ", k == r);
        }
        fputs("] = (1 - lambda)*b - lambda*a = 0\n", out);
        char *det = scalar_str(d, s->det, FMT_TEXT);
        fprintf(out, "    a + b = %s    (zero: the %s parallel)\n", det,
                nb == 2 ? "lines are" : "line and the plane are");
        pc_free(det);
    }
    if (s->nparams == 0)
        return;
    /* lambda on the first line, from its origin */
    slong o = flat_origin(s, 0, s->nfirst);
    char *l = scalar_str(d, s->params, FMT_TEXT);
    fprintf(out, "    lambda = %s%s,  %s = ", s->has_sv ? "b/(a + b) = " : "",
            l, M);
    pc_free(l);
    text_factor(out, s->args[o].name);
    fputs(" + ", out);
    text_direction(out, s, o == 0 ? 1 : 0, o);
    fputs("*lambda\n", out);
    /* mu on the second flat */
    o = flat_origin(s, s->nfirst, s->nargs);
    fputs("   ", out);
    for (slong j = 1; j < s->nparams; j++) {
        char *m = scalar_str(d, s->params + j, FMT_TEXT);
        fprintf(out, " %s = %s,", param_name(s, j, FMT_TEXT), m);
        pc_free(m);
    }
    fprintf(out, "  %s = ", M);
    text_factor(out, s->args[o].name);
    for (slong j = s->nfirst, k = 1; j < s->nargs; j++) {
        if (j == o)
            continue;
        fputs(" + ", out);
        text_direction(out, s, j, o);
        fprintf(out, "*%s", param_name(s, k++, FMT_TEXT));
    }
    fputs("\n", out);
}

static void text_steps(FILE *out, const Derived *d, slong origin)
{
    const char *solve = NULL;
    for (slong i = 0; i < d->nsteps; i++) {
        const DerivedStep *s = &d->steps[i];
        if (s->op == STEP_SOLVE) {
            if (!solve || strcmp(solve, s->expr) != 0)
                fprintf(out, "%s\n", s->expr);
            solve = s->expr;
            fprintf(out, "    %s = ", s->value.name);
            if (s->pending)
                fputs("(holds an unknown that no solve determines)\n", out);
            else {
                text_value(out, d, &s->value, origin);
                fputs("\n", out);
            }
            continue;
        }
        solve = NULL;
        fprintf(out, "%s = %s", s->value.name, s->expr);
        if (s->pending) {
            fputs("  =  (holds an unknown that no solve determines)\n", out);
            continue;
        }
        if (s->op == STEP_MEET) {
            fputs("\n", out);
            text_meet(out, d, s);
            fprintf(out, "    %s = ", s->value.name);
        } else {
            fputs("  =  ", out);
        }
        text_value(out, d, &s->value, origin);
        fputs("\n", out);
    }
}

/* ---- LaTeX --------------------------------------------------------------- */

/* LaTeX for a name: the printer's rule (book.h) */
static void latex_name(FILE *out, const char *name)
{
    char *s = book_latex_name(name);
    fputs(s, out);
    pc_free(s);
}

/* source text in \texttt{}, with TeX's special characters escaped */
static void latex_source(FILE *out, const char *s)
{
    fputs("\\texttt{", out);
    for (; *s; s++) {
        switch (*s) {
        case '_':
        case '#':
        case '%':
        case '&':
        case '$':
        case '{':
        case '}':
            fprintf(out, "\\%c", *s);
            break;
        case '^':
            fputs("\\^{}", out);
            break;
        case '~':
            fputs("\\~{}", out);
            break;
        case '\\':
            fputs("\\textbackslash{}", out);
            break;
        case '\n':
        case '\r':
        case '\t':
            fputc(' ', out);
            break;
        default:
            fputc(*s, out);
        }
    }
    fputs("}", out);
}

/* an argument in a product: its name, or its source text in parentheses */
static void latex_factor(FILE *out, const char *name)
{
    if (is_identifier(name)) {
        latex_name(out, name);
    } else {
        fputs("\\left(", out);
        latex_source(out, name);
        fputs("\\right)", out);
    }
}

static void latex_value(FILE *out, const Derived *d, const DerivedOutput *o,
                        slong origin)
{
    char *v = format_output_rhs(d, o, FMT_LATEX, origin);
    fputs(v, out);
    pc_free(v);
    if (o->kind == KIND_VECTOR)
        fputs(" \\quad \\text{(vector)}", out);
}

static void latex_coord_name(FILE *out, slong k, slong n)
{
    if (k < 2)
        fputc('a' + (int)k, out);
    else if (n == 3)
        fputc('c', out);
    else
        fprintf(out, "c_{%ld}", (long)(k - 1));
}

static void latex_vertex(FILE *out, const DerivedStep *s, slong j)
{
    slong lo = j < s->nfirst ? 0 : s->nfirst;
    slong hi = j < s->nfirst ? s->nfirst : s->nargs;
    if (s->args[j].kind == KIND_VECTOR) {
        fputs("\\left(", out);
        latex_factor(out, s->args[flat_origin(s, lo, hi)].name);
        fputs(" + ", out);
        latex_factor(out, s->args[j].name);
        fputs("\\right)", out);
    } else {
        latex_factor(out, s->args[j].name);
    }
}

static void latex_direction(FILE *out, const DerivedStep *s, slong j, slong o)
{
    if (s->args[j].kind == KIND_VECTOR) {
        latex_factor(out, s->args[j].name);
        return;
    }
    fputs("\\left(", out);
    latex_factor(out, s->args[j].name);
    fputs(" - ", out);
    latex_factor(out, s->args[o].name);
    fputs("\\right)", out);
}

static void latex_meet(FILE *out, const Derived *d, const DerivedStep *s)
{
    slong nb = s->nargs - s->nfirst, n = nb + 1;
    if (s->has_sv) {
        fprintf(out, "  &\\quad \\text{%s-theorem in the simplex } ",
                nb == 2 ? "S" : "V");
        for (slong j = 0, k = 0; j < s->nargs; j++)
            if (j != s->sv_w) {
                fputs(k++ ? ", " : "", out);
                latex_vertex(out, s, j);
            }
        fputs(":\\quad ", out);
        latex_vertex(out, s, s->sv_w);
        fputs(" = ", out);
        for (slong k = 0, j = 0; k < n; k++, j++) {
            if (j == s->sv_w)
                j++;
            fputs(k ? " + " : "", out);
            latex_coord_name(out, k, n);
            fputs(" ", out);
            latex_vertex(out, s, j);
        }
        fputs(" \\\\\n", out);
        for (slong k = 0; k < n; k++) {
            char *v = scalar_str(d, s->sv_coord + k, FMT_LATEX);
            fputs(k ? ",\\quad " : "  &\\quad ", out);
            latex_coord_name(out, k, n);
            fprintf(out, " = %s", v);
            pc_free(v);
        }
        fputs(" \\\\\n  &\\quad \\begin{vmatrix} ", out);
        for (slong k = 0; k < n; k++) {
            fputs(k ? " & " : "", out);
            latex_coord_name(out, k, n);
        }
        fputs(" \\\\ 1 - \\lambda & \\lambda", out);
        for (slong k = 2; k < n; k++)
            fputs(" & 0", out);
        for (slong r = 2; r < n; r++) {
            fputs(" \\\\ ", out);
            for (slong k = 0; k < n; k++)
                fprintf(out, "%s%d", k ? " & " : "", k == r);
        }
        char *det = scalar_str(d, s->det, FMT_LATEX);
        char *l = scalar_str(d, s->params, FMT_LATEX);
        fprintf(out,
                " \\end{vmatrix} = 0 \\;\\Rightarrow\\; \\lambda = "
                "\\frac{b}{a + b} = %s,\\quad a + b = %s \\\\\n",
                l, det);
        pc_free(l);
        pc_free(det);
    } else if (s->nparams > 0) {
        char *l = scalar_str(d, s->params, FMT_LATEX);
        fprintf(out, "  &\\quad \\lambda = %s \\\\\n", l);
        pc_free(l);
    }
    if (s->nparams == 0)
        return;
    slong o = flat_origin(s, 0, s->nfirst);
    fputs("  &\\quad ", out);
    latex_name(out, s->value.name);
    fputs(" = ", out);
    latex_factor(out, s->args[o].name);
    fputs(" + ", out);
    latex_direction(out, s, o == 0 ? 1 : 0, o);
    fputs(" \\lambda = ", out);
    o = flat_origin(s, s->nfirst, s->nargs);
    latex_factor(out, s->args[o].name);
    for (slong j = s->nfirst, k = 1; j < s->nargs; j++) {
        if (j == o)
            continue;
        fputs(" + ", out);
        latex_direction(out, s, j, o);
        fprintf(out, " %s", param_name(s, k++, FMT_LATEX));
    }
    for (slong j = 1; j < s->nparams; j++) {
        char *m = scalar_str(d, s->params + j, FMT_LATEX);
        fprintf(out, ",\\quad %s = %s", param_name(s, j, FMT_LATEX), m);
        pc_free(m);
    }
    fputs(" \\\\\n", out);
}

/* The rows of an align* body (separated by " \\" and a newline), each
 * broken where it is wider than the page (latexbreak.h): what follows its
 * alignment point ("R &= ...", "&\quad ...") in lines, continued under it
 * ("&\qquad ..."), so every line is balanced. */
static void put_rows(FILE *out, const char *body)
{
    /* the left column is as wide as its widest entry: every row's right
     * part starts there */
    double left = 0;
    for (const char *q = body; q && *q;) {
        const char *e = strstr(q, " \\\\\n");
        size_t n = e ? (size_t)(e - q) : strlen(q);
        const char *amp = memchr(q, '&', n);
        if (amp) {
            double w = latex_width(q, (size_t)(amp - q));
            left = w > left ? w : left;
        }
        q = e ? e + 4 : NULL;
    }
    const char *p = body;
    while (*p) {
        const char *e = strstr(p, " \\\\\n");
        size_t n = e ? (size_t)(e - p) : strlen(p);
        char *row = pc_xstrndup(p, n);
        /* (a trailing newline of the last row stays outside) */
        size_t rn = strlen(row);
        int nl = rn > 0 && row[rn - 1] == '\n';
        if (nl)
            row[--rn] = '\0';
        char *amp = strchr(row, '&');
        if (amp && !budget_late() && /* (past the deadline: discarded) */
            left + latex_width(amp, strlen(amp)) > LATEX_LINE_UNITS) {
            /* the head: through "&=" or "&\quad" */
            char *rest = amp + 1;
            if (*rest == '=')
                rest++;
            else if (strncmp(rest, "\\quad", 5) == 0)
                rest += 5;
            fwrite(row, 1, (size_t)(rest - row), out);
            double head = left + latex_width(amp, (size_t)(rest - amp)) + 2;
            char **ls;
            size_t k = latex_break(&ls, rest, LATEX_LINE_UNITS - head);
            for (size_t i = 0; i < k; i++) {
                if (i > 0)
                    fputs(" \\\\\n  &\\qquad ", out);
                else
                    fputs(" ", out);
                fputs(ls[i], out);
            }
            latex_lines_free(ls, k);
        } else {
            fputs(row, out);
        }
        if (nl)
            fputs("\n", out);
        pc_free(row);
        if (!e)
            break;
        fputs(" \\\\\n", out);
        p = e + 4;
    }
}

static void latex_steps_rows(FILE *out, const Derived *d, slong origin);

static void latex_steps(FILE *out, const Derived *d, slong origin)
{
    char *body = NULL;
    size_t len = 0;
    FILE *m = pc_xopen_memstream(&body, &len);
    latex_steps_rows(m, d, origin);
    pc_xclose_memstream(m);
    /* the rows between \begin{align*} and \end{align*} */
    static const char begin[] = "\\begin{align*}\n",
                      end[] = "\n\\end{align*}\n";
    size_t lb = strlen(begin), le = strlen(end);
    if (len >= lb + le && strncmp(body, begin, lb) == 0 &&
        strcmp(body + len - le, end) == 0) {
        body[len - le] = '\0';
        fputs(begin, out);
        put_rows(out, body + lb);
        fputs(end, out);
    } else {
        fputs(body, out);
    }
    pc_free(body);
}

static void latex_steps_rows(FILE *out, const Derived *d, slong origin)
{
    const char *solve = NULL;
    fputs("\\begin{align*}\n", out);
    for (slong i = 0; i < d->nsteps; i++) {
        const DerivedStep *s = &d->steps[i];
        if (s->op == STEP_SOLVE && (!solve || strcmp(solve, s->expr) != 0)) {
            fputs("  & ", out);
            latex_source(out, s->expr);
            fputs(" \\\\\n", out);
        }
        solve = s->op == STEP_SOLVE ? s->expr : NULL;
        fputs("  ", out);
        latex_name(out, s->value.name);
        fputs(" &= ", out);
        if (s->op != STEP_SOLVE) {
            latex_source(out, s->expr);
            if (s->op == STEP_MEET && !s->pending) {
                fputs(" \\\\\n", out);
                latex_meet(out, d, s);
                fputs("  &= ", out);
            } else {
                fputs(" = ", out);
            }
        }
        if (s->pending)
            fputs("\\text{(holds an unknown that no solve determines)}", out);
        else
            latex_value(out, d, &s->value, origin);
        fputs(i + 1 < d->nsteps ? " \\\\\n" : "\n", out);
    }
    fputs("\\end{align*}\n", out);
}

/* ---- JSON ---------------------------------------------------------------- */

static void json_ratfun(FILE *out, const Derived *d, const RatFun x)
{
    char *s = format_weight(x, &d->ring);
    json_string(out, s);
    pc_free(s);
}

/* "kind": .., "terms": {..} or "value": ".." (contract section 4's form) */
static void json_value(FILE *out, const Derived *d, const DerivedOutput *o)
{
    fprintf(out, "\"kind\": \"%s\", ", kind_name(o->kind));
    if (o->kind == KIND_SCALAR) {
        fputs("\"value\": ", out);
        json_ratfun(out, d, o->scalar);
        return;
    }
    fputs("\"terms\": {", out);
    for (slong k = 0; k < o->eq->len; k++) {
        fputs(k ? ", " : "", out);
        json_string(out, d->points[o->eq->terms[k].point]);
        fputs(": ", out);
        json_ratfun(out, d, &o->w[k]);
    }
    fputs("}", out);
}

static const char *op_name(StepOp op)
{
    switch (op) {
    case STEP_ALONG:
        return "along";
    case STEP_DIVIDE:
        return "divide";
    case STEP_MEET:
        return "meet";
    case STEP_SUBST:
        return "subst";
    case STEP_DIFF:
        return "diff";
    case STEP_BEZIER:
        return "bezier";
    case STEP_SOLVE:
        return "solve";
    case STEP_EXPR:
        break;
    }
    return "expr";
}

static void json_step(FILE *out, const Derived *d, const DerivedStep *s)
{
    fputs("{\"name\": ", out);
    json_string(out, s->value.name);
    fprintf(out, ", \"line\": %d, \"op\": \"%s\", \"expr\": ", s->value.line,
            op_name(s->op));
    json_string(out, s->expr);
    fputs(", ", out);
    if (s->pending) {
        fputs("\"pending\": true}", out);
        return;
    }
    json_value(out, d, &s->value);
    if (s->nargs > 0) {
        fputs(", \"args\": [", out);
        for (slong k = 0; k < s->nargs; k++) {
            fputs(k ? ", {\"name\": " : "{\"name\": ", out);
            json_string(out, s->args[k].name);
            fputs(", ", out);
            json_value(out, d, &s->args[k]);
            fputs("}", out);
        }
        fputs("]", out);
    }
    if (s->op == STEP_ALONG || s->op == STEP_DIVIDE || s->op == STEP_BEZIER ||
        (s->op == STEP_SUBST && s->nargs == 0)) {
        fputs(s->op == STEP_SUBST ? ", \"by\": " : ", \"ratio\": ", out);
        json_ratfun(out, d, s->scalar);
    }
    if (s->var) {
        fputs(", \"var\": ", out);
        json_string(out, s->var);
    }
    if (s->op == STEP_DIFF)
        fprintf(out, ", \"order\": %ld", s->order);
    if (s->nparams > 0) {
        fputs(", \"lambda\": ", out);
        json_ratfun(out, d, s->params);
        fputs(", \"mu\": [", out);
        for (slong j = 1; j < s->nparams; j++) {
            fputs(j > 1 ? ", " : "", out);
            json_ratfun(out, d, s->params + j);
        }
        fputs("]", out);
    }
    if (s->has_sv) {
        fputs(", \"simplex\": [", out);
        for (slong j = 0, k = 0; j < s->nargs; j++)
            if (j != s->sv_w) {
                fputs(k++ ? ", " : "", out);
                json_string(out, s->args[j].name);
            }
        fputs("], \"w\": ", out);
        json_string(out, s->args[s->sv_w].name);
        fputs(", \"coords\": [", out);
        for (slong k = 0; k <= s->nparams; k++) {
            fputs(k ? ", " : "", out);
            json_ratfun(out, d, s->sv_coord + k);
        }
        fputs("], \"det\": ", out);
        json_ratfun(out, d, s->det);
    }
    fputs("}", out);
}

/* derive's JSON object (format_derived) with "steps" added before its
 * closing brace */
static void json_steps(FILE *out, const Derived *d)
{
    char *obj = NULL;
    size_t len = 0;
    FILE *mem = pc_xopen_memstream(&obj, &len);
    format_derived(mem, d, FMT_JSON, -1);
    pc_xclose_memstream(mem);
    while (len > 0 && (obj[len - 1] == '\n' || obj[len - 1] == '}'))
        if (obj[--len] == '}')
            break;
    fwrite(obj, 1, len, out);
    pc_free(obj);
    fputs(",\n \"steps\": [", out);
    for (slong i = 0; i < d->nsteps; i++) {
        fputs(i ? ",\n  " : "", out);
        json_step(out, d, &d->steps[i]);
    }
    fputs("]}\n", out);
}

void steps_print(FILE *out, const Derived *d, FormatStyle st, slong origin)
{
    if (st == FMT_JSON)
        json_steps(out, d);
    else if (st == FMT_LATEX)
        latex_steps(out, d, origin);
    else
        text_steps(out, d, origin);
}

/*
 * emit_c.c - printing a Plan as C99.
 *
 * Every Plan register that an output needs becomes one `const double rN`
 * with a comment naming the scheme line it comes from; constants and inputs
 * are written inline.  The single-sample functions are straight-line code.
 * The batch functions work in blocks of BLOCK samples:
 *
 *   uniform registers (consts only)            once per call
 *   for each block:
 *     params -> x0, x1 ... (tail padded)       fixed-length loop over the
 *     varying registers -> weights w0[], w1[]  block: gcc -O2 vectorises it
 *     out[i][c] = sum_k wk[i] * Pk[c]          specialised for dim 2 and 3
 *
 * In the batch code each weight is peeled (plan_peel): a weight -x is
 * computed as x and the points' coordinates are negated once per call.
 * NAME_M_batch has its own fused loop for dim 2 and 3 (emit_batch_fast):
 * the rows written straight to a restrict out, the numerators summed and
 * multiplied by 1/L once, a block whose rows or L are not finite handed
 * to NAME_M_batch_checked (docs/codegen.md, "Batch code").
 *
 * The pole flag (sum of POLE checks of the output's denominator factors)
 * marks the samples whose coordinates are overwritten with NaN, whatever
 * the points are; the _checked variants return/count them.
 *
 * User names become C argument names unchanged unless they clash with a C
 * keyword, a <math.h>/<stddef.h> name, a generated function or a local of
 * the generated code; those get a trailing _ (names of a reserved family,
 * M_PI or __x, first get the prefix a_).  Function names are the prefix
 * and the output's name; emit_c_clash reports when two coincide.
 */
#include "codegen/emit_c.h"
#include "codegen/collapse.h"
#include "base/numfmt.h"
#include "base/mem.h"

#include <ctype.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

enum { BLOCK = 64 }; // samples per block in the generated batch code

/* keywords: neither an argument nor a --prefix */
static const char *const keywords[] = {
    /* C99 */
    "auto", "break", "case", "char", "const", "continue", "default", "do",
    "double", "else", "enum", "extern", "float", "for", "goto", "if", "inline",
    "int", "long", "register", "restrict", "return", "short", "signed",
    "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned",
    "void", "volatile", "while", "_Bool", "_Complex", "_Imaginary", "bool",
    "true", "false",
    /* C++ keywords: the header may be included from C++ */
    "alignas", "alignof", "and", "and_eq", "asm", "bitand", "bitor", "catch",
    "char16_t", "char32_t", "char8_t", "class", "co_await", "co_return",
    "co_yield", "compl", "concept", "const_cast", "consteval", "constexpr",
    "constinit", "decltype", "delete", "dynamic_cast", "explicit", "export",
    "friend", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
    "nullptr", "operator", "or", "or_eq", "private", "protected", "public",
    "reinterpret_cast", "requires", "static_assert", "static_cast",
    "template", "this", "thread_local", "throw", "try", "typeid", "typename",
    "using", "virtual", "wchar_t", "xor", "xor_eq", NULL};

/* other names an argument must not take (a function name neither) */
static const char *const reserved[] = {
    /* macros of common standard headers a user's file may include first */
    "EDOM", "ERANGE", "EILSEQ", "EOF", "BUFSIZ", "CHAR_BIT", "CHAR_MAX",
    "CHAR_MIN", "SCHAR_MAX", "SCHAR_MIN", "UCHAR_MAX", "SHRT_MAX", "SHRT_MIN",
    "USHRT_MAX", "INT_MAX", "INT_MIN", "UINT_MAX", "LONG_MAX", "LONG_MIN",
    "ULONG_MAX", "LLONG_MAX", "LLONG_MIN", "ULLONG_MAX", "SIZE_MAX",
    "RAND_MAX", "EXIT_SUCCESS", "EXIT_FAILURE", "SEEK_SET", "SEEK_CUR",
    "SEEK_END", "assert", "stdin", "stdout", "stderr", "complex", "I",
    /* <math.h>, <stddef.h> names a user could pick (macros first) */
    "NAN", "INFINITY", "HUGE_VAL", "HUGE_VALF", "HUGE_VALL", "NULL",
    "math_errhandling", "fpclassify", "isfinite", "isnormal", "isgreater",
    "isgreaterequal", "isless", "islessequal", "islessgreater", "isunordered",
    "signbit", "isnan", "isinf", "offsetof", "size_t", "ptrdiff_t",
    "max_align_t", "float_t", "double_t", "errno", "j0", "j1", "jn", "y0",
    "y1", "yn", "exp", "log", "pow", "sqrt", "sin", "cos", "tan", "fabs",
    "floor", "ceil", "round", "gamma", "erf", "fma", "fmin", "fmax",
    /* predefined outside strict ISO mode (gcc -std=gnu99) */
    "unix", "linux", "i386",
    /* names of the generated code */
    "n", "dim", "out", "status", "i0", "m", "j", "c", "nbad", "nb", "bad", "o",
    "fb", "nfull", "chk", NULL};

/* generated names follow these shapes: r12 w3 x0 p0 pad0 q1 k0_2 */
static int internal_shape(const char *s)
{
    static const char *const heads[] = {"r", "w", "x", "p", "pad", "q", "k"};
    for (size_t h = 0; h < sizeof heads / sizeof *heads; h++) {
        size_t n = strlen(heads[h]);
        if (strncmp(s, heads[h], n) != 0 || !isdigit((unsigned char)s[n]))
            continue;
        const char *q = s + n;
        while (isdigit((unsigned char)*q))
            q++;
        if (*q == '_' && isdigit((unsigned char)q[1])) // k0_2
            for (q++; isdigit((unsigned char)*q);)
                q++;
        if (*q == '\0')
            return 1;
    }
    return 0;
}

static int in(const char *const *list, const char *s)
{
    for (int i = 0; list[i]; i++)
        if (strcmp(list[i], s) == 0)
            return 1;
    return 0;
}

static int in_list(const char *s)
{
    return in(keywords, s) || in(reserved, s);
}

/* names of macro families of <math.h> (FP_NAN, MATH_ERRNO, GNU's M_PI),
 * <float.h> and <stdint.h> (FLT_MAX, DBL_EPSILON, INT8_MAX), and the
 * identifiers C reserves (__x, _X) */
static int reserved_family(const char *s)
{
    static const char *const heads[] = {
        "FP_",   "MATH_", "M_",     "__",     "FLT_",    "DBL_",
        "LDBL_", "INT8_", "INT16_", "INT32_", "INT64_",  "UINT8_",
        "UINT16_", "UINT32_", "UINT64_", "INTMAX_", "UINTMAX_", "INTPTR_",
        "UINTPTR_", "PTRDIFF_", "SIG_", "WCHAR_", "WINT_"};
    for (size_t h = 0; h < sizeof heads / sizeof *heads; h++)
        if (strncmp(s, heads[h], strlen(heads[h])) == 0)
            return 1;
    return s[0] == '_' && isupper((unsigned char)s[1]);
}

static int is_reserved(const char *s)
{
    return in_list(s) || internal_shape(s) || reserved_family(s);
}

unsigned emit_c_parse_functions(const char *list, const char **bad)
{
    static const struct {
        const char *name;
        unsigned bits;
    } items[] = {{"plain", EMIT_C_ONE},
                 {"checked", EMIT_C_ONE_CHECKED},
                 {"batch", EMIT_C_BATCH},
                 {"batch_checked", EMIT_C_BATCH_CHECKED},
                 {"all", EMIT_C_ALL}};
    unsigned want = 0;
    const char *s = list;
    for (;;) {
        size_t n = strcspn(s, ",");
        unsigned bits = 0;
        for (size_t i = 0; i < sizeof items / sizeof *items; i++)
            if (strlen(items[i].name) == n && strncmp(items[i].name, s, n) == 0)
                bits = items[i].bits;
        if (bits == 0) {
            *bad = s;
            return 0;
        }
        want |= bits;
        if (s[n] == '\0')
            return want;
        s += n + 1;
    }
}

int emit_c_valid_prefix(const char *s)
{
    /* function names are PREFIX_OUTPUT, at file scope: any identifier but
     * a keyword or one that C reserves there (any beginning with _, C11
     * 7.1.3) */
    if (!s || !isalpha((unsigned char)s[0]))
        return 0;
    for (const char *q = s; *q; q++)
        if (!(isalnum((unsigned char)*q) || *q == '_'))
            return 0;
    return !in(keywords, s);
}


/* a C identifier from any text: other characters become _; one that would
 * start with neither a letter nor _ gets the prefix pc_ ("3d-curve.pcs" ->
 * pc_3d_curve).  A scheme's own name (`scheme NAME`) is an identifier
 * already and stays as it is: contract section 5 names NAME_M. */
static char *identifier(const char *s)
{
    size_t n = strlen(s);
    char *r = pc_xmalloc(n + 4);
    size_t k = 0;
    if (!(isalpha((unsigned char)s[0]) || s[0] == '_')) {
        memcpy(r, "pc_", 3);
        k = 3;
    }
    for (size_t i = 0; i < n; i++)
        r[k++] = isalnum((unsigned char)s[i]) ? s[i] : '_';
    r[k] = '\0';
    return r;
}

typedef enum Variant { ONE, ONE_CHECKED, BATCH, BATCH_CHECKED } Variant;
enum { NVARIANTS = 4 };

static const char *const variant_suffix[] = {"", "_checked", "_batch",
                                             "_batch_checked"};

typedef struct Names {
    unsigned want; // EMIT_C_* bits: the variants that are public
    char *prefix;  // owned
    char **fn;    // owned: function name of output i, variant v at 4*i + v
    char **in;    // C names of params then consts (owned)
    char **pt;    // C names of points (owned)
    int nfn, nin, npt;
} Names;

static int taken(const Names *N, int nin, int npt, const char *s)
{
    for (int i = 0; i < N->nfn; i++)
        if (strcmp(N->fn[i], s) == 0)
            return 1;
    for (int i = 0; i < nin; i++)
        if (strcmp(N->in[i], s) == 0)
            return 1;
    for (int i = 0; i < npt; i++)
        if (strcmp(N->pt[i], s) == 0)
            return 1;
    return 0;
}

/* the argument name of a user name: unchanged unless reserved or taken
 * (by a function or an earlier argument), then with _ appended until free;
 * a name of a reserved family (M_PI, __x) first gets the prefix a_ */
static char *c_name(const Names *N, int nin, int npt, const char *user)
{
    char *s = identifier(user);
    if (reserved_family(s)) {
        char *t = pc_xasprintf("a_%s", s);
        free(s);
        s = t;
    }
    while (is_reserved(s) || taken(N, nin, npt, s)) {
        size_t n = strlen(s);
        s = pc_xrealloc(s, n + 2);
        s[n] = '_';
        s[n + 1] = '\0';
    }
    return s;
}

static void names_init(Names *N, const Plan *p, const char *prefix)
{
    N->want = EMIT_C_ALL;
    N->prefix = identifier(prefix ? prefix : p->name);
    N->nfn = p->noutputs * NVARIANTS;
    N->fn = pc_xcalloc((size_t)N->nfn + 1, sizeof *N->fn);
    N->nin = p->nparams + p->nconsts;
    N->npt = p->npoints;
    N->in = pc_xcalloc((size_t)N->nin + 1, sizeof *N->in);
    N->pt = pc_xcalloc((size_t)N->npt + 1, sizeof *N->pt);
    for (int i = 0; i < p->noutputs; i++) {
        char *oname = identifier(p->outputs[i].name);
        for (int v = 0; v < NVARIANTS; v++)
            N->fn[NVARIANTS * i + v] =
                pc_xasprintf("%s_%s%s", N->prefix, oname, variant_suffix[v]);
        free(oname);
    }
    for (int i = 0; i < N->nin; i++)
        N->in[i] = c_name(
            N, i, 0, i < p->nparams ? p->params[i] : p->consts[i - p->nparams]);
    for (int i = 0; i < N->npt; i++)
        N->pt[i] = c_name(N, N->nin, i, p->points[i]);
}

static void names_clear(Names *N)
{
    for (int i = 0; i < N->nfn; i++)
        free(N->fn[i]);
    for (int i = 0; i < N->nin; i++)
        free(N->in[i]);
    for (int i = 0; i < N->npt; i++)
        free(N->pt[i]);
    free(N->fn);
    free(N->in);
    free(N->pt);
    free(N->prefix);
}

int emit_c_check(const Plan *p, const Derived *d, const char *prefix,
                 FILE *err)
{
    int o1, o2;
    char *clash = NULL;
    if (!emit_c_clash(p, prefix, &o1, &o2, &clash))
        return 0;
    if (o1 == o2)
        derived_error(d, err, d->outputs[o1].span,
                      "the C function %s that emit-c would write for %s is a "
                      "C keyword or macro; rename the output or give another "
                      "--prefix",
                      clash, d->outputs[o1].name);
    else
        derived_error(d, err, d->outputs[o2].span,
                      "emit-c would write the C function %s for both %s "
                      "(line %d) and %s; rename one of them",
                      clash, d->outputs[o1].name, d->outputs[o1].line,
                      d->outputs[o2].name);
    free(clash);
    return 1;
}

int emit_c_clash(const Plan *p, const char *prefix, int *o1, int *o2,
                 char **name)
{
    Names N;
    int found = 0;
    names_init(&N, p, prefix);
    for (int a = 0; a < N.nfn && !found; a++) {
        /* a keyword or a macro of the headers: it would not compile */
        if (in_list(N.fn[a])) {
            *o1 = *o2 = a / NVARIANTS;
            found = 1;
            *name = pc_xstrdup(N.fn[a]);
        }
        for (int b = a + 1; b < N.nfn && !found; b++)
            if (strcmp(N.fn[a], N.fn[b]) == 0) {
                *o1 = a / NVARIANTS;
                *o2 = b / NVARIANTS;
                found = 1;
                *name = pc_xstrdup(N.fn[a]);
            }
    }
    names_clear(&N);
    return found;
}

/* ---- printing helpers -------------------------------------------------- */

/* a double literal that reads back exactly: 2.0, 0.5, (-3.0), 1e+20 */
void emit_c_double(FILE *out, double v)
{
    char buf[40];
    pc_snprintf(buf, sizeof buf, "%.17g", v);
    /* the shortest of %.15g/%.16g/%.17g that round-trips */
    for (int prec = 15; prec < 17; prec++) {
        char t[40];
        pc_snprintf(t, sizeof t, "%.*g", prec, v);
        if (pc_strtod(t, NULL) == v) {
            memcpy(buf, t, sizeof t);
            break;
        }
    }
    int plain = strspn(buf, "-0123456789") == strlen(buf);
    fprintf(out, v < 0 ? "(%s%s)" : "%s%s", buf, plain ? ".0" : "");
}

/* Argument lists wrap at 80 columns, continuation aligned after '('. */
typedef struct Line {
    FILE *out;
    int col, indent;
} Line;

static void line_start(Line *L, FILE *out, const char *head)
{
    L->out = out;
    fputs(head, out);
    L->col = (int)strlen(head);
    L->indent = L->col;
}

static void line_arg(Line *L, const char *text, int last)
{
    int len = (int)strlen(text) + (last ? 1 : 2);
    if (L->col > L->indent && L->col + 1 + len > 79) {
        fprintf(L->out, "\n%*s", L->indent, "");
        L->col = L->indent;
    } else if (L->col > L->indent) {
        fputc(' ', L->out);
        L->col++;
    }
    fprintf(L->out, "%s%s", text, last ? ")" : ",");
    L->col += len;
}

void emit_c_params(FILE *out, const char *head, char *const *in, int nparams,
                   int nin, char *const *pt, int npt, int batch, int status,
                   int restr)
{
    Line L;
    line_start(&L, out, head);
    if (batch)
        line_arg(&L, "size_t n", 0);
    for (int i = 0; i < nin; i++) {
        char *arg = pc_xasprintf(
            "%s%s",
            batch && i < nparams
                ? (restr ? "const double *restrict " : "const double *")
                : "double ",
            in[i]);
        line_arg(&L, arg, 0);
        free(arg);
    }
    for (int i = 0; i < npt; i++) {
        char *arg = pc_xasprintf("const double *%s", pt[i]);
        line_arg(&L, arg, 0);
        free(arg);
    }
    line_arg(&L, "int dim", 0);
    line_arg(&L, restr ? "double *restrict out" : "double *out", !status);
    if (status)
        line_arg(&L, "unsigned char *status", 1);
}

/* restr: the definition of the fast _batch, whose param arrays and out
 * are restrict (compatible with the prototype, which has no qualifier) */
static void signature_ex(FILE *out, const Plan *p, const Names *N, int oi,
                         Variant v, int restr)
{
    static const char *const ret[] = {"void ", "int ", "void ", "size_t "};
    /* a _checked variant that only its plain one calls is private */
    char *head = pc_xasprintf("%s%s%s(", N->want & (1u << v) ? "" : "static ",
                              ret[v], N->fn[NVARIANTS * oi + v]);
    emit_c_params(out, head, N->in, p->nparams, N->nin, N->pt, N->npt,
                  v == BATCH || v == BATCH_CHECKED, v == BATCH_CHECKED, restr);
    free(head);
}

static void signature(FILE *out, const Plan *p, const Names *N, int oi,
                      Variant v)
{
    signature_ex(out, p, N, oi, v, 0);
}

/* ---- one output -------------------------------------------------------- */

typedef struct Ctx {
    FILE *out;
    const Plan *p;
    const Names *N;
    int oi; // the output's index
    const PlanOutput *o;
    unsigned char *live; // registers this output needs
    int batch;           // inputs are x0.. (loop copies) instead of names
    const char **role;   // per register: what it is, or NULL
} Ctx;

static void operand(const Ctx *C, int r)
{
    const PlanIns *x = &C->p->ins[r];
    if (x->op == PLAN_CONST)
        emit_c_double(C->out, C->p->k[x->a]);
    else if (x->op == PLAN_INPUT && C->batch && x->a < C->p->nparams)
        fprintf(C->out, "x%d", x->a);
    else if (x->op == PLAN_INPUT)
        fputs(C->N->in[x->a], C->out);
    else
        fprintf(C->out, "r%d", r);
}

/* const double rN = EXPR;  line comment */
static void instruction(const Ctx *C, int r, const char *indent)
{
    const PlanIns *x = &C->p->ins[r];
    FILE *out = C->out;
    fprintf(out, "%sconst double r%d = ", indent, r);
    switch ((PlanOp)x->op) {
    case PLAN_NEG:
        fputc('-', out);
        operand(C, x->a);
        break;
    case PLAN_ADD:
    case PLAN_SUB:
    case PLAN_MUL:
    case PLAN_DIV:
        operand(C, x->a);
        fprintf(out, " %s ",
                x->op == PLAN_ADD   ? "+"
                : x->op == PLAN_SUB ? "-"
                : x->op == PLAN_MUL ? "*"
                                    : "/");
        operand(C, x->b);
        break;
    case PLAN_POWI:
        fputs("pow(", out);
        operand(C, x->a);
        fprintf(out, ", %d.0)", x->b);
        break;
    case PLAN_FN: {
        int f = x->b & 255, q = x->b >> 8;
        static const char *const cfn[PLAN_NFNS] = {
            [PLAN_FN_SQRT] = "sqrt", [PLAN_FN_SIN] = "sin",
            [PLAN_FN_COS] = "cos",   [PLAN_FN_SINH] = "sinh",
            [PLAN_FN_COSH] = "cosh", [PLAN_FN_EXP] = "exp",
            [PLAN_FN_LOG] = "log",   [PLAN_FN_ASIN] = "asin",
            [PLAN_FN_ACOS] = "acos", [PLAN_FN_ATAN] = "atan",
        };
        if (f == PLAN_FN_SIGN) {
            fputs("(double)((", out);
            operand(C, x->a);
            fputs(" > 0.0) - (", out);
            operand(C, x->a);
            fputs(" < 0.0))", out);
        } else if (f == PLAN_FN_ROOT && q == 3) {
            fputs("cbrt(", out);
            operand(C, x->a);
            fputs(")", out);
        } else if (f == PLAN_FN_ROOT && q % 2) { /* odd: real root */
            fputs("(", out);
            operand(C, x->a);
            fputs(" < 0.0 ? -pow(-", out);
            operand(C, x->a);
            fprintf(out, ", 1.0 / %d.0) : pow(", q);
            operand(C, x->a);
            fprintf(out, ", 1.0 / %d.0))", q);
        } else if (f == PLAN_FN_ROOT) {
            fputs("pow(", out);
            operand(C, x->a);
            fprintf(out, ", 1.0 / %d.0)", q);
        } else {
            fprintf(out, "%s(", cfn[f]);
            operand(C, x->a);
            fputs(")", out);
        }
        break;
    }
    case PLAN_DIST:
        fprintf(out, "pcdist_%s(%s, %s, dim)", C->N->prefix,
                C->N->pt[x->a], C->N->pt[x->b]);
        break;
    case PLAN_COORD: /* coord(P, k): NaN when dim < k (docs/codegen.md) */
        fprintf(out, "(dim > %d ? %s[%d] : (double)NAN)", x->b,
                C->N->pt[x->a], x->b);
        break;
    case PLAN_ATAN2:
        fputs("atan2(", out);
        operand(C, x->a);
        fputs(", ", out);
        operand(C, x->b);
        fputs(")", out);
        break;
    case PLAN_DOMAIN: { /* the argument outside the function's domain */
        int f = x->b & 255;
        fputs("(double)(", out);
        if (f == PLAN_FN_ASIN || f == PLAN_FN_ACOS) {
            fputs("fabs(", out);
            operand(C, x->a);
            fputs(") > 1.0)", out);
        } else {
            operand(C, x->a);
            fputs(f == PLAN_FN_LOG ? " <= 0.0)" : " < 0.0)", out);
        }
        break;
    }
    case PLAN_POLE: /* not ?: - gcc does not if-convert that under the
                       default -ftrapping-math, and the loop would stay
                       scalar */
        fputs("(double)(", out);
        operand(C, x->a);
        fputs(" == 0.0)", out);
        break;
    default:
        break;
    }
    fprintf(out, "; /* line %d", x->line);
    if (C->role[r])
        fprintf(out, ": %s", C->role[r]);
    fputs(" */\n", out);
}

/* every needed computing instruction whose uniformity is `uniform` (or
 * all of them when uniform < 0) */
static void instructions(const Ctx *C, int uniform, const char *indent)
{
    for (int r = 0; r < C->p->nins; r++) {
        const PlanIns *x = &C->p->ins[r];
        if (!C->live[r] || x->op == PLAN_CONST || x->op == PLAN_INPUT)
            continue;
        if (uniform >= 0 && x->uniform != uniform)
            continue;
        instruction(C, r, indent);
    }
}

static int uses_point(const PlanOutput *o, int point)
{
    for (int k = 0; k < o->nterms; k++)
        if (o->point[k] == point)
            return 1;
    return 0;
}

/* (void)X; for every argument this output does not read */
static void unused_args(const Ctx *C)
{
    const Plan *p = C->p;
    for (int i = 0; i < C->N->nin; i++) {
        int used = 0;
        for (int r = 0; r < p->nins && !used; r++)
            used = C->live[r] && p->ins[r].op == PLAN_INPUT && p->ins[r].a == i;
        if (!used)
            fprintf(C->out, "    (void)%s;\n", C->N->in[i]);
    }
    int dist = 0; /* distances and coordinates read points and dim */
    for (int r = 0; r < p->nins; r++)
        dist |= C->live[r] &&
                (p->ins[r].op == PLAN_DIST || p->ins[r].op == PLAN_COORD);
    for (int i = 0; i < C->N->npt; i++) {
        int used = C->o->kind != PLAN_SCALAR && uses_point(C->o, i);
        for (int r = 0; r < p->nins && !used; r++)
            used = C->live[r] &&
                   ((p->ins[r].op == PLAN_DIST &&
                     (p->ins[r].a == i || p->ins[r].b == i)) ||
                    (p->ins[r].op == PLAN_COORD && p->ins[r].a == i));
        if (!used)
            fprintf(C->out, "    (void)%s;\n", C->N->pt[i]);
    }
    if (C->o->kind == PLAN_SCALAR && !dist)
        fputs("    (void)dim;\n", C->out);
}

/* does the output check a function's domain (status 4)? */
static int uses_domain(const Ctx *C)
{
    for (int r = 0; r < C->p->nins; r++)
        if (C->live[r] && C->p->ins[r].op == PLAN_DOMAIN)
            return 1;
    return 0;
}

/* the weight expression of slot k: its register or an inline operand */
static void weight(const Ctx *C, int k)
{
    operand(C, C->o->reg[k]);
}

/* int NAME_M_checked(...): straight-line weights, then the coordinates */
static void emit_one(const Ctx *C)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    signature(out, C->p, C->N, C->oi, ONE_CHECKED);
    fputs("\n{\n", out);
    unused_args(C);
    if (o->kind != PLAN_SCALAR)
        fputs("    int c;\n", out);
    instructions(C, -1, "    ");
    if (o->bad >= 0) {
        fputs("    if (", out);
        operand(C, o->bad);
        fputs(" != 0.0) { /* a denominator vanishes or overflows */\n", out);
        if (o->kind == PLAN_SCALAR)
            fputs("        out[0] = (double)NAN;\n", out);
        else
            fputs("        for (c = 0; c < dim; c++)\n"
                  "            out[c] = (double)NAN;\n",
                  out);
        fputs("        return ", out);
        if (uses_domain(C)) {
            operand(C, o->bad);
            fputs(" >= 1048576.0 ? 4 : ", out);
        }
        operand(C, o->bad);
        fputs(" >= 1.0 ? 1 : 2; /* 1 pole, 2 overflow", out);
        fputs(uses_domain(C) ? ", 4 domain */\n    }\n" : " */\n    }\n", out);
    }
    if (o->kind == PLAN_SCALAR) {
        fputs("    out[0] = ", out);
        weight(C, 0);
        fputs(";\n", out);
        /* x - x is 0 unless x is NaN or infinite */
        fputs("    if (!(out[0] - out[0] == 0.0)) { /* not finite: a NaN "
              "input, or beyond double */\n"
              "        out[0] = (double)NAN;\n"
              "        return 3;\n"
              "    }\n",
              out);
    } else {
        fputs("    for (c = 0; c < dim; c++)\n        out[c] = ", out);
        if (o->nterms == 0)
            fputs("0.0", out);
        for (int k = 0; k < o->nterms; k++) {
            if (k)
                fputs("\n                 + ", out);
            weight(C, k);
            fprintf(out, " * %s[c]", C->N->pt[o->point[k]]);
        }
        fputs(";\n", out);
        fputs("    for (c = 0; c < dim; c++)\n"
              "        if (!(out[c] - out[c] == 0.0)) { /* not finite: a NaN "
              "input, or beyond double */\n"
              "            for (c = 0; c < dim; c++)\n"
              "                out[c] = (double)NAN;\n"
              "            return 3;\n"
              "        }\n",
              out);
    }
    fputs("    return 0;\n}\n\n", out);
}

/* A weight slot of the batch code: w = sign * root (plan_peel); the block
 * loop computes root, the points' coordinates are negated once per call
 * (the locals kK_C, qK) where the sign is -1. */
typedef struct Slot {
    int root, sign;
} Slot;

static int scaled(const Slot *s)
{
    return s->sign != 1;
}

/* the coordinate loop for a known dim (2, 3) or any dim (0) */
static void emit_apply(const Ctx *C, const Slot *slot, int dim,
                       const char *ind)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    if (dim > 0) {
        for (int k = 0; k < o->nterms; k++) {
            const char *P = C->N->pt[o->point[k]];
            fprintf(out, "%sconst double ", ind);
            for (int c = 0; c < dim; c++) {
                fprintf(out, "%sk%d_%d = ", c ? ", " : "", k, c);
                fprintf(out, "%s%s[%d]", scaled(&slot[k]) ? "-" : "", P, c);
            }
            fputs(";\n", out);
        }
        /* a full block gets a fixed trip count: gcc -O2 then vectorises
         * the interleaved stores, which it does not for a variable one */
        for (int full = 1; full >= 0; full--) {
            fprintf(out, full ? "%sif (m == %d) {\n" : "%s} else {\n", ind,
                    BLOCK);
            if (full)
                fprintf(out, "%s    for (j = 0; j < %d; j++) {\n", ind, BLOCK);
            else
                fprintf(out, "%s    for (j = 0; j < m; j++) {\n", ind);
            fprintf(out, "%s        double *o = out + (i0 + j) * %d;\n", ind,
                    dim);
            for (int c = 0; c < dim; c++) {
                fprintf(out, "%s        o[%d] = ", ind, c);
                if (o->nterms == 0)
                    fputs("0.0", out);
                for (int k = 0; k < o->nterms; k++)
                    fprintf(out, "%sw%d[j] * k%d_%d", k ? " + " : "", k, k, c);
                fputs(";\n", out);
            }
            fprintf(out, "%s    }\n", ind);
        }
        fprintf(out, "%s}\n", ind);
        return;
    }
    /* any dim: coordinate by coordinate, the scaled coordinates hoisted */
    fprintf(out, "%sfor (c = 0; c < dim; c++) {\n", ind);
    for (int k = 0; k < o->nterms; k++) {
        fprintf(out, "%s    const double q%d = %s%s[c];\n", ind, k,
                scaled(&slot[k]) ? "-" : "", C->N->pt[o->point[k]]);
    }
    fprintf(out, "%s    double *o = out + i0 * (size_t)dim + (size_t)c;\n",
            ind);
    fprintf(out, "%s    for (j = 0; j < m; j++)\n", ind);
    fprintf(out, "%s        o[j * (size_t)dim] = ", ind);
    if (o->nterms == 0)
        fputs("0.0", out);
    for (int k = 0; k < o->nterms; k++)
        fprintf(out, "%sw%d[j] * q%d", k ? " + " : "", k, k);
    fputs(";\n", out);
    fprintf(out, "%s}\n", ind);
}

static int param_used(const Ctx *C, int i)
{
    for (int r = 0; r < C->p->nins; r++)
        if (C->live[r] && C->p->ins[r].op == PLAN_INPUT && C->p->ins[r].a == i)
            return 1;
    return 0;
}

/* size_t NAME_M_batch_checked(...): blocks of BLOCK samples */
static void emit_batch(Ctx *C)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    const Plan *p = C->p;
    int scalar = o->kind == PLAN_SCALAR;
    int nslots = scalar ? 1 : o->nterms;
    Slot *slot = pc_xcalloc((size_t)nslots + 1, sizeof *slot);
    char **owned = pc_xcalloc((size_t)nslots + 1, sizeof *owned);
    /* what the batch code computes: the roots of the peeled weights, their
     * uniform factors, the pole flag (a scalar is written as it is) */
    memset(C->live, 0, (size_t)p->nins);
    for (int k = 0; k < nslots; k++) {
        Slot *s = &slot[k];
        if (scalar) {
            s->root = o->reg[k];
            s->sign = 1;
        } else {
            s->root = plan_peel(p, o->reg[k], &s->sign);
        }
        C->live[s->root] = 1;
        if (scaled(s) && !C->role[s->root]) {
            owned[k] = pc_xasprintf("%s, negated",
                                 C->role[o->reg[k]] ? C->role[o->reg[k]]
                                                    : "weight");
            C->role[s->root] = owned[k];
        }
    }
    if (o->bad >= 0)
        C->live[o->bad] = 1;
    plan_live_close(p, C->live);

    signature(out, p, C->N, C->oi, BATCH_CHECKED);
    fputs("\n{\n", out);
    unused_args(C);
    for (int i = 0; i < p->nparams; i++)
        if (param_used(C, i))
            fprintf(out, "    double pad%d[%d]; /* %s, tail block padded */\n",
                    i, BLOCK, C->N->in[i]);
    for (int k = 0; k < nslots; k++) {
        const char *r = C->role[slot[k].root];
        fprintf(out, "    double w%d[%d]; /* %s */\n", k, BLOCK,
                scalar ? "value" : r ? r : "weight");
    }
    if (o->bad >= 0)
        fprintf(out, "    double fb[%d]; /* pole flags, +0.5: overflow */\n",
                BLOCK);
    fputs("    size_t i0, j, nbad = 0;\n", out);
    if (!scalar)
        fputs("    int c;\n", out);
    C->batch = 0;
    instructions(C, 1, "    ");
    /* non-finite consts or point coordinates: every sample is status 3 */
    fputs("    int bad_in = 0;\n", out);
    for (int i = p->nparams; i < C->N->nin; i++)
        fprintf(out, "    bad_in |= !(%s - %s == 0.0);\n", C->N->in[i],
                C->N->in[i]);
    if (!scalar) {
        int any_pt = 0;
        for (int k = 0; k < o->nterms; k++)
            any_pt |= o->point[k] >= 0;
        if (any_pt) {
            fputs("    for (c = 0; c < dim; c++) {\n", out);
            for (int k = 0; k < o->nterms; k++) {
                if (o->point[k] < 0)
                    continue;
                const char *nm = C->N->pt[o->point[k]];
                fprintf(out, "        bad_in |= !(%s[c] - %s[c] == 0.0);\n",
                        nm, nm);
            }
            fputs("    }\n", out);
        }
    }
    fprintf(out, "    for (i0 = 0; i0 < n; i0 += %d) {\n", BLOCK);
    fprintf(out, "        const size_t m = n - i0 < %d ? n - i0 : %d;\n", BLOCK,
            BLOCK);
    if (o->bad >= 0)
        fputs("        int nb = 0; /* poles in the block */\n", out);
    for (int i = 0; i < p->nparams; i++) {
        if (!param_used(C, i))
            continue;
        fprintf(out, "        const double *p%d = %s + i0;\n", i, C->N->in[i]);
    }
    int any = 0;
    for (int i = 0; i < p->nparams; i++)
        any |= param_used(C, i);
    if (any) {
        fprintf(out, "        if (m < %d) {\n", BLOCK);
        for (int i = 0; i < p->nparams; i++) {
            if (!param_used(C, i))
                continue;
            fprintf(out,
                    "            for (j = 0; j < %d; j++)\n"
                    "                pad%d[j] = j < m ? p%d[j] : 0.0;\n"
                    "            p%d = pad%d;\n",
                    BLOCK, i, i, i, i);
        }
        fputs("        }\n", out);
    }
    fprintf(out, "        for (j = 0; j < %d; j++) {\n", BLOCK);
    for (int i = 0; i < p->nparams; i++)
        if (param_used(C, i))
            fprintf(out, "            const double x%d = p%d[j];\n", i, i);
    C->batch = 1;
    instructions(C, 0, "            ");
    if (o->bad >= 0) {
        fputs("            fb[j] = ", out);
        operand(C, o->bad);
        fputs(";\n", out);
    }
    for (int k = 0; k < nslots; k++) {
        fprintf(out, "            w%d[j] = ", k);
        operand(C, slot[k].root);
        fputs(";\n", out);
    }
    C->batch = 0;
    fputs("        }\n", out);
    /* counted in a loop of its own, in an int: inside the weight loop the
     * count (with two flags per sample) keeps gcc -O2 from vectorising it,
     * and clang vectorises an int sum but not a double one */
    if (o->bad >= 0)
        fprintf(out,
                "        for (j = 0; j < %d; j++)\n"
                "            nb += fb[j] != 0.0;\n",
                BLOCK);
    if (scalar) {
        fputs("        for (j = 0; j < m; j++)\n"
              "            out[i0 + j] = w0[j];\n",
              out);
    } else {
        fputs("        if (dim == 3) {\n", out);
        emit_apply(C, slot, 3, "            ");
        fputs("        } else if (dim == 2) {\n", out);
        emit_apply(C, slot, 2, "            ");
        fputs("        } else {\n", out);
        emit_apply(C, slot, 0, "            ");
        fputs("        }\n", out);
    }
    if (o->bad >= 0) {
        fputs("        if (nb != 0) /* poles or overflows in this block: NaN "
              "rows */\n"
              "            for (j = 0; j < m; j++) {\n"
              "                if (fb[j] == 0.0)\n"
              "                    continue;\n"
              "                nbad++;\n",
              out);
        if (scalar)
            fputs("                out[i0 + j] = (double)NAN;\n", out);
        else
            fputs("                for (c = 0; c < dim; c++)\n"
                  "                    out[(i0 + j) * (size_t)dim + (size_t)c]"
                  " = (double)NAN;\n",
                  out);
        fputs(
            "            }\n"
            "        if (status != NULL)\n"
            "            for (j = 0; j < m; j++)\n"
            "                status[i0 + j] = (unsigned char)(",
            out);
        if (uses_domain(C))
            fputs("fb[j] >= 1048576.0 ? 4 : ", out);
        fputs("fb[j] >= 1.0 ? 1 : fb[j] != 0.0 ? 2 : 0);\n", out);
    } else
        fputs("        if (status != NULL)\n"
              "            for (j = 0; j < m; j++)\n"
              "                status[i0 + j] = 0;\n",
              out);
    /* samples not finite for another reason: a NaN parameter, or a
     * weight beyond double (x - x is 0 unless x is NaN or infinite),
     * counted over the block's weights in a loop of fixed length (it
     * vectorises, like the pole count); the rows are looked at only when
     * one is not finite.  Non-finite points or consts were found before
     * the loop (bad_in). */
    /* w - w is 0, or NaN when w is NaN or infinite; the sum of them
     * compared with != (like the pole count) vectorises */
    fprintf(out,
            "        if (status != NULL) { /* only when asked: it costs "
            "~1 ns a sample */\n"
            "            int nf = bad_in;\n"
            "            for (j = 0; j < %d; j++)\n"
            "                nf += ",
            BLOCK);
    for (int k = 0; k < nslots; k++)
        fprintf(out, "%s(w%d[j] - w%d[j])", k ? "\n                      + "
                                              : "",
                k, k);
    if (nslots == 0) /* an output that is identically zero */
        fputs("(double)0", out);
    fputs(" != 0.0;\n", out);
    fputs("            if (nf != 0)\n"
          "                for (j = 0; j < m; j++) {\n",
          out);
    if (o->bad >= 0)
        fputs("                    if (fb[j] != 0.0)\n"
              "                        continue;\n",
              out);
    fputs("                    if (!bad_in", out);
    for (int k = 0; k < nslots; k++)
        fprintf(out, "\n                        && w%d[j] - w%d[j] == 0.0", k,
                k);
    fputs(")\n                        continue;\n", out);
    if (scalar)
        fputs("                    out[i0 + j] = (double)NAN;\n", out);
    else
        fputs("                    for (c = 0; c < dim; c++)\n"
              "                        out[(i0 + j) * (size_t)dim + "
              "(size_t)c] = (double)NAN;\n",
              out);
    fputs("                    nbad++;\n"
          "                    status[i0 + j] = 3;\n"
          "                }\n"
          "        }\n",
          out);
    fputs("    }\n    return nbad;\n}\n\n", out);
    for (int k = 0; k < nslots; k++) {
        if (owned[k])
            C->role[slot[k].root] = NULL;
        free(owned[k]);
    }
    free(owned);
    free(slot);
}

/* ---- the fast _batch ---------------------------------------------------- */

/* 1 when r is a factor of the product L: a leaf of its MUL/POWI tree */
static int factor_of(const Plan *p, int L, int r, int depth)
{
    if (L == r)
        return 1;
    const PlanIns *x = &p->ins[L];
    if (depth > 256)
        return 0;
    if (x->op == PLAN_MUL)
        return factor_of(p, x->a, r, depth + 1) ||
               factor_of(p, x->b, r, depth + 1);
    if (x->op == PLAN_POWI)
        return factor_of(p, x->a, r, depth + 1);
    return 0;
}

/* In the pole flag bad, the register 1/L whose overflow it checks, when
 * every other flag in it checks a factor of L (lower.c): then 1/L made NaN
 * where L * (1/L) is not about 1 marks every flagged sample, and the fast
 * _batch needs no flags.  -1 when bad has another shape (a function's
 * domain, a flag of something else). */
static int pole_inverse(const Plan *p, int bad)
{
    int stack[512], ns = 0, inv = -1, poles[512], np = 0;
    stack[ns++] = bad;
    while (ns > 0) {
        const PlanIns *x = &p->ins[stack[--ns]];
        if (x->op == PLAN_POLE) {
            const PlanIns *d = &p->ins[x->a];
            if (d->op == PLAN_DIV && p->ins[d->a].op == PLAN_CONST &&
                p->k[p->ins[d->a].a] == 1.0) {
                if (inv >= 0 && inv != x->a)
                    return -1;
                inv = x->a;
            } else if (np < 512) {
                poles[np++] = x->a;
            } else {
                return -1;
            }
        } else if (x->op == PLAN_ADD || x->op == PLAN_MUL) {
            if (ns + 2 > 512)
                return -1;
            stack[ns++] = x->a;
            stack[ns++] = x->b;
        } else if (x->op != PLAN_CONST) {
            return -1; // a DOMAIN flag, or a shape lower.c does not make
        }
    }
    if (inv < 0)
        return -1;
    for (int i = 0; i < np; i++)
        if (!factor_of(p, p->ins[inv].b, poles[i], 0))
            return -1;
    return inv;
}

/* 1 when register r reads register x (through any instruction): one pass
 * from x to r, the Plan being in dependency order (mark: nins bytes) */
static int reads(const Plan *p, int r, int x, unsigned char *mark)
{
    if (r < x)
        return 0;
    memset(mark + x, 0, (size_t)(r - x + 1));
    mark[x] = 1;
    for (int i = x + 1; i <= r; i++) {
        const PlanIns *in = &p->ins[i];
        switch ((PlanOp)in->op) {
        case PLAN_NEG:
        case PLAN_POWI:
        case PLAN_POLE:
        case PLAN_FN:
        case PLAN_DOMAIN:
            mark[i] = in->a >= x && mark[in->a];
            break;
        case PLAN_ADD:
        case PLAN_SUB:
        case PLAN_MUL:
        case PLAN_DIV:
        case PLAN_ATAN2:
            mark[i] = (in->a >= x && mark[in->a]) || (in->b >= x && mark[in->b]);
            break;
        default:
            mark[i] = 0;
        }
    }
    return mark[r];
}

/* A weight w = f1 * f2 * ... * inv as a product: the factors beside inv
 * on the chain of MULs from w down to inv (lower.c builds it so), into
 * f[] (at most nmax); their number, or -1 when w is not of that shape */
static int inverse_factors(const Plan *p, int w, int inv, int *f, int nmax,
                           unsigned char *seen)
{
    int n = 0;
    while (w != inv) {
        const PlanIns *x = &p->ins[w];
        if (x->op != PLAN_MUL || n == nmax)
            return -1;
        int ina = reads(p, x->a, inv, seen);
        int inb = reads(p, x->b, inv, seen);
        if (ina == inb) // both or neither
            return -1;
        f[n++] = ina ? x->b : x->a;
        w = ina ? x->a : x->b;
    }
    return n;
}

void emit_c_chk_sum(FILE *out, const char *ind, const char *head)
{
    /* in halves, in loops of fixed length that vectorise (a plain sum of
     * doubles does not at -O2: gcc keeps its order; nor does an int count
     * of a double compare with SSE2) */
    for (int h = BLOCK / 2; h >= 8; h /= 2)
        fprintf(out,
                "%sfor (j = 0; j < %d; j++)\n"
                "%s    chk[j] += chk[j + %d];\n",
                ind, h, ind, h);
    fprintf(out,
            "%s%s chk[0] + chk[1] + chk[2] + chk[3] + chk[4] + chk[5] + "
            "chk[6] + chk[7];\n",
            ind, head);
}

/* (void)NAME_M_batch_checked(N, param + OFF..., consts, points, dim, DST,
 * NULL); or, N NULL, (void)NAME_M_checked(params, consts, points, dim,
 * DST); */
static void checked_call(const Ctx *C, const char *ind, const char *n,
                         const char *off, const char *dst)
{
    Line L;
    char *head = pc_xasprintf(
        "%s(void)%s(", ind,
        C->N->fn[NVARIANTS * C->oi + (n ? BATCH_CHECKED : ONE_CHECKED)]);
    line_start(&L, C->out, head);
    free(head);
    if (n)
        line_arg(&L, n, 0);
    for (int i = 0; i < C->N->nin; i++) {
        char *a = pc_xasprintf("%s%s", C->N->in[i],
                               i < C->p->nparams ? off : "");
        line_arg(&L, a, 0);
        free(a);
    }
    for (int i = 0; i < C->N->npt; i++)
        line_arg(&L, C->N->pt[i], 0);
    line_arg(&L, "dim", 0);
    line_arg(&L, dst, !n);
    if (n)
        line_arg(&L, "NULL", 1);
    fputs(";\n", C->out);
}

/* void NAME_M_batch(...) for dim 2 and 3: the weights and the coordinates
 * in one fixed-length loop per block, written straight to out (restrict:
 * out does not overlap the inputs), the tail block through a local
 * buffer; a pole or an overflow makes 1/L NaN, so no flags.  Other dims,
 * scalars and outputs with domain checks call _batch_checked.  0 when it
 * did not apply (nothing written). */
static int emit_batch_fast(Ctx *C)
{
    FILE *out = C->out;
    const PlanOutput *o = C->o;
    const Plan *p = C->p;
    if (o->kind == PLAN_SCALAR || o->nterms == 0 || uses_domain(C))
        return 0;
    int inv = -1;
    if (o->bad >= 0 && (inv = pole_inverse(p, o->bad)) < 0)
        return 0;
    enum { NF = 32 };
    Slot *slot = pc_xcalloc((size_t)o->nterms, sizeof *slot);
    int *nf = pc_xcalloc((size_t)o->nterms, sizeof *nf);
    int *f = pc_xcalloc((size_t)o->nterms * NF, sizeof *f);
    unsigned char *seen = pc_xmalloc((size_t)p->nins + 1);
    /* with 1/L a factor of every weight, the coordinates are summed from
     * the numerators and multiplied by 1/L once each: fewer products, and
     * the sums do not wait for the division */
    int hoist = inv >= 0;
    for (int k = 0; k < o->nterms; k++) {
        slot[k].root = plan_peel(p, o->reg[k], &slot[k].sign);
        if (hoist)
            nf[k] = inverse_factors(p, slot[k].root, inv, f + k * NF, NF,
                                    seen);
        hoist &= nf[k] >= 0;
    }
    free(seen);
    memset(C->live, 0, (size_t)p->nins);
    for (int k = 0; k < o->nterms; k++) {
        if (!hoist)
            C->live[slot[k].root] = 1;
        for (int i = 0; hoist && i < nf[k]; i++)
            C->live[f[k * NF + i]] = 1;
    }
    if (hoist)
        C->live[inv] = 1;
    plan_live_close(p, C->live);
    if (inv >= 0 && !C->live[inv]) { // the weights do not use 1/L
        free(slot);
        free(nf);
        free(f);
        return 0;
    }

    signature_ex(out, p, C->N, C->oi, BATCH, 1);
    fputs("\n{\n", out);
    fprintf(out, "    const size_t nfull = n - n %% %d; /* in full blocks */\n"
                 "    double chk[%d]; /* per sample: finite or not */\n"
                 "    size_t i0, j;\n",
            BLOCK, BLOCK);
    /* other dims, the tail block and a block with a value that is not
     * finite: the general code (which also writes NaN at poles and
     * overflows, and is what this computes where it can) */
    fputs("    if (dim != 2 && dim != 3) {\n", out);
    checked_call(C, "        ", "n", "", "out");
    fputs("        return;\n    }\n", out);
    C->batch = 0;
    instructions(C, 1, "    ");
    for (int dim = 3; dim >= 2; dim--) {
        fprintf(out, dim == 3 ? "    if (dim == 3) {\n" : "    } else {\n");
        for (int k = 0; k < o->nterms; k++) {
            const char *P = C->N->pt[o->point[k]];
            fputs("        const double ", out);
            for (int c = 0; c < dim; c++)
                fprintf(out, "%sk%d_%d = %s%s[%d]", c ? ", " : "", k, c,
                        scaled(&slot[k]) ? "-" : "", P, c);
            fputs(";\n", out);
        }
        fprintf(out, "        for (i0 = 0; i0 < nfull; i0 += %d) {\n", BLOCK);
        for (int i = 0; i < p->nparams; i++)
            if (param_used(C, i))
                fprintf(out, "            const double *p%d = %s + i0;\n", i,
                        C->N->in[i]);
        fprintf(out,
                "            double *o = out + i0 * %d;\n"
                "            for (j = 0; j < %d; j++) {\n",
                dim, BLOCK);
        for (int i = 0; i < p->nparams; i++)
            if (param_used(C, i))
                fprintf(out, "                const double x%d = p%d[j];\n", i,
                        i);
        C->batch = 1;
        instructions(C, 0, "                ");
        for (int k = 0; hoist && k < o->nterms; k++) {
            fprintf(out, "                const double w%d = ", k);
            for (int i = 0; i < nf[k]; i++) {
                fputs(i ? " * " : "", out);
                operand(C, f[k * NF + i]);
            }
            fputs(nf[k] == 0 ? "1.0;" : ";", out);
            const char *r = C->role[o->reg[k]] ? C->role[o->reg[k]]
                                                : C->role[slot[k].root];
            fprintf(out, " /* %s%s, times the denominator */\n",
                    r ? r : "weight", scaled(&slot[k]) ? ", negated" : "");
        }
        for (int c = 0; c < dim; c++) {
            fprintf(out, "                const double q%d = %s", c,
                    hoist ? "(" : "");
            for (int k = 0; k < o->nterms; k++) {
                fputs(k ? " + " : "", out);
                if (hoist)
                    fprintf(out, "w%d", k);
                else
                    operand(C, slot[k].root);
                fprintf(out, " * k%d_%d", k, c);
            }
            if (hoist) {
                fputs(") * ", out);
                operand(C, inv);
            }
            fputs(";\n", out);
        }
        for (int c = 0; c < dim; c++)
            fprintf(out, "                o[%d * j%s] = q%d;\n", dim,
                    c == 0 ? "" : c == 1 ? " + 1" : " + 2", c);
        /* the coordinates and the denominator L summed: not finite when
         * one of them is (a pole makes 1/L infinite; L beyond double makes
         * 1/L 0 and the coordinates wrong), or rarely when the sum
         * overflows */
        fputs("                chk[j] = q0 + q1", out);
        fputs(dim == 3 ? " + q2" : "", out);
        if (inv >= 0) {
            fputs(" + ", out);
            operand(C, p->ins[inv].b);
        }
        fputs(";\n", out);
        C->batch = 0;
        fputs("            }\n", out);
        emit_c_chk_sum(out, "            ", "chk[0] =");
        fputs("            if (!(chk[0] - chk[0] == 0.0)) /* not finite */\n",
              out);
        char *nn = pc_xasprintf("%d", BLOCK);
        checked_call(C, "                ", nn, " + i0", "o");
        free(nn);
        fputs("        }\n", out);
    }
    fputs("    }\n    if (nfull < n)\n", out);
    checked_call(C, "        ", "n - nfull", " + nfull", "out + nfull * (size_t)dim");
    fputs("}\n\n", out);
    free(slot);
    free(nf);
    free(f);
    return 1;
}

/* the call of the _checked variant with the arguments of the variant v
 * (ONE or BATCH) being defined */
static void emit_forward(const Ctx *C, Variant v)
{
    signature(C->out, C->p, C->N, C->oi, v);
    fputs("\n{\n", C->out);
    checked_call(C, "    ", v == BATCH ? "n" : NULL, "", "out");
    fputs("}\n\n", C->out);
}

static void set_roles(const Plan *p, const PlanOutput *o, const char **role,
                      char **owned)
{
    for (int k = 0; k < o->nterms; k++) {
        int r = o->reg[k];
        if (p->ins[r].op == PLAN_CONST || p->ins[r].op == PLAN_INPUT)
            continue;
        free(owned[r]);
        if (o->point[k] < 0)
            owned[r] = pc_xasprintf("value of %s", o->name);
        else
            owned[r] = pc_xasprintf("weight of %s in %s", p->points[o->point[k]],
                                 o->name);
        role[r] = owned[r];
    }
    if (o->bad >= 0 && p->ins[o->bad].op != PLAN_CONST) {
        role[o->bad] = "pole flag";
        const PlanIns *x = &p->ins[o->bad];
        if (x->op == PLAN_POLE && p->ins[x->a].op != PLAN_INPUT &&
            p->ins[x->a].op != PLAN_CONST)
            role[x->a] = "denominator";
    }
    for (int r = 0; r < p->nins; r++) {
        const PlanIns *x = &p->ins[r];
        if (!role[r] && x->op == PLAN_DIV && p->ins[x->a].op == PLAN_CONST &&
            p->k[p->ins[x->a].a] == 1)
            role[r] = "1/denominator";
        if (x->op == PLAN_POLE && !role[x->a] &&
            p->ins[x->a].op != PLAN_INPUT && p->ins[x->a].op != PLAN_CONST)
            role[x->a] = "denominator factor";
    }
}

static const char *kind_word(PlanKind k)
{
    return k == PLAN_SCALAR ? "scalar" : k == PLAN_POINT ? "point" : "vector";
}

static void banner(FILE *out, const Plan *p, const Names *N, const char *source,
                   const char *what)
{
    fprintf(out, "/*\n * %s generated by pointcalc emit-c", what);
    if (source) { // a file name may hold "*/", "/*" (-Wcomment) or a
                  // newline: not in a comment
        fputs(" from ", out);
        for (const char *c = source; *c; c++)
            if (c[0] == '*' && c[1] == '/')
                fputs("*\\", out);
            else if (c[0] == '/' && c[1] == '*')
                fputs("/\\", out);
            else
                fputc(*c == '\n' || *c == '\r' ? ' ' : *c, out);
    }
    fprintf(out, " (scheme %s).\n * Do not edit; regenerate instead.\n *\n",
            p->name);
    for (int i = 0; i < p->noutputs; i++) {
        const PlanOutput *o = &p->outputs[i];
        fprintf(out, " * %s (%s, line %d)", o->name, kind_word(o->kind),
                o->line);
        if (o->kind != PLAN_SCALAR) {
            fputs(" = ", out);
            for (int k = 0; k < o->nterms; k++)
                fprintf(out, "%s%s*w%d", k ? " + " : "", p->points[o->point[k]],
                        k);
            if (o->nterms == 0)
                fputs("0", out);
        }
        int need = plan_output_min_dim(p, i, NULL);
        if (need) /* coord(P, k): dim >= k (docs/codegen.md) */
            fprintf(out, "\n *   reads coordinate %d of the points: needs "
                         "dim >= %d (else NaN, status 3)",
                    need, need);
        fputs("\n", out);
    }
    fprintf(out,
            " *\n"
            " * %s_M(...) evaluates output M for one parameter value,\n"
            " * %s_M_batch(n, ...) for n values (params as arrays), both\n"
            " * writing dim coordinates per value (one number for a scalar).\n"
            " * Poles: where a denominator of the reduced equation is 0 the\n"
            " * coordinates are NaN.  %s_M_checked returns 0 ok, 1 pole,\n"
            " * 2 overflow (a denominator beyond double), 3 not finite (a NaN\n"
            " * input, a numerator beyond double), 4 domain (a function's\n"
            " * argument outside its domain); the coordinates are NaN unless 0.\n"
            " * %s_M_batch_checked returns how many samples are not 0 and\n"
            " * sets status[i] to that code when status is not NULL (with\n"
            " * status NULL, 3 is not looked for).\n"
            " */\n",
            N->prefix, N->prefix, N->prefix, N->prefix);
}

static void prototypes(FILE *out, const Plan *p, const Names *N)
{
    for (int i = 0; i < p->noutputs; i++)
        for (int v = ONE; v <= BATCH_CHECKED; v++) {
            if (!(N->want & (1u << v)))
                continue;
            signature(out, p, N, i, (Variant)v);
            fputs(";\n", out);
        }
}

void emit_c(FILE *out, const Plan *p, const char *prefix, const char *source)
{
    emit_c_ex(out, p, prefix, source, EMIT_C_ALL);
}

void emit_c_ex(FILE *out, const Plan *p, const char *prefix,
               const char *source, unsigned functions)
{
    emit_c_kernel(out, p, prefix, source, functions, NULL);
}

/* the collapsed batch function of output i (col, collapse.h), today's as
 * its static fallback; 0 when the output keeps today's */
static int emit_collapsed(Ctx *C, Names *N, const Collapse *col, int i)
{
    if (!col || i >= col->n || !col->o[i].ok)
        return 0;
    char **fn = &N->fn[NVARIANTS * i + BATCH_CHECKED], *pub = *fn;
    char *fallback = pc_xasprintf("pcw_%s", pub);
    if (!collapse_name_free(fallback, N->fn, N->nfn) ||
        !collapse_name_free(fallback, N->in, N->nin) ||
        !collapse_name_free(fallback, N->pt, N->npt)) {
        free(fallback);
        return 0;
    }
    unsigned want = N->want;
    *fn = fallback;
    N->want &= ~(unsigned)EMIT_C_BATCH_CHECKED;
    emit_batch(C);
    *fn = pub;
    N->want = want;
    CollapseNames CN = {pub,    fallback, !(want & EMIT_C_BATCH_CHECKED),
                        N->in,  C->p->nparams, N->nin,
                        N->pt,  N->npt};
    collapse_emit_batch(C->out, &col->o[i], &CN, C->o->line);
    free(fallback);
    return 1;
}

void emit_c_kernel(FILE *out, const Plan *p, const char *prefix,
                   const char *source, unsigned functions,
                   const Collapse *col)
{
    Names N;
    names_init(&N, p, prefix);
    N.want = functions & EMIT_C_ALL ? functions & EMIT_C_ALL : EMIT_C_ALL;
    banner(out, p, &N, source, "C99");
    if (col)
        collapse_banner(out, col);
    fputs("#include <math.h>\n#include <stddef.h>\n\n", out);
    prototypes(out, p, &N);
    fputs("\n", out);
    for (int r = 0; r < p->nins; r++)
        if (p->ins[r].op == PLAN_DIST) { /* the metric atoms' distances */
            fprintf(out,
                    "static inline double pcdist_%s(const double *p, const "
                    "double *q, int dim)\n"
                    "{\n"
                    "    double s = 0.0;\n"
                    "    int c;\n"
                    "    for (c = 0; c < dim; c++)\n"
                    "        s += (p[c] - q[c]) * (p[c] - q[c]);\n"
                    "    return sqrt(s);\n"
                    "}\n\n",
                    N.prefix);
            break;
        }
    unsigned char *live = pc_xmalloc((size_t)p->nins + 1);
    const char **role = pc_xcalloc((size_t)p->nins + 1, sizeof *role);
    char **owned = pc_xcalloc((size_t)p->nins + 1, sizeof *owned);
    for (int i = 0; i < p->noutputs; i++) {
        Ctx C = {out, p, &N, i, &p->outputs[i], live, 0, role};
        plan_live(p, i, live);
        memset(role, 0, sizeof *role * (size_t)p->nins);
        set_roles(p, C.o, role, owned);
        fprintf(out, "/* ---- %s (line %d) ---- */\n\n", C.o->name, C.o->line);
        if (N.want & (EMIT_C_ONE | EMIT_C_ONE_CHECKED))
            emit_one(&C);
        if (N.want & EMIT_C_ONE)
            emit_forward(&C, ONE);
        int collapsed = 0;
        if (N.want & (EMIT_C_BATCH | EMIT_C_BATCH_CHECKED)) {
            collapsed = emit_collapsed(&C, &N, col, i);
            if (!collapsed)
                emit_batch(&C);
        }
        if (N.want & EMIT_C_BATCH) {
            /* the collapsed kernel is its _batch_checked; else the fused
             * weights loop where it applies */
            plan_live(p, i, live);
            if (collapsed || !emit_batch_fast(&C))
                emit_forward(&C, BATCH);
        }
    }
    for (int r = 0; r < p->nins; r++)
        free(owned[r]);
    free(owned);
    free(role);
    free(live);
    names_clear(&N);
}

void emit_c_header(FILE *out, const Plan *p, const char *prefix,
                   const char *source)
{
    emit_c_header_ex(out, p, prefix, source, EMIT_C_ALL);
}

void emit_c_header_ex(FILE *out, const Plan *p, const char *prefix,
                      const char *source, unsigned functions)
{
    Names N;
    names_init(&N, p, prefix);
    N.want = functions & EMIT_C_ALL ? functions & EMIT_C_ALL : EMIT_C_ALL;
    banner(out, p, &N, source, "Header");
    char *guard = pc_xmalloc(strlen(N.prefix) + 16);
    size_t k = 0;
    for (const char *s = N.prefix; *s; s++)
        guard[k++] = (char)toupper((unsigned char)*s);
    strcpy(guard + k, "_POINTCALC_H");
    fprintf(out, "#ifndef %s\n#define %s\n\n#include <stddef.h>\n\n", guard,
            guard);
    fputs("#ifdef __cplusplus\nextern \"C\" {\n#endif\n\n", out);
    prototypes(out, p, &N);
    fputs("\n#ifdef __cplusplus\n}\n#endif\n\n", out);
    fprintf(out, "#endif /* %s */\n", guard);
    free(guard);
    names_clear(&N);
}

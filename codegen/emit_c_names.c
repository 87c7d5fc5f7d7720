/*
 * emit_c_names.c - the names of the generated C (emit_c.h).
 *
 * User names become C argument names unchanged unless they clash with a C
 * keyword, a <math.h>/<stddef.h> name, a generated function or a local of
 * the generated code; those get a trailing _ (names of a reserved family,
 * M_PI or __x, first get the prefix a_).  Function names are the prefix
 * and the output's name; emit_c_clash reports when two coincide.  Also the
 * --functions list, the --prefix check and the functions' signatures.
 */
#include "base/mem.h"
#include "codegen/emit_c_int.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

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
    "reinterpret_cast", "requires", "static_assert", "static_cast", "template",
    "this", "thread_local", "throw", "try", "typeid", "typename", "using",
    "virtual", "wchar_t", "xor", "xor_eq", NULL};

/* other names an argument must not take (a function name neither) */
static const char *const reserved[] = {
    /* macros of common standard headers a user's file may include first */
    "EDOM", "ERANGE", "EILSEQ", "EOF", "BUFSIZ", "CHAR_BIT", "CHAR_MAX",
    "CHAR_MIN", "SCHAR_MAX", "SCHAR_MIN", "UCHAR_MAX", "SHRT_MAX", "SHRT_MIN",
    "USHRT_MAX", "INT_MAX", "INT_MIN", "UINT_MAX", "LONG_MAX", "LONG_MIN",
    "ULONG_MAX", "LLONG_MAX", "LLONG_MIN", "ULLONG_MAX", "SIZE_MAX", "RAND_MAX",
    "EXIT_SUCCESS", "EXIT_FAILURE", "SEEK_SET", "SEEK_CUR", "SEEK_END",
    "assert", "stdin", "stdout", "stderr", "complex", "I",
    /* <math.h>, <stddef.h> names a user could pick (macros first) */
    "NAN", "INFINITY", "HUGE_VAL", "HUGE_VALF", "HUGE_VALL", "NULL",
    "math_errhandling", "fpclassify", "isfinite", "isnormal", "isgreater",
    "isgreaterequal", "isless", "islessequal", "islessgreater", "isunordered",
    "signbit", "isnan", "isinf", "offsetof", "size_t", "ptrdiff_t",
    "max_align_t", "float_t", "double_t", "errno", "j0", "j1", "jn", "y0", "y1",
    "yn", "exp", "log", "pow", "sqrt", "sin", "cos", "tan", "fabs", "floor",
    "ceil", "round", "gamma", "erf", "fma", "fmin", "fmax", "copysign",
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
        "FP_",      "MATH_",    "M_",      "__",      "FLT_",     "DBL_",
        "LDBL_",    "INT8_",    "INT16_",  "INT32_",  "INT64_",   "UINT8_",
        "UINT16_",  "UINT32_",  "UINT64_", "INTMAX_", "UINTMAX_", "INTPTR_",
        "UINTPTR_", "PTRDIFF_", "SIG_",    "WCHAR_",  "WINT_"};
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

static const char *const variant_suffix[] = {"", "_checked", "_batch",
                                             "_batch_checked"};

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
        pc_free(s);
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

void emit_names_init(Names *N, const Plan *p, const char *prefix)
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
        pc_free(oname);
    }
    for (int i = 0; i < N->nin; i++)
        N->in[i] = c_name(
            N, i, 0, i < p->nparams ? p->params[i] : p->consts[i - p->nparams]);
    for (int i = 0; i < N->npt; i++)
        N->pt[i] = c_name(N, N->nin, i, p->points[i]);
}

void emit_names_clear(Names *N)
{
    for (int i = 0; i < N->nfn; i++)
        pc_free(N->fn[i]);
    for (int i = 0; i < N->nin; i++)
        pc_free(N->in[i]);
    for (int i = 0; i < N->npt; i++)
        pc_free(N->pt[i]);
    pc_free(N->fn);
    pc_free(N->in);
    pc_free(N->pt);
    pc_free(N->prefix);
}

int emit_c_check(const Plan *p, const Derived *d, const char *prefix, FILE *err)
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
    pc_free(clash);
    return 1;
}

int emit_c_clash(const Plan *p, const char *prefix, int *o1, int *o2,
                 char **name)
{
    Names N;
    int found = 0;
    emit_names_init(&N, p, prefix);
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
    emit_names_clear(&N);
    return found;
}

/* restr: the definition of the fast _batch, whose param arrays and out
 * are restrict (compatible with the prototype, which has no qualifier) */
void emit_signature_ex(FILE *out, const Plan *p, const Names *N, int oi,
                       Variant v, int restr)
{
    static const char *const ret[] = {"void ", "int ", "void ", "size_t "};
    /* a _checked variant that only its plain one calls is private */
    char *head = pc_xasprintf("%s%s%s(", N->want & (1u << v) ? "" : "static ",
                              ret[v], N->fn[NVARIANTS * oi + v]);
    cwrite_params(out, head, N->in, p->nparams, N->nin, N->pt, N->npt,
                  v == BATCH || v == BATCH_CHECKED, v == BATCH_CHECKED, restr);
    pc_free(head);
}

void emit_signature(FILE *out, const Plan *p, const Names *N, int oi, Variant v)
{
    emit_signature_ex(out, p, N, oi, v, 0);
}

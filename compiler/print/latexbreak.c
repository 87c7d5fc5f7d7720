/*
 * latexbreak.c - LaTeX math broken into lines that fit the page
 * (latexbreak.h).
 *
 * The math is read as a sequence of words: the pieces between spaces at
 * brace depth 0 outside \left ... \right (the printers separate terms,
 * operators and factors by spaces).  A word wider than the line is
 * expanded into smaller words by the rewrites of latexbreak.h, the opening
 * and closing delimiters glued to its first and last piece (pre, post), so
 * a line never starts with "\Bigr)".  Lines are then filled greedily,
 * breaking before the last +, - or = that leaves the line at least a third
 * full, else before the word that does not fit.
 */
#include "compiler/print/latexbreak.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "base/mem.h"
#include "base/strbuf.h"

/* ---- reading ------------------------------------------------------------ */

/* s[i] == '{': the index after its matching '}' (or n) */
static size_t group_end(const char *s, size_t n, size_t i)
{
    int depth = 0;
    for (; i < n; i++) {
        if (s[i] == '\\' && i + 1 < n) {
            i++;
            continue;
        }
        if (s[i] == '{')
            depth++;
        else if (s[i] == '}' && --depth == 0)
            return i + 1;
    }
    return n;
}

/* the length of the inside of the group s[k..e) ("{...}", e from
 * group_end; an unclosed group runs to e) */
static size_t inner_len(const char *s, size_t k, size_t e)
{
    return e > k + 1 && s[e - 1] == '}' ? e - k - 2 : e - k - 1;
}

/* a command's name at s[i] == '\\': its length after the backslash */
static size_t command_len(const char *s, size_t n, size_t i)
{
    size_t k = i + 1;
    if (k < n && !isalpha((unsigned char)s[k]))
        return 1;
    while (k < n && isalpha((unsigned char)s[k]))
        k++;
    return k - i - 1;
}

static int is_cmd(const char *s, size_t n, size_t i, const char *name)
{
    size_t l = strlen(name);
    return s[i] == '\\' && command_len(s, n, i) == l &&
           strncmp(s + i + 1, name, l) == 0;
}

/* the characters of text s[0..n) as set (escapes count one) */
static double text_width(const char *s, size_t n)
{
    double w = 0;
    for (size_t i = 0; i < n; i++) {
        if (s[i] == '\\' && i + 1 < n) {
            i += command_len(s, n, i);
            w += 1;
        } else if (s[i] != '{' && s[i] != '}') {
            w += 1;
        }
    }
    return w;
}

/* the end of a delimiter after \left, \Bigl ...: "(", "|", "\{", "." */
static size_t delim_end(const char *s, size_t n, size_t i)
{
    if (i < n && s[i] == '\\')
        return i + 1 + command_len(s, n, i);
    return i < n ? i + 1 : n;
}

/* the end of a script's argument at s[i] (after ^ or _) */
static size_t script_end(const char *s, size_t n, size_t i)
{
    if (i >= n)
        return n;
    if (s[i] == '{')
        return group_end(s, n, i);
    if (s[i] == '\\')
        return i + 1 + command_len(s, n, i);
    return i + 1;
}

double latex_width(const char *s, size_t n)
{
    static const char *const words[] = {"sin",    "cos",    "ln",
                                        "sinh",   "cosh",   "arcsin",
                                        "arccos", "arctan", "exp"};
    double w = 0;
    size_t i = 0;
    while (i < n) {
        char c = s[i];
        if (c == '\\') {
            size_t l = command_len(s, n, i), k = i + 1 + l;
            if (is_cmd(s, n, i, "left") || is_cmd(s, n, i, "right") ||
                is_cmd(s, n, i, "Bigl") || is_cmd(s, n, i, "Bigr") ||
                is_cmd(s, n, i, "bigl") || is_cmd(s, n, i, "bigr") ||
                is_cmd(s, n, i, "Big") || is_cmd(s, n, i, "big")) {
                size_t e = delim_end(s, n, k);
                w += (e > k && s[k] == '.') ? 0 : 0.8;
                i = e;
            } else if (is_cmd(s, n, i, "frac") && k < n && s[k] == '{') {
                size_t e1 = group_end(s, n, k);
                size_t e2 = e1 < n && s[e1] == '{' ? group_end(s, n, e1) : e1;
                double a = latex_width(s + k + 1, inner_len(s, k, e1));
                double b =
                    e2 > e1 ? latex_width(s + e1 + 1, inner_len(s, e1, e2)) : 0;
                w += (a > b ? a : b) + 0.6;
                i = e2;
            } else if (is_cmd(s, n, i, "sqrt")) {
                if (k < n && s[k] == '[')
                    while (k < n && s[k] != ']')
                        k++, w += 0.5;
                if (k < n && s[k] == ']')
                    k++;
                size_t e = k < n && s[k] == '{' ? group_end(s, n, k) : k;
                w += (e > k ? latex_width(s + k + 1, inner_len(s, k, e)) : 0) +
                     1.4;
                i = e;
            } else if ((is_cmd(s, n, i, "texttt") || is_cmd(s, n, i, "text") ||
                        is_cmd(s, n, i, "mathit") ||
                        is_cmd(s, n, i, "mathrm") ||
                        is_cmd(s, n, i, "operatorname")) &&
                       k < n && s[k] == '{') {
                size_t e = group_end(s, n, k);
                w += text_width(s + k + 1, inner_len(s, k, e));
                if (is_cmd(s, n, i, "operatorname"))
                    w += 0.5;
                i = e;
            } else if (is_cmd(s, n, i, "quad")) {
                w += 2;
                i = k;
            } else if (is_cmd(s, n, i, "qquad")) {
                w += 4;
                i = k;
            } else if (l == 1 && (s[i + 1] == ',' || s[i + 1] == ' ' ||
                                  s[i + 1] == ';')) {
                w += 0.4;
                i = k;
            } else if (l == 1 && s[i + 1] == '\\') {
                i = k; /* a line break */
            } else {
                double cw = 1;
                for (size_t j = 0; j < sizeof words / sizeof words[0]; j++)
                    if (is_cmd(s, n, i, words[j]))
                        cw = 0.9 * (double)strlen(words[j]) + 0.3;
                if (is_cmd(s, n, i, "cdot") || is_cmd(s, n, i, "times"))
                    cw = 2;
                w += cw;
                i = k;
            }
        } else if (c == '{') {
            size_t e = group_end(s, n, i);
            w += latex_width(s + i + 1, inner_len(s, i, e));
            i = e;
        } else if (c == '^' || c == '_') {
            size_t e = script_end(s, n, i + 1);
            if (e > i + 1 && s[i + 1] == '{')
                w += 0.7 * latex_width(s + i + 2, inner_len(s, i + 1, e));
            else
                w += 0.7 * latex_width(s + i + 1, e - i - 1);
            i = e;
        } else if (c == '+' || c == '-' || c == '=' || c == '<' || c == '>') {
            w += 2.2;
            i++;
        } else if (c == ' ' || c == '&' || c == '}' || c == '\n') {
            i++;
        } else if (c == '(' || c == ')' || c == ',' || c == '.') {
            w += 0.7;
            i++;
        } else {
            w += 1;
            i++;
        }
    }
    return w;
}

/* ---- words --------------------------------------------------------------- */

typedef struct Word {
    char *pre, *core, *post; // what is glued before and after the core
    double w;                // the width of all three
} Word;

typedef struct Words {
    Word *w;
    size_t n, cap;
} Words;

static void words_push(Words *ws, char *pre, char *core, char *post)
{
    if (ws->n == ws->cap) {
        ws->cap = ws->cap ? 2 * ws->cap : 16;
        ws->w = pc_xrealloc(ws->w, sizeof(Word) * ws->cap);
    }
    Word *x = &ws->w[ws->n++];
    x->pre = pre;
    x->core = core;
    x->post = post;
    x->w = latex_width(pre, strlen(pre)) + latex_width(core, strlen(core)) +
           latex_width(post, strlen(post));
}

/* appends x as it is (its width known) */
static void words_keep(Words *ws, const Word *x)
{
    if (ws->n == ws->cap) {
        ws->cap = ws->cap ? 2 * ws->cap : 16;
        ws->w = pc_xrealloc(ws->w, sizeof(Word) * ws->cap);
    }
    ws->w[ws->n++] = *x;
}

static char *cat(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    char *r = pc_xmalloc(la + lb + 1);
    memcpy(r, a, la);
    memcpy(r + la, b, lb + 1);
    return r;
}

/* the words of s[0..n): split at spaces outside braces and \left..\right */
static void split_words(Words *ws, const char *s, size_t n)
{
    size_t i = 0;
    while (i < n) {
        while (i < n && isspace((unsigned char)s[i]))
            i++;
        if (i >= n)
            break;
        size_t start = i;
        int depth = 0;
        while (i < n && (depth > 0 || !isspace((unsigned char)s[i]))) {
            if (s[i] == '\\') {
                if (is_cmd(s, n, i, "left"))
                    depth++;
                else if (is_cmd(s, n, i, "right"))
                    depth--;
                i += 1 + command_len(s, n, i);
                continue;
            }
            if (s[i] == '{')
                depth++;
            else if (s[i] == '}')
                depth--;
            i++;
        }
        words_push(ws, pc_xstrdup(""), pc_xstrndup(s + start, i - start),
                   pc_xstrdup(""));
    }
}

/* the words of inner, with open glued before the first and close after
 * the last, appended to ws; 0 when inner has no words */
static int push_wrapped(Words *ws, const char *inner, size_t n,
                        const char *open, const char *close)
{
    Words in = {0};
    split_words(&in, inner, n);
    if (in.n == 0) {
        pc_free(in.w);
        return 0;
    }
    for (size_t k = 0; k < in.n; k++) {
        Word *x = &in.w[k];
        char *pre = k == 0 ? cat(open, x->pre) : pc_xstrdup(x->pre);
        char *post = k + 1 == in.n ? cat(x->post, close) : pc_xstrdup(x->post);
        words_push(ws, pre, x->core, post);
        pc_free(x->pre);
        pc_free(x->post);
    }
    pc_free(in.w);
    return 1;
}

/* the matching \right of the \left at s[i] (the index of its backslash),
 * or n */
static size_t right_of(const char *s, size_t n, size_t i)
{
    int depth = 0;
    while (i < n) {
        if (s[i] == '\\') {
            if (is_cmd(s, n, i, "left"))
                depth++;
            else if (is_cmd(s, n, i, "right") && --depth == 0)
                return i;
            i += 1 + command_len(s, n, i);
            continue;
        }
        i++;
    }
    return n;
}

/* x's core rewritten into smaller words (latexbreak.h), appended to out
 * with x's pre and post glued on; 0 when it cannot be */
static int expand(Words *out, const Word *x, double width)
{
    const char *s = x->core;
    size_t n = strlen(s);
    if (n > 1 && s[0] == '-' && s[1] == '\\') {
        /* -\frac{..}{..}: the sign goes before the first piece */
        Word y = *x;
        y.pre = cat(x->pre, "-");
        y.core = pc_xstrdup(s + 1);
        int ok = expand(out, &y, width);
        pc_free(y.pre);
        pc_free(y.core);
        return ok;
    }
    if (is_cmd(s, n, 0, "operatorname") && n > 13 && s[13] == '{') {
        /* \operatorname{natx}\left(...\right): the name goes before the
         * first piece of its argument list */
        size_t e = group_end(s, n, 13);
        if (e < n && is_cmd(s, n, e, "left")) {
            Word y = *x;
            char *name = pc_xmalloc(e + 1);
            memcpy(name, s, e);
            name[e] = '\0';
            y.pre = cat(x->pre, name);
            y.core = pc_xstrdup(s + e);
            int ok = expand(out, &y, width);
            pc_free(name);
            pc_free(y.pre);
            pc_free(y.core);
            return ok;
        }
    }
    Words mid = {0};
    int ok = 0;
    if (is_cmd(s, n, 0, "left")) {
        size_t d0 = 5, d1 = delim_end(s, n, d0);
        size_t r = right_of(s, n, 0);
        if (r < n) {
            size_t e0 = r + 6, e1 = delim_end(s, n, e0);
            char *open = pc_xmalloc(d1 - d0 + 8);
            sprintf(open, "\\Bigl%.*s ", (int)(d1 - d0), s + d0);
            char *close = pc_xmalloc(e1 - e0 + n - e1 + 8);
            sprintf(close, " \\Bigr%.*s%s", (int)(e1 - e0), s + e0, s + e1);
            ok = push_wrapped(&mid, s + d1, r - d1, open, close);
            pc_free(open);
            pc_free(close);
        }
    } else if (is_cmd(s, n, 0, "frac") && n > 5 && s[5] == '{') {
        size_t e1 = group_end(s, n, 5);
        size_t e2 = e1 < n && s[e1] == '{' ? group_end(s, n, e1) : e1;
        if (e2 > e1) {
            /* (what follows the fraction, ",\quad", goes after it) */
            const char *num = s + 6, *den = s + e1 + 1;
            size_t nn = inner_len(s, 5, e1), dn = inner_len(s, e1, e2);
            double wd = latex_width(den, dn);
            int one = nn == 1 && num[0] == '1';
            char *close = cat(" \\Bigr)", s + e2);
            if (wd <= 0.6 * width && !one) {
                char *f = pc_xmalloc(dn + 16);
                sprintf(f, "\\frac{1}{%.*s}", (int)dn, den);
                words_push(&mid, pc_xstrdup(""), f, pc_xstrdup(""));
                ok = push_wrapped(&mid, num, nn, "\\Bigl( ", close);
            } else {
                ok = push_wrapped(&mid, num, nn, "\\Bigl( ", " \\Bigr)");
                words_push(&mid, pc_xstrdup(""), pc_xstrdup("\\Big/"),
                           pc_xstrdup(""));
                ok &= push_wrapped(&mid, den, dn, "\\Bigl( ", close);
            }
            pc_free(close);
        }
    } else if (is_cmd(s, n, 0, "sqrt") && n > 5 && s[5] == '{' &&
               group_end(s, n, 5) == n) {
        ok = push_wrapped(&mid, s + 6, inner_len(s, 5, n), "\\Bigl( ",
                          " \\Bigr)^{1/2}");
    } else if (is_cmd(s, n, 0, "texttt") && n > 7 && s[7] == '{' &&
               group_end(s, n, 7) == n) {
        /* source text: one word per space-separated piece */
        const char *t = s + 8;
        size_t tn = inner_len(s, 7, n), i = 0;
        while (i < tn) {
            size_t j = i;
            while (j < tn && t[j] != ' ')
                j++;
            while (j < tn && t[j] == ' ')
                j++;
            char *piece = pc_xmalloc(j - i + 16);
            sprintf(piece, "\\texttt{%.*s}", (int)(j - i), t + i);
            words_push(&mid, pc_xstrdup(""), piece, pc_xstrdup(""));
            i = j;
        }
        ok = mid.n > 1;
    }
    if (ok) {
        for (size_t k = 0; k < mid.n; k++) {
            Word *y = &mid.w[k];
            char *pre = k == 0 ? cat(x->pre, y->pre) : pc_xstrdup(y->pre);
            char *post =
                k + 1 == mid.n ? cat(y->post, x->post) : pc_xstrdup(y->post);
            words_push(out, pre, y->core, post);
            pc_free(y->pre);
            pc_free(y->post);
        }
    } else {
        for (size_t k = 0; k < mid.n; k++) {
            pc_free(mid.w[k].pre);
            pc_free(mid.w[k].core);
            pc_free(mid.w[k].post);
        }
    }
    pc_free(mid.w);
    return ok;
}

static int is_op(const Word *x)
{
    const char *c = x->core;
    return x->pre[0] == '\0' &&
           (strcmp(c, "+") == 0 || strcmp(c, "-") == 0 || strcmp(c, "=") == 0 ||
            strcmp(c, "&=") == 0 || strcmp(c, "\\Big/") == 0);
}

/* ---- lines --------------------------------------------------------------- */

size_t latex_break(char ***lines, const char *s, double width)
{
    Words ws = {0};
    split_words(&ws, s, strlen(s));
    /* expand what is too wide, until nothing more can be (each expansion
     * makes smaller words: it ends) */
    for (int round = 0; round < 64; round++) {
        Words next = {0};
        int changed = 0;
        for (size_t k = 0; k < ws.n; k++) {
            Word *x = &ws.w[k];
            if (x->w > width && expand(&next, x, width)) {
                pc_free(x->pre);
                pc_free(x->core);
                pc_free(x->post);
                changed = 1;
            } else {
                words_keep(&next, x); /* not measured again */
            }
        }
        pc_free(ws.w);
        ws = next;
        if (!changed)
            break;
    }
    /* fill the lines */
    size_t nl = 0, cap = 4;
    char **out = pc_xmalloc(sizeof(char *) * cap);
    size_t k = 0;
    while (k < ws.n) {
        size_t end = k;
        double w = 0;
        while (end < ws.n && (end == k || w + 0.5 + ws.w[end].w <= width)) {
            w += ws.w[end].w + (end > k ? 0.5 : 0);
            end++;
        }
        if (end < ws.n && !is_op(&ws.w[end])) {
            /* break before the last operator that leaves a third */
            double acc = 0;
            size_t best = k;
            for (size_t j = k; j < end; j++) {
                if (j > k && is_op(&ws.w[j]) && acc >= width / 3)
                    best = j;
                acc += ws.w[j].w + 0.5;
            }
            if (best > k)
                end = best;
        }
        StrBuf b = {0};
        for (size_t j = k; j < end; j++) {
            const Word *x = &ws.w[j];
            if (j > k && x->pre[0] == '\0' && ws.w[j - 1].post[0] == '\0' &&
                strncmp(x->core, "\\texttt{", 8) == 0 &&
                strncmp(ws.w[j - 1].core, "\\texttt{", 8) == 0 && b.len > 0 &&
                b.s[b.len - 1] == '}') {
                /* pieces of one source text: one \texttt again */
                b.s[--b.len] = '\0';
                sb_puts(&b, x->core + 8);
                continue;
            }
            if (j > k)
                sb_puts(&b, " ");
            sb_puts(&b, x->pre);
            sb_puts(&b, x->core);
            sb_puts(&b, x->post);
        }
        if (nl == cap) {
            cap *= 2;
            out = pc_xrealloc(out, sizeof(char *) * cap);
        }
        out[nl++] = sb_take(&b);
        k = end;
    }
    for (size_t j = 0; j < ws.n; j++) {
        pc_free(ws.w[j].pre);
        pc_free(ws.w[j].core);
        pc_free(ws.w[j].post);
    }
    pc_free(ws.w);
    if (nl == 0)
        out[nl++] = pc_xstrdup("");
    *lines = out;
    return nl;
}

void latex_lines_free(char **lines, size_t n)
{
    for (size_t i = 0; i < n; i++)
        pc_free(lines[i]);
    pc_free(lines);
}

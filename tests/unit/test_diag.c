/*
 * test_diag.c - base/diag.c on its own: the "FILE:LINE:COL: error: message"
 * format, the source line and the caret span under it; line and column
 * from byte offsets (first line, a last line without a newline, a tab, a
 * multi-byte UTF-8 character, an escaped control byte or bidi control
 * before the span); spans at and past the end of the file; held messages
 * flushed in source order with each note after its error, and rolled
 * back; the bound of DIAG_MAX_ERRORS errors per file and its note, both
 * streaming and held; the long-line excerpt window with "..."; and
 * diag_put_location / diag_put_excerpt through a sink.  Every expected
 * text is written by hand from the format diag.h documents.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/diag.h"
#include "base/source.h"

/* One diagnostics run over text: messages go to a memory stream. */
typedef struct Run {
    Source src;
    Diag d;
    FILE *mem;
    char *out;
    size_t len;
} Run;

static void run_open(Run *r, const char *name, const char *text, size_t len)
{
    r->out = NULL;
    r->len = 0;
    r->mem = open_memstream(&r->out, &r->len);
    source_init(&r->src, name, text, len);
    diag_init(&r->d, &r->src, r->mem);
}

/* closes the stream: r->out holds everything written (caller frees) */
static void run_close(Run *r)
{
    fclose(r->mem);
    source_clear(&r->src);
}

/* the whole output of one error with message "m" at span of text */
static char *one_error(const char *text, size_t len, int start, int end)
{
    Run r;
    run_open(&r, "x.pcs", text, len);
    diag_error(&r.d, (Span){start, end}, "m");
    assert_int_equal(r.d.nerrors, 1);
    run_close(&r);
    return r.out;
}

static int count(const char *hay, const char *needle)
{
    int n = 0;
    for (const char *p = hay; (p = strstr(p, needle)) != NULL; p++)
        n++;
    return n;
}

static void test_format_line_col_caret(void **state)
{
    (void)state;
    Run r;
    const char *text = "point A, B\nM = Q\n";
    run_open(&r, "x.pcs", text, strlen(text));
    /* "point A, B\n" is 11 bytes: Q is byte 15, line 2 column 5 */
    diag_error(&r.d, (Span){15, 16}, "undefined name '%s' (%d)", "Q", 7);
    run_close(&r);
    assert_string_equal(r.out, "x.pcs:2:5: error: undefined name 'Q' (7)\n"
                               "M = Q\n"
                               "    ^\n");
    free(r.out);
}

static void test_caret_spans_with_tildes(void **state)
{
    (void)state;
    const char *text = "point A, B\nM = A*t + B\n";
    /* "A*t + B" is bytes 15..22 of the text */
    char *s = one_error(text, strlen(text), 15, 22);
    assert_string_equal(s, "x.pcs:2:5: error: m\n"
                           "M = A*t + B\n"
                           "    ^~~~~~~\n");
    free(s);
    /* an empty span: the caret alone */
    s = one_error(text, strlen(text), 15, 15);
    assert_string_equal(s, "x.pcs:2:5: error: m\nM = A*t + B\n    ^\n");
    free(s);
    /* a span over the line break: marks stop at the end of its line */
    s = one_error(text, strlen(text), 6, 20);
    assert_string_equal(s, "x.pcs:1:7: error: m\n"
                           "point A, B\n"
                           "      ^~~~\n");
    free(s);
}

static void test_first_line_and_first_column(void **state)
{
    (void)state;
    const char *text = "point A, B\nM = A\n";
    char *s = one_error(text, strlen(text), 0, 5);
    assert_string_equal(s, "x.pcs:1:1: error: m\npoint A, B\n^~~~~\n");
    free(s);
}

static void test_last_line_without_newline(void **state)
{
    (void)state;
    const char *text = "a\nbc";
    char *s = one_error(text, strlen(text), 3, 4);
    assert_string_equal(s, "x.pcs:2:2: error: m\nbc\n ^\n");
    free(s);
}

static void test_tab_is_one_column_and_kept_in_caret(void **state)
{
    (void)state;
    const char *text = "\tM = Q\n";
    /* tab, M, space, =, space: Q is the sixth character */
    char *s = one_error(text, strlen(text), 5, 6);
    assert_string_equal(s, "x.pcs:1:6: error: m\n\tM = Q\n\t    ^\n");
    free(s);
}

static void test_utf8_counts_characters(void **state)
{
    (void)state;
    /* e-acute is 2 bytes (c3 a9); the arrow U+2192 is 3 (e2 86 92) */
    const char *text = "\xc3\xa9 = \xe2\x86\x92Q\n";
    /* Q: byte 2+3+3 = 8, character 6 */
    char *s = one_error(text, strlen(text), 8, 9);
    assert_string_equal(s, "x.pcs:1:6: error: m\n"
                           "\xc3\xa9 = \xe2\x86\x92Q\n"
                           "     ^\n");
    free(s);
    /* a span over the two multi-byte characters: one mark per character */
    s = one_error(text, strlen(text), 0, 9);
    assert_string_equal(s, "x.pcs:1:1: error: m\n"
                           "\xc3\xa9 = \xe2\x86\x92Q\n"
                           "^~~~~~\n");
    free(s);
}

static void test_escaped_bytes_line_up(void **state)
{
    (void)state;
    /* a control byte shows as \x01 (four columns), but counts one */
    const char *text = "\x01Q\n";
    char *s = one_error(text, strlen(text), 1, 2);
    assert_string_equal(s, "x.pcs:1:2: error: m\n\\x01Q\n    ^\n");
    free(s);
    /* the bidi override U+202E shows as \u202e (six columns) */
    text = "\xe2\x80\xaeQ\n";
    s = one_error(text, strlen(text), 3, 4);
    assert_string_equal(s, "x.pcs:1:2: error: m\n\\u202eQ\n      ^\n");
    free(s);
    /* an escaped byte inside the span: '~' under each of its columns */
    text = "a\x7f"
           "b\n";
    s = one_error(text, strlen(text), 0, 3);
    assert_string_equal(s, "x.pcs:1:1: error: m\na\\x7fb\n^~~~~~\n");
    free(s);
}

static void test_crlf_lines(void **state)
{
    (void)state;
    const char *text = "a\r\nbQ\r\n";
    char *s = one_error(text, strlen(text), 4, 5);
    assert_string_equal(s, "x.pcs:2:2: error: m\nbQ\n ^\n");
    free(s);
}

static void test_spans_at_end_of_file(void **state)
{
    (void)state;
    /* the end of a last line without a newline */
    const char *text = "M = ";
    char *s = one_error(text, strlen(text), 4, 4);
    assert_string_equal(s, "x.pcs:1:5: error: m\nM = \n    ^\n");
    free(s);
    /* the end of a file that ends in a newline: the empty line after it */
    text = "M = A\n";
    s = one_error(text, strlen(text), 6, 6);
    assert_string_equal(s, "x.pcs:2:1: error: m\n\n^\n");
    free(s);
    /* a span past the end is clamped to it */
    text = "ab";
    s = one_error(text, strlen(text), 100, 200);
    assert_string_equal(s, "x.pcs:1:3: error: m\nab\n  ^\n");
    free(s);
    /* an empty file */
    s = one_error("", 0, 0, 0);
    assert_string_equal(s, "x.pcs:1:1: error: m\n\n^\n");
    free(s);
}

static void test_note_and_verror(void **state)
{
    (void)state;
    Run r;
    const char *text = "point A\nparam A\n";
    run_open(&r, "x.pcs", text, strlen(text));
    diag_error(&r.d, (Span){14, 15}, "redefinition of '%s'", "A");
    diag_note(&r.d, (Span){6, 7}, "first declared here");
    /* a note is not an error */
    assert_int_equal(r.d.nerrors, 1);
    run_close(&r);
    assert_string_equal(r.out, "x.pcs:2:7: error: redefinition of 'A'\n"
                               "param A\n"
                               "      ^\n"
                               "x.pcs:1:7: note: first declared here\n"
                               "point A\n"
                               "      ^\n");
    free(r.out);
}

static void verror(Diag *d, Span span, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    diag_verror(d, span, fmt, ap);
    va_end(ap);
}

static void test_verror_counts(void **state)
{
    (void)state;
    Run r;
    run_open(&r, "x.pcs", "ab\n", 3);
    verror(&r.d, (Span){1, 2}, "%s-%d", "v", 3);
    assert_int_equal(r.d.nerrors, 1);
    run_close(&r);
    assert_string_equal(r.out, "x.pcs:1:2: error: v-3\nab\n ^\n");
    free(r.out);
}

static void test_null_out_counts_only(void **state)
{
    (void)state;
    Source src;
    Diag d;
    source_init(&src, "x.pcs", "ab\n", 3);
    diag_init(&d, &src, NULL);
    diag_error(&d, (Span){0, 1}, "one");
    diag_note(&d, (Span){0, 1}, "a note");
    diag_error(&d, (Span){1, 2}, "two");
    assert_int_equal(d.nerrors, 2);
    /* held with no output: nothing is kept */
    diag_hold(&d);
    diag_error(&d, (Span){1, 2}, "three");
    assert_int_equal(d.nerrors, 3);
    assert_int_equal(d.nmsgs, 0);
    diag_flush(&d);
    source_clear(&src);
}

static void test_held_messages_in_source_order(void **state)
{
    (void)state;
    Run r;
    const char *text = "a\nb\nc\n";
    run_open(&r, "x.pcs", text, strlen(text));
    diag_hold(&r.d);
    diag_error(&r.d, (Span){4, 5}, "on c");  /* line 3, reported first */
    diag_error(&r.d, (Span){0, 1}, "on a");  /* line 1 */
    diag_note(&r.d, (Span){4, 5}, "note c"); /* stays after "on a" */
    diag_error(&r.d, (Span){0, 1}, "on a2"); /* same place: report order */
    diag_error(&r.d, (Span){2, 3}, "on b");
    assert_int_equal(r.d.nerrors, 4);
    /* nothing is written before the flush */
    fflush(r.mem);
    assert_int_equal(r.len, 0);
    diag_flush(&r.d);
    assert_int_equal(r.d.hold, 0);
    assert_int_equal(r.d.nmsgs, 0);
    /* after the flush, messages are written at once again */
    diag_error(&r.d, (Span){0, 1}, "late");
    run_close(&r);
    assert_string_equal(r.out, "x.pcs:1:1: error: on a\na\n^\n"
                               "x.pcs:3:1: note: note c\nc\n^\n"
                               "x.pcs:1:1: error: on a2\na\n^\n"
                               "x.pcs:2:1: error: on b\nb\n^\n"
                               "x.pcs:3:1: error: on c\nc\n^\n"
                               "x.pcs:1:1: error: late\na\n^\n");
    free(r.out);
}

static void test_rollback_drops_held_messages(void **state)
{
    (void)state;
    Run r;
    const char *text = "a\nb\n";
    run_open(&r, "x.pcs", text, strlen(text));
    diag_hold(&r.d);
    diag_error(&r.d, (Span){2, 3}, "kept");
    int nmsgs = r.d.nmsgs, nerrors = r.d.nerrors;
    diag_error(&r.d, (Span){0, 1}, "dropped");
    diag_note(&r.d, (Span){0, 1}, "dropped note");
    assert_int_equal(r.d.nerrors, 2);
    diag_rollback(&r.d, nmsgs, nerrors);
    assert_int_equal(r.d.nerrors, 1);
    assert_int_equal(r.d.nmsgs, 1);
    diag_flush(&r.d);
    run_close(&r);
    /* and no note about unshown errors: the dropped one is forgotten */
    assert_string_equal(r.out, "x.pcs:2:1: error: kept\nb\n^\n");
    free(r.out);
}

static void test_error_bound_streaming(void **state)
{
    (void)state;
    Run r;
    run_open(&r, "x.pcs", "ab\n", 3);
    for (int i = 0; i < DIAG_MAX_ERRORS + 2; i++) {
        diag_error(&r.d, (Span){0, 1}, "e%d", i);
        diag_note(&r.d, (Span){1, 2}, "n%d", i);
    }
    assert_int_equal(r.d.nerrors, DIAG_MAX_ERRORS + 2);
    run_close(&r);
    assert_int_equal(count(r.out, ": error: "), DIAG_MAX_ERRORS);
    /* the notes of the errors not shown are not shown either */
    assert_int_equal(count(r.out, ": note: n"), DIAG_MAX_ERRORS);
    assert_non_null(strstr(r.out, "x.pcs:1:1: error: e49\n"));
    assert_null(strstr(r.out, "e50"));
    assert_null(strstr(r.out, "n50"));
    /* one note, at the end, when the first error is not shown */
    const char *tail = "x.pcs:1:2: note: n49\nab\n ^\n"
                       "x.pcs: note: further errors are not shown (at most "
                       "50 are); fix the first ones and run again\n";
    size_t n = strlen(r.out), t = strlen(tail);
    assert_true(n > t);
    assert_string_equal(r.out + n - t, tail);
    free(r.out);
}

/* the note after DIAG_MAX_ERRORS + extra held errors are flushed */
static char *held_over(int extra)
{
    Run r;
    run_open(&r, "x.pcs", "ab\n", 3);
    diag_hold(&r.d);
    for (int i = 0; i < DIAG_MAX_ERRORS + extra; i++) {
        /* reported from the last to the first: the flush sorts them */
        int at = (DIAG_MAX_ERRORS + extra - 1 - i) % 2;
        diag_error(&r.d, (Span){at, at + 1}, "e%d", i);
    }
    diag_note(&r.d, (Span){0, 1}, "after the last");
    diag_flush(&r.d);
    run_close(&r);
    return r.out;
}

static void test_error_bound_held(void **state)
{
    (void)state;
    char *s = held_over(3);
    assert_int_equal(count(s, ": error: "), DIAG_MAX_ERRORS);
    /* the last reported (e52) is at column 1, so it is shown; the note
     * follows e52 and is shown with it */
    assert_non_null(strstr(s, "x.pcs:1:1: error: e52\n"));
    assert_non_null(strstr(s, "x.pcs:1:1: note: after the last\n"));
    const char *end = "x.pcs: note: 3 more errors are not shown (at most 50 "
                      "are); fix the first ones and run again\n";
    assert_string_equal(s + strlen(s) - strlen(end), end);
    free(s);

    s = held_over(1);
    assert_int_equal(count(s, ": error: "), DIAG_MAX_ERRORS);
    end = "x.pcs: note: 1 more error is not shown (at most 50 are); fix "
          "the first ones and run again\n";
    assert_string_equal(s + strlen(s) - strlen(end), end);
    free(s);

    /* exactly the bound: no note */
    s = held_over(0);
    assert_int_equal(count(s, ": error: "), DIAG_MAX_ERRORS);
    assert_null(strstr(s, "not shown"));
    free(s);
}

static void test_error_bound_held_note_of_muted_error(void **state)
{
    (void)state;
    Run r;
    run_open(&r, "x.pcs", "ab\n", 3);
    diag_hold(&r.d);
    for (int i = 0; i < DIAG_MAX_ERRORS; i++)
        diag_error(&r.d, (Span){0, 1}, "e%d", i);
    diag_error(&r.d, (Span){1, 2}, "over");
    diag_note(&r.d, (Span){0, 1}, "muted note");
    diag_flush(&r.d);
    run_close(&r);
    assert_null(strstr(r.out, "over"));
    assert_null(strstr(r.out, "muted note"));
    assert_int_equal(count(r.out, "1 more error is not shown"), 1);
    free(r.out);
}

/* a line of n bytes 'a'.. 'z' repeated */
static char *letters(int n)
{
    char *s = malloc((size_t)n + 2);
    for (int i = 0; i < n; i++)
        s[i] = (char)('a' + i % 26);
    s[n] = '\n';
    s[n + 1] = '\0';
    return s;
}

/* the expected excerpt: prefix, line[from, to), suffix, then pad spaces
 * and the caret */
static char *window(const char *line, int from, int to, const char *pre,
                    const char *post, int pad)
{
    size_t cap =
        strlen(pre) + (size_t)(to - from) + strlen(post) + (size_t)pad + 8;
    char *s = malloc(cap);
    size_t k = 0;
    memcpy(s + k, pre, strlen(pre));
    k += strlen(pre);
    memcpy(s + k, line + from, (size_t)(to - from));
    k += (size_t)(to - from);
    memcpy(s + k, post, strlen(post));
    k += strlen(post);
    s[k++] = '\n';
    memset(s + k, ' ', (size_t)pad);
    k += (size_t)pad;
    s[k++] = '^';
    s[k++] = '\n';
    s[k] = '\0';
    return s;
}

/* the excerpt part of a diagnostic (after the first line) */
static const char *excerpt_of(const char *msg)
{
    const char *nl = strchr(msg, '\n');
    assert_non_null(nl);
    return nl + 1;
}

static void test_long_line_window(void **state)
{
    (void)state;
    /* the span near the end of a 300-byte line: 60 bytes before it, cut
     * on the left only */
    char *line = letters(300);
    char *s = one_error(line, strlen(line), 200, 201);
    char *want = window(line, 140, 300, "...", "", 3 + 60);
    assert_true(strncmp(s, "x.pcs:1:201: error: m\n", 22) == 0);
    assert_string_equal(excerpt_of(s), want);
    free(s);
    free(want);

    /* near the start: cut on the right only, 160 bytes shown */
    s = one_error(line, strlen(line), 10, 11);
    want = window(line, 0, 160, "", "...", 10);
    assert_string_equal(excerpt_of(s), want);
    free(s);
    free(want);
    free(line);

    /* in the middle of a 400-byte line: cut on both sides */
    line = letters(400);
    s = one_error(line, strlen(line), 150, 151);
    want = window(line, 90, 250, "...", "...", 3 + 60);
    assert_true(strncmp(s, "x.pcs:1:151: error: m\n", 22) == 0);
    assert_string_equal(excerpt_of(s), want);
    free(s);
    free(want);
    free(line);

    /* exactly DIAG_EXCERPT_WIDTH bytes: shown whole */
    line = letters(DIAG_EXCERPT_WIDTH);
    s = one_error(line, strlen(line), 150, 151);
    want = window(line, 0, DIAG_EXCERPT_WIDTH, "", "", 150);
    assert_string_equal(excerpt_of(s), want);
    free(s);
    free(want);
    free(line);
}

static void test_long_line_window_cut_on_a_character(void **state)
{
    (void)state;
    /* "x", 100 two-byte e-acutes (bytes 1..200), 100 'b' (201..300): the
     * window would start at byte 190, inside an e-acute; it starts at
     * 189 instead, the first byte of that character */
    char text[400];
    size_t k = 0;
    text[k++] = 'x';
    for (int i = 0; i < 100; i++) {
        text[k++] = '\xc3';
        text[k++] = '\xa9';
    }
    for (int i = 0; i < 100; i++)
        text[k++] = 'b';
    text[k++] = '\n';
    char *s = one_error(text, k, 250, 251);
    /* column: x, 100 characters, 49 b before the span */
    assert_true(strncmp(s, "x.pcs:1:151: error: m\n", 22) == 0);
    /* shown: 6 e-acutes (bytes 189..200), 100 b; caret after 6 + 49 */
    char want[400];
    size_t w = 0;
    memcpy(want + w, "...", 3);
    w += 3;
    memcpy(want + w, text + 189, 112);
    w += 112;
    want[w++] = '\n';
    memset(want + w, ' ', 3 + 6 + 49);
    w += 3 + 6 + 49;
    memcpy(want + w, "^\n", 3);
    assert_string_equal(excerpt_of(s), want);
    free(s);
}

/* a sink that appends to a buffer */
typedef struct Buf {
    char text[1024];
    size_t n;
    int calls;
} Buf;

static void buf_put(void *ctx, const char *s, size_t n)
{
    Buf *b = ctx;
    assert_true(b->n + n < sizeof b->text);
    memcpy(b->text + b->n, s, n);
    b->n += n;
    b->text[b->n] = '\0';
    b->calls++;
}

static void test_sink_location_and_excerpt(void **state)
{
    (void)state;
    Source src;
    const char *text = "point A, B\nM = A*t\n";
    source_init(&src, "dir/x.pcs", text, strlen(text));
    Buf b = {.n = 0};
    DiagSink k = {buf_put, &b};
    diag_put_location(&k, &src, (Span){15, 18}, "warning");
    assert_string_equal(b.text, "dir/x.pcs:2:5: warning: ");
    assert_true(b.calls > 0);
    b.n = 0;
    b.text[0] = '\0';
    diag_put_excerpt(&k, &src, (Span){15, 18});
    assert_string_equal(b.text, "M = A*t\n    ^~~\n");
    /* a span before the start is clamped to it */
    b.n = 0;
    diag_put_location(&k, &src, (Span){-5, -1}, "error");
    assert_string_equal(b.text, "dir/x.pcs:1:1: error: ");
    /* the whole file (the budget's phases before and after the
     * statements): the name alone */
    b.n = 0;
    diag_put_location(&k, &src, DIAG_WHOLE_FILE, "error");
    assert_string_equal(b.text, "dir/x.pcs: error: ");
    source_clear(&src);
}

static void test_file_name_escaped(void **state)
{
    (void)state;
    Source src;
    source_init(&src, "a\x1b[2Jb.pcs", "q\n", 2);
    Buf b = {.n = 0};
    DiagSink k = {buf_put, &b};
    diag_put_location(&k, &src, (Span){0, 1}, "error");
    assert_string_equal(b.text, "a\\x1b[2Jb.pcs:1:1: error: ");
    source_clear(&src);

    char *out = NULL;
    size_t len = 0;
    FILE *mem = open_memstream(&out, &len);
    diag_fput_escaped(mem, "t\tx\n\xe2\x80\xae\xc3\xa9");
    fclose(mem);
    /* a tab and a valid character as themselves */
    assert_string_equal(out, "t\tx\\x0a\\u202e\xc3\xa9");
    free(out);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_format_line_col_caret),
        cmocka_unit_test(test_caret_spans_with_tildes),
        cmocka_unit_test(test_first_line_and_first_column),
        cmocka_unit_test(test_last_line_without_newline),
        cmocka_unit_test(test_tab_is_one_column_and_kept_in_caret),
        cmocka_unit_test(test_utf8_counts_characters),
        cmocka_unit_test(test_escaped_bytes_line_up),
        cmocka_unit_test(test_crlf_lines),
        cmocka_unit_test(test_spans_at_end_of_file),
        cmocka_unit_test(test_note_and_verror),
        cmocka_unit_test(test_verror_counts),
        cmocka_unit_test(test_null_out_counts_only),
        cmocka_unit_test(test_held_messages_in_source_order),
        cmocka_unit_test(test_rollback_drops_held_messages),
        cmocka_unit_test(test_error_bound_streaming),
        cmocka_unit_test(test_error_bound_held),
        cmocka_unit_test(test_error_bound_held_note_of_muted_error),
        cmocka_unit_test(test_long_line_window),
        cmocka_unit_test(test_long_line_window_cut_on_a_character),
        cmocka_unit_test(test_sink_location_and_excerpt),
        cmocka_unit_test(test_file_name_escaped),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

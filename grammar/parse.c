/*
 * parse.c - the front end in one call (parse.h): a reentrant flex scanner
 * over the source's bytes feeding the pure bison parser; syntax errors go
 * to the Diag at their spans, and the Scheme is what the parser built
 * (partial when there were errors).
 */
#include "grammar/parse.h"

/* the parser's header first: the scanner's uses its types */
#include "grammar/parser.h"

#include "grammar/lexer.h"

/* jq's jq_parse / PostgreSQL's raw_parser: init scanner, scan bytes, parse,
 * tear down. */
Scheme *parse_scheme(const Source *src, Arena *arena, Diag *diag)
{
    LexState lex = {.arena = arena, .diag = diag};
    Parser parser = {.arena = arena, .diag = diag};
    parser.scheme = arena_new(arena, Scheme);
    yyscan_t scanner;
    if (pc_yylex_init_extra(&lex, &scanner) != 0) {
        diag_error(diag, (Span){0, 0}, "cannot initialise the scanner");
        return parser.scheme;
    }
    YY_BUFFER_STATE buf = pc_yy_scan_bytes(src->text, (int)src->len, scanner);
    pc_yyparse(scanner, &parser);
    pc_yy_delete_buffer(buf, scanner);
    pc_yylex_destroy(scanner);
    return parser.scheme;
}

#!/usr/bin/env python3
"""tests/lint/funclen.py [--max N] FILE.c... - functions longer than N lines
(default 120) and files longer than 1000 lines.  A function may be longer
when the comment above it gives the reason, with a line 'long: <reason>'.
Exit 1 when any function or file is over without one (make lint)."""
import re
import sys

MAX_FUNC = 120
MAX_FILE = 1000

def functions(text):
    """(name, first line, line count, comment above) of each top-level
    function definition: a line at column 0 ending a signature, then a body
    from '{' at column 0 to '}' at column 0."""
    lines = text.split("\n")
    out = []
    i = 0
    while i < len(lines):
        if lines[i] == "{":
            # the signature: back to the first line at column 0 that
            # starts it (not a comment, not blank)
            j = i - 1
            while j > 0 and lines[j - 1].strip() and not lines[j - 1].startswith(("}", "/", " *", "#")) \
                    and not lines[j].startswith(("static", "void", "int", "double")) \
                    and lines[j].startswith((" ", "\t")):
                j -= 1
            while j > 0 and lines[j].startswith((" ", "\t")):
                j -= 1
            k = i + 1
            while k < len(lines) and lines[k] != "}":
                k += 1
            m = re.search(r"(\w+)\s*\(", lines[j])
            name = m.group(1) if m else lines[j].strip()
            c = j - 1
            comment = []
            while c >= 0 and (lines[c].startswith(("/*", " *", "//")) or lines[c].endswith("*/")):
                comment.append(lines[c])
                c -= 1
            out.append((name, i + 1, k - i + 1, "\n".join(comment)))
            i = k
        i += 1
    return out

def main(argv):
    limit = MAX_FUNC
    if len(argv) > 1 and argv[1] == "--max":
        limit = int(argv[2])
        argv = argv[2:]
    bad = 0
    for path in argv[1:]:
        text = open(path, encoding="utf-8").read()
        n = text.count("\n")
        if n > MAX_FILE:
            print("%s: %d lines (over %d: split it by function family)" % (path, n, MAX_FILE))
            bad += 1
        for name, line, count, comment in functions(text):
            if count > limit and "long:" not in comment:
                print("%s:%d: %s is %d lines (over %d, and no 'long:' reason above it)"
                      % (path, line, name, count, limit))
                bad += 1
    return 1 if bad else 0

if __name__ == "__main__":
    sys.exit(main(sys.argv))

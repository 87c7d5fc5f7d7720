#!/usr/bin/env bash
# The LaTeX that `derive --format latex --standalone` writes, for every
# example, with and without --steps: always checked for balanced braces and
# environments; compiled with pdflatex where it is installed (the optional
# dependency texlive-latex-base): every body in one document, which must
# compile without an error, and no line may run more than 20 pt beyond
# the page (an overfull \hbox: display math that was not broken).
# Usage: tests/latex_test.sh build/pointcalc
set -u
pc=${1:-build/pointcalc}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
n=0
mkdir "$tmp/docs"
for f in examples/*.pcs; do
    b=$(basename "$f" .pcs)
    for steps in "" --steps; do
        out="$tmp/docs/$b${steps:+_steps}.tex"
        if ! "$pc" derive "$f" --format latex --standalone $steps > "$out"; then
            echo "FAIL: derive $f --format latex --standalone $steps"
            fail=1
            continue
        fi
        n=$((n + 1))
        sed -e '1,/^\\begin{document}$/d' -e '/^\\end{document}$/d' "$out" \
            >> "$tmp/all_body.tex"
    done
done

# balanced braces (outside \{ \}), \begin/\end pairs, no double
# subscripts, whole documents
wellformed=1
python3 - "$tmp"/docs/*.tex <<'PY' || { fail=1; wellformed=0; }
import re, sys
bad = 0
for path in sys.argv[1:]:
    s = open(path).read()
    t = s.replace("\\{", "").replace("\\}", "")
    depth, why = 0, None
    for ch in t:
        depth += (ch == "{") - (ch == "}")
        if depth < 0:
            why = "a } without its {"
            break
    if depth and not why:
        why = "unbalanced braces"
    envs = []
    for m in re.finditer(r"\\(begin|end)\{([^}]*)\}", s):
        if m.group(1) == "begin":
            envs.append(m.group(2))
        elif not envs or envs.pop() != m.group(2):
            why = why or "\\end{%s} does not close the last \\begin" % m.group(2)
    if envs:
        why = why or "unclosed \\begin{%s}" % envs[-1]
    if re.search(r"_\{[^{}]*\}_", s) or re.search(r"_[A-Za-z0-9]_", s):
        why = why or "a double subscript"
    if not s.startswith("\\documentclass") or "\\end{document}" not in s:
        why = why or "not a whole document"
    if why:
        print("FAIL: %s: %s" % (path, why))
        bad = 1
sys.exit(bad)
PY

if command -v pdflatex >/dev/null 2>&1; then
    { printf '\\documentclass{article}\n\\usepackage{amsmath}\n\\begin{document}\n'
      cat "$tmp/all_body.tex"
      printf '\\end{document}\n'; } > "$tmp/all.tex"
    if (cd "$tmp" && pdflatex -interaction=nonstopmode -halt-on-error all.tex \
            > /dev/null 2>&1); then
        # no line wider than the page: overfull boxes beyond 20 pt
        # (TeX does not break display math; derive breaks it, book.c and
        # latexbreak.c) fail, with the lines they come from
        over=$(grep -E '^Overfull \\hbox \(([0-9.]+)pt too wide\)' "$tmp/all.log" |
               awk -F'[(p]' '$2 + 0 > 20')
        if [ -n "$over" ]; then
            echo "FAIL: LaTeX lines wider than the page (over 20 pt):"
            printf '%s\n' "$over" | head -10
            printf '%s\n' "$over" | grep -oE 'lines? [0-9]+' | grep -oE '[0-9]+' |
                head -5 | while read -r l; do
                    sed -n "${l}p" "$tmp/all.tex" | cut -c1-200
                done
            fail=1
        elif [ $wellformed = 1 ]; then
            echo "latex: $n documents well-formed, all compiled with pdflatex," \
                 "no line wider than the page"
        fi
    else
        echo "FAIL: pdflatex on the examples' LaTeX:"
        grep -B2 -A6 '^!' "$tmp/all.log" | head -20
        fail=1
    fi
elif [ $wellformed = 1 ]; then
    echo "latex: $n documents well-formed (pdflatex not installed: not compiled)"
fi
exit $fail

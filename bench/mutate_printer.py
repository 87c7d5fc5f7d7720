#!/usr/bin/env python3
"""The printer's mutation experiment (issue 9): one-line changes to
the book printer (compiler/print/book_*.c), each built and run against the tests of what derive
prints (test_book's goldens, test_schemes' read-back, tests/printback.py,
tests/latex_test.sh).  A mutant that no test kills is a rule no test pins.

Run from a scratch copy of the tree (it edits the printer's files and
restores them):  git worktree add /tmp/mut HEAD && cd /tmp/mut &&
      python3 bench/mutate_printer.py
"""
import glob
import subprocess
import sys

MUTANTS = [
    ("1 - x in text", 'str_puts(b, "(1 - ");', 'str_puts(b, "(1 + ");'),
    ("exponents", "    if (e <= 1)\n        return;",
     "    if (e <= 2)\n        return;"),
    ("signs in a sum", 'str_puts(b, s->t[i].neg ? " - " : " + ");',
     'str_puts(b, s->t[i].neg ? " + " : " + ");'),
    ("fewest terms", "int better = lc < lb ||", "int better = lc > lb ||"),
    ("Bernstein coefficients",
     "fmpz_bin_uiui(bin, (ulong)(n - i), (ulong)(k - i));",
     "fmpz_bin_uiui(bin, (ulong)(n - i), (ulong)k);"),
    ("the point's place", "        return a->point2 ? -1 : 1;",
     "        return a->point2 ? -1 : 3;"),
    ("denominator sign", "    *flip = d->t[0].neg;", "    *flip = 0;"),
    ("all-minus numerators", "    return s->n > 0;\n}", "    return 0;\n}"),
    ("LaTeX words", 'str_puts(b, "\\\\mathit{");', 'str_puts(b, "{");'),
    ("differences, positive first", "                    pt.point2 = pt.point;\n",
     ""),
    ("parentheses of a denominator",
     "int pd = den->n > 1 || den->t[0].n + !fmpz_is_one(den->t[0].coeff) > 1;",
     "int pd = den->n > 2 || den->t[0].n + !fmpz_is_one(den->t[0].coeff) > 1;"),
    ("powers collection", "Atom xa = {AT_VAR, x, NULL, NULL, NULL, (ulong)k};",
     "Atom xa = {AT_VAR, x, NULL, NULL, NULL, (ulong)k + 1};"),
    ("d/dt", 'str_puts(b, "\\\\frac{\\\\mathrm{d}");', 'str_puts(b, "\\\\frac{d");'),
    ("multline width", "if (i > 0 && (int)(line.len + item.len + 1) > width)",
     "if (i > 0 && (int)(line.len + item.len + 1) > 2 * width)"),
    ("ascending order", "for (slong k = len - 1; k >= 0; k--) {",
     "for (slong k = 0; k < len; k++) {"),
    ("common factor", "if (!fmpz_mpoly_is_one(g, r->ctx) && eq->len > 1) {",
     "if (0) {"),
    ("factor order by degree", "            return da < db ? -1 : 1;",
     "            return da < db ? 1 : -1;"),
]

TESTS = [
    ["build/tests/test_book"],
    ["build/tests/test_schemes"],
    ["python3", "tests/printback.py", "build/pointcalc", "examples/desargues_arc.pcs",
     "examples/double_contact.pcs", "examples/space_cubic.pcs",
     "examples/conic_weight.pcs", "examples/ellipse_central_angle.pcs"],
    ["tests/latex_test.sh", "build/pointcalc"],
]


def run(cmd):
    return subprocess.run(cmd, stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL).returncode


def main():
    paths = sorted(glob.glob("compiler/print/book_*.c"))
    origs = {p: open(p).read() for p in paths}
    survivors = []
    try:
        for name, old, new in MUTANTS:
            where = [p for p in paths if origs[p].count(old) == 1]
            if len(where) != 1 or sum(o.count(old) for o in origs.values()) != 1:
                print(f"?? {name}: the line to change is not unique or gone")
                survivors.append(name)
                continue
            path = where[0]
            for p in paths:
                open(p, "w").write(origs[p])
            open(path, "w").write(origs[path].replace(old, new))
            if run(["make", "-j2", "build/pointcalc", "build/tests/test_book",
                    "build/tests/test_schemes"]):
                print(f"killed (does not build): {name}")
                continue
            killer = next((t[0] if t[0] != "python3" else t[1]
                           for t in TESTS if run(t)), None)
            if killer:
                print(f"killed by {killer}: {name}")
            else:
                print(f"SURVIVED: {name}")
                survivors.append(name)
    finally:
        for p in paths:
            open(p, "w").write(origs[p])
    print(f"{len(MUTANTS) - len(survivors)}/{len(MUTANTS)} mutants killed")
    return 1 if survivors else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""A second reader of what `pointcalc derive` prints (issue 9).

For every scheme given, the text form (book style) and the JSON form
(the contract's weights) are read independently of pointcalc - by Python's
own expression parser - and evaluated at random values of the params and
consts and random point coordinates: exactly (fractions) when the scheme
has no scalar functions, in double precision (relative 1e-9) when it has.
Every output must agree.  Names the text is written through (scalar
definitions whose value is a function, derive prints results through them)
are evaluated from their own JSON values first.  Usage: printback.py POINTCALC FILE.pcs...
"""
import json
import math
import os
import random
import re
import subprocess
import sys
import tempfile
from fractions import Fraction

def natural(u, k, y):
    """natx (y = 0) / naty of law k at u, read independently of pointcalc:
    composite Simpson on 512 and 1024 intervals, extrapolated (O(h^6))"""
    u, k = float(u), [float(c) / (j + 1) for j, c in enumerate(k)]
    f = math.sin if y else math.cos
    res = []
    for n in (512, 1024):
        h = u / n
        tot = 0.0
        for i in range(n + 1):
            s = h * i
            ph = sum(c * s ** (j + 1) for j, c in enumerate(k))
            tot += f(ph) * (1 if i in (0, n) else 4 if i % 2 else 2)
        res.append(tot * h / 3)
    return res[1] + (res[1] - res[0]) / 15


FUNCS = {
    "sqrt": lambda x: math.sqrt(x),
    "sin": math.sin, "cos": math.cos, "tan": math.tan,
    "asin": math.asin, "acos": math.acos, "atan": math.atan,
    "atan2": math.atan2, "sinh": math.sinh, "cosh": math.cosh,
    "tanh": math.tanh, "exp": math.exp, "ln": math.log,
    "abs": abs, "sign": lambda x: (x > 0) - (x < 0),
    "root": lambda x, q: math.copysign(abs(x) ** (1.0 / q), x),
    "natx": lambda u, *k: natural(u, k, 0),
    "naty": lambda u, *k: natural(u, k, 1),
    "pi": math.pi,
    "dist": None,  # per sample: a value for each pair of points
    "coord": None,  # per sample: a value for each point and index
}
WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def python_expr(s):
    """pointcalc's expression syntax as Python: ^ is **, every scheme name
    v_NAME (so no name is a Python keyword or a function of ours), every
    integer a Fraction"""
    s = s.replace("^", "**")
    s = WORD.sub(lambda m: m.group(0) if m.group(0) in FUNCS
                 else "v_" + m.group(0), s)
    # integers exact: 1/2 is a half, not 0.5
    return re.sub(r"(?<![A-Za-z_0-9.])(\d+)(?![0-9.])", r"F(\1)", s)


def value(expr, env):
    return eval(python_expr(expr), {"__builtins__": {}}, env)


def close(x, y, exact):
    if exact:
        return x == y
    return abs(x - y) <= 1e-9 * max(1.0, abs(x), abs(y))


def check(pc, path, rng):
    js = subprocess.run([pc, "derive", path, "--format", "json"],
                        capture_output=True, text=True, check=True).stdout
    tx = subprocess.run([pc, "derive", path], capture_output=True,
                        text=True, check=True).stdout
    d = json.loads(js)
    printed = {}
    for line in tx.splitlines():
        name, rhs = line.split(" = ", 1)
        printed[name] = rhs.replace("    (vector)", "")
    exact = not any(f + "(" in js for f in FUNCS) and "pi" not in \
        WORD.findall(js)
    # names the text is written through (a = dist(A, C)^2, c = sqrt(...),
    # the book's a, c, gamma): their values, derived as outputs of a copy
    # of the scheme, in JSON (which never uses them)
    known = set(d["points"]) | set(d["params"]) | set(d["consts"]) | \
        set(FUNCS)
    named = sorted({w for rhs in printed.values() for w in WORD.findall(rhs)
                    if w not in known})
    named_values = {}
    if named:
        src = open(path).read()
        src = re.sub(r"(?m)^(output[ \t])", r"# \1", src)
        src += "\noutput " + ", ".join(named) + "\n"
        with tempfile.NamedTemporaryFile("w", suffix=".pcs",
                                         delete=False) as tf:
            tf.write(src)
        try:
            nj = subprocess.run([pc, "derive", tf.name, "--format", "json"],
                                capture_output=True, text=True,
                                check=True).stdout
        finally:
            os.unlink(tf.name)
        for o in json.loads(nj)["outputs"]:
            named_values[o["name"]] = o["value"]
    fails = 0
    for o in d["outputs"]:
        rhs = printed.get(o["name"])
        if rhs is None:
            print(f"FAIL {path}: {o['name']} not printed")
            fails += 1
            continue
        for attempt in range(400):
            env = dict(FUNCS)
            env["F"] = Fraction
            env["dist"] = lambda p, q: abs(p - q) + Fraction(1, 3)
            env["coord"] = lambda p, k: p * (k + 1) + k * k
            # params in (0, 1) first; later tries anywhere in (0, 4), as
            # ranges may depend on consts ([b, a])
            top = 99 if attempt < 20 else 399
            for n in d["params"]:
                env["v_" + n] = Fraction(rng.randint(1, top), 100)
            for n in d["consts"]:
                env["v_" + n] = Fraction(rng.randint(1, 399), 100)
            for n in d["points"]:
                env["v_" + n] = Fraction(rng.randint(-999, 999), 97)
            try:
                for n, v in named_values.items():
                    env["v_" + n] = value(v, env)
                if o["kind"] == "scalar":
                    want = value(o["value"], env)
                else:
                    want = sum((value(w, env) * env["v_" + p]
                                for p, w in o["terms"].items()),
                               Fraction(0))
                got = value(rhs, env)
            except (ValueError, ZeroDivisionError, OverflowError):
                continue  # outside a domain or at a pole: other values
            if not close(want, got, exact):
                print(f"FAIL {path}: {o['name']}: printed {rhs}\n"
                      f"  evaluates to {got}, the JSON weights to {want}")
                fails += 1
            break
        else:
            print(f"FAIL {path}: {o['name']}: no sample point evaluates")
            fails += 1
    return fails, len(d["outputs"])


def main():
    pc, files = sys.argv[1], sys.argv[2:]
    rng = random.Random(20261125)
    fails = total = 0
    for f in files:
        k, n = check(pc, f, rng)
        fails += k
        total += n
    print(f"printback: {total - fails}/{total} outputs of {len(files)} "
          f"schemes read back by a second reader")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())

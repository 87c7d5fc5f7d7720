#!/usr/bin/env python3
"""sympy.lambdify on the Desargues arc, for bench_codegen (ns/point).

    python3 bench/lambdify.py N

Reads the reduced weights from `build/pointcalc derive --format json`
(falls back to the closed formula), lambdifies M(t) in 3D with and without
cse=True and times it.  With numpy: one vectorised call over N values.
Without numpy: the `math` module, a Python loop over min(N, 10^5) values.
Prints nothing (exit 0) when sympy is missing, so the bench skips cleanly.
"""
import json
import subprocess
import sys
import time

try:
    import sympy
except ImportError:
    sys.exit(0)
try:
    import numpy
except ImportError:
    numpy = None

A = (0.0, 0.0, 0.0)
B = (1.0, 0.2, -0.3)
C = (0.1, 1.0, 0.4)
D = (-0.2, 0.3, 1.0)


def weights(t):
    try:
        js = subprocess.run(
            ["build/pointcalc", "derive", "examples/desargues_arc.pcs",
             "--format", "json"], capture_output=True, text=True, check=True)
        out = [o for o in json.loads(js.stdout)["outputs"] if o["name"] == "M"][0]
        return [sympy.sympify(out["terms"][p], locals={"t": t}) for p in "ABCD"]
    except Exception:
        d = 2 * t**2 - 2 * t + 1
        return [(1 - t)**3 / d, t**2 * (1 - t) / d, t * (1 - t)**2 / d, t**3 / d]


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 10**6
    t = sympy.Symbol("t")
    w = weights(t)
    coords = [sum(wk * P[c] for wk, P in zip(w, (A, B, C, D))) for c in range(3)]
    if numpy is None:
        n = min(n, 10**5)
        ts = [i / (n - 1) for i in range(n)]
        module, what = "math", "math module, python loop"
    else:
        ts = numpy.linspace(0.0, 1.0, n)
        module, what = "numpy", "numpy"
    for cse in (False, True):
        f = sympy.lambdify(t, coords, modules=module, cse=cse)
        best = []
        for _ in range(3):
            t0 = time.perf_counter()
            if numpy is None:
                for x in ts:
                    f(x)
            else:
                f(ts)
            best.append(time.perf_counter() - t0)
        best.sort()
        label = "sympy.lambdify" + (" cse=True" if cse else "")
        print("  %-26s %8.3f ns/point  (%s, n = %d)"
              % (label, best[1] * 1e9 / n, what, n))


if __name__ == "__main__":
    main()

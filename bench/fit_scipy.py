#!/usr/bin/env python3
"""fit_scipy.py [-r ROUNDS] N ... - SciPy's least_squares on pointcalc fit's problem
(bench/bench_fit.c, docs/fit.md): Runge's function 1/(1 + 25x^2) on
[-1, 1], the order-(N-1) interpolation curve through N nodes at t = k/(N-1),
m = 100 (t_i = i/m, i = 0..m), residuals r_i = f(x(t_i)) - y(t_i), the same
exact Jacobian, the same log-gap unknowns and the same starts (Chebyshev,
uniform, 8 seeded random ones: splitmix64 as in driver/cli/fit.c).  Prints
per N the best MSE, its nodes and the median time of all starts; prints
"skipped" when NumPy or SciPy is missing.
"""
import sys
import time

try:
    import numpy as np
    from scipy.optimize import least_squares
except ImportError:
    print("  skipped (no scipy)")
    sys.exit(0)

MASK = (1 << 64) - 1


def splitmix_starts(s, nu):
    state = (s * 7919) & MASK
    u = []
    for _ in range(nu):
        state = (state + 0x9E3779B97F4A7C15) & MASK
        z = state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        z ^= z >> 31
        u.append(3 * ((z >> 11) * 2.0**-53) - 1.5)
    return np.array(u)


def lagrange(n, t):
    p = np.arange(n) / (n - 1)
    phi = np.ones((len(t), n))
    for k in range(n):
        for j in range(n):
            if j != k:
                phi[:, k] *= (t - p[j]) / (p[k] - p[j])
    return phi


def problem(n, lo=-1.0, hi=1.0, m=100):
    t = np.arange(m + 1) / m
    phi = lagrange(n, t)
    f = lambda x: 1 / (1 + 25 * x * x)
    fp = lambda x: -50 * x / (1 + 25 * x * x) ** 2
    L = hi - lo

    def nodes(u):
        v = np.concatenate(([0.0], u))
        s = np.exp(v - v.max())
        s /= s.sum()
        S = np.concatenate(([0.0], np.cumsum(s)))
        x = lo + L * S
        x[-1] = hi
        return x, s, S

    def res(u):
        x, _, _ = nodes(u)
        X = phi @ x
        return f(X) - phi @ f(x)

    def jac(u):
        x, s, S = nodes(u)
        X = phi @ x
        Jx = phi[:, 1:-1] * (fp(X)[:, None] - fp(x[1:-1])[None, :])
        nu = n - 2
        D = np.zeros((nu, nu))
        for k in range(1, n - 1):
            for j in range(1, n - 1):
                D[k - 1, j - 1] = L * s[j] * ((1.0 if j < k else 0.0) - S[k])
        return Jx @ D

    def starts():
        out = []
        for s in range(10):
            if s >= 2:
                out.append(splitmix_starts(s, n - 2))
                continue
            k = np.arange(n)
            x = (lo + hi) / 2 - L / 2 * np.cos(np.pi * k / (n - 1)) if s == 0 \
                else lo + L * k / (n - 1)
            g = np.diff(x)
            out.append(np.log(g[1:] / g[0]))
        return out

    return res, jac, starts, nodes, m


def run(n, rounds=5):
    res, jac, starts, nodes, m = problem(n)
    times, best = [], None
    for _ in range(rounds):
        t0 = time.perf_counter()
        for u0 in starts():
            r = least_squares(res, u0, jac=jac, method="trf", xtol=1e-15,
                              ftol=1e-15, gtol=1e-15, max_nfev=3000)
            mse = 2 * r.cost / (m + 1)
            if best is None or mse < best[0]:
                best = (mse, nodes(r.x)[0])
        times.append((time.perf_counter() - t0) * 1e3)
    times.sort()
    print("  %2d nodes: scipy %8.3f ms [%.3f..%.3f] (10 starts), MSE %.17g, "
          "nodes %s" % (n, times[len(times) // 2], times[0], times[-1],
                        best[0], " ".join("%.17g" % v for v in best[1])))


if __name__ == "__main__":
    args, rounds = sys.argv[1:], 5
    if args[:1] == ["-r"]:
        rounds, args = int(args[1]), args[2:]
    for a in args or ["6", "11"]:
        run(int(a), rounds)

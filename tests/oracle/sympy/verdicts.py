"""verdicts.py - what the SymPy checks of the monograph's formulas share:
the OK / MISPRINT / FAIL verdicts, numeric comparison of printed and derived
weights at random parameter values (40 digits), and the split of a 2D point
into the weights of a simplex.  A check script calls use_symbols(SYM) once
(the names its substitution dicts may use as strings) and ends with
finish()."""
import random
import sys

import mpmath as mp
import sympy as sp

mp.mp.dps = 40
R = sp.Rational

failures = []
misprints = []
_SYM = {}


def use_symbols(sym):
    """sym: name -> sympy symbol, for substitution dicts with string keys
    (kept by reference: the script may add names later)."""
    global _SYM
    _SYM = sym


def report(ok, label, msg=''):
    print(f"{'OK      ' if ok else 'FAIL    '} {label}{(': ' + msg) if msg else ''}")
    if not ok:
        failures.append(label)


def misprint(label, msg):
    """A printed formula that the derivation shows wrong (an expected verdict)."""
    print(f"MISPRINT {label}: {msg}")
    misprints.append(label)


def remark(msg):
    print(f"REMARK   {msg}")


def fix(s):
    """Substitution dict; string keys (from dict(s, phi=...)) name symbols."""
    return {(_SYM[k] if isinstance(k, str) else k): v for k, v in s.items()}


def num(e, s):
    z = sp.N(sp.sympify(e).subs(fix(s)), 35)
    return mp.mpc(mp.mpf(str(sp.re(z))), mp.mpf(str(sp.im(z))))


def same(e1, e2, samples, tol=1e-20):
    """Numeric equality at every substitution dict in samples."""
    for s in samples:
        d1, d2 = num(e1, s), num(e2, s)
        if abs(d1 - d2) > tol * max(1.0, abs(d1), abs(d2)):
            return False
    return True


def rnd(lo, hi):
    return R(random.randint(int(lo * 1000) + 1, int(hi * 1000) - 1), 1000)


def compare(label, printed, derived, samples, expect_ok=True, why='', correct=None):
    """printed, derived: lists of weights.  expect_ok False: a known misprint;
    correct: the corrected printed-style form, checked equal to derived."""
    ok = all(same(p, d, samples) for p, d in zip(printed, derived))
    if correct is not None and not all(same(p, d, samples) for p, d in zip(correct, derived)):
        report(False, label, "the stated correction does not equal the derived weights")
        return
    shown = ', '.join(str(sp.simplify(d)) for d in (correct if correct is not None else derived))
    if len(shown) > 220:
        shown = '(long; equal to the ' + ('printed form)' if ok else 'correction above)')
    if ok and expect_ok:
        report(True, label, f"agrees; derived {shown}")
    elif not ok and not expect_ok:
        misprint(label, f"{why}\n           derived: {shown}")
    else:
        report(False, label, f"verdict changed (printed {'agrees' if ok else 'differs'}); "
                             f"derived: {shown}")


def decompose(M, O, P1, P2):
    """p, q with M - O = p (P1 - O) + q (P2 - O), all 2D coordinate tuples."""
    p, q = sp.symbols('p_ q_')
    sol = sp.solve([M[i] - O[i] - p * (P1[i] - O[i]) - q * (P2[i] - O[i]) for i in range(2)],
                   [p, q], dict=True)[0]
    return sp.simplify(sol[p]), sp.simplify(sol[q])


def point_from(weights, O, P1, P2):
    p, q = weights
    return tuple(O[i] + p * (P1[i] - O[i]) + q * (P2[i] - O[i]) for i in range(2))


def npt(P, s):
    return tuple(mp.mpf(str(sp.N(sp.sympify(P[i]).subs(fix(s)), 40))) for i in range(2))


def ndist(P, Q):
    return mp.sqrt(sum((mp.mpf(P[i]) - mp.mpf(Q[i])) ** 2 for i in range(2)))


def finish():
    print(f"\n{len(misprints)} misprints confirmed, {len(failures)} failures")
    sys.exit(1 if failures else 0)

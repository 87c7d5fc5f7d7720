#!/usr/bin/env python3
"""The natural-parametrization article, checked independently (issue 21,
docs/errata.md NP1-NP2, docs/natural.md):

1. (13)-(15): the leading coefficient a solved from (10)-(12) by SymPy,
   compared with the printed forms ((13) agrees; (14), (15) differ unless
   S = 1).
2. pointcalc natural's clothoids, quadratic and cubic segments: the end
   point and end angle recomputed from the printed coefficients and length
   by mpmath's quadrature at 30 digits (not pointcalc's Gauss-Legendre
   panels), on a few configurations and a composite G3 curve.
"""
import json
import os
import subprocess
import sys

import mpmath as mp
import sympy as sp

fails = 0


def verdict(name, ok):
    global fails
    print(f"CHECK {name}: {'agrees' if ok else 'DIFFERS'}")
    if not ok:
        fails += 1


S, a, b, c, d, dphi = sp.symbols("S a b c d dphi", positive=True)
laws = {
    "(13)": (sp.Eq(dphi, a * S**2 / 2 + b * S), 2 / S * (dphi / S - b)),
    "(14)": (sp.Eq(dphi, a * S**3 / 3 + b * S**2 / 2 + c * S),
             3 / S * (dphi / S**2 - b * S / 2 - c)),
    "(15)": (sp.Eq(dphi, a * S**4 / 4 + b * S**3 / 3 + c * S**2 / 2 + d * S),
             4 / S * (dphi / S**3 - b * S**2 / 3 - c * S / 2 - d)),
}
expect = {"(13)": True, "(14)": False, "(15)": False}  # errata NP1, NP2
for name, (eq, printed) in laws.items():
    solved = sp.solve(eq, a)[0]
    same = sp.simplify(solved - printed) == 0
    print(f"{name}: a = {sp.factor(solved)}; printed {'=' if same else '!='} "
          f"{printed}")
    verdict(f"{name} printed as derived is {expect[name]}", same == expect[name])
    if not same:  # right at S = 1 only
        verdict(f"{name} agrees at S = 1",
                sp.simplify((solved - printed).subs(S, 1)) == 0)

mp.mp.dps = 30
pc = os.environ.get("PC_BIN", "build/pointcalc")


def end_of(seg, x0, y0):
    k = [mp.mpf(v) for v in seg["k"]]
    L = mp.mpf(seg["length"])
    phi0 = mp.mpf(seg["phi0"])

    def phi(s):
        return phi0 + sum(kj * s**(j + 1) / (j + 1) for j, kj in enumerate(k))

    x = x0 + mp.quad(lambda s: mp.cos(phi(s)), [0, L / 2, L])
    y = y0 + mp.quad(lambda s: mp.sin(phi(s)), [0, L / 2, L])
    return x, y, phi(L)


def run(args):
    out = subprocess.run([pc, "natural", "--format", "json"] + args,
                         capture_output=True, text=True, check=True).stdout
    return json.loads(out)


cases = [
    ["--from", "0,0,0.3", "--to", "1,0.2,-0.4"],
    ["--from", "0,0,2.8", "--to", "1,0,2.9"],
    ["--from", "-1,2,-2.9", "--to", "3,1,1.0"],
    ["--from", "0,0,0.3", "--to", "1,0.2,-0.4", "--law", "quadratic",
     "--k0", "0.5"],
    ["--from", "0,0,0.3", "--to", "1,0.2,-0.4", "--law", "cubic",
     "--k0", "0.5", "--dk0", "-2"],
    ["--from", "0,0,0.2", "--through", "1,0.3", "--through", "2,0.1",
     "--to", "3,-0.2,-0.3", "--law", "cubic"],
]
for args in cases:
    r = run(args)
    pts = r["points"]
    worst = 0
    for i, seg in enumerate(r["segments"]):
        x, y, ph = end_of(seg, mp.mpf(pts[i][0]), mp.mpf(pts[i][1]))
        err = max(abs(x - pts[i + 1][0]), abs(y - pts[i + 1][1]))
        turn = mp.fmod(ph - pts[i + 1][2], 2 * mp.pi)
        turn = min(abs(turn), abs(2 * mp.pi - abs(turn)))
        worst = max(worst, err, turn)
    print(f"{' '.join(args)}: end point and angle within {mp.nstr(worst, 3)}")
    verdict(f"natural {' '.join(args[:4])}... reaches its ends", worst < 1e-12)

print("check_natural: %s" % ("all agree" if not fails else f"{fails} differ"))
sys.exit(1 if fails else 0)

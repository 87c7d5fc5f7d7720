#!/bin/sh
# Monograph 5.2: Runge's function 1/(1 + 25x^2) on [-1, 1], the curve of
# order 5 through 6 nodes (docs/fit.md).  Expect the nodes -1, -0.233198,
# -0.0605405, 0.0605405, 0.233198, 1 and MSE 2.83922e-05 (the book:
# 0.0000284), x(t) = 22.886*t^5 - 57.215*t^4 + 57.076*t^3 - 28.398*t^2 +
# 7.652*t - 1 as printed.  With an argument N: N nodes (table 5.1: 5..11).
PC=${PC:-build/pointcalc}
exec "$PC" fit --target '1/(1 + 25*x^2)' --on -1,1 --nodes "${1:-6}"

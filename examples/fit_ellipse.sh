#!/bin/sh
# Monograph 5.3, example 1: the ellipse y = sqrt(b^2 - b^2 x^2 / a^2), a = 4,
# b = 3, with the curve of order 3 (4 nodes).  The book's nodes +-1.877016
# and MSE 0.00014577 are those of m = 10 samples (--samples 10 reproduces
# them and its x(t), y(t)); with the chapter's m = 100 the optimum is
# +-1.889359, MSE 0.000535656 (docs/fit.md, errata).
PC=${PC:-build/pointcalc}
"$PC" fit --target 'sqrt(9 - 9*x^2/16)' --on -4,4 --nodes 4 --samples 10 &&
    "$PC" fit --target 'sqrt(9 - 9*x^2/16)' --on -4,4 --nodes 4

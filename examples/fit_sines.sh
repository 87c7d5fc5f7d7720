#!/bin/sh
# Monograph 5.3, example 2: sin(x) + sin(10x) on [-0.5, 0.5] with 6 nodes
# (expect +-0.265069, +-0.084952, MSE 2.47154e-06, as printed) and on
# [-1, 1] with 10 nodes (the book's nodes give MSE 0.000462 only with m =
# 50 samples; the optimum is 4.59061e-08 with m = 100: docs/fit.md).
PC=${PC:-build/pointcalc}
"$PC" fit --target 'sin(x) + sin(10*x)' --on -0.5,0.5 --nodes 6 &&
    "$PC" fit --target 'sin(x) + sin(10*x)' --on -1,1 --nodes 10

#!/bin/sh
# Monograph 5.2, figure 5.4: Runge's function on [-2.5, 2.5] with 6 and 7
# nodes.  Expect MSE 0.000558734 and 1.93625e-05 (the book: 0.0005587 and
# 0.00001936).
PC=${PC:-build/pointcalc}
"$PC" fit --target '1/(1 + 25*x^2)' --on -2.5,2.5 --nodes 6 &&
    "$PC" fit --target '1/(1 + 25*x^2)' --on -2.5,2.5 --nodes 7

#!/bin/sh
# Monograph table 5.1: Runge's function on [-1, 1] with 5 ... 11 nodes, m =
# 100; one line per node count: N, the MSE, the book's MSE (docs/fit.md
# compares them: 5 nodes is the book's m = 10, 9 to 11 nodes are where its
# search stopped early).
PC=${PC:-build/pointcalc}
book="5:0.000963 6:2.84e-05 7:5.14e-07 8:1.01e-08 9:8.15e-10 10:2.67e-08 11:4e-09"
for nb in $book; do
    n=${nb%%:*}
    mse=$("$PC" fit --target '1/(1 + 25*x^2)' --on -1,1 --nodes "$n" |
        sed -n 's/^MSE: //p') || exit 1
    echo "$n nodes: MSE $mse (book ${nb#*:})"
done

/* docs/tutorial.md: the emitted parabola used from a C program */
#include <stdio.h>

#include "parabola.h"

int main(void)
{
    const double A[2] = {0, 0}, B[2] = {4, 0}, C[2] = {2, 4};
    double t[3] = {0, 0.5, 1}, out[6];
    parabola_M_batch(3, t, A, B, C, 2, out);
    for (int i = 0; i < 3; i++)
        printf("t = %.2f: (%g, %g)\n", t[i], out[2 * i], out[2 * i + 1]);
    return 0;
}

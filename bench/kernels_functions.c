/*
 * kernels_functions.c - careful hand-written loops for the transcendental
 * schemes of bench_functions.c: what a C programmer writes for the ellipse
 * by central angle (2.11) and by compression (2.24), calling sin and cos
 * once each per sample, the point differences formed once per call.
 */
#include <math.h>
#include <stddef.h>

void hand_ellipse_angle(size_t n, const double *restrict phi, double a,
                        double b, const double *A, const double *B,
                        const double *C, double *restrict out);
void hand_ellipse_compression(size_t n, const double *restrict phi,
                              const double *A, const double *B, const double *C,
                              double *restrict out);

/* M = C + (A - C) b cos(phi)/sqrt(q) + (B - C) a sin(phi)/sqrt(q),
 * q = a^2 sin^2 + b^2 cos^2 */
void hand_ellipse_angle(size_t n, const double *restrict phi, double a,
                        double b, const double *A, const double *B,
                        const double *C, double *restrict out)
{
    const double ua0 = b * (A[0] - C[0]), ua1 = b * (A[1] - C[1]),
                 ua2 = b * (A[2] - C[2]);
    const double ub0 = a * (B[0] - C[0]), ub1 = a * (B[1] - C[1]),
                 ub2 = a * (B[2] - C[2]);
    const double a2 = a * a, b2 = b * b;
    for (size_t i = 0; i < n; i++) {
        const double s = sin(phi[i]), c = cos(phi[i]);
        const double r = 1.0 / sqrt(a2 * s * s + b2 * c * c);
        const double wa = c * r, wb = s * r;
        out[3 * i] = C[0] + ua0 * wa + ub0 * wb;
        out[3 * i + 1] = C[1] + ua1 * wa + ub1 * wb;
        out[3 * i + 2] = C[2] + ua2 * wa + ub2 * wb;
    }
}

/* M = C + (A - C) cos(phi) + (B - C) sin(phi) */
void hand_ellipse_compression(size_t n, const double *restrict phi,
                              const double *A, const double *B, const double *C,
                              double *restrict out)
{
    const double u0 = A[0] - C[0], u1 = A[1] - C[1], u2 = A[2] - C[2];
    const double v0 = B[0] - C[0], v1 = B[1] - C[1], v2 = B[2] - C[2];
    for (size_t i = 0; i < n; i++) {
        const double s = sin(phi[i]), c = cos(phi[i]);
        out[3 * i] = C[0] + u0 * c + v0 * s;
        out[3 * i + 1] = C[1] + u1 * c + v1 * s;
        out[3 * i + 2] = C[2] + u2 * c + v2 * s;
    }
}

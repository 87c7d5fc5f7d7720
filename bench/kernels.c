/*
 * kernels.c - the hand-written contestants and the floors of
 * bench_codegen, compiled at run time into the same shared object as the
 * generated code, with the same compiler and the same flags, so that every
 * comparison is like for like.  Points are 3D, output row-major.
 */
#include <stddef.h>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

void hand_simple(size_t n, const double *t, const double *A, const double *B,
                 const double *C, const double *D, double *out);
void hand_careful(size_t n, const double *restrict t, const double *A,
                  const double *B, const double *C, const double *D,
                  double *restrict out);
void floor_store(size_t n, const double *t, const double *A, const double *B,
                 const double *C, const double *D, double *out);
void floor_stream(size_t n, const double *t, const double *A, const double *B,
                  const double *C, const double *D, double *out);
void floor_read_store(size_t n, const double *t, const double *A,
                      const double *B, const double *C, const double *D,
                      double *out);

/* the weights per sample, then the coordinates */
void hand_simple(size_t n, const double *t, const double *A, const double *B,
                 const double *C, const double *D, double *out)
{
    for (size_t i = 0; i < n; i++) {
        double s = t[i], u = 1.0 - s;
        double inv = 1.0 / ((2.0 * s - 2.0) * s + 1.0);
        double s2 = s * s, u2 = u * u;
        double wa = u2 * u * inv, wb = s2 * u * inv, wc = s * u2 * inv,
               wd = s2 * s * inv;
        double *o = out + 3 * i;
        o[0] = wa * A[0] + wb * B[0] + wc * C[0] + wd * D[0];
        o[1] = wa * A[1] + wb * B[1] + wc * C[1] + wd * D[1];
        o[2] = wa * A[2] + wb * B[2] + wc * C[2] + wd * D[2];
    }
}

/* what an engineer writes for this one curve: M_c(t) = (k3 t^3 + k2 t^2 +
 * k1 t + k0) / (2t^2 - 2t + 1) per coordinate, coefficients combined once,
 * Horner, one division per sample */
void hand_careful(size_t n, const double *restrict t, const double *A,
                  const double *B, const double *C, const double *D,
                  double *restrict out)
{
    double k[3][4];
    for (int c = 0; c < 3; c++) {
        k[c][0] = A[c];
        k[c][1] = -3.0 * A[c] + C[c];
        k[c][2] = 3.0 * A[c] + B[c] - 2.0 * C[c];
        k[c][3] = -A[c] - B[c] + C[c] + D[c];
    }
    for (size_t i = 0; i < n; i++) {
        double s = t[i];
        double inv = 1.0 / ((2.0 * s - 2.0) * s + 1.0);
        double *o = out + 3 * i;
        o[0] = (((k[0][3] * s + k[0][2]) * s + k[0][1]) * s + k[0][0]) * inv;
        o[1] = (((k[1][3] * s + k[1][2]) * s + k[1][1]) * s + k[1][0]) * inv;
        o[2] = (((k[2][3] * s + k[2][2]) * s + k[2][1]) * s + k[2][0]) * inv;
    }
}

/* the pure store floor: 3 doubles per point, nothing read */
void floor_store(size_t n, const double *t, const double *A, const double *B,
                 const double *C, const double *D, double *out)
{
    (void)t, (void)B, (void)C, (void)D;
    const double a0 = A[0], a1 = A[1], a2 = A[2];
    for (size_t i = 0; i < n; i++) {
        double *o = out + 3 * i;
        o[0] = a0;
        o[1] = a1;
        o[2] = a2;
    }
}

/* the same with non-temporal (streaming) stores, where SSE2 has them */
void floor_stream(size_t n, const double *t, const double *A, const double *B,
                  const double *C, const double *D, double *out)
{
#if defined(__SSE2__)
    (void)t, (void)B, (void)C, (void)D;
    size_t m = 3 * n, i = 0;
    /* the coordinates repeat with period 3; 6 values (two points) a step */
    const double v[9] = {A[0], A[1], A[2], A[0], A[1], A[2], A[0], A[1], A[2]};
    if (((size_t)out & 15) != 0) { /* 16-byte alignment for movntpd */
        out[0] = v[0];
        i = 1;
    }
    const double *w = v + (i % 3);
    for (; i + 6 <= m; i += 6) {
        _mm_stream_pd(out + i, _mm_set_pd(w[1], w[0]));
        _mm_stream_pd(out + i + 2, _mm_set_pd(w[3], w[2]));
        _mm_stream_pd(out + i + 4, _mm_set_pd(w[5], w[4]));
    }
    for (; i < m; i++)
        out[i] = v[i % 3];
    _mm_sfence();
#else
    floor_store(n, t, A, B, C, D, out);
#endif
}

/* reading t and storing it three times (the bench's former "floor") */
void floor_read_store(size_t n, const double *t, const double *A,
                      const double *B, const double *C, const double *D,
                      double *out)
{
    (void)A, (void)B, (void)C, (void)D;
    for (size_t i = 0; i < n; i++) {
        double *o = out + 3 * i;
        o[0] = t[i];
        o[1] = t[i];
        o[2] = t[i];
    }
}

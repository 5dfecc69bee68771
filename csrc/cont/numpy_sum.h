// numpy's sum of a contiguous float64 array, the same double: the engine's C sums what the
// Python sums with numpy (po_correct.cpp's vector norms, dense_lapack.cpp's weighted norm);
// and numpy.linalg.norm of a contiguous array through numpy's own CBLAS ddot.
#ifndef WASHER_NUMPY_SUM_H
#define WASHER_NUMPY_SUM_H

// numpy's pairwise summation (the inner loop of np.add.reduce over a contiguous axis):
// sequential below 8 terms, 8 accumulators up to 128, halves beyond.
inline double pairwise_sum(const double *a, long n) {
    if (n < 8) {
        double res = 0.;
        for (long i = 0; i < n; ++i) res += a[i];
        return res;
    }
    if (n <= 128) {
        double r[8];
        for (int j = 0; j < 8; ++j) r[j] = a[j];
        long i = 8;
        for (; i < n - (n % 8); i += 8)
            for (int j = 0; j < 8; ++j) r[j] += a[i + j];
        double res = ((r[0] + r[1]) + (r[2] + r[3])) + ((r[4] + r[5]) + (r[6] + r[7]));
        for (; i < n; ++i) res += a[i];
        return res;
    }
    long n2 = n / 2;
    n2 -= n2 % 8;
    return pairwise_sum(a, n2) + pairwise_sum(a + n2, n - n2);
}

#include <cmath>
#include <cstdint>

// numpy's bundled OpenBLAS's cblas_ddot (ILP64), as ndarray.dot of two float64 vectors calls it
typedef double (*numpy_cblas_ddot_t)(int64_t n, const double *x, int64_t incx, const double *y,
                                     int64_t incy);

// numpy.linalg.norm of a contiguous float64 array (any shape: it is ravelled): sqrt(0.0 +
// DDOT(x, x)) (ndarray.dot's sum starts at 0.0; numpy's sqrt is IEEE's)
inline double numpy_norm(numpy_cblas_ddot_t dot, int64_t n, const double *x) {
    double s = 0.0;
    s += dot(n, x, 1, x, 1);
    return std::sqrt(s);
}

#endif

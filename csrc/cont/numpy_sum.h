// numpy's sum of a contiguous float64 array, the same double: the engine's C sums what the
// Python sums with numpy (po_correct.cpp's vector norms, dense_lapack.cpp's weighted norm).
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

#endif

// numpy.linalg.svd of a small square matrix from C, the same bits: the engine's C takes
// singular vectors where the Python took them from numpy (floquet.cpp's deflation,
// fold_tests.cpp's left null vector).
#ifndef WASHER_NUMPY_SVD_H
#define WASHER_NUMPY_SVD_H
#include <cstdint>
#include <vector>

// GESDD of numpy's bundled OpenBLAS (scipy_openblas64_: 64-bit integers)
typedef void (*numpy_gesdd_t)(const char *jobz, const int64_t *m, const int64_t *n, double *a,
                              const int64_t *lda, double *s, double *u, const int64_t *ldu,
                              double *vt, const int64_t *ldvt, double *work,
                              const int64_t *lwork, int64_t *iwork, int64_t *info, size_t);

// np.linalg.svd (full_matrices) of the n x n matrix a in Fortran order (overwritten):
// GESDD with JOBZ = 'A' and the workspace GESDD asks for (numpy asks at every call, 0 read
// as 1; the answer depends on n alone, so it is asked where *lwork <= 0 and kept there).
// s (n), U and VT (n x n, Fortran order). Returns GESDD's info.
inline int64_t numpy_gesdd(void *routine, int n, double *a, double *s, double *U, double *VT,
                           int64_t *lwork) {
    numpy_gesdd_t gesdd = reinterpret_cast<numpy_gesdd_t>(routine);
    int64_t m = n, info = 0;
    std::vector<int64_t> iwork(8 * (size_t)n);
    if (*lwork <= 0) {
        double query = 0.0;
        int64_t q = -1;
        gesdd("A", &m, &m, a, &m, s, U, &m, VT, &m, &query, &q, iwork.data(), &info, 1);
        if (info != 0) return info;
        *lwork = (int64_t)query;
        if (*lwork == 0) *lwork = 1;
    }
    std::vector<double> work(*lwork);
    int64_t lw = *lwork;
    gesdd("A", &m, &m, a, &m, s, U, &m, VT, &m, work.data(), &lw, iwork.data(), &info, 1);
    return info;
}

#endif

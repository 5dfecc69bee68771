// The test functions of the fold locus of equilibria at a point in one call: see
// cont_fold_tests in cont_api.h. numpy's calls of washer.cont.systems.fold's reference
// (np.linalg.svd's GESDD for the left null vector, ndarray's dot for <w, .>, GEEV for
// the spectrum) made from C with the same routines of numpy's bundled OpenBLAS, the same
// workspaces and the same elementwise arithmetic in the same order: the same bits
// (tests/test_fold_tests.py), without the Python around about ten numpy calls a point.
#include <cmath>
#include <cstdint>
#include <vector>
#include "cont.h"
#include "numpy_cabs.h"
#include "numpy_svd.h"

namespace {
typedef int64_t int64;          // numpy's OpenBLAS (scipy_openblas64_)
typedef double (*dot_t)(int64 n, const double *x, int64 incx, const double *y, int64 incy);

// a @ b of two contiguous vectors as numpy's DOUBLE_dot sums it: 0.0 + DDOT
double dot(dot_t f, int n, const double *a, const double *b) {
    double s = 0.0;
    s += f(n, a, 1, b, 1);
    return s;
}
}  // namespace

extern "C" int cont_fold_tests(void *const *routines, int n, const double *A, int lda,
                               const double *w_ref, const double *phi, const double *F,
                               double h2, double imag_tol, double *w, double *out,
                               int64_t *lwork, int *geev_lwork) {
    if (n <= 0 || lda < n) return -1;
    dot_t ddot = reinterpret_cast<dot_t>(routines[1]);
    const size_t nn = (size_t)n * n;
    // np.linalg.svd(A.T): A.T copied to Fortran order is A's rows as they are
    std::vector<double> buf(4 * nn + n);
    double *a = buf.data(), *U = a + nn, *VT = U + nn, *s = VT + nn;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) a[(size_t)i * n + j] = A[(size_t)i * lda + j];
    if (numpy_gesdd(routines[0], n, a, s, U, VT, lwork) != 0) return 1;
    for (int i = 0; i < n; ++i)
        if (std::isnan(s[i])) return 1;
    // the last row of numpy's vt (row-major) is VT's last row in Fortran order
    for (int j = 0; j < n; ++j) w[j] = VT[n - 1 + (size_t)j * n];
    // oriented against the previous point's (a nan product turns it, as the reference)
    if (!(dot(ddot, n, w, w_ref) >= 0))
        for (int j = 0; j < n; ++j) w[j] = -w[j];
    if (phi) out[0] = dot(ddot, n, w, phi);
    if (F) {
        // <w, (F[0] - 2 F[1] + F[2]) / h^2>
        std::vector<double> d(n);
        for (int j = 0; j < n; ++j) d[j] = (F[j] - 2.0 * F[n + j] + F[2 * n + j]) / h2;
        out[1] = dot(ddot, n, w, d.data());
    }
    if (geev_lwork) {
        // the product of the real parts of the complex pairs (Im > 0), in the order of
        // the sorted spectrum; out[3] = 0 where there is none
        std::vector<double> lam(2 * (size_t)n), ework(nn + 2 * (size_t)n + 64 * (size_t)n);
        int st = cont_eigenvalues_sorted(routines[2], n, A, lda, lam.data(), ework.data(),
                                         64 * n, geev_lwork);
        if (st != 0 && st != 4) return 1 + st;          // 2, 3, 4: the eigenvalues' status
        bool any = false;
        double prod = 0.0;
        for (int i = 0; i < n; ++i) {
            double re = lam[2 * i], im = st == 4 ? 0.0 : lam[2 * i + 1];
            if (std::fabs(im) > imag_tol * (1.0 + numpy_cabs(re, im)) && im > 0) {
                prod = any ? prod * re : re;
                any = true;
            }
        }
        out[2] = prod;
        out[3] = any ? 1.0 : 0.0;
    }
    return 0;
}

// The Floquet multipliers of a periodic orbit from its pair (P0, P1), the trivial one
// deflated first (washer.cont.floquet.deflated_pencil, Fairgrieve and Jepson's circuit
// pencil as AUTO's FLOWKM deflates it), in one call: see cont_floquet_deflated in
// cont_api.h. Every step is the one the Python makes through numpy and scipy, calling
// the same routines of the same libraries with the same arguments (numpy's GESDD, DGEMM,
// DGEMV and DDOT in its bundled OpenBLAS, ILP64; scipy's DGGEV in its own, LP64) and the
// same elementwise arithmetic in the same order, so the multipliers are the Python's bit
// for bit (tests/test_floquet_pencil.py holds them so); the Python around the ~15 numpy
// calls is what is saved (about 450K instructions a point at NDIM 3).
#include <cmath>
#include <algorithm>
#include <cstdint>
#include <vector>
#include "cont.h"
#include "numpy_sum.h"
#include "numpy_cabs.h"
#include "numpy_svd.h"

namespace {
typedef int64_t int64;          // numpy's OpenBLAS (scipy_openblas64_)
typedef int int32;              // scipy's (scipy_openblas, LP64)
enum { RowMajor = 101, NoTrans = 111, Trans = 112 };   // CBLAS's enumerations

typedef void (*gemm_t)(int order, int ta, int tb, int64 m, int64 n, int64 k, double alpha,
                       const double *a, int64 lda, const double *b, int64 ldb, double beta,
                       double *c, int64 ldc);
typedef void (*gemv_t)(int order, int trans, int64 m, int64 n, double alpha, const double *a,
                       int64 lda, const double *x, int64 incx, double beta, double *y,
                       int64 incy);
typedef numpy_cblas_ddot_t dot_t;
typedef void (*ggev_t)(const char *jobvl, const char *jobvr, const int32 *n, double *a,
                       const int32 *lda, double *b, const int32 *ldb, double *alphar,
                       double *alphai, double *beta, double *vl, const int32 *ldvl, double *vr,
                       const int32 *ldvr, double *work, const int32 *lwork, int32 *info, size_t,
                       size_t);

// numpy.linalg.norm of a contiguous vector (numpy_sum.h)
double norm(dot_t dot, int64 n, const double *x) { return numpy_norm(dot, n, x); }
}  // namespace

extern "C" int cont_floquet_deflated(void *const *routines, int n, const double *P0,
                                     const double *P1, double *mu, int64_t *lwork) {
    if (n < 2) return 1;
    gemm_t gemm = reinterpret_cast<gemm_t>(routines[1]);
    gemv_t gemv = reinterpret_cast<gemv_t>(routines[2]);
    dot_t dot = reinterpret_cast<dot_t>(routines[3]);
    ggev_t ggev = reinterpret_cast<ggev_t>(routines[4]);
    const size_t nn = (size_t)n * n;
    for (size_t k = 0; k < nn; ++k)
        if (!std::isfinite(P0[k]) || !std::isfinite(P1[k])) return 1;
    std::vector<double> buf(8 * nn + 4 * n);
    double *C1 = buf.data(), *D = C1 + nn, *U = D + nn, *VT = U + nn, *A = VT + nn,
           *B = A + nn, *Af = B + nn, *Bf = Af + nn, *s = Bf + nn, *y = s + n, *v = y + n,
           *w = v + n;
    // C0 = P0, C1 = -P1; D = C0 - C1 in Fortran order (numpy's svd copies so)
    for (size_t k = 0; k < nn; ++k) C1[k] = -P1[k];
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) D[i + (size_t)j * n] = P0[(size_t)i * n + j] - C1[(size_t)i * n + j];
    // np.linalg.svd(D)
    int64 m = n;
    if (numpy_gesdd(routines[0], n, D, s, U, VT, lwork) != 0) return 2;
    // numpy's vt (row-major) is VT's Fortran array read across: vt[i][j] = VT[i + j n],
    // i.e. VT's buffer is vt^T row-major = H1 = vt.T row-major. numpy's matmul C0 @ vt.T
    // passes vt's buffer with TransB (vt.T is not C-contiguous), as here.
    std::vector<double> vt(nn);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) vt[(size_t)i * n + j] = VT[i + (size_t)j * n];
    gemm(RowMajor, NoTrans, Trans, m, m, m, 1.0, P0, m, vt.data(), m, 0.0, A, m);
    gemm(RowMajor, NoTrans, Trans, m, m, m, 1.0, C1, m, vt.data(), m, 0.0, B, m);
    // y = A[:, -1] / |A[:, -1]| + B[:, -1] / |B[:, -1]| (the columns copied contiguous,
    // as ravel does for norm)
    for (int i = 0; i < n; ++i) {
        y[i] = A[(size_t)i * n + n - 1];
        v[i] = B[(size_t)i * n + n - 1];
    }
    double na = norm(dot, m, y), nb = norm(dot, m, v);
    for (int i = 0; i < n; ++i) y[i] = y[i] / na + v[i] / nb;
    for (int i = 0; i < n; ++i) v[i] = y[i];
    v[0] += std::copysign(norm(dot, m, y), y[0] != 0 ? y[0] : 1.0);
    double vv = 0.0;
    vv += dot(m, v, 1, v, 1);
    double beta = 2.0 / vv;
    // A -= beta * outer(v, v @ A): v @ A is numpy's GEMV (row-major, transposed)
    for (double *M : {A, B}) {
        gemv(RowMajor, Trans, m, m, 1.0, M, m, v, 1, 0.0, w, 1);
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) M[(size_t)i * n + j] -= beta * (v[i] * w[j]);
    }
    double one = A[n - 1] / B[n - 1];
    if (!std::isfinite(one)) return 1;
    for (size_t k = 0; k < nn; ++k)
        if (!std::isfinite(A[k]) || !std::isfinite(B[k])) return 1;
    // scipy's ggev on A[1:, :n-1], B[1:, :n-1] (copied to Fortran order), its workspace
    // asked with both eigenvector flags set (scipy's default in the query), then used
    // without vectors
    int32 k = n - 1, one32 = 1, info32 = 0;
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
            Af[i + (size_t)j * k] = A[(size_t)(i + 1) * n + j];
            Bf[i + (size_t)j * k] = B[(size_t)(i + 1) * n + j];
        }
    std::vector<double> ar(k), ai(k), be(k);
    if (lwork[1] <= 0) {
        std::vector<double> Aq(Af, Af + (size_t)k * k), Bq(Bf, Bf + (size_t)k * k),
            vl((size_t)k * k), vr((size_t)k * k);
        double query = 0.0;
        int32 q = -1;
        ggev("V", "V", &k, Aq.data(), &k, Bq.data(), &k, ar.data(), ai.data(), be.data(),
             vl.data(), &k, vr.data(), &k, &query, &q, &info32, 1, 1);
        if (info32 != 0) return 3;
        lwork[1] = (int64)query;
    }
    int32 lw32 = (int32)lwork[1];
    std::vector<double> gwork(lw32 > 1 ? lw32 : 1);
    double dummy = 0.0;
    ggev("N", "N", &k, Af, &k, Bf, &k, ar.data(), ai.data(), be.data(), &dummy, &one32, &dummy,
         &one32, gwork.data(), &lw32, &info32, 1, 1);
    if (info32 != 0) return 3;
    mu[0] = one;
    mu[1] = 0.0;
    for (int i = 0; i < k; ++i) {
        if (be[i] == 0.0) return 3;          // infinite eigenvalues: the Python's cases
        // alpha = alphar + 1j * alphai, then alpha / beta as numpy divides complex by
        // complex (beta + 0j): Smith's quotient with the ratio 0
        double re = ar[i] + (0.0 * ai[i] - 1.0 * 0.0), im = 0.0 + (0.0 * 0.0 + 1.0 * ai[i]);
        double rat = 0.0 / be[i], scl = 1.0 / (be[i] + 0.0 * rat);
        double qr = (re + im * rat) * scl, qi = (im - re * rat) * scl;
        bool finite = std::isfinite(qr) && std::isfinite(qi);
        mu[2 * (i + 1)] = finite ? qr : INFINITY;
        mu[2 * (i + 1) + 1] = finite ? qi : 0.0;
    }
    return 0;
}

namespace {
// numpy's sort order of floats: nan after every number
bool before(double a, double b) { return a < b || (b != b && a == a); }
}  // namespace

extern "C" int cont_multipliers_sorted(int n, const double *mu, int trivial, double *out) {
    if (n <= 0) return -1;
    std::vector<int> rest;
    rest.reserve(n);
    int k = 0;
    if (trivial) {
        // np.argmin of |mu - 1| with nan as inf: the first of the smallest
        int i1 = -1;
        double best = INFINITY;
        bool all_nan = true;
        for (int i = 0; i < n; ++i) {
            double d = numpy_cabs(mu[2 * i] - 1.0, mu[2 * i + 1] - 0.0);
            if (d != d) d = INFINITY;
            else all_nan = false;
            if (i1 < 0 || d < best) {
                i1 = i;
                best = d;
            }
        }
        if (all_nan) return 1;                  // the Python raises numpy's error
        out[0] = mu[2 * i1];
        out[1] = mu[2 * i1 + 1];
        k = 1;
        for (int i = 0; i < n; ++i)
            if (i != i1) rest.push_back(i);
    } else {
        for (int i = 0; i < n; ++i) rest.push_back(i);
    }
    // the others by ||mu| - 1|, a stable sort (np.argsort's kind="stable")
    std::vector<double> key(n);
    for (int i : rest) key[i] = std::fabs(numpy_cabs(mu[2 * i], mu[2 * i + 1]) - 1.0);
    std::stable_sort(rest.begin(), rest.end(),
                     [&key](int a, int b) { return before(key[a], key[b]); });
    for (int i : rest) {
        out[2 * k] = mu[2 * i];
        out[2 * k + 1] = mu[2 * i + 1];
        ++k;
    }
    return 0;
}

extern "C" int cont_floquet_multipliers(void *const *routines, int n, const double *P0,
                                        const double *P1, double *mu, int64_t *lwork) {
    std::vector<double> raw(2 * (size_t)std::max(n, 1));
    const int rc = cont_floquet_deflated(routines, n, P0, P1, raw.data(), lwork);
    if (rc != 0) return rc;
    if (cont_multipliers_sorted(n, raw.data(), 1, mu) != 0) {
        std::copy(raw.begin(), raw.end(), mu);
        return 5;
    }
    return 0;
}

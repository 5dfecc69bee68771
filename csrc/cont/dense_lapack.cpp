// LAPACK's LU and eigenvalues of a small dense matrix in numpy's way, through function
// pointers to numpy's own LAPACK: see cont_dense_lu, cont_dense_lu_solve and
// cont_eigenvalues_sorted in cont_api.h. numpy.linalg's gufuncs (umath_linalg) copy the
// row-major matrix into Fortran order, call the same routines and read the results the
// same way; done here in one call, the Python around numpy's calls is saved and the
// values are theirs bit for bit (tests/test_dense_lapack.py holds them so).
#include <cmath>
#include <cstdint>
#include <limits>
#include "cont.h"
#include "numpy_sum.h"

namespace {
typedef int64_t lapack_int;     // numpy's bundled OpenBLAS is ILP64 (scipy_openblas64_)
typedef void (*getrf_t)(const lapack_int *m, const lapack_int *n, double *a,
                        const lapack_int *lda, lapack_int *ipiv, lapack_int *info);
typedef void (*getrs_t)(const char *trans, const lapack_int *n, const lapack_int *nrhs,
                        const double *a, const lapack_int *lda, const lapack_int *ipiv,
                        double *b, const lapack_int *ldb, lapack_int *info, size_t);
typedef void (*geev_t)(const char *jobvl, const char *jobvr, const lapack_int *n, double *a,
                       const lapack_int *lda, double *wr, double *wi, double *vl,
                       const lapack_int *ldvl, double *vr, const lapack_int *ldvr,
                       double *work, const lapack_int *lwork, lapack_int *info, size_t, size_t);
}  // namespace

extern "C" int cont_dense_lu(void *getrf, int n, const double *M, int ldm,
                             const double *last, double *lu, int64_t *ipiv,
                             double *sign_logdet) {
    if (n <= 0 || ldm < n) return -1;
    int rows = last ? n - 1 : n;
    for (int i = 0; i < rows; ++i)          // Fortran order: lu[i + j n] = M[i][j]
        for (int j = 0; j < n; ++j) lu[i + (size_t)j * n] = M[(size_t)i * ldm + j];
    if (last)
        for (int j = 0; j < n; ++j) lu[n - 1 + (size_t)j * n] = last[j];
    lapack_int nn = n, info = 0;
    reinterpret_cast<getrf_t>(getrf)(&nn, &nn, lu, &nn, ipiv, &info);
    if (info != 0) {                        // numpy's slogdet of a singular matrix
        sign_logdet[0] = 0.0;
        sign_logdet[1] = -std::numeric_limits<double>::infinity();
        return (int)info;
    }
    // numpy's slogdet_from_factored_diagonal: the pivots' parity, then the diagonal's
    // signs and the logarithms of its magnitudes summed in order from 0.0
    bool odd = false;
    for (int i = 0; i < n; ++i) odd ^= (ipiv[i] != i + 1);
    double sign = odd ? -1.0 : 1.0, logdet = 0.0;
    for (int i = 0; i < n; ++i) {
        double d = lu[i + (size_t)i * n];
        if (d < 0) {
            sign = -sign;
            d = -d;
        }
        logdet += std::log(d);
    }
    sign_logdet[0] = sign;
    sign_logdet[1] = logdet;
    return 0;
}

extern "C" int cont_scaled_slogdet(void *getrf, void *ddot, int n, const double *S,
                                   double *work, int64_t *ipiv, double *out) {
    if (n <= 0) return -1;
    const size_t nn = (size_t)n * n;
    const double scale = numpy_norm(reinterpret_cast<numpy_cblas_ddot_t>(ddot), (int64_t)nn, S);
    out[0] = scale;
    if (!std::isfinite(scale) || scale == 0) return 1;
    double *scaled = work, *lu = work + nn;
    for (size_t i = 0; i < nn; ++i) scaled[i] = S[i] / scale;
    return cont_dense_lu(getrf, n, scaled, n, nullptr, lu, ipiv, out + 1) == 0 ? 0 : 2;
}

extern "C" int cont_dense_lu_solve(void *getrs, int n, const double *lu, const int64_t *ipiv,
                                   const double *b, double *x) {
    if (n <= 0) return -1;
    for (int i = 0; i < n; ++i) x[i] = b[i];
    lapack_int nn = n, one = 1, info = 0;
    reinterpret_cast<getrs_t>(getrs)("N", &nn, &one, lu, &nn, ipiv, x, &nn, &info, 1);
    if (info != 0) return (int)info;
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(x[i])) return 1;
    return 0;
}

extern "C" int cont_eigenvalues_sorted(void *geev, int n, const double *A, int lda,
                                       double *w, double *work, int lwork_max, int *lwork) {
    if (n <= 0 || lda < n) return -1;
    double *a = work, *wr = a + (size_t)n * n, *wi = wr + n, *rest = wi + n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            double v = A[(size_t)i * lda + j];
            if (!std::isfinite(v)) return 1;        // numpy.linalg's "infs or NaNs"
            a[i + (size_t)j * n] = v;
        }
    lapack_int nn = n, one = 1, info = 0, lw = -1;
    double dummy = 0.0;
    geev_t f = reinterpret_cast<geev_t>(geev);
    if (*lwork <= 0) {
        // numpy's init_geev asks GEEV for its workspace first (its blocked steps depend on
        // it) and gives that much; the answer depends on n alone, so it is asked once
        double query = 0.0;
        f("N", "N", &nn, a, &nn, wr, wi, &dummy, &one, &dummy, &one, &query, &lw, &info, 1, 1);
        if (info != 0) return 2;
        *lwork = (int)(lapack_int)query;
    }
    lw = *lwork;
    if (lw > lwork_max) return 3;
    f("N", "N", &nn, a, &nn, wr, wi, &dummy, &one, &dummy, &one, rest, &lw, &info, 1, 1);
    if (info != 0) return 2;
    int real = 1;
    for (int i = 0; i < n; ++i) {
        if (!std::isfinite(wr[i]) || !std::isfinite(wi[i])) return 2;
        if (wi[i] != 0.0) real = 0;
    }
    // by decreasing real part, equal ones in LAPACK's order (a stable insertion sort)
    for (int i = 0; i < n; ++i) {
        double re = wr[i], im = wi[i];
        int k = i;
        while (k > 0 && w[2 * (k - 1)] < re) {
            w[2 * k] = w[2 * (k - 1)];
            w[2 * k + 1] = w[2 * (k - 1) + 1];
            --k;
        }
        w[2 * k] = re;
        w[2 * k + 1] = im;
    }
    return real ? 4 : 0;
}

extern "C" int cont_ae_tangent(void *getrf, void *getrs, int n, const double *J, int ldj,
                               const double *ref, const double *theta, double big,
                               double *border, double *lu, int64_t *ipiv, double *sign_logdet,
                               int *info, double *t) {
    if (n <= 0 || ldj < n) return -1;
    for (int j = 0; j < n; ++j) border[j] = theta[j] * ref[j];
    *info = cont_dense_lu(getrf, n, J, ldj, border, lu, ipiv, sign_logdet);
    if (*info != 0) return 1;
    // the solve of M z = e_n (GESV's values), then |z| in the weighted inner product
    double *z = t;
    for (int i = 0; i < n; ++i) z[i] = 0.0;
    z[n - 1] = 1.0;
    if (cont_dense_lu_solve(getrs, n, lu, ipiv, z, z) != 0) return 2;
    double *terms = lu + (size_t)n * n;         // the caller's room after the factors
    for (int i = 0; i < n; ++i) terms[i] = theta[i] * z[i] * z[i];
    double nz = std::sqrt(std::fabs(pairwise_sum(terms, n)));
    if (!std::isfinite(nz) || nz == 0.0 || nz > big) return 2;
    for (int i = 0; i < n; ++i) t[i] = z[i] / nz;
    return 0;
}

extern "C" int cont_ae_equilibrium_point(void *const *routines, int ndim, const double *J,
                                         const double *ref, const double *theta, double big,
                                         double imag_tol, double trace_tol,
                                         double conservative_tol, double *border, double *lu,
                                         int64_t *ipiv, double *sign_logdet, int *info,
                                         double *t, double *w, double *ework, int lwork_max,
                                         int *lwork, double *out) {
    if (ndim <= 0 || ndim > 8) return -1;
    const int n = ndim + 1;
    int st = cont_ae_tangent(routines[0], routines[1], n, J, n, ref, theta, big, border, lu,
                             ipiv, sign_logdet, info, t);
    if (st != 0) return st;
    // the eigenvalues of f_u, the leading NDIM columns of J's rows
    st = cont_eigenvalues_sorted(routines[2], ndim, J, n, w, ework, lwork_max, lwork);
    if (st != 0 && st != 4) return 10 + st;
    const bool real = st == 4;
    // equilibrium.neutral_tolerance: the trace summed in order from 0.0, the largest
    // magnitude of f_u's entries (all finite here: GEEV took them)
    double neutral = 0.0;
    if (ndim % 2 == 0) {
        double trace = 0.0, largest = 0.0;
        for (int i = 0; i < ndim; ++i) trace += J[(size_t)i * n + i];
        for (int i = 0; i < ndim; ++i)
            for (int j = 0; j < ndim; ++j) {
                double a = std::fabs(J[(size_t)i * n + j]);
                if (a > largest) largest = a;
            }
        if (std::fabs(trace) < trace_tol * largest) neutral = conservative_tol;
    }
    // equilibrium.stable_count and hopf_pair (Python's complex abs is libm's hypot)
    int stable = 0, pair = -1;
    for (int i = 0; i < ndim; ++i) {
        double re = w[2 * i], im = w[2 * i + 1];
        if (re <= neutral) ++stable;
        if (!real && std::fabs(im) > imag_tol * (1.0 + std::hypot(re, im))
            && (pair < 0 || std::fabs(re) < std::fabs(w[2 * pair])))
            pair = i;
    }
    out[0] = neutral;
    out[1] = stable;
    out[2] = pair;
    out[3] = real ? 1.0 : 0.0;
    return 0;
}

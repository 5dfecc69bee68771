/* The corrector of algebraic continuation (washer.cont.compiled_newton), included by the
 * two C files that call it: the bridge of compiled user files (compiled_shim.c: FUNC
 * called directly) and ae_callback.c (the user's Python func called back). The includer
 * defines, before including this file,
 *
 *   static int ae_eval(void *ctx, int ndim, int npar, const int *icp, int rows, int first,
 *                      const double *us, const double *ps, double *fs, double *scratch);
 *
 * f at the rows first..rows-1 of us (rows, ndim) with PAR the rows of ps (rows, npar),
 * into fs (rows, ndim), in the order of the rows; nonzero: the evaluation failed.
 * An includer whose equations come with their exact Jacobians (the generated C of
 * sympy problems: ae_generated.c) also defines AE_EXACT_JACOBIAN and
 *
 *   static int ae_exact(void *ctx, int ndim, int npar, int ip, const double *u,
 *                       const double *par, double *J, int stride);
 *
 * [f_u, f_PAR(ip + 1)] at (u, par) into J (ndim rows of stride `stride`): -1 where this
 * run's Jacobians are differences (JAC = 0), 0 evaluated, else the evaluation failed.
 *
 * This is a second copy of one meaning, the package's one Newton loop
 * (washer/cont/newton.py's newton as washer.cont.iterator.Continuation.correct runs it,
 * with washer.cont.problem.Problem.jacobian's difference stencil): a change to either
 * must be made in both (tests/test_compiled_newton.py holds them to the same iterates).
 * The layout of `work` (us, ps, fs at its start) is read by compiled_newton.py's
 * PythonEquations too, which checks the pointers it is passed against it.
 */
#ifndef WASHER_AE_CORRECT_H
#define WASHER_AE_CORRECT_H
#include <math.h>
#include <string.h>
#include <stddef.h>

/* The points of Problem.jacobian's central differences at x = (u, PAR(ip + 1)) after the
   point (u, PAR) itself: row 0 (u, PAR), rows 1..k u_j + h_j then PAR(ip + 1) + h, rows
   k + 1..2k the minus side (k = NDIM + 1; us (2k + 1, NDIM), ps (2k + 1, npar)), f at
   rows first..2k into fs (ae_eval, the includer's); h_j = hmach (1 + |x_j|). Returns
   ae_eval's status (0: evaluated). */
static int ae_points(void *ctx, int n, int npar, int ip, const int *icp, const double *par,
                     const double *x, double hmach, int first, double *us, double *ps,
                     double *fs, double *h, double *scratch)
{
    const int k = n + 1, rows = 2 * k + 1;
    for (int j = 0; j <= n; j++) h[j] = hmach * (1 + fabs(x[j]));
    for (int r = 0; r < rows; r++) {
        memcpy(us + (size_t)r * n, x, sizeof(double) * n);
        memcpy(ps + (size_t)r * npar, par, sizeof(double) * npar);
        ps[(size_t)r * npar + ip] = x[n];
    }
    for (int j = 0; j < n; j++) {
        us[(size_t)(1 + j) * n + j] = x[j] + h[j];
        us[(size_t)(1 + k + j) * n + j] = x[j] - h[j];
    }
    ps[(size_t)(1 + n) * npar + ip] = x[n] + h[n];
    ps[(size_t)(1 + k + n) * npar + ip] = x[n] - h[n];
    return ae_eval(ctx, n, npar, icp, rows, first, us, ps, fs, scratch);
}

/* [f_u, f_PAR(ip + 1)] (n, n + 1) row-major, with row stride `stride`, from ae_points'
   values: (f(z + h_j e_j) - f(z - h_j e_j)) / (2 h_j). Returns 0, or 3 if not finite. */
static int ae_jacobian(int n, const double *fs, const double *h, double *J, int stride)
{
    const int k = n + 1;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < k; j++) {
            double v = (fs[(size_t)(1 + j) * n + i] - fs[(size_t)(1 + k + j) * n + i])
                       / (2 * h[j]);
            if (!isfinite(v)) return 3;
            J[(size_t)i * stride + j] = v;
        }
    return 0;
}

/* f at x into fs's row 0 (not if first = 1: already there) and [f_u, f_PAR(ip + 1)] at x
   into J (n rows of stride `stride`): the includer's exact Jacobian (ae_exact) where it
   gives one, else ae_points' central differences (ae_jacobian). Returns 0, nonzero if
   f failed or the Jacobian is not finite. */
static int ae_f_jacobian(void *ctx, int n, int npar, int ip, const int *icp, const double *par,
                         const double *x, double hmach, int first, double *us, double *ps,
                         double *fs, double *h, double *scratch, double *J, int stride)
{
#ifdef AE_EXACT_JACOBIAN
    memcpy(us, x, sizeof(double) * n);
    memcpy(ps, par, sizeof(double) * npar);
    ps[ip] = x[n];
    int e = ae_exact(ctx, n, npar, ip, us, ps, J, stride);
    if (e > 0) return 1;
    if (e == 0) {
        if (!first && ae_eval(ctx, n, npar, icp, 1, 0, us, ps, fs, scratch)) return 1;
        for (int i = 0; i < n; i++)
            for (int j = 0; j <= n; j++)
                if (!isfinite(J[(size_t)i * stride + j])) return 3;
        return 0;
    }
#endif
    if (ae_points(ctx, n, npar, ip, icp, par, x, hmach, first, us, ps, fs, h, scratch))
        return 1;
    return ae_jacobian(n, fs, h, J, stride);
}

/* Gaussian elimination with partial pivoting (LAPACK's GETRF order: the largest |entry|
   of the column, the first one of equal size) of M (m, m) row-major, applied to b (m,);
   the determinant as sign and log|det| into det (if not NULL). Returns 0, or 3 for a
   zero or non-finite pivot. */
static int ae_eliminate(int m, double *M, double *b, double *det)
{
    double sign = 1.0, logdet = 0.0;
    for (int col = 0; col < m; col++) {
        int p = col;
        double best = fabs(M[(size_t)col * m + col]);
        for (int r = col + 1; r < m; r++) {
            double v = fabs(M[(size_t)r * m + col]);
            if (v > best) { best = v; p = r; }
        }
        if (best == 0.0 || !isfinite(best)) return 3;
        if (p != col) {
            for (int j = 0; j < m; j++) {
                double t = M[(size_t)col * m + j];
                M[(size_t)col * m + j] = M[(size_t)p * m + j];
                M[(size_t)p * m + j] = t;
            }
            double t = b[col]; b[col] = b[p]; b[p] = t;
            sign = -sign;
        }
        double piv = M[(size_t)col * m + col];
        if (det) {
            if (piv < 0) sign = -sign;
            logdet += log(fabs(piv));
        }
        for (int r = col + 1; r < m; r++) {
            double f = M[(size_t)r * m + col] / piv;
            if (f == 0.0) continue;
            for (int j = col + 1; j < m; j++)
                M[(size_t)r * m + j] -= f * M[(size_t)col * m + j];
            b[r] -= f * b[col];
        }
    }
    if (det) { det[0] = sign; det[1] = logdet; }
    return 0;
}

/* Back substitution of ae_eliminate's upper triangle: y (m,) from b. 0, or 3 if not finite. */
static int ae_back(int m, const double *M, const double *b, double *y)
{
    for (int i = m - 1; i >= 0; i--) {
        double s = b[i];
        for (int j = i + 1; j < m; j++) s -= M[(size_t)i * m + j] * y[j];
        y[i] = s / M[(size_t)i * m + i];
        if (!isfinite(y[i])) return 3;
    }
    return 0;
}

/* The corrector of algebraic continuation in one foreign call: the compiled form of the
   package's one Newton loop (washer.cont.newton.newton) as iterator.Continuation.correct
   runs it on equilibria with the sphere arclength (AUTO's SOLVAE/STEPAE), for FUNC with
   JAC = 0, or generated equations with their exact Jacobians (AE_EXACT_JACOBIAN)
   (washer.cont.compiled_newton chooses it; every other case is the Python loop):

     unknowns x = (U(1..NDIM), PAR(ip + 1)), PAR the other parameters (npar), ICP icp;
     per iteration: F = f(u, PAR), the central differences [f_u, f_PAR(ip + 1)] with
     h_j = hmach (1 + |z_j|) (Problem.jacobian's stencil: the same points and quotients)
     or the exact ones (ae_exact: Problem.jacobian's dfdu and dfdp with JAC = 1),
     the arclength row r = 2 theta (x - x_ref) / |ds| and c = <r, x - x_ref> / 2 - |ds|,
     the correction dx of [J; r] dx = -[F; c] (LU with partial pivoting), x += dx;
     stop when |dx_lambda| / (1 + |x_lambda|) <= epsl and max|dx_u| / (1 + max|x_u|) <=
     epsu; diverging when max of the two grows beyond `divergence` times its first value.
   jac: NULL, or (NDIM, NDIM + 1) row-major: [f_u, f_PAR(ip + 1)] at the converged x (the
   Jacobian the continuation evaluates there next, the same values). tangent: NULL, or
   3 (NDIM + 1) + 3 doubles (with jac): z of [J; theta ref] z = e_last, the secant ref =
   (x - x_ref) / ds, the determinant of [J; theta ref] as sign and log|det|, and 1 when
   they were computed (0: a zero pivot; the caller computes them).

   work: at least (2 NDIM + 3) (2 NDIM + npar) + (NDIM + 1) (NDIM + 4) doubles; scratch:
   NDIM (NDIM + npar) for FUNC's DFDU/DFDP. Returns 0 converged (x, *iterations set),
   1 diverging, 2 no convergence in itnw iterations (*iterations = itnw), 3 a non-finite
   residual, Jacobian or correction, or a zero pivot: the caller runs the Python loop;
   4 converged (x, *iterations set) but f failed, or gave a non-finite Jacobian, at the
   converged point: jac and tangent not set (the caller evaluates the Jacobian there). */
static int ae_correct(void *ctx, int ndim, int npar, int ip, const int *icp, const double *par,
                      const double *x_pred, const double *x_ref, const double *theta,
                      double ds, double epsl, double epsu, int itnw, double divergence,
                      double hmach, double *x, int *iterations, double *jac,
                      double *tangent, double *work, double *scratch)
{
    const int n = ndim, k = ndim + 1, np1 = ndim + 1, rows = 2 * k + 1;
    double *us = work;                              /* (rows, n) */
    double *ps = us + (size_t)rows * n;             /* (rows, npar) */
    double *fs = ps + (size_t)rows * npar;          /* (rows, n) */
    double *M = fs + (size_t)rows * n;              /* (np1, np1) row-major */
    double *b = M + (size_t)np1 * np1;              /* (np1,) */
    double *h = b + np1;                            /* (k,) */
    double *d = h + k;                              /* (np1,) */
    const double ads = fabs(ds);
    double delref = -1.0;
    for (int i = 0; i < np1; i++) x[i] = x_pred[i];
    *iterations = 0;
    for (int it = 1; it <= itnw; it++) {
        if (ae_f_jacobian(ctx, n, npar, ip, icp, par, x, hmach, 0, us, ps, fs, h, scratch,
                          M, np1))
            return 3;
        for (int i = 0; i < n; i++) {
            if (!isfinite(fs[i])) return 3;
            b[i] = -fs[i];
        }
        double c = 0.0;
        for (int j = 0; j < np1; j++) {
            d[j] = x[j] - x_ref[j];
            M[(size_t)n * np1 + j] = 2 * (theta[j] * d[j]) / ads;
        }
        for (int j = 0; j < np1; j++) c += M[(size_t)n * np1 + j] * d[j];
        b[n] = -(c / 2 - ads);
        if (ae_eliminate(np1, M, b, NULL)) return 3;
        if (ae_back(np1, M, b, d)) return 3;          /* d becomes the correction dx */
        for (int j = 0; j < np1; j++) x[j] += d[j];
        double mdx = 0.0, mx = 0.0;
        for (int j = 0; j < n; j++) {
            if (fabs(d[j]) > mdx) mdx = fabs(d[j]);
            if (fabs(x[j]) > mx) mx = fabs(x[j]);
        }
        double du = mdx / (1 + mx), dl = fabs(d[n]) / (1 + fabs(x[n]));
        *iterations = it;
        if (dl <= epsl && du <= epsu) {
            if (jac) {
                if (ae_f_jacobian(ctx, n, npar, ip, icp, par, x, hmach, 1, us, ps, fs, h,
                                  scratch, jac, np1))
                    return 4;
                if (tangent) {
                    /* the secant ref = (x - x_ref) / ds, z of [J; theta ref] z = e_last
                       and the determinant of that matrix (Continuation.tangent) */
                    tangent[2 * np1 + 2] = 0.0;
                    for (int j = 0; j < np1; j++) tangent[np1 + j] = (x[j] - x_ref[j]) / ds;
                    memcpy(M, jac, sizeof(double) * (size_t)n * np1);
                    for (int j = 0; j < np1; j++) {
                        M[(size_t)n * np1 + j] = theta[j] * tangent[np1 + j];
                        b[j] = j == n ? 1.0 : 0.0;
                    }
                    if (ae_eliminate(np1, M, b, tangent + 2 * np1) == 0
                            && ae_back(np1, M, b, tangent) == 0)
                        tangent[2 * np1 + 2] = 1.0;
                }
            }
            return 0;
        }
        double size = du > dl ? du : dl;
        if (delref < 0) delref = divergence * (size > 1e-300 ? size : 1e-300);
        else if (size > delref) return 1;
    }
    return 2;
}

#endif

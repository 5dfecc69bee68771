/* The first Lyapunov coefficient at a Hopf point in C: the compiled form of
 * washer.cont.normal_form.first_lyapunov (Kuznetsov, 3rd ed., eq 3.20; AUTO's FNGHEQ),
 * for the test GH of the Hopf locus (systems/hopf.py) where the compiled corrector runs
 * it (washer.cont.corrector_algebraic). Included after ae_correct.h (ae_eval: f at a batch of
 * points, stage 2, as Problem.func_many evaluates normal_form._directional's stencil).
 *
 * This is a second copy of one meaning, first_lyapunov: a change to either must be made
 * in both (tests/test_compiled_newton.py holds them to the same values). The same
 * stencils, quotients, Richardson extrapolation and polarisation; the eigenvectors are
 * those of the eigenvalues nearest i omega (A q = lambda q) and -i omega (A^T p = mu p),
 * here by inverse iteration from the shifts (LAPACK's QR iteration in Python), q of unit
 * norm with its largest component real and positive (LAPACK leaves its sign free), and
 * the linear solves Gaussian elimination with partial pivoting: l1 agrees with
 * first_lyapunov's to rounding (its own difference noise, ~1e-9 of its terms, is larger).
 */
#ifndef WASHER_AE_LYAPUNOV_H
#define WASHER_AE_LYAPUNOV_H
#include <complex.h>
#include <math.h>
#include <string.h>

/* normal_form.FD2_STEP, FD3_STEP */
#define AE_FD2 1e-3
#define AE_FD3 4e-3
/* The rows of the larger of the two batches (1 + 12 directions x 4 offsets). */
#define AE_L1_ROWS 49

/* Doubles of ae_first_lyapunov's work (corrector_algebraic.l1_work_size the same). */
static size_t ae_l1_work_size(int n, int npar)
{
    return (size_t)AE_L1_ROWS * (2 * (size_t)n + npar) + 2 * ((size_t)n * n + 6 * (size_t)n)
           + (size_t)n * n + 40 * (size_t)n;
}

/* Complex Gaussian elimination with partial pivoting (zgetrf's pivot: the largest
   |re| + |im|) of M (n, n) row-major, solving M y = b in place of b. 0, or 3 singular
   or not finite. */
static int ae_csolve(int n, double complex *M, double complex *b)
{
    for (int c = 0; c < n; c++) {
        int p = c;
        double best = fabs(creal(M[c * n + c])) + fabs(cimag(M[c * n + c]));
        for (int r = c + 1; r < n; r++) {
            double v = fabs(creal(M[r * n + c])) + fabs(cimag(M[r * n + c]));
            if (v > best) { best = v; p = r; }
        }
        if (best == 0.0 || !isfinite(best)) return 3;
        if (p != c) {
            for (int j = 0; j < n; j++) {
                double complex t = M[c * n + j]; M[c * n + j] = M[p * n + j]; M[p * n + j] = t;
            }
            double complex t = b[c]; b[c] = b[p]; b[p] = t;
        }
        for (int r = c + 1; r < n; r++) {
            double complex f = M[r * n + c] / M[c * n + c];
            if (f == 0.0) continue;
            for (int j = c + 1; j < n; j++) M[r * n + j] -= f * M[c * n + j];
            b[r] -= f * b[c];
        }
    }
    for (int i = n - 1; i >= 0; i--) {
        double complex s = b[i];
        for (int j = i + 1; j < n; j++) s -= M[i * n + j] * b[j];
        b[i] = s / M[i * n + i];
        if (!isfinite(creal(b[i])) || !isfinite(cimag(b[i]))) return 3;
    }
    return 0;
}

/* The eigenvector of (T ? A^T : A) (n, n) for its eigenvalue nearest `shift`: inverse
   iteration from (1, ..., 1), three solves, into v (unit norm, largest |v_k| real and
   positive). M: n n complex scratch. 0, or 3. */
static int ae_eigvec(int n, const double *A, int T, double complex shift, double complex *M,
                     double complex *v)
{
    for (int i = 0; i < n; i++) v[i] = 1.0;
    for (int it = 0; it < 3; it++) {
        for (int i = 0; i < n; i++)
            for (int j = 0; j < n; j++)
                M[i * n + j] = (T ? A[j * n + i] : A[i * n + j]) - (i == j ? shift : 0.0);
        if (ae_csolve(n, M, v)) return 3;
        double s = 0.0;
        for (int i = 0; i < n; i++) s += creal(v[i]) * creal(v[i]) + cimag(v[i]) * cimag(v[i]);
        s = sqrt(s);
        for (int i = 0; i < n; i++) v[i] /= s;
    }
    int k = 0;
    for (int i = 1; i < n; i++) if (cabs(v[i]) > cabs(v[k])) k = i;
    double complex ph = conj(v[k]) / cabs(v[k]);
    for (int i = 0; i < n; i++) v[i] *= ph;
    v[k] = creal(v[k]);
    return 0;
}

/* normal_form._directional: D2 (k2, n) along the rows of W2 and, if k3, D3 (k3, n) along
   those of W3, f at x and at x + c w (c = +-h, +-2h; +-h, +-2h, +-4h for the third) in one
   batch (rows 1 + 4 k2 + 6 k3 <= AE_L1_ROWS), Richardson-extrapolated from h and 2h. */
static int ae_directional(void *ctx, int n, int npar, const int *icp, const double *x,
                          const double *par, int k2, const double *W2, int k3,
                          const double *W3, double *D2, double *D3, double *us, double *ps,
                          double *fs, double *scratch)
{
    const double h2 = AE_FD2, h3 = AE_FD3;
    const double c2[4] = {h2, -h2, 2 * h2, -2 * h2};
    const double c3[6] = {h3, -h3, 2 * h3, -2 * h3, 4 * h3, -4 * h3};
    const int rows = 1 + 4 * k2 + 6 * k3;
    for (int r = 0; r < rows; r++) memcpy(ps + (size_t)r * npar, par, sizeof(double) * npar);
    memcpy(us, x, sizeof(double) * n);
    int r = 1;
    for (int k = 0; k < k2; k++)
        for (int c = 0; c < 4; c++, r++)
            for (int i = 0; i < n; i++) us[(size_t)r * n + i] = x[i] + c2[c] * W2[k * n + i];
    for (int k = 0; k < k3; k++)
        for (int c = 0; c < 6; c++, r++)
            for (int i = 0; i < n; i++) us[(size_t)r * n + i] = x[i] + c3[c] * W3[k * n + i];
    if (ae_eval(ctx, 2, n, npar, icp, rows, 0, us, ps, fs, scratch)) return 1;
    const double *f0 = fs;
    for (int k = 0; k < k2; k++) {
        const double *F = fs + (size_t)(1 + 4 * k) * n;
        for (int i = 0; i < n; i++) {
            double dh = (F[i] - 2 * f0[i] + F[n + i]) / pow(h2, 2);
            double d2h = (F[2 * n + i] - 2 * f0[i] + F[3 * n + i]) / pow(2 * h2, 2);
            D2[k * n + i] = (4 * dh - d2h) / 3;
        }
    }
    for (int k = 0; k < k3; k++) {
        const double *F = fs + (size_t)(1 + 4 * k2 + 6 * k) * n;
        for (int i = 0; i < n; i++) {
            double dh = (F[2 * n + i] - 2 * F[i] + 2 * F[n + i] - F[3 * n + i])
                        / (2 * pow(h3, 3));
            double d2h = (F[4 * n + i] - 2 * F[2 * n + i] + 2 * F[3 * n + i] - F[5 * n + i])
                         / (2 * pow(2 * h3, 3));
            D3[k * n + i] = (4 * dh - d2h) / 3;
        }
    }
    return 0;
}

/* l1 at the Hopf point x (n,), PAR par (npar,), frequency omega, A = f_u(x, PAR) (n, n)
   row-major, into *l1 (normal_form.first_lyapunov). work: ae_l1_work_size(n, npar)
   doubles, its start the batch's us, ps, fs (AE_L1_ROWS rows each). Returns 0, 1 if f
   failed, 3 for a singular or non-finite step (the caller computes it in Python). */
static int ae_first_lyapunov(void *ctx, int n, int npar, const int *icp, const double *x,
                             const double *par, double omega, const double *A, double *l1,
                             double *work, double *scratch)
{
    double *us = work, *ps = us + (size_t)AE_L1_ROWS * n, *fs = ps + (size_t)AE_L1_ROWS * npar;
    double complex *M = (double complex *)(fs + (size_t)AE_L1_ROWS * n);
    double complex *q = M + (size_t)n * n, *p = q + n, *Bqq = p + n, *h20 = Bqq + n,
                   *Cq = h20 + n, *tmp = Cq + n;
    double *R = (double *)(tmp + n), *h11 = R + (size_t)n * n, *dirs = h11 + n,
           *D2 = dirs + 12 * (size_t)n, *D3 = D2 + 12 * (size_t)n, *a = D3 + 4 * (size_t)n,
           *b = a + n, *Bqqb = b + n;
    if (ae_eigvec(n, A, 0, I * omega, M, q)) return 3;
    if (ae_eigvec(n, A, 1, -I * omega, M, p)) return 3;
    /* p / conj(<p, q>), <p, q> = conj(p) . q */
    double complex pq = 0.0;
    for (int i = 0; i < n; i++) pq += conj(p[i]) * q[i];
    for (int i = 0; i < n; i++) p[i] /= conj(pq);
    for (int i = 0; i < n; i++) { a[i] = creal(q[i]); b[i] = cimag(q[i]); }
    for (int i = 0; i < n; i++) {
        dirs[i] = a[i]; dirs[n + i] = b[i];
        dirs[2 * n + i] = a[i] + b[i]; dirs[3 * n + i] = a[i] - b[i];
    }
    int st = ae_directional(ctx, n, npar, icp, x, par, 4, dirs, 4, dirs, D2, D3, us, ps, fs,
                            scratch);
    if (st) return st;
    const double *D2a = D2, *D2b = D2 + n, *D2s = D2 + 2 * n, *D2d = D2 + 3 * n;
    const double *D3a = D3, *D3b = D3 + n, *D3s = D3 + 2 * n, *D3d = D3 + 3 * n;
    for (int i = 0; i < n; i++) {
        double Bab = (D2s[i] - D2d[i]) / 4;
        Bqqb[i] = D2a[i] + D2b[i];
        Bqq[i] = (D2a[i] - D2b[i]) + I * (2 * Bab);
        double reC = (2.0 / 3) * D3a[i] + (D3s[i] + D3d[i]) / 6;
        double imC = (2.0 / 3) * D3b[i] + (D3s[i] - D3d[i]) / 6;
        Cq[i] = reC + I * imC;
    }
    /* h11 = A^-1 B(q, conj q) (real), h20 = (2 i omega - A)^-1 B(q, q) */
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) M[i * n + j] = A[i * n + j];
        tmp[i] = Bqqb[i];
    }
    if (ae_csolve(n, M, tmp)) return 3;
    for (int i = 0; i < n; i++) h11[i] = creal(tmp[i]);
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) M[i * n + j] = (i == j ? 2 * I * omega : 0.0) - A[i * n + j];
        h20[i] = Bqq[i];
    }
    if (ae_csolve(n, M, h20)) return 3;
    /* B(u, w) of (a, h11), (b, h11), (a, c), (b, d), (a, d), (b, c): directions u + w
       (rows 0..5) then u - w (rows 6..11) */
    for (int i = 0; i < n; i++) {
        double c = creal(h20[i]), d = cimag(h20[i]);
        const double U[6] = {a[i], b[i], a[i], b[i], a[i], b[i]};
        const double Wp[6] = {h11[i], h11[i], c, d, d, c};
        for (int k = 0; k < 6; k++) {
            dirs[k * n + i] = U[k] + Wp[k];
            dirs[(6 + k) * n + i] = U[k] - Wp[k];
        }
    }
    st = ae_directional(ctx, n, npar, icp, x, par, 12, dirs, 0, NULL, D2, NULL, us, ps, fs,
                        scratch);
    if (st) return st;
    double complex val = 0.0;
    for (int i = 0; i < n; i++) {
        double B[6];
        for (int k = 0; k < 6; k++) B[k] = (D2[k * n + i] - D2[(6 + k) * n + i]) / 4;
        double complex Bqh11 = B[0] + I * B[1];
        double complex Bqbh20 = (B[2] + B[3]) + I * (B[4] - B[5]);
        val += conj(p[i]) * (Cq[i] - 2 * Bqh11 + Bqbh20);
    }
    *l1 = creal(val) / (2 * omega);
    return isfinite(*l1) ? 0 : 3;
}

#endif

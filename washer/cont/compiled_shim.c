/* The bridge between washer and an AUTO-07p user file (Fortran or C), compiled with it.
 *
 * One entry per user routine with a single C signature whatever the user's language,
 * and batched entries that loop over many points in one foreign call (stencils of
 * finite differences, collocation points), so the FFI cost is paid once per batch.
 * Arrays from Python are C-ordered: points are rows (k, ndim); Jacobians come back
 * row-major (k, ndim, ndim), transposed here from AUTO's column-major DFDU(NDIM,NDIM).
 *
 * WASHER_FORTRAN = 1: the user routines are gfortran's func_, stpnt_, ... (all
 * arguments by reference; argument orders of AUTO's Fortran interface). Routines the
 * file does not define are weak symbols (NULL). WASHER_FORTRAN = 0: the C file's
 * table `user` (auto_f2c.h).
 *
 * GETP, AUTO's support routine for PVLS (support.f90:GETP), reads the context that
 * washer_set_context stores before each PVLS call.
 */
#include <math.h>
#include <string.h>
#include <stddef.h>

#if WASHER_FORTRAN
extern void func_(const int *ndim, const double *u, const int *icp, const double *par,
                  const int *ijac, double *f, double *dfdu, double *dfdp) __attribute__((weak));
extern void stpnt_(const int *ndim, double *u, double *par, const double *t)
    __attribute__((weak));
extern void bcnd_(const int *ndim, const double *par, const int *icp, const int *nbc,
                  const double *u0, const double *u1, double *fb, const int *ijac,
                  double *dbc) __attribute__((weak));
extern void icnd_(const int *ndim, const double *par, const int *icp, const int *nint,
                  const double *u, const double *uold, const double *udot,
                  const double *upold, double *fi, const int *ijac, double *dint)
    __attribute__((weak));
extern void fopt_(const int *ndim, const double *u, const int *icp, const double *par,
                  const int *ijac, double *fs, double *dfdu, double *dfdp) __attribute__((weak));
extern void pvls_(const int *ndim, const double *u, double *par) __attribute__((weak));
#else
#define WRAPPER
#include "auto_f2c.h"
#endif

/* ------------------------------------------------------------------ context for GETP */
static struct {
    int ips, ndim, ntst, ncol, nbc, nint, nins;
    const double *dtm;          /* (ntst,) mesh interval lengths, NULL: uniform */
    double rds, fldf, hbff, biff, spbf;
    const double *eig;          /* (2 * ndim,) re, im alternating, NULL: none */
    int eig_wanted;             /* GETP asked for EIG or STA while eig was NULL */
} ctx = {1, 0, 0, 0, 0, 0, 0, NULL, 0, 0, 0, 0, 0, NULL, 0};

/* Whether GETP was asked for eigenvalues it did not have since the last call (then reset). */
int washer_eig_wanted(void)
{
    int w = ctx.eig_wanted;
    ctx.eig_wanted = 0;
    return w;
}

void washer_set_context(int ips, int ndim, int ntst, int ncol, int nbc, int nint,
                        const double *dtm)
{
    ctx.ips = ips; ctx.ndim = ndim; ctx.ntst = ntst; ctx.ncol = ncol;
    ctx.nbc = nbc; ctx.nint = nint; ctx.dtm = dtm;
}

void washer_set_measures(double rds, double fldf, double hbff, double biff, double spbf,
                         int nins, const double *eig)
{
    ctx.rds = rds; ctx.fldf = fldf; ctx.hbff = hbff; ctx.biff = biff; ctx.spbf = spbf;
    ctx.nins = nins; ctx.eig = eig;
}

/* Lagrange quadrature weights of NCOL + 1 equally spaced nodes on [0, 1] (AUTO's WINT). */
static void wint(int ncol, double *w)
{
    /* integrate each Lagrange basis polynomial with a Gauss-Legendre rule exact for its degree */
    static const double gx[8] = {-0.9602898564975363, -0.7966664774136267,
        -0.5255324099163290, -0.1834346424956498, 0.1834346424956498, 0.5255324099163290,
        0.7966664774136267, 0.9602898564975363};
    static const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
        0.3626837833783620, 0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
        0.1012285362903763};
    for (int i = 0; i <= ncol; i++) {
        double s = 0.0;
        for (int g = 0; g < 8; g++) {
            double x = 0.5 * (gx[g] + 1.0), l = 1.0;
            for (int j = 0; j <= ncol; j++)
                if (j != i) l *= (x - (double)j / ncol) / ((double)(i - j) / ncol);
            s += 0.5 * gw[g] * l;
        }
        w[i] = s;
    }
}

/* u is UPS(NDIM*NCOL, NTST+1) in AUTO's layout = the NTPL mesh points one after another. */
static double mesh_value(const double *u, int j, int ic) { return u[j * ctx.ndim + ic - 1]; }

static double dtm_of(int j) { return ctx.dtm ? ctx.dtm[j] : 1.0 / ctx.ntst; }

static double integral(const double *u, int ic, int square)
{
    double w[64], s = 0.0;
    if (ctx.ncol <= 0 || ctx.ncol > 63) return 0.0;
    wint(ctx.ncol, w);
    for (int j = 0; j < ctx.ntst; j++) {
        double part = 0.0;
        for (int k = 0; k <= ctx.ncol; k++) {
            double v = mesh_value(u, j * ctx.ncol + k, ic);
            part += w[k] * (square ? v * v : v);
        }
        s += dtm_of(j) * part;
    }
    return s;
}

static double getp_c(const char *code, int ic, const double *u)
{
    char c[4] = {0, 0, 0, 0};
    for (int i = 0; i < 3 && code[i]; i++)
        c[i] = (code[i] >= 'a' && code[i] <= 'z') ? code[i] - 32 : code[i];
    int ntpl = ctx.ntst * ctx.ncol + 1;
    double v = 0.0;
    if (ctx.ips <= 1 || ctx.ips == 5 || ctx.ips == 11) {
        if (!strcmp(c, "NRM")) v = fabs(u[ic - 1]);
        else if (!strcmp(c, "INT") || !strcmp(c, "MAX") || !strcmp(c, "MIN") ||
                 !strcmp(c, "BV1")) v = u[ic - 1];
        else if (!strcmp(c, "HBF")) v = ctx.hbff;
        else if (!strcmp(c, "BIF")) v = ctx.biff;
    } else {
        if (!strcmp(c, "NRM")) v = sqrt(integral(u, ic, 1));
        else if (!strcmp(c, "INT")) v = integral(u, ic, 0);
        else if (!strcmp(c, "MAX") || !strcmp(c, "MIN") || !strcmp(c, "MXT") ||
                 !strcmp(c, "MNT")) {
            int best = 0, want_max = (c[1] == 'A' || c[1] == 'X');
            for (int j = 1; j < ntpl; j++) {
                double a = mesh_value(u, j, ic), b = mesh_value(u, best, ic);
                if (want_max ? a > b : a < b) best = j;
            }
            if (c[2] == 'T') {       /* time of the extremum */
                int jj = best / ctx.ncol, kk = best % ctx.ncol;
                double t = 0.0;
                for (int j = 0; j < jj && j < ctx.ntst; j++) t += dtm_of(j);
                if (jj < ctx.ntst) t += dtm_of(jj) * kk / ctx.ncol;
                v = t;
            } else v = mesh_value(u, best, ic);
        }
        else if (!strcmp(c, "DTM")) v = (ic >= 1 && ic <= ctx.ntst) ? dtm_of(ic - 1) : 0.0;
        else if (!strcmp(c, "WIN")) {
            double w[64];
            if (ctx.ncol > 0 && ctx.ncol < 64 && ic >= 0 && ic <= ctx.ncol) {
                wint(ctx.ncol, w); v = w[ic];
            }
        }
        else if (!strcmp(c, "BV1")) v = mesh_value(u, ntpl - 1, ic);
        else if (!strcmp(c, "BIF")) v = ctx.biff;
        else if (!strcmp(c, "SPB")) v = ctx.spbf;
    }
    if (!strcmp(c, "BV0")) v = u[ic - 1];
    else if (!strcmp(c, "STP")) v = ctx.rds;
    else if (!strcmp(c, "FLD")) v = ctx.fldf;
    else if (!strcmp(c, "STA")) { v = ctx.nins; if (!ctx.eig) ctx.eig_wanted = 1; }
    else if (!strcmp(c, "EIG")) {
        if (!ctx.eig) ctx.eig_wanted = 1;
        v = (ctx.eig && ic >= 1 && ic <= 2 * ctx.ndim) ? ctx.eig[ic - 1] : 0.0;
    }
    else if (!strcmp(c, "NDI") || !strcmp(c, "NDX")) v = ctx.ndim;
    else if (!strcmp(c, "NTS")) v = ctx.ntst;
    else if (!strcmp(c, "NCO")) v = ctx.ncol;
    else if (!strcmp(c, "NBC")) v = ctx.nbc;
    else if (!strcmp(c, "NIN")) v = ctx.nint;
    return v;
}

/* Fortran: DOUBLE PRECISION FUNCTION GETP(CODE, IC, UPS), CHARACTER*3 CODE (the hidden
   length argument follows the others). C: getp(code, ic, u). */
double getp_(const char *code, const int *ic, const double *u, size_t len)
{
    char c[4] = {' ', ' ', ' ', 0};
    for (size_t i = 0; i < 3 && i < len; i++) c[i] = code[i];
    for (int i = 2; i >= 0 && c[i] == ' '; i--) c[i] = 0;
    return getp_c(c, *ic, u);
}

double getp(const char *code, int ic, const double *u) { return getp_c(code, ic, u); }

/* GE(IAM,N,M1A,A,NRHS,NDX,U,M1F,F,IR,IC,DET): AUTO's linear solver that user files call
   (support.f90:GE -> GELI): solves A U = F for NRHS right-hand sides by Gaussian
   elimination with complete pivoting; A and F are overwritten, DET is det(A). Column-major
   A(M1A,N), U(NDX,NRHS), F(M1F,NRHS); IR, IC: pivot rows / columns (1-based). */
void ge_(const int *iam, const int *n_, const int *m1a_, double *a, const int *nrhs_,
         const int *ndx_, double *u, const int *m1f_, double *f, int *ir, int *ic, double *det)
{
    int n = *n_, m1a = *m1a_, nrhs = *nrhs_, ndx = *ndx_, m1f = *m1f_;
    (void)iam;
    for (int i = 0; i < n; i++) { ir[i] = i + 1; ic[i] = i + 1; }
    double d = 1.0;
#define A_(i, j) a[(i) + (size_t)(j) * m1a]
#define F_(i, j) f[(i) + (size_t)(j) * m1f]
    for (int k = 0; k < n; k++) {
        int pr = k, pc = k;
        double best = -1.0;
        for (int j = k; j < n; j++)
            for (int i = k; i < n; i++)
                if (fabs(A_(i, j)) > best) { best = fabs(A_(i, j)); pr = i; pc = j; }
        if (pr != k) {
            for (int j = 0; j < n; j++) { double t = A_(k, j); A_(k, j) = A_(pr, j); A_(pr, j) = t; }
            for (int j = 0; j < nrhs; j++) { double t = F_(k, j); F_(k, j) = F_(pr, j); F_(pr, j) = t; }
            int t = ir[k]; ir[k] = ir[pr]; ir[pr] = t;
            d = -d;
        }
        if (pc != k) {
            for (int i = 0; i < n; i++) { double t = A_(i, k); A_(i, k) = A_(i, pc); A_(i, pc) = t; }
            int t = ic[k]; ic[k] = ic[pc]; ic[pc] = t;
            d = -d;
        }
        double piv = A_(k, k);
        d *= piv;
        if (piv == 0.0) continue;
        for (int i = k + 1; i < n; i++) {
            double m = A_(i, k) / piv;
            if (m == 0.0) continue;
            for (int j = k; j < n; j++) A_(i, j) -= m * A_(k, j);
            for (int j = 0; j < nrhs; j++) F_(i, j) -= m * F_(k, j);
        }
    }
    for (int r = 0; r < nrhs; r++) {
        for (int i = n - 1; i >= 0; i--) {
            double sum = F_(i, r);
            for (int j = i + 1; j < n; j++) sum -= A_(i, j) * u[(ic[j] - 1) + (size_t)r * ndx];
            u[(ic[i] - 1) + (size_t)r * ndx] = A_(i, i) != 0.0 ? sum / A_(i, i) : 0.0;
        }
    }
#undef A_
#undef F_
    *det = d;
}

/* ------------------------------------------------------------------ user routines */
int washer_has(const char *name)
{
#if WASHER_FORTRAN
    if (!strcmp(name, "func")) return func_ != NULL;
    if (!strcmp(name, "stpnt")) return stpnt_ != NULL;
    if (!strcmp(name, "bcnd")) return bcnd_ != NULL;
    if (!strcmp(name, "icnd")) return icnd_ != NULL;
    if (!strcmp(name, "fopt")) return fopt_ != NULL;
    if (!strcmp(name, "pvls")) return pvls_ != NULL;
    return 0;
#else
    (void)name;
    return 1;
#endif
}

static void call_func(int ndim, const double *u, const int *icp, const double *par, int ijac,
                      double *f, double *dfdu, double *dfdp)
{
#if WASHER_FORTRAN
    func_(&ndim, u, icp, par, &ijac, f, dfdu, dfdp);
#else
    user.func(ndim, u, icp, par, ijac, f, dfdu, dfdp);
#endif
}

/* f at k points: us (k, ndim), pars (k, npar) with row stride par_stride (0: one PAR
   for all points), fs (k, ndim). scratch: ndim * (ndim + npar) doubles for DFDU/DFDP,
   which FUNC may touch even with IJAC = 0. */
void washer_func_batch(int k, int ndim, int npar, const double *us, const double *pars,
                       int par_stride, const int *icp, double *fs, double *scratch)
{
    for (int i = 0; i < k; i++) {
        memset(fs + (size_t)i * ndim, 0, sizeof(double) * ndim);
        call_func(ndim, us + (size_t)i * ndim, icp, pars + (size_t)i * par_stride, 0,
                  fs + (size_t)i * ndim, scratch, scratch + (size_t)ndim * ndim);
    }
    (void)npar;
}

/* The user's Jacobians (IJAC = 1: DFDU; IJAC = 2: DFDU and DFDP) at k points.
   dfdus (k, ndim, ndim) row-major; dfdps (k, ndim, npar) row-major or NULL. */
void washer_jac_batch(int k, int ndim, int npar, const double *us, const double *pars,
                      int par_stride, const int *icp, int ijac, double *fs, double *dfdus,
                      double *dfdps, double *scratch)
{
    double *a = scratch, *b = scratch + (size_t)ndim * ndim;
    for (int i = 0; i < k; i++) {
        memset(a, 0, sizeof(double) * (size_t)ndim * (ndim + npar));
        memset(fs + (size_t)i * ndim, 0, sizeof(double) * ndim);
        call_func(ndim, us + (size_t)i * ndim, icp, pars + (size_t)i * par_stride, ijac,
                  fs + (size_t)i * ndim, a, b);
        double *J = dfdus + (size_t)i * ndim * ndim;
        for (int r = 0; r < ndim; r++)
            for (int c = 0; c < ndim; c++) J[r * ndim + c] = a[r + c * ndim];
        if (dfdps) {
            double *P = dfdps + (size_t)i * ndim * npar;
            for (int r = 0; r < ndim; r++)
                for (int c = 0; c < npar; c++) P[r * npar + c] = b[r + c * ndim];
        }
    }
}

void washer_stpnt(int ndim, double t, double *u, double *par)
{
#if WASHER_FORTRAN
    stpnt_(&ndim, u, par, &t);
#else
    user.stpnt(ndim, t, u, par);
#endif
}

void washer_pvls(int ndim, const double *u, double *par)
{
#if WASHER_FORTRAN
    pvls_(&ndim, u, par);
#else
    user.pvls(ndim, u, par);
#endif
}

/* BCND: fb (nbc,), dbc column-major (nbc, 2 ndim + npar) when ijac > 0. */
void washer_bcnd(int ndim, const double *par, const int *icp, int nbc, const double *u0,
                 const double *u1, int ijac, double *fb, double *dbc)
{
#if WASHER_FORTRAN
    bcnd_(&ndim, par, icp, &nbc, u0, u1, fb, &ijac, dbc);
#else
    user.bcnd(ndim, par, icp, nbc, u0, u1, ijac, fb, dbc);
#endif
}

/* ICND at k points (collocation points): u, uold, udot, upold (k, ndim); fi (k, nint). */
void washer_icnd_batch(int k, int ndim, const double *par, const int *icp, int nint,
                       const double *u, const double *uold, const double *udot,
                       const double *upold, double *fi, double *scratch)
{
    int ijac = 0;
    for (int i = 0; i < k; i++) {
        size_t o = (size_t)i * ndim;
#if WASHER_FORTRAN
        icnd_(&ndim, par, icp, &nint, u + o, uold + o, udot + o, upold + o,
              fi + (size_t)i * nint, &ijac, scratch);
#else
        user.icnd(ndim, par, icp, nint, u + o, uold + o, udot + o, upold + o, ijac,
                  fi + (size_t)i * nint, scratch);
#endif
    }
}

/* FOPT (IPS = 5, 15): the objective fs and, with ijac, its derivatives (column-major). */
void washer_fopt(int ndim, const double *u, const int *icp, const double *par, int ijac,
                 double *fs, double *dfdu, double *dfdp)
{
#if WASHER_FORTRAN
    fopt_(&ndim, u, icp, par, &ijac, fs, dfdu, dfdp);
#else
    user.fopt(ndim, u, icp, par, ijac, fs, dfdu, dfdp);
#endif
}

/* The objective FOPT (IJAC = 0: the value only) at k points: us (k, ndim) rows, pars
   (k, par_stride) rows (par_stride = 0: one PAR for all) -> fs (k,). */
void washer_fopt_batch(int k, int ndim, const double *us, const double *pars, int par_stride,
                       const int *icp, double *fs, double *scratch)
{
    for (int i = 0; i < k; i++)
        washer_fopt(ndim, us + (size_t)i * ndim, icp, pars + (size_t)i * par_stride, 0,
                    fs + i, scratch, scratch + ndim);
}

/* ------------------------------------------------------- the algebraic corrector */
/* The points of Problem.jacobian's central differences at x = (u, PAR(ip + 1)) after the
   point (u, PAR) itself: row 0 (u, PAR), rows 1..k u_j + h_j then PAR(ip + 1) + h, rows
   k + 1..2k the minus side (k = NDIM + 1; us (2k + 1, NDIM), ps (2k + 1, npar)), f at
   rows first..2k into fs; h_j = hmach (1 + |x_j|). */
static void ae_points(int n, int npar, int ip, const int *icp, const double *par,
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
    for (int r = first; r < rows; r++) {
        double *f = fs + (size_t)r * n;
        memset(f, 0, sizeof(double) * n);
        call_func(n, us + (size_t)r * n, icp, ps + (size_t)r * npar, 0, f, scratch,
                  scratch + (size_t)n * n);
    }
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
   JAC = 0 (washer.cont.compiled_newton chooses it; every other case is the Python loop):

     unknowns x = (U(1..NDIM), PAR(ip + 1)), PAR the other parameters (npar), ICP icp;
     per iteration: F = f(u, PAR), the central differences [f_u, f_PAR(ip + 1)] with
     h_j = hmach (1 + |z_j|) (Problem.jacobian's stencil: the same points and quotients),
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
   residual, Jacobian or correction, or a zero pivot: the caller runs the Python loop. */
int washer_ae_correct(int ndim, int npar, int ip, const int *icp, const double *par,
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
        ae_points(n, npar, ip, icp, par, x, hmach, 0, us, ps, fs, h, scratch);
        for (int i = 0; i < n; i++) {
            if (!isfinite(fs[i])) return 3;
            b[i] = -fs[i];
        }
        if (ae_jacobian(n, fs, h, M, np1)) return 3;
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
                ae_points(n, npar, ip, icp, par, x, hmach, 1, us, ps, fs, h, scratch);
                if (ae_jacobian(n, fs, h, jac, np1)) return 4;
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

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
 * WASHER_TRACED_BATCH = 1 (a Python file's func traced into C, washer.cont.user_problem.
 * tracer): the file also defines washer_traced_batch, f at many points at once, which
 * washer_func_batch calls instead of FUNC point by point.
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
#if WASHER_TRACED_BATCH
int washer_traced_batch(int k, int ndim, const double *us, const double *pars, int par_stride,
                        double *fs);
#endif

void washer_func_batch(int k, int ndim, int npar, const double *us, const double *pars,
                       int par_stride, const int *icp, double *fs, double *scratch)
{
#if WASHER_TRACED_BATCH
    if (washer_traced_batch(k, ndim, us, pars, par_stride, fs) == 0) return;
#endif
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

/* ------------------------------------------- the periodic corrector's f and f_u */
/* The corrector of periodic orbits (csrc/cont/po_correct.cpp) calls f and f_u through
   function pointers of the generated C's signature (k points, one PAR for all when
   pstride is 0), which carry no context: washer_po_bind stores the run's sizes, ICP and
   FUNC's scratch for them before each correction. */
static struct {
    int ndim, npar;
    const int *icp;
    double *scratch;            /* ndim * (ndim + npar) + ndim doubles */
} po = {0, 0, NULL, NULL};

void washer_po_bind(int ndim, int npar, const int *icp, double *scratch)
{
    po.ndim = ndim; po.npar = npar; po.icp = icp; po.scratch = scratch;
}

/* f at k points (washer_func_batch with the bound context). */
void washer_po_func(int k, const double *us, const double *pars, int pstride, double *fs)
{
    washer_func_batch(k, po.ndim, po.npar, us, pars, pstride, po.icp, fs, po.scratch);
}

/* The user's DFDU (IJAC = 1) at k points, row-major (k, ndim, ndim), as washer_jac_batch
   gives it (f goes to the scratch's tail); Jp is not written (f_p is differenced). */
void washer_po_jac(int k, const double *us, const double *pars, int pstride, double *J,
                   double *Jp)
{
    const int n = po.ndim;
    double *f = po.scratch + (size_t)n * (n + po.npar);
    (void)Jp;
    for (int i = 0; i < k; i++)
        washer_jac_batch(1, n, po.npar, us + (size_t)i * n, pars + (size_t)i * pstride,
                         0, po.icp, 1, f, J + (size_t)i * n * n, NULL, po.scratch);
}

void washer_stpnt(int ndim, double t, double *u, double *par)
{
#if WASHER_FORTRAN
    stpnt_(&ndim, u, par, &t);
#else
    user.stpnt(ndim, t, u, par);
#endif
}

/* AUTO's COMMON /BLHOM/ (homcont.f90): ITWIST, ISTART, IEQUIB, NFIXED, NPSI, NUNSTAB, NSTAB,
 * NREV, which a user's STPNT or PVLS may read (kpr's STPNT sets the equilibrium only for
 * IEQUIB /= 0, cir's PVLS only for IEQUIB = 0). Defined here so that every file links,
 * whether it declares the block or not; a Fortran file's COMMON of that name is this
 * storage, and so is a C file's `blhom_1` (auto_f2c.h names it blhom_, as AUTO's does). */
int blhom_[8];

void washer_set_homcont(const int *values)
{
    memcpy(blhom_, values, sizeof blhom_);
}

void washer_pvls(int ndim, const double *u, double *par)
{
#if WASHER_FORTRAN
    pvls_(&ndim, u, par);
#else
    user.pvls(ndim, u, par);
#endif
}

/* PVLS of an algebraic problem (IPS 0, 1 and their loci) as one call: GETP's context of
 * equilibria without eigenvalues, PAR(1..npar) copied to `first` (the caller's to call
 * again with eigenvalues where GETP asked for them), PVLS, and whether GETP asked for
 * eigenvalues (washer_eig_wanted: read and reset). The same calls
 * washer.cont.user_problem.user_files_native
 * makes one by one. */
int washer_pvls_ae(int ndim, const double *u, double *par, double *first, int npar)
{
    washer_set_measures(0.0, 0.0, 0.0, 0.0, 0.0, 0, NULL);
    washer_set_context(1, ndim, 0, 0, 0, 0, NULL);
    memcpy(first, par, (size_t)npar * sizeof(double));
    washer_pvls(ndim, u, par);
    return washer_eig_wanted();
}

/* PVLS of a boundary-value solution (AUTO's PVLSBV: IPS 2, 4 and their loci) as one
 * call, the same calls washer.cont.user_problem.user_files_native makes one by one for
 * it: the node values u (ntpl, ndim) copied into AUTO's UPS(NDIM*NCOL, NTST+1) in `ups`
 * (ndim * ncol * (ntst + 1) doubles, the columns past NTPL zero), GETP's mesh interval
 * lengths t[(j+1) ncol] - t[j ncol] of the node times t (ntpl,) into `dtm` (ntst,) (t
 * NULL: a uniform mesh), GETP's measures with the multipliers `eig` (2 ndim doubles, re
 * and im alternating; NULL: none) and their stable count nins, PAR(1..npar) copied to
 * `first`, PVLS, and whether GETP asked for eigenvalues it did not have (then the caller
 * restores PAR from `first` and calls again with them). ctx keeps dtm and eig: the
 * caller holds them until the next call. */
int washer_pvls_bvp(int ips, int ndim, int ntst, int ncol, int nbc, int nint, int ntpl,
                    const double *u, const double *t, double *dtm, double *ups, int nins,
                    const double *eig, double *par, double *first, int npar)
{
    size_t n = (size_t)ntpl * ndim, size = (size_t)ndim * ncol * (ntst + 1);
    memcpy(ups, u, n * sizeof(double));
    if (size > n) memset(ups + n, 0, (size - n) * sizeof(double));
    if (t)
        for (int j = 0; j < ntst; j++) dtm[j] = t[(size_t)(j + 1) * ncol] - t[(size_t)j * ncol];
    washer_set_measures(0.0, 0.0, 0.0, 0.0, 0.0, nins, eig);
    washer_set_context(ips, ndim, ntst, ncol, nbc, nint, t ? dtm : NULL);
    memcpy(first, par, (size_t)npar * sizeof(double));
    washer_pvls(ndim, ups, par);
    return washer_eig_wanted();
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
static int ae_eval(void *ctx, int stage, int ndim, int npar, const int *icp, int rows,
                   int first, const double *us, const double *ps, double *fs,
                   double *scratch)
{
    (void)ctx; (void)stage;
    for (int r = first; r < rows; r++) {
        double *f = fs + (size_t)r * ndim;
        memset(f, 0, sizeof(double) * ndim);
        call_func(ndim, us + (size_t)r * ndim, icp, ps + (size_t)r * npar, 0, f, scratch,
                  scratch + (size_t)ndim * ndim);
    }
    return 0;
}

#include "ae_correct.h"
#include "ae_lyapunov.h"

/* washer.cont.corrector_algebraic's corrector with this file's FUNC (ae_correct.h). */
int washer_ae_correct(int kind, int ndim, int npar, int ip, int ip2, const int *icp,
                      const double *par, const double *v_old, const double *x_pred,
                      const double *x_ref, const double *theta, double ds, double epsl,
                      double epsu, int itnw, double divergence, double hmach, double h2,
                      double *x, int *iterations, double *jac, double *work,
                      double *scratch)
{
    return ae_correct(NULL, kind, ndim, npar, ip, ip2, icp, par, v_old, x_pred, x_ref, theta,
                      ds, epsl, epsu, itnw, divergence, hmach, h2, x, iterations, jac,
                      work, scratch);
}

/* The first Lyapunov coefficient with this file's FUNC (ae_lyapunov.h). */
int washer_ae_l1(int ndim, int npar, const int *icp, const double *x, const double *par,
                 double omega, const double *A, double *l1, double *work, double *scratch)
{
    return ae_first_lyapunov(NULL, ndim, npar, icp, x, par, omega, A, l1, work, scratch);
}

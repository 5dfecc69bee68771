/* The corrector of algebraic continuation (washer.cont.corrector_algebraic), included by the
 * two C files that call it: the bridge of compiled user files (user_files_bridge.c: FUNC
 * called directly) and ae_callback.c (the user's Python func called back). The includer
 * defines, before including this file,
 *
 *   static int ae_eval(void *ctx, int stage, int ndim, int npar, const int *icp, int rows,
 *                      int first, const double *us, const double *ps, double *fs,
 *                      double *scratch);
 *
 * f at the rows first..rows-1 of us (rows, ndim) with PAR the rows of ps (rows, npar),
 * into fs (rows, ndim), in the order of the rows; nonzero: the evaluation failed. stage 0:
 * the point (row 0) and the central differences of f_u and f_PAR (Problem.jacobian's
 * stencil); stage 1: the mixed second differences of the loci (Problem.
 * second_derivatives' stencil, one batch).
 * An includer whose equations come with their exact Jacobians (the generated C of
 * sympy problems: ae_generated.c; the user's dfdu and dfdp of Python problems called
 * back: ae_callback.c) also defines AE_EXACT_JACOBIAN and
 *
 *   static int ae_exact(void *ctx, int ndim, int npar, int ip, const double *u,
 *                       const double *par, double *J, int stride);
 *
 * [f_u, f_PAR(ip + 1)] at (u, par) into J (ndim rows of stride `stride`): -1 where this
 * run's Jacobians are differences (JAC = 0), 0 evaluated, else the evaluation failed
 * (equilibria only: corrector_algebraic does not give the loci such equations).
 *
 * This is a second copy of one meaning, the package's one Newton loop
 * (washer/cont/newton.py's newton as washer.cont.iterator.Continuation.correct runs it,
 * with washer.cont.problem.Problem.jacobian's difference stencil, Problem.
 * second_derivatives' and the extended systems of washer/cont/systems/fold.py and
 * hopf.py): a change to either must be made in both (tests/test_compiled_newton.py holds
 * them to the same iterates). The layout of `work` (ae_work_size) is read by
 * corrector_algebraic.py's PythonEquations too, which checks the pointers it is passed
 * against it.
 */
#ifndef WASHER_AE_CORRECT_H
#define WASHER_AE_CORRECT_H
#include <math.h>
#include <string.h>
#include <stddef.h>

/* The systems: equilibria f(u, PAR) = 0 in (U, PAR(ip + 1)) (EquilibriumSystem); the
   fold locus (f, A phi, <phi, phi> - 1) in (U, phi, PAR(ip2 + 1), PAR(ip + 1))
   (FoldSystem); the Hopf locus (f, A^2 v + kappa v, <v, v> - 1, <A^T v_old - A v_old, v>)
   in (U, v, kappa, PAR(ip2 + 1), PAR(ip + 1)) (HopfSystem); A = f_u. */
enum { AE_EQUILIBRIUM = 0, AE_FOLD = 1, AE_HOPF = 2 };

/* Sizes of a system: unknowns nx (the last one PAR(ip + 1)), difference directions k1
   (U and the free parameters), second-difference vectors m2. */
static void ae_sizes(int kind, int n, int *nx, int *k1, int *m2)
{
    *nx = kind == AE_HOPF ? 2 * n + 3 : kind == AE_FOLD ? 2 * n + 2 : n + 1;
    *k1 = kind == AE_EQUILIBRIUM ? n + 1 : n + 2;
    *m2 = kind == AE_HOPF ? 3 : kind == AE_FOLD ? 1 : 0;
}

/* Doubles of `work` (corrector_algebraic.work_size computes the same): stage 0's us, ps, fs
   (r1 = 2 k1 + 1 rows), stage 1's (r2 = 4 k1 m2 rows), then the Newton matrix and the
   vectors of ae_system. */
static size_t ae_work_size(int kind, int n, int npar)
{
    int nx, k1, m2;
    ae_sizes(kind, n, &nx, &k1, &m2);
    size_t r1 = 2 * (size_t)k1 + 1, r2 = 4 * (size_t)k1 * m2;
    return (r1 + r2) * (2 * (size_t)n + npar) + (size_t)nx * nx + 2 * (size_t)nx + npar
           + 2 * (size_t)k1 + (size_t)m2 * (1 + n) + (size_t)k1 * m2 * n + (size_t)n * k1
           + (size_t)n;
}

/* Gaussian elimination with partial pivoting (LAPACK's GETRF order: the largest |entry|
   of the column, the first one of equal size) of M (m, m) row-major, applied to b (m,).
   Returns 0, or 3 for a zero or non-finite pivot. */
static int ae_eliminate(int m, double *M, double *b)
{
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
        }
        double piv = M[(size_t)col * m + col];
        for (int r = col + 1; r < m; r++) {
            double f = M[(size_t)r * m + col] / piv;
            if (f == 0.0) continue;
            for (int j = col + 1; j < m; j++)
                M[(size_t)r * m + j] -= f * M[(size_t)col * m + j];
            b[r] -= f * b[col];
        }
    }
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

/* One system at work: its sizes, constants and the pieces of `work`. */
typedef struct {
    void *ctx;
    int kind, n, npar, ip, ip2, nx, k1, m2, r1, r2;
    const int *icp;
    const double *par, *v_old;
    double hmach, h2;
    double *us, *ps, *fs, *us2, *ps2, *fs2;     /* stage 0 (r1 rows), stage 1 (r2 rows) */
    double *M, *b, *d, *pz, *h, *hs, *kk, *W, *T, *Jz, *av, *scratch;
} ae_sys;

static void ae_setup(ae_sys *S, void *ctx, int kind, int n, int npar, int ip, int ip2,
                     const int *icp, const double *par, const double *v_old, double hmach,
                     double h2, double *work, double *scratch)
{
    S->ctx = ctx; S->kind = kind; S->n = n; S->npar = npar; S->ip = ip; S->ip2 = ip2;
    S->icp = icp; S->par = par; S->v_old = v_old; S->hmach = hmach; S->h2 = h2;
    S->scratch = scratch;
    ae_sizes(kind, n, &S->nx, &S->k1, &S->m2);
    S->r1 = 2 * S->k1 + 1;
    S->r2 = 4 * S->k1 * S->m2;
    double *w = work;
    S->us = w; w += (size_t)S->r1 * n;
    S->ps = w; w += (size_t)S->r1 * npar;
    S->fs = w; w += (size_t)S->r1 * n;
    S->us2 = w; w += (size_t)S->r2 * n;
    S->ps2 = w; w += (size_t)S->r2 * npar;
    S->fs2 = w; w += (size_t)S->r2 * n;
    S->M = w; w += (size_t)S->nx * S->nx;       /* (nx, nx) row-major */
    S->b = w; w += S->nx;
    S->d = w; w += S->nx;
    S->h = w; w += S->k1;
    S->pz = w; w += npar;
    S->hs = w; w += S->k1;
    S->kk = w; w += S->m2;
    S->W = w; w += (size_t)S->m2 * n;
    S->T = w; w += (size_t)S->k1 * S->m2 * n;
    S->Jz = w; w += (size_t)n * S->k1;
    S->av = w; w += n;
}

/* The parameters at x (the locus system's _p: PAR(ip + 1) = x[nx - 1], PAR(ip2 + 1) =
   x[nx - 2]) into pz, and the differenced coordinates z = (U, PAR(ip + 1), PAR(ip2 + 1))
   read through ae_z. */
static void ae_params(ae_sys *S, const double *x)
{
    memcpy(S->pz, S->par, sizeof(double) * S->npar);
    S->pz[S->ip] = x[S->nx - 1];
    if (S->kind != AE_EQUILIBRIUM) S->pz[S->ip2] = x[S->nx - 2];
}

static double ae_z(const ae_sys *S, const double *x, int j)
{
    return j < S->n ? x[j] : j == S->n ? x[S->nx - 1] : x[S->nx - 2];
}

static int ae_pidx(const ae_sys *S, int j)      /* the PAR index of direction j >= n */
{
    return j == S->n ? S->ip : S->ip2;
}

/* Stage 0: the points of Problem.jacobian's central differences after the point (U, PAR)
   itself: row 0, rows 1..k1 z_j + h_j, rows k1 + 1..2 k1 the minus side (h_j = hmach
   (1 + |z_j|)), f at rows first..2 k1; then Jz = [f_u, f_PAR] (n, k1) row-major, the
   quotients (f(z + h_j e_j) - f(z - h_j e_j)) / (2 h_j). Returns ae_eval's status, or 3
   for a non-finite quotient. */
static int ae_first(ae_sys *S, const double *x, int first, double *Jz, int stride)
{
    const int n = S->n, npar = S->npar, k = S->k1, rows = S->r1;
    double *us = S->us, *ps = S->ps, *fs = S->fs, *h = S->h;
    for (int j = 0; j < k; j++) h[j] = S->hmach * (1 + fabs(ae_z(S, x, j)));
    for (int r = 0; r < rows; r++) {
        memcpy(us + (size_t)r * n, x, sizeof(double) * n);
        memcpy(ps + (size_t)r * npar, S->pz, sizeof(double) * npar);
    }
    for (int j = 0; j < k; j++) {
        double z = ae_z(S, x, j);
        if (j < n) {
            us[(size_t)(1 + j) * n + j] = z + h[j];
            us[(size_t)(1 + k + j) * n + j] = z - h[j];
        } else {
            int i = ae_pidx(S, j);
            ps[(size_t)(1 + j) * npar + i] = z + h[j];
            ps[(size_t)(1 + k + j) * npar + i] = z - h[j];
        }
    }
    int st = ae_eval(S->ctx, 0, n, npar, S->icp, rows, first, us, ps, fs, S->scratch);
    if (st) return st;
    for (int i = 0; i < n; i++)
        for (int j = 0; j < k; j++) {
            double v = (fs[(size_t)(1 + j) * n + i] - fs[(size_t)(1 + k + j) * n + i])
                       / (2 * h[j]);
            if (!isfinite(v)) return 3;
            Jz[(size_t)i * stride + j] = v;
        }
    return 0;
}

/* Stage 1: T[s, m, :] = f_zz[e_s, W_m] (k1, m2, n) from Problem.second_derivatives'
   stencil: [f(z + h e_s + k w) - f(z + h e_s - k w) - f(z - h e_s + k w) + f(z - h e_s
   - k w)] / (4 h k), h = h2 (1 + |z_s|), k = h2 (1 + max|u|) / max|w|; the rows in the
   order (s, m, sign pair). Returns ae_eval's status, or 3 if not finite. */
static int ae_second(ae_sys *S, const double *x)
{
    static const double sa[4] = {1.0, 1.0, -1.0, -1.0}, sb[4] = {1.0, -1.0, 1.0, -1.0};
    const int n = S->n, npar = S->npar, k1 = S->k1, m2 = S->m2;
    double umax = 0.0;
    for (int i = 0; i < n; i++) if (fabs(x[i]) > umax) umax = fabs(x[i]);
    for (int m = 0; m < m2; m++) {
        double wn = 0.0;
        for (int i = 0; i < n; i++)
            if (fabs(S->W[(size_t)m * n + i]) > wn) wn = fabs(S->W[(size_t)m * n + i]);
        S->kk[m] = S->h2 * (1 + umax) / (wn > 1e-300 ? wn : 1e-300);
    }
    for (int s = 0; s < k1; s++) S->hs[s] = S->h2 * (1 + fabs(ae_z(S, x, s)));
    for (int s = 0; s < k1; s++)
        for (int m = 0; m < m2; m++)
            for (int g = 0; g < 4; g++) {
                size_t r = ((size_t)s * m2 + m) * 4 + g;
                double *u = S->us2 + r * n, *p = S->ps2 + r * npar;
                const double *w = S->W + (size_t)m * n;
                for (int i = 0; i < n; i++) u[i] = x[i] + sb[g] * (S->kk[m] * w[i]);
                memcpy(p, S->pz, sizeof(double) * npar);
                double ah = sa[g] * S->hs[s];
                if (s < n) u[s] += ah;
                else p[ae_pidx(S, s)] += ah;
            }
    int st = ae_eval(S->ctx, 1, n, npar, S->icp, S->r2, 0, S->us2, S->ps2, S->fs2,
                     S->scratch);
    if (st) return st;
    for (int s = 0; s < k1; s++)
        for (int m = 0; m < m2; m++) {
            const double *F = S->fs2 + ((size_t)s * m2 + m) * 4 * n;
            double q = 4 * S->hs[s] * S->kk[m];
            for (int i = 0; i < n; i++) {
                double v = (F[i] - F[n + i] - F[2 * n + i] + F[3 * n + i]) / q;
                if (!isfinite(v)) return 3;
                S->T[((size_t)s * m2 + m) * n + i] = v;
            }
        }
    return 0;
}

/* The column of J holding the derivative along difference direction s (U, PAR(ip + 1),
   PAR(ip2 + 1)). */
static int ae_col(const ae_sys *S, int s)
{
    return s < S->n ? s : s == S->n ? S->nx - 1 : S->nx - 2;
}

/* The system at x: G (nx - 1,) when G is not NULL (f at x evaluated: first = 0), and its
   Jacobian J (nx - 1, nx) row-major with row stride `stride`, as the systems' residual and
   jacobian compute them. Returns 0, ae_eval's status, or 3 for a non-finite value. */
static int ae_system(ae_sys *S, const double *x, double *G, double *J, int stride)
{
    const int n = S->n, k1 = S->k1, nx = S->nx;
    ae_params(S, x);
    if (S->kind == AE_EQUILIBRIUM) {
#ifdef AE_EXACT_JACOBIAN
        /* the includer's exact [f_u, f_PAR(ip + 1)] (Problem.jacobian's dfdu and dfdp
           with JAC = 1), f at x alone */
        memcpy(S->us, x, sizeof(double) * n);
        memcpy(S->ps, S->pz, sizeof(double) * S->npar);
        int e = ae_exact(S->ctx, n, S->npar, S->ip, S->us, S->ps, J, stride);
        if (e > 0) return 1;
        if (e == 0) {
            if (G) {
                if (ae_eval(S->ctx, 0, n, S->npar, S->icp, 1, 0, S->us, S->ps, S->fs,
                            S->scratch))
                    return 1;
                for (int i = 0; i < n; i++) G[i] = S->fs[i];
            }
            for (int i = 0; i < n; i++)
                for (int j = 0; j <= n; j++)
                    if (!isfinite(J[(size_t)i * stride + j])) return 3;
            return 0;
        }
#endif
        int st = ae_first(S, x, G ? 0 : 1, J, stride);
        if (st) return st;
        if (G) for (int i = 0; i < n; i++) G[i] = S->fs[i];
        return 0;
    }
    int st = ae_first(S, x, G ? 0 : 1, S->Jz, k1);
    if (st) return st;
    const double *Jz = S->Jz, *f = S->fs;
    #define A_(i, j) Jz[(size_t)(i) * k1 + (j)]
    #define J_(i, j) J[(size_t)(i) * stride + (j)]
    const double *v = x + n;                       /* phi or v */
    /* A v */
    for (int i = 0; i < n; i++) {
        double s = 0.0;
        for (int l = 0; l < n; l++) s += A_(i, l) * v[l];
        S->av[i] = s;
    }
    if (S->kind == AE_FOLD) {
        memcpy(S->W, v, sizeof(double) * n);                        /* W = [phi] */
    } else {
        memcpy(S->W, S->av, sizeof(double) * n);                    /* [A v, v, v_old] */
        memcpy(S->W + n, v, sizeof(double) * n);
        memcpy(S->W + 2 * n, S->v_old, sizeof(double) * n);
    }
    st = ae_second(S, x);
    if (st) return st;
    for (int i = 0; i < nx - 1; i++)
        for (int j = 0; j < nx; j++) J_(i, j) = 0.0;
    /* the f-rows: A and f_PAR(ip + 1), f_PAR(ip2 + 1) */
    for (int i = 0; i < n; i++)
        for (int s = 0; s < k1; s++) J_(i, ae_col(S, s)) = A_(i, s);
    const double *T = S->T;
    const int m2 = S->m2;
    if (S->kind == AE_FOLD) {
        /* FoldSystem: A phi rows: d(A phi)/ds = f_zz[e_s, phi], A; <phi, phi> - 1 */
        for (int i = 0; i < n; i++) {
            for (int s = 0; s < k1; s++) J_(n + i, ae_col(S, s)) = T[(size_t)s * m2 * n + i];
            for (int j = 0; j < n; j++) J_(n + i, n + j) = A_(i, j);
        }
        for (int j = 0; j < n; j++) J_(2 * n, n + j) = 2 * v[j];
        if (G) {
            double pp = 0.0;
            for (int i = 0; i < n; i++) { G[i] = f[i]; G[n + i] = S->av[i]; pp += v[i] * v[i]; }
            G[2 * n] = pp - 1.0;
        }
    } else {
        /* HopfSystem: d/ds (A^2 v) = A_s (A v) + A (A_s v); d/ds <A^T vo - A vo, v> =
           <vo, A_s v> - <v, A_s vo>; A^2 + kappa I; v; 2 v; w = A^T vo - A vo */
        const double kappa = x[2 * n], *vo = S->v_old;
        for (int s = 0; s < k1; s++) {
            const double *FAv = T + ((size_t)s * m2 + 0) * n, *Fv = T + ((size_t)s * m2 + 1) * n,
                         *Fvo = T + ((size_t)s * m2 + 2) * n;
            int c = ae_col(S, s);
            double a = 0.0, bsum = 0.0;
            for (int i = 0; i < n; i++) {
                double g = 0.0;
                for (int l = 0; l < n; l++) g += A_(i, l) * Fv[l];
                J_(n + i, c) = FAv[i] + g;
                a += Fv[i] * vo[i];
                bsum += Fvo[i] * v[i];
            }
            J_(2 * n + 1, c) = a - bsum;
        }
        for (int i = 0; i < n; i++) {
            for (int j = 0; j < n; j++) {
                double s = 0.0;
                for (int l = 0; l < n; l++) s += A_(i, l) * A_(l, j);
                J_(n + i, n + j) = s + (i == j ? kappa : 0.0);
            }
            J_(n + i, 2 * n) = v[i];
            J_(2 * n, n + i) = 2 * v[i];
            double wt = 0.0, wa = 0.0;
            for (int l = 0; l < n; l++) { wt += A_(l, i) * vo[l]; wa += A_(i, l) * vo[l]; }
            J_(2 * n + 1, n + i) = wt - wa;
        }
        if (G) {
            double vv = 0.0, ph = 0.0;
            for (int i = 0; i < n; i++) {
                double s = 0.0;
                for (int l = 0; l < n; l++) s += A_(i, l) * S->av[l];
                G[i] = f[i];
                G[n + i] = s + kappa * v[i];
                vv += v[i] * v[i];
                ph += J_(2 * n + 1, n + i) * v[i];
            }
            G[2 * n] = vv - 1.0;
            G[2 * n + 1] = ph;
        }
    }
    for (int i = 0; i < nx - 1; i++)
        for (int j = 0; j < nx; j++)
            if (!isfinite(J_(i, j))) return 3;
    if (G) for (int i = 0; i < nx - 1; i++) if (!isfinite(G[i])) return 3;
    #undef A_
    #undef J_
    return 0;
}

/* The corrector of algebraic continuation in one foreign call: the compiled form of the
   package's one Newton loop (washer.cont.newton.newton) as iterator.Continuation.correct
   runs it on equilibria and on the fold and Hopf loci with the sphere arclength (AUTO's
   SOLVAE/STEPAE), for FUNC with difference Jacobians, or generated equations with their
   exact Jacobians (AE_EXACT_JACOBIAN, equilibria) (washer.cont.corrector_algebraic chooses
   it; every other case is the Python loop):

     unknowns x (nx = ae_sizes' count; the last one PAR(ip + 1), on the loci the one
     before it PAR(ip2 + 1)), PAR the other parameters (npar), ICP icp; v_old (NDIM,) the
     Hopf locus' previous v (HopfSystem.v_old; unused otherwise);
     per iteration: G and its Jacobian J at x (ae_system: f, the central differences
     [f_u, f_PAR] with h_j = hmach (1 + |z_j|), Problem.jacobian's stencil, or on
     equilibria the includer's exact ones (ae_exact: Problem.jacobian's dfdu and dfdp
     with JAC = 1); on the loci
     the mixed second differences with step h2, Problem.second_derivatives' stencil), the
     arclength row r = 2 theta (x - x_ref) / |ds| and c = <r, x - x_ref> / 2 - |ds|, the
     correction dx of [J; r] dx = -[G; c] (LU with partial pivoting), x += dx;
     stop when |dx_last| / (1 + |x_last|) <= epsl and max|dx_other| / (1 + max|x_other|)
     <= epsu; diverging when max of the two grows beyond `divergence` times its first
     value.
   jac: NULL, or (nx - 1, nx) row-major: J at the converged x (the Jacobian the
   continuation evaluates there next, the same values: its tangent and test functions
   read it; the tangent itself is solved in Python, Continuation.tangent).

   work: ae_work_size(kind, NDIM, npar) doubles; scratch: NDIM (NDIM + npar) for FUNC's
   DFDU/DFDP. Returns 0 converged (x, *iterations set), 1 diverging, 2 no convergence in
   itnw iterations (*iterations = itnw), 3 a non-finite residual, Jacobian or correction,
   a zero pivot or a failed f: the caller runs the Python loop; 4 converged (x,
   *iterations set) but f failed, or gave a non-finite Jacobian, at the converged point:
   jac not set (the caller evaluates the Jacobian there). */
static int ae_correct(void *ctx, int kind, int ndim, int npar, int ip, int ip2,
                      const int *icp, const double *par, const double *v_old,
                      const double *x_pred, const double *x_ref, const double *theta,
                      double ds, double epsl, double epsu, int itnw, double divergence,
                      double hmach, double h2, double *x, int *iterations, double *jac,
                      double *work, double *scratch)
{
    ae_sys sys, *S = &sys;
    ae_setup(S, ctx, kind, ndim, npar, ip, ip2, icp, par, v_old, hmach, h2, work, scratch);
    const int np1 = S->nx, m = np1 - 1;            /* unknowns, equations */
    double *M = S->M, *b = S->b, *d = S->d;
    const double ads = fabs(ds);
    double delref = -1.0;
    for (int i = 0; i < np1; i++) x[i] = x_pred[i];
    *iterations = 0;
    for (int it = 1; it <= itnw; it++) {
        if (ae_system(S, x, b, M, np1)) return 3;
        for (int i = 0; i < m; i++) {
            if (!isfinite(b[i])) return 3;
            b[i] = -b[i];
        }
        double c = 0.0;
        for (int j = 0; j < np1; j++) {
            d[j] = x[j] - x_ref[j];
            M[(size_t)m * np1 + j] = 2 * (theta[j] * d[j]) / ads;
        }
        for (int j = 0; j < np1; j++) c += M[(size_t)m * np1 + j] * d[j];
        b[m] = -(c / 2 - ads);
        if (ae_eliminate(np1, M, b)) return 3;
        if (ae_back(np1, M, b, d)) return 3;          /* d becomes the correction dx */
        for (int j = 0; j < np1; j++) x[j] += d[j];
        double mdx = 0.0, mx = 0.0;
        for (int j = 0; j < m; j++) {
            if (fabs(d[j]) > mdx) mdx = fabs(d[j]);
            if (fabs(x[j]) > mx) mx = fabs(x[j]);
        }
        double du = mdx / (1 + mx), dl = fabs(d[m]) / (1 + fabs(x[m]));
        *iterations = it;
        if (dl <= epsl && du <= epsu) {
            if (jac && ae_system(S, x, NULL, jac, np1)) return 4;
            return 0;
        }
        double size = du > dl ? du : dl;
        if (delref < 0) delref = divergence * (size > 1e-300 ? size : 1e-300);
        else if (size > delref) return 1;
    }
    return 2;
}

#endif

/* The corrector of algebraic continuation (include/ae_correct.h) for equations given in
 * Python (washer.cont.corrector_algebraic): f is evaluated by a call back into Python, which
 * calls the user's func point by point (or in one batch) exactly as the Python loop
 * does; with the user's Jacobians (JAC = 1, -1) on equilibria, [f_u, f_PAR(ICP(1))] too
 * (stage 3: Problem.jacobian, as the Python loop calls it). Compiled on first use
 * (washer.cont.user_problem.c_library), as the bridge of user files is.
 */
#include <stddef.h>
#include <string.h>

typedef int (*ae_callback)(int stage, int rows, int first, const double *us,
                           const double *ps, double *fs);

/* The context of the corrector's f: the call back, and whether it gives the Jacobian. */
typedef struct {
    ae_callback callback;
    int exact;          /* 1: stage 3 gives [f_u, f_PAR(ip + 1)]; 0: differences */
} ae_python;

static int ae_eval(void *ctx, int stage, int ndim, int npar, const int *icp, int rows,
                   int first, const double *us, const double *ps, double *fs,
                   double *scratch)
{
    (void)ndim; (void)npar; (void)icp; (void)scratch;
    return ((const ae_python *)ctx)->callback(stage, rows, first, us, ps, fs);
}

/* The call back's [f_u, f_PAR(ip + 1)] at the point (u, par) of the stage-0 rows (row 0
   of us, ps: ae_system puts it there), written (NDIM, NDIM + 1) row-major into the
   stage-0 fs, then into J with its stride. */
#define AE_EXACT_JACOBIAN 1
static int ae_exact(void *ctx, int ndim, int npar, int ip, const double *u,
                    const double *par, double *J, int stride);

#include "ae_correct.h"

static int ae_exact(void *ctx, int ndim, int npar, int ip, const double *u,
                    const double *par, double *J, int stride)
{
    (void)ip;
    const ae_python *c = (const ae_python *)ctx;
    if (!c->exact) return -1;
    /* stage 0's fs follows its us and ps in the corrector's `work` (ae_setup: par is
       stage 0's ps there): (2 k1 + 1) NDIM doubles, more than the NDIM (NDIM + 1) of
       the Jacobian; PythonEquations checks the three pointers against its views */
    const int n = ndim, r1 = 2 * (n + 1) + 1;
    double *fs = (double *)par + (size_t)r1 * npar;
    if (c->callback(3, 1, 0, u, par, fs)) return 1;
    for (int i = 0; i < n; i++)
        memcpy(J + (size_t)i * stride, fs + (size_t)i * (n + 1), sizeof(double) * (n + 1));
    return 0;
}
#include "ae_lyapunov.h"

/* ae_correct with f from `callback` (nonzero return: the evaluation failed, the corrector
   returns 3 and the caller runs the Python loop). */
int washer_ae_correct_cb(ae_callback callback, int exact, int kind, int ndim, int npar,
                         int ip, int ip2, const double *par, const double *v_old,
                         const double *x_pred, const double *x_ref, const double *theta,
                         double ds, double epsl, double epsu, int itnw, double divergence,
                         double hmach, double h2, double *x, int *iterations, double *jac,
                         double *work)
{
    ae_python ctx = {callback, exact && kind == AE_EQUILIBRIUM};
    return ae_correct(&ctx, kind, ndim, npar, ip, ip2, NULL, par, v_old, x_pred, x_ref,
                      theta, ds, epsl, epsu, itnw, divergence, hmach, h2, x, iterations, jac,
                      work, NULL);
}

/* ae_work_size, for corrector_algebraic.work_size's test. */
size_t washer_ae_work_size(int kind, int ndim, int npar)
{
    return ae_work_size(kind, ndim, npar);
}

/* ae_first_lyapunov (ae_lyapunov.h) with f from `callback` (stage 2). */
int washer_ae_l1_cb(ae_callback callback, int ndim, int npar, const double *x,
                    const double *par, double omega, const double *A, double *l1,
                    double *work)
{
    ae_python ctx = {callback, 0};
    return ae_first_lyapunov(&ctx, ndim, npar, NULL, x, par, omega, A, l1, work, NULL);
}

/* ae_l1_work_size, for corrector_algebraic.l1_work_size's test. */
size_t washer_ae_l1_work_size(int ndim, int npar)
{
    return ae_l1_work_size(ndim, npar);
}

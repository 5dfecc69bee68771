/* The corrector of algebraic continuation (include/ae_correct.h) for equations given in
 * Python (washer.cont.compiled_newton): f is evaluated by a call back into Python, which
 * calls the user's func point by point (or in one batch) exactly as the Python loop
 * does. Compiled on first use (washer.cont.compile), as the bridge of user files is.
 */
#include <stddef.h>

typedef int (*ae_callback)(int stage, int rows, int first, const double *us,
                           const double *ps, double *fs);

static int ae_eval(void *ctx, int stage, int ndim, int npar, const int *icp, int rows,
                   int first, const double *us, const double *ps, double *fs,
                   double *scratch)
{
    (void)ndim; (void)npar; (void)icp; (void)scratch;
    return (*(ae_callback *)ctx)(stage, rows, first, us, ps, fs);
}

#include "ae_correct.h"
#include "ae_lyapunov.h"

/* ae_correct with f from `callback` (nonzero return: the evaluation failed, the corrector
   returns 3 and the caller runs the Python loop). */
int washer_ae_correct_cb(ae_callback callback, int kind, int ndim, int npar, int ip, int ip2,
                         const double *par, const double *v_old, const double *x_pred,
                         const double *x_ref, const double *theta, double ds, double epsl,
                         double epsu, int itnw, double divergence, double hmach, double h2,
                         double *x, int *iterations, double *jac, double *work)
{
    return ae_correct(&callback, kind, ndim, npar, ip, ip2, NULL, par, v_old, x_pred, x_ref,
                      theta, ds, epsl, epsu, itnw, divergence, hmach, h2, x, iterations, jac,
                      work, NULL);
}

/* ae_work_size, for compiled_newton.work_size's test. */
size_t washer_ae_work_size(int kind, int ndim, int npar)
{
    return ae_work_size(kind, ndim, npar);
}

/* ae_first_lyapunov (ae_lyapunov.h) with f from `callback` (stage 2). */
int washer_ae_l1_cb(ae_callback callback, int ndim, int npar, const double *x,
                    const double *par, double omega, const double *A, double *l1,
                    double *work)
{
    return ae_first_lyapunov(&callback, ndim, npar, NULL, x, par, omega, A, l1, work, NULL);
}

/* ae_l1_work_size, for compiled_newton.l1_work_size's test. */
size_t washer_ae_l1_work_size(int ndim, int npar)
{
    return ae_l1_work_size(ndim, npar);
}

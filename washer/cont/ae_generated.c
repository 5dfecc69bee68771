/* The corrector of algebraic continuation (include/ae_correct.h) for the generated C of
 * sympy problems (washer.cont.user_problem.user_files_sympy): its washer_sym_func and
 * washer_sym_jac are
 * called through function pointers, f over all the rows of a difference stencil in one
 * call (as Problem.func_many calls the generated func_batch), and with JAC = 1 the exact
 * [f_u, f_PAR(ICP(1))] (as Problem.jacobian's dfdu and dfdp give them). Compiled on
 * first use (washer.cont.user_problem.c_library) by washer.cont.corrector_algebraic.
 */
#include <stddef.h>

typedef void (*ae_sym_func)(int k, const double *U, const double *P, int pstride, double *F);
typedef void (*ae_sym_jac)(int k, const double *U, const double *P, int pstride, double *J,
                           double *Jp);

typedef struct {
    ae_sym_func func;
    ae_sym_jac jac;     /* NULL: differences of func (JAC = 0) */
    int npar_sym;       /* the highest PAR index the expressions use (Jp's columns) */
    double *jwork;      /* NDIM (NDIM + max(npar_sym, 1)) doubles for jac's J and Jp */
} ae_generated;

static int ae_eval(void *ctx, int stage, int ndim, int npar, const int *icp, int rows,
                   int first, const double *us, const double *ps, double *fs,
                   double *scratch)
{
    (void)stage; (void)icp; (void)scratch;
    const ae_generated *g = (const ae_generated *)ctx;
    g->func(rows - first, us + (size_t)first * ndim, ps + (size_t)first * npar, npar,
            fs + (size_t)first * ndim);
    return 0;
}

#define AE_EXACT_JACOBIAN 1
static int ae_exact(void *ctx, int ndim, int npar, int ip, const double *u,
                    const double *par, double *J, int stride)
{
    (void)npar;
    const ae_generated *g = (const ae_generated *)ctx;
    if (g->jac == NULL) return -1;
    const int n = ndim, np = g->npar_sym;
    double *fu = g->jwork, *fp = g->jwork + (size_t)n * n;
    g->jac(1, u, par, 0, fu, fp);
    for (int i = 0; i < n; i++) {
        for (int j = 0; j < n; j++) J[(size_t)i * stride + j] = fu[(size_t)i * n + j];
        /* a parameter the expressions do not use: a zero column (user_files_sympy.py's dfdp) */
        J[(size_t)i * stride + n] = ip < np ? fp[(size_t)i * np + ip] : 0.0;
    }
    return 0;
}

#include "ae_correct.h"

/* ae_correct with the generated functions of `g`. */
int washer_ae_correct_gen(ae_generated *g, int ndim, int npar, int ip, const double *par,
                          const double *x_pred, const double *x_ref, const double *theta,
                          double ds, double epsl, double epsu, int itnw, double divergence,
                          double hmach, double *x, int *iterations, double *jac,
                          double *work)
{
    return ae_correct(g, AE_EQUILIBRIUM, ndim, npar, ip, -1, NULL, par, NULL, x_pred, x_ref,
                      theta, ds, epsl, epsu, itnw, divergence, hmach, 0.0, x, iterations, jac,
                      work, NULL);
}

/* The continuation engine's compiled linear algebra (washer._cont). Plain C prototypes
 * only: cffi's cdef() reads this file.
 *
 * The bordered collocation matrix of a boundary-value problem on NTST intervals of
 * NCOL collocation points, NDIM components, NPAR free parameters (washer/cont/collocation.py):
 *   unknowns  x = (U at the NTST*NCOL + 1 nodes, node-major, NDIM each; NPAR parameters),
 *             nx = (NTST*NCOL + 1)*NDIM + NPAR;
 *   rows      the NCOL*NDIM collocation equations of every interval (each touching the
 *             NCOL + 1 nodes of its interval and the parameters), then NE = NDIM + NPAR
 *             dense rows (boundary conditions, integral conditions, the border row).
 *   blocks    (NTST, NCOL*NDIM, (NCOL+1)*NDIM) row-major: d(collocation_j)/d(U_j);
 *   parcols   (NTST, NCOL*NDIM, NPAR): d(collocation_j)/d(parameters);
 *   extra     (NE, nx): the dense rows.
 * cont_bvp_factor eliminates (AUTO's CONPAR, REDUCE, DIMRGE): the interior nodes of
 * every interval (condensation of parameters, partial pivoting within the interval's
 * rows), then the interval end nodes 1..NTST-1 one after the other (partial pivoting
 * within the two blocks of rows involved), then a dense LU of what is left in
 * (U(0), U(1), parameters). It returns the determinant as sign and log|det| (unless
 * sign_logdet is NULL: cont_bvp_sign_logdet gives it later) and the pair (P0, P1) (row-major NDIM x NDIM) with P0 U(0) + P1 U(1) = 0 for every solution of
 * the collocation rows with the parameters held (the monodromy matrix is -P1^-1 P0).
 * Return values: 0 success, 1 a zero pivot (exactly singular), 2 bad sizes.
 */
typedef struct cont_bvp cont_bvp;

cont_bvp *cont_bvp_new(int ntst, int ncol, int ndim, int npar);
void cont_bvp_free(cont_bvp *f);
int cont_bvp_factor(cont_bvp *f, const double *blocks, const double *parcols,
                    const double *extra, double *sign_logdet, double *P0, double *P1);
/* The determinant of the last factorisation as sign and log|det| (the sum of the logs of
 * its pivots, in elimination order; cont_bvp_factor gives the same when its sign_logdet
 * is not NULL). Returns 1 when a pivot was zero (sign 0, log|det| = -inf), else 0. */
int cont_bvp_sign_logdet(const cont_bvp *f, double *sign_logdet);
int cont_bvp_solve(const cont_bvp *f, const double *rhs, double *x);
/* After cont_bvp_factor: the matrix with the same collocation rows (blocks, parcols) and
 * other dense rows `extra` (NE, nx), reduced onto S = (U(0), parameters):
 * Sc (NE, NDIM + NPAR) row-major, Sc = M_RS - M_RI M_II^-1 M_IS with R the dense rows and
 * I the unknowns after U(0) (the eliminations of the factorisation replayed on the new
 * rows, then U(NTST) eliminated with the reduced collocation rows). Returns 0, 1 when
 * M_II is singular, 2 when called before a factorisation. */
/* After cont_bvp_factor: the same matrix with a new border row (the last dense row, nx)
 * factorised, in place: the eliminations of the collocation rows are kept, the new row is
 * taken through them and the remaining dense system factorised again. The solves, the
 * determinant and the Floquet pair are then those cont_bvp_factor gives for the matrix
 * with that row, to the bit. Returns 0, 1 when the remaining system has a zero pivot (as
 * cont_bvp_factor), 2 when called before a factorisation, 3 when the factorisation had a
 * zero pivot before the remaining system (nothing is changed: factorise afresh). */
int cont_bvp_reborder(cont_bvp *f, const double *row);
/* cont_bvp_factor (sign_logdet NULL) of the matrix given by its values `vals` in
 * Collocation.jacobian_general's assembly order (the blocks, the parameter columns one
 * after the other, then the ntail values of the boundary and integral rows at the dense
 * rows' positions (rows, cols)) and the border row (nx): the blocks, parameter columns and
 * dense rows reduction.pieces makes of them, copied (csrc/cont/po_correct.cpp). Returns
 * cont_bvp_factor's value, or 2 for bad sizes or positions. */
int cont_bvp_factor_values(cont_bvp *fac, int ntst, int ncol, int ndim, int npar,
                           const double *vals, int ntail, const int *rows, const int *cols,
                           const double *border, double *P0, double *P1);
int cont_bvp_schur(const cont_bvp *f, const double *extra, double *Sc);
/* The BP test of cycles at a point after cont_bvp_factor of a matrix with its collocation
 * rows (washer.cont.systems.periodic's own-phase test; the Python: reduction.dense_rows,
 * PeriodicOrbits._own_phase_row, cont_bvp_schur, linalg.scaled_slogdet): the dense rows
 * (NE, nx) are zeros with the values tail (ntail) at (rows, cols), then row `phase`
 * replaced by w_node[q] * (T * F[q, i]) on the NTST*NCOL + 1 nodes (F (nodes, NDIM): f at
 * the nodes) and 0 in the parameter columns, and the last row theta * tangent (nx each);
 * reduced onto S as cont_bvp_schur into Sc (NE, NE), whose scaled determinant
 * (cont_scaled_slogdet with getrf, ddot) goes to out (3). Returns cont_scaled_slogdet's
 * value (0, 1, 2), 10 + cont_bvp_schur's where that is not 0, -1 for bad arguments. */
int cont_bvp_bp_test(const cont_bvp *f, void *getrf, void *ddot, const double *tail,
                     const int *rows, const int *cols, int ntail, int phase,
                     const double *w_node, double T, const double *F, const double *theta,
                     const double *tangent, double *Sc, double *out);

/* The collocation blocks (NTST, NCOL*NDIM, (NCOL+1)*NDIM), row-major, of the equations
 * sum_k WP[k, c] U_jk - dtm[j] T f(sum_k WT[k, c] U_jk) = 0 with respect to U_j:
 *   blocks[j, c*NDIM + i, k*NDIM + l] = WP[k, c] delta_il - dtm[j] T WT[k, c] A[j, c, i, l]
 * WT, WP (NCOL + 1, NCOL) row-major (GENWTS), dtm (NTST,), A (NTST, NCOL, NDIM, NDIM) the
 * Jacobians of f at the Gauss points. Returns 0, or 2 for bad sizes. */
int cont_coll_blocks(int ntst, int ncol, int ndim, const double *WT, const double *WP,
                     const double *dtm, double T, const double *A, double *blocks);

/* The corrector of periodic orbits (IPS 2: NBC = NDIM periodicity conditions, one integral
 * phase condition, two free parameters) on the plane arclength, the whole Newton loop in
 * one call (csrc/cont/po_correct.cpp; the compiled form of Continuation.correct with
 * PeriodicOrbits' residual and difference Jacobian). f is evaluated by
 *   feval(rows, us (rows, NDIM), pars, prow, fs (rows, NDIM)) -> 0, or nonzero when f
 *   failed; pars: one parameter vector (NPAR) for all points (prow 0), or the parameters
 *   point by point, (NPAR, prow = rows) (a Jacobian's difference points in one call, up
 *   to one_call_max Gauss points: VectorField.fu_fp's FU_FP_ONE_CALL_MAX); or, instead of feval, the generated C of a sympy problem
 *   (washer.cont.user_files_sympy: washer_sym_func, washer_sym_jac, U (k, NDIM), P with
 *   pstride 0, Jp (k, NDIM, npar_jp)) or a compiled user file's FUNC and DFDU (its
 *   bridge's washer_po_func, washer_po_jac, which leaves Jp alone) called directly: sfunc
 *   for f, sjac (or NULL: f_u by differences) for the exact f_u;
 * ddot: the BLAS ddot for the phase condition's and the border row's inner products (the
 *   one numpy's `@` calls: the same rounding), or NULL for sums in order.
 * The unknowns x = (U (NTST*NCOL + 1, NDIM) node-major, PAR(ipa + 1), PAR(ipb + 1)),
 * nx = (NTST*NCOL + 1)*NDIM + 2; the period is PAR(11) (index 10); par0 (NPAR) the other
 * parameters. WT, WP (NCOL + 1, NCOL), dtm (NTST), w_node (nodes), U_old, up_old (nodes,
 * NDIM) the phase reference, bc_offset (NDIM) or NULL, row (nx) the border row; the
 * iteration stops as Continuation.correct (EPSU, EPSL, ITNW, the divergence factor),
 * refactorising up to max(NWTN, 1) iterations. Out: x (nx) the last iterate, x_J (nx) the
 * iterate of the last factorisation, vals its Jacobian's values in
 * Collocation.jacobian_general's assembly order (NTST*NCOL*NDIM*((NCOL+1)*NDIM + 2) +
 * 2 NDIM + nx), P0, P1 (NDIM x NDIM) its Floquet pair; fac holds that factorisation;
 * info = (iterations, iteration of the last factorisation, residuals, Jacobians).
 * Returns 0 converged, 1 diverged, 2 no convergence in ITNW iterations, 3 hand over to
 * the Python loop (f failed, a non-finite residual, Jacobian or correction, a zero
 * pivot), 4 bad sizes. */
typedef int (*cont_po_feval)(int rows, const double *us, const double *pars, int prow,
                             double *fs);
typedef double (*cont_ddot)(const int *n, const double *x, const int *incx, const double *y,
                            const int *incy);
typedef void (*cont_po_sym_func)(int k, const double *U, const double *P, int pstride,
                                 double *F);
typedef void (*cont_po_sym_jac)(int k, const double *U, const double *P, int pstride,
                                double *J, double *Jp);
int cont_po_correct(cont_bvp *fac, cont_po_feval feval, cont_po_sym_func sfunc,
                    cont_po_sym_jac sjac, int npar_jp, cont_ddot ddot, int ntst, int ncol,
                    int ndim, int npar, int ipa, int ipb, const double *WT, const double *WP,
                    const double *dtm, const double *w_node, const double *U_old,
                    const double *up_old, const double *bc_offset, const double *par0,
                    const double *x_pred, const double *x_ref, const double *row, double ds,
                    double epsl, double epsu, int itnw, int nwtn, double divergence,
                    double fd_step, int one_call_max, double *x, double *x_J,
                    double *vals, double *P0, double *P1, int *info);
/* The Jacobian of cont_po_correct's iterations at one point x (nx), the same values as
 * an iteration there gives (the phase row from w_node and up_old): vals in
 * Collocation.jacobian_general's assembly order, f evaluated as in cont_po_correct (the
 * Gauss points, then the difference points). Returns 0, 3 when f failed or a value is
 * not finite, 4 bad sizes. */
int cont_po_jacobian(cont_po_feval feval, cont_po_sym_func sfunc, cont_po_sym_jac sjac,
                     int npar_jp, int ntst, int ncol, int ndim, int npar, int ipa, int ipb,
                     const double *WT, const double *WP, const double *dtm,
                     const double *w_node, const double *up_old, const double *par0,
                     const double *x, double fd_step, int one_call_max, double *vals);

/* Fortran's ESw.d (exp3 = 0) and ESw.dE3 (exp3 = 1) edit descriptors as gfortran writes
 * them, the text of AUTO-07p's b-, s- and d-files (csrc/cont/es_format.cpp; the reference
 * is washer.auto.es_format's Python formatter, which the tests hold it to):
 * v (k, m) row-major; each value right-justified in `width` characters (never cut): a
 * sign if negative (-0.0 too), one digit, '.', `digits` digits (correctly rounded, ties
 * to even), then 'E' and a signed 2-digit exponent, or with exp3 (or for a 2-digit-wide
 * exponent beyond 99 without exp3, then without the 'E') a signed 3-digit one; NaN
 * (either sign) as 'NaN', the infinities as 'Infinity' and '-Infinity'. Lines of at
 * most `per_line` values, each starting with `indent` blanks; a row always starts a new
 * line; lines are separated by '\n' (none at the end). out holds at least
 * k * m * max(width, digits + 8) + k * ceil(m / per_line) * (indent + 1) + 1 characters
 * (a value's text is at most digits + 8 wide); a NUL ends the text. Returns its length
 * (-1 for bad arguments). */
int cont_format_es(const double *v, int k, int m, int per_line, int indent, int width,
                   int digits, int exp3, char *out);

/* A continuation point's text in AUTO's b- and d-files (io.f90 WRLINE, ae.f90 PRINTEIG;
 * csrc/cont/auto_point.cpp, the numbers by es_format.cpp's field; the reference is
 * washer.auto.es_format.python_point_text): with n >= 0 the b-file line
 * (I4 br, I6 pt, I4 ty, I5 lab, the n values v in ES19.10E3, a newline), then in the
 * d-file text `dhead` as given (the bar and the screen heading), the screen line (I4 br,
 * I6 pt, a blank, `name` right-justified in 3, I5 lab, the first min(n, 8) values in
 * ES14.5, a newline); with neig >= 0 PRINTEIG's block: a newline, I4 ebr, I6 ept,
 * '         Eigenvalues  :   Stable:' and I4 the count of real parts below 0, then per
 * eigenvalue a newline, I4 ebr, I6 ept, '         Eigenvalue', I3 its number, ':', its
 * real and imaginary parts in ES14.5, and a final newline; with neig >= 0 and nstable >= 0
 * instead PVSPBV's Floquet block: I4 ebr, I6 ept, '         Multipliers:     Stable:' and
 * I4 nstable, then per multiplier a newline, I4 ebr, I6 ept, '         Multiplier', I3 its
 * number, a blank, its real and imaginary parts and its modulus (hypot) in ES14.5, the
 * modulus after '  Abs. Val.', and a final newline. eig: neig real parts (cplx = 0,
 * imaginary parts 0.0) or neig (re, im) pairs (cplx = 1). Integers are right-justified
 * and never cut. out: the b text, then the d text, then a NUL; *blen the b text's length;
 * returns the whole length. out holds at least 80 + 20 n + strlen(name) + strlen(dhead) +
 * 8 * 14 + 40 + neig * 90 characters. */
int cont_auto_point(int br, int pt, int ty, int lab, const char *name, const double *v, int n,
                    const char *dhead, int ebr, int ept, const double *eig, int neig, int cplx,
                    int nstable, char *out, int *blen);

/* A small dense matrix's LU and eigenvalues by numpy's own LAPACK (csrc/cont/dense_lapack.cpp;
 * the routines' addresses from washer.cont.lapack: numpy's bundled OpenBLAS, 64-bit integers),
 * the values numpy.linalg's solve, slogdet and eigvals give, bit for bit.
 * cont_dense_lu: GETRF of M (n x n, row stride ldm; with `last` not NULL, M's first n - 1
 * rows and then the row `last` (n)) copied into lu (n * n, Fortran order);
 * ipiv (n) its pivots; sign_logdet (2) numpy's slogdet of M ((0, -inf) where GETRF finds an
 * exact zero pivot). Returns GETRF's info (-1 bad sizes).
 * cont_dense_lu_solve: x (n) = M^-1 b by GETRS on cont_dense_lu's factors (GESV's values).
 * Returns GETRS's info, or 1 where x is not finite.
 * cont_eigenvalues_sorted: GEEV's eigenvalues of A (n x n, row stride lda) with numpy's
 * workspace (GEEV's own answer to a query, made where *lwork <= 0 and kept in *lwork), as
 * (re, im) pairs in w (2 n) by decreasing real part (equal real parts in GEEV's order); work
 * holds n * n + 2 n + lwork_max doubles. Returns 0 (some complex), 4 (all
 * real), 1 (A not finite), 2 (GEEV failed or a value not finite), 3 (lwork_max too small),
 * -1 bad sizes. */
int cont_dense_lu(void *getrf, int n, const double *M, int ldm, const double *last, double *lu,
                  int64_t *ipiv, double *sign_logdet);
/* cont_scaled_slogdet: the BP test's determinant of S (n x n, row-major) as
 * washer.cont.systems.bvp's bp_value takes it with numpy: out[0] = numpy.linalg.norm(S)
 * (sqrt(0.0 + DDOT(S, S)), ddot numpy's CBLAS ddot), out[1], out[2] numpy's slogdet of
 * S / out[0] (cont_dense_lu). work: 2 n * n doubles, ipiv n. Returns 0, 1 (the norm is 0 or
 * not finite: out[1], out[2] untouched), 2 (GETRF found an exact zero pivot: (0, -inf)),
 * -1 bad sizes. */
int cont_scaled_slogdet(void *getrf, void *ddot, int n, const double *S, double *work,
                        int64_t *ipiv, double *out);
int cont_dense_lu_solve(void *getrs, int n, const double *lu, const int64_t *ipiv,
                        const double *b, double *x);
int cont_eigenvalues_sorted(void *geev, int n, const double *A, int lda, double *w,
                            double *work, int lwork_max, int *lwork);

/* The Floquet multipliers of the pair (P0, P1) (n x n each, row-major; P0 y(0) + P1 y(1) =
 * 0) with the trivial one deflated first, washer.cont.floquet's deflated pencil and QZ
 * (csrc/cont/floquet.cpp): the same calls of the same libraries as its Python, so the same
 * bits. routines: numpy's GESDD, CBLAS DGEMM, DGEMV and DDOT (ILP64) and scipy's DGGEV
 * (LP64) (washer.cont.lapack.floquet_routines). mu (2 n): (re, im) pairs, the trivial
 * multiplier first, then DGGEV's order; non-finite quotients are (inf, 0). lwork (2):
 * GESDD's and DGGEV's workspace, asked for where <= 0 and kept (functions of n alone).
 * Returns 0, or 1 (n < 2 or something not finite to deflate by), 2 (GESDD failed),
 * 3 (DGGEV failed or an infinite eigenvalue): the Python then computes them itself. */
int cont_floquet_deflated(void *const *routines, int n, const double *P0, const double *P1,
                          double *mu, int64_t *lwork);
/* The multipliers mu (n (re, im) pairs) in AUTO's order, washer.cont.floquet.sort_multipliers
 * made as numpy makes it (the same values of numpy's complex absolute value): with trivial,
 * the one of least |mu - 1| first (the first such; nan distances never win), then the others
 * by ||mu| - 1|, ties in their order, nan last. out (2 n). Returns 0, 1 (trivial and every
 * distance nan: the Python raises), -1 (n <= 0). */
int cont_multipliers_sorted(int n, const double *mu, int trivial, double *out);
/* cont_floquet_deflated, then cont_multipliers_sorted with the trivial one, in one call
 * (washer.cont.floquet.pencil_multipliers with the trivial multiplier deflated): mu (2 n)
 * in AUTO's order. Returns 0, cont_floquet_deflated's value where it is not 0 (mu
 * undefined), or 5 where the sort failed (mu then holds the unsorted multipliers). */
int cont_floquet_multipliers(void *const *routines, int n, const double *P0, const double *P1,
                             double *mu, int64_t *lwork);

/* The test functions of the fold locus of equilibria at a point (washer.cont.systems.fold;
 * csrc/cont/fold_tests.cpp), numpy's values bit for bit. routines: numpy's GESDD, CBLAS
 * DDOT and GEEV (ILP64; washer.cont.lapack.routines). A (n x n, row stride lda) = f_u.
 * w (n): the left null vector of A, the last right singular vector of A^T by GESDD (JOBZ
 * 'A'), turned where <w, w_ref> >= 0 fails. With phi (n) not NULL, out[0] = <w, phi> (BT);
 * with F (3 x n: f at u + h phi, u, u - h phi) not NULL, out[1] = <w, (F[0] - 2 F[1] +
 * F[2]) / h2> (CP); with geev_lwork not NULL (GEEV's workspace, asked for where <= 0 and
 * kept), out[2] the product of the real parts of the eigenvalues of A with Im > 0 and
 * |Im| > imag_tol (1 + |lambda|), in the order of cont_eigenvalues_sorted, out[3] 1 where
 * there is one, else 0 (ZH). lwork (1): GESDD's workspace, asked for where <= 0 and kept.
 * Returns 0, 1 (GESDD failed or a singular value nan), 2 (A not finite for GEEV), 3 (GEEV
 * failed), 4 (its workspace beyond 64 n), -1 (bad sizes). */
int cont_fold_tests(void *const *routines, int n, const double *A, int lda,
                    const double *w_ref, const double *phi, const double *F, double h2,
                    double imag_tol, double *w, double *out, int64_t *lwork, int *geev_lwork);

/* The unit tangent of a dense algebraic point (washer.cont.linalg.unit_tangent): border (n) =
 * theta * ref elementwise, cont_dense_lu of [J; border] (J (n - 1) x n, row stride ldj) into
 * lu (n * n + n doubles: the factors, then room for the norm's terms), ipiv, sign_logdet and
 * *info (GETRF's); z = [J; border]^-1 e_n by cont_dense_lu_solve; t (n) = z / sqrt|<z, z>|
 * with <a, b> = sum(theta * a * b) summed as numpy sums it. Returns 0 (t the unit tangent),
 * 1 (GETRF found an exact zero pivot), 2 (z not finite, or its norm 0, not finite or above
 * big), -1 (bad sizes); on 1 and 2 t is not the tangent. */
int cont_ae_tangent(void *getrf, void *getrs, int n, const double *J, int ldj,
                    const double *ref, const double *theta, double big, double *border,
                    double *lu, int64_t *ipiv, double *sign_logdet, int *info, double *t);

/* An equilibrium's point values after its corrector in one call (washer.cont.systems.
 * equilibrium.EquilibriumSystem.point_values): J = [f_u f_PAR] (ndim x (ndim + 1),
 * row-major, ndim <= 8). routines: numpy's GETRF, GETRS and GEEV. First cont_ae_tangent
 * with n = ndim + 1 (border, lu (n * n + n), ipiv, sign_logdet, info, t as there); then
 * cont_eigenvalues_sorted of f_u into w (2 ndim) with ework (ndim^2 + 2 ndim + lwork_max)
 * and *lwork as there; then out[0] = equilibrium.neutral_tolerance of f_u (conservative_tol
 * where ndim is even and |trace| < trace_tol max |f_u[i, j]|, else 0), out[1] the count of
 * real parts <= out[0] (stable_count), out[2] the index in w of equilibrium.hopf_pair's
 * eigenvalue (|Im| > imag_tol (1 + hypot), the least |Re|, the first of equal ones; -1
 * for none or all real), out[3] 1 where all are real (w's imaginary parts 0), else 0.
 * Returns 0; 1, 2 the tangent's status (nothing else computed); 11, 12, 13 the
 * eigenvalues' statuses 1, 2, 3 plus 10 (A not finite, GEEV failed, lwork_max too small);
 * -1 bad sizes (ndim outside 1..8). */
int cont_ae_equilibrium_point(void *const *routines, int ndim, const double *J,
                              const double *ref, const double *theta, double big,
                              double imag_tol, double trace_tol, double conservative_tol,
                              double *border, double *lu, int64_t *ipiv, double *sign_logdet,
                              int *info, double *t, double *w, double *ework, int lwork_max,
                              int *lwork, double *out);

/* ADAPT's interpolation (csrc/cont/adapt.cpp; washer.cont.collocation.evaluator): for
 * each time t[i] of nt, the interval j[i] of the mesh tm (NTST + 1,) with lengths dtm
 * (NTST,) it lies in (numpy's searchsorted 'right' less one, clipped to 0..NTST-1) and the
 * weights W (NCOL + 1, nt) row-major of the NCOL + 1 equally spaced nodes of that interval
 * (the Lagrange basis at z = (t - tm[j]) / dtm[j]; others (NCOL, NCOL + 1) row-major, the
 * other nodes of each basis function, and denom (NCOL + 1,), their products, as
 * collocation._lagrange_nodes gives them). Returns 0; 1 where tm is not increasing or a
 * time is NaN (nothing is written: numpy computes it); 2 for bad sizes. */
int cont_mesh_weights(int ntst, int ncol, const double *tm, const double *dtm, int nt,
                      const double *t, const double *others, const double *denom, int *j,
                      double *W);
/* out (nt, width) row-major: the sum over k = 0..NCOL of W[k, i] U[j[i] NCOL + k, :], in
 * order from 0.0, for U (n_nodes, width) row-major. */
void cont_mesh_apply(int nt, int ncol, const int *j, const double *W, const double *U,
                     int width, double *out);
/* ADAPT's new mesh (csrc/cont/adapt.cpp; washer.cont.collocation.new_mesh: EQDF, NEWMSH) of
 * ntst_new intervals, tm_new (ntst_new + 1,), for the profile U (NTST*NCOL + 1, ndim)
 * row-major on the mesh tm (NTST + 1,) with lengths dtm: periodic != 0 wraps EQDF's last
 * jump around; cntdif (NCOL + 1,) CNTDIF's weights; small EQDF's threshold of a zero
 * derivative; pow_loop, pow_data numpy's power loop for doubles and its data. Returns 0;
 * 1 where EQDF is not finite or not non-decreasing after NEWMSH's perturbation (nothing
 * is written: numpy computes it); 2 for bad sizes. */
int cont_new_mesh(int ntst, int ncol, int ndim, const double *tm, const double *dtm,
                  const double *U, int periodic, const double *cntdif, double small,
                  void *pow_loop, void *pow_data, int ntst_new, double *tm_new);
/* ADAPT's mesh in one call (csrc/cont/adapt.cpp; washer.cont.collocation.adapt): the new
 * mesh of the same NTST (cont_new_mesh's arguments) tm_new (NTST + 1,), its interval
 * lengths dtm_new (NTST,), node times t_new and node weights w_new (NTST*NCOL + 1,) as
 * Mesh.node_times and Mesh.node_weights compute them (wi (NCOL + 1,): WINT's weights),
 * and the interpolation from the old mesh onto t_new, j and W as cont_mesh_weights gives
 * them (others, denom its arguments). Returns cont_new_mesh's status where it is not 0,
 * else cont_mesh_weights'. */
int cont_adapt_mesh(int ntst, int ncol, int ndim, const double *tm, const double *dtm,
                    const double *U, int periodic, const double *cntdif, double small,
                    void *pow_loop, void *pow_data, const double *others,
                    const double *denom, const double *wi, double *tm_new, double *dtm_new,
                    double *t_new, double *w_new, int *j, double *W);
/* After cont_bvp_factor (or cont_bvp_reborder) of a matrix M (nx, nx) without a zero pivot:
 * the unit tangent t = z / sqrt|<z, theta z>| of z = M^-1 e_nx (csrc/cont/bvp_tangent.cpp),
 * <a, b> = 0.0 + ddot(a, theta b) with ddot numpy's own CBLAS ddot (numpy's dot of two
 * vectors). Returns 0; 1 where z is not finite or its norm is 0, not finite or above big
 * (t then holds z or its division partly done: the caller computes it again); 2 for bad
 * arguments. */
int cont_bvp_unit_tangent(const cont_bvp *f, int nx, const double *theta, double big,
                          void *ddot, double *t);

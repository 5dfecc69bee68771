/* washer kernel C ABI. Plain C prototypes only: cffi's cdef() reads this file.
 *
 * Conventions
 *   P      kernel parameter vector, length washer_n_params(), order of washer/machine/layout.py
 *          (Omega in Hz, everything else SI).
 *   u      ground-frame state (q, q_dot), length 12 (eq 48).
 *   xi     rotating-frame state (eps, eps_dot), length 12 (eq 59).
 *   law    speed law of theta(t): 0 constant speed, 1 spin-up of eq 66.
 *   frame  rotating-frame variant: 0 frozen at tau = P[tau0], 1 averaged over tau.
 *   J      row-major 12x12 Jacobian d(rhs)/d(state); Jp row-major 12 x washer_n_diff()
 *          derivative with respect to the parameters of washer_diff_param(); either may be NULL.
 *   Return value: 0 success, otherwise a WASHER_E* code (washer_error_message()).
 * Every call is re-entrant; cffi releases the GIL around it.
 */

int washer_n_params(void);
int washer_n_rods(void);
int washer_n_diff(void);
int washer_diff_param(int column);              /* kernel index of Jp column */
const char *washer_param_name(int index);
const char *washer_inputs_hash(void);
const char *washer_error_message(int code);

/* M(q, theta) (row-major 6x6, eq 49) and f (eq 48) for given theta, w, w_dot. */
int washer_mass_forces(const double *q, const double *qd, double theta, double w, double wd,
                       const double *P, double *M, double *f);
/* theta, theta_dot, theta_ddot (rad, rad/s, rad/s^2) of the speed law at time t. */
int washer_speed_law(double t, const double *P, int law, double *theta3);

int washer_rhs_fixed(double t, const double *u, const double *P, int law, double *du);
int washer_jac_fixed(double t, const double *u, const double *P, int law, double *J, double *Jp);
int washer_rhs_rot(const double *xi, const double *P, int frame, double *dxi);
int washer_jac_rot(const double *xi, const double *P, int frame, double *J, double *Jp);

/* Batched forms: n states (row i at u + 12 i); parameter set i at P + i*pstride
 * (pstride 0: one set for all). t has n entries. Stops at the first failure:
 * *nfail (if not NULL) receives its index, or -1. */
int washer_rhs_fixed_batch(int n, const double *t, const double *u, const double *P, int pstride,
                           int law, double *du, int *nfail);
int washer_rhs_rot_batch(int n, const double *xi, const double *P, int pstride, int frame,
                         double *dxi, int *nfail);
int washer_jac_rot_batch(int n, const double *xi, const double *P, int pstride, int frame,
                         double *J, double *Jp, int *nfail);
/* The rhs and its Jacobians together, for n states (the rhs is a by-product of the
 * Jacobians: the same values as washer_rhs_rot_batch's, bit for bit). jp_columns: the
 * columns of Jp computed (bit j: column j), the others 0; a column's values are the same
 * whatever else is asked for (the parameter derivatives not asked for are skipped). */
int washer_rhs_jac_rot_batch(int n, const double *xi, const double *P, int pstride, int frame,
                             double *dxi, double *J, double *Jp, unsigned jp_columns,
                             int *nfail);

/* Interrupting long work. Integrations check a process-wide flag between steps
 * and return WASHER_EINTERRUPTED when it is set. While one runs, SIGINT (Ctrl-C)
 * sets the flag and is passed on to the handler installed before (Python's, which
 * raises KeyboardInterrupt when the call returns); with no handler (SIG_DFL,
 * SIG_IGN) SIGINT keeps its usual effect. washer_request_interrupt sets the flag
 * from any thread; each integration started while none runs clears it. */
void washer_request_interrupt(void);
int washer_interrupt_pending(void);

/* Adaptive Dormand-Prince 5(4) integration with dense output.
 * system: 0 ground frame (mode = law), 1 rotating frame (mode = frame).
 * Integrates from t0 with state y0 (12) and writes y(tout[k]) into yout + 12 k,
 * for nout finite, non-decreasing times tout[k] (those <= t0 get y0); a NaN or
 * infinite time is WASHER_ENONFINITE_INPUT, a decreasing one WASHER_EBAD_ARGUMENT.
 * *h_io: initial step in (<= 0: automatic), last accepted step out. stats[0..3] += evaluations, accepted, rejected steps;
 * stats[4] = number of outputs written. max_steps <= 0: no limit. */
int washer_integrate(int system, int mode, double t0, const double *y0, const double *P,
                     double rtol, double atol, int nout, const double *tout, double *yout,
                     double *h_io, long max_steps, long *stats);

/* Ground-frame flow with variational equations, in one DOPRI5 run (mode = law):
 * u1 = u(t1) from u(t0) = u0 (12), Phi = du(t1)/du0 (row-major 12x12; over one period
 * t1 - t0 = 1/Omega at constant speed: the monodromy matrix), and s = du(t1)/dp along
 * the direction dir (length washer_n_diff(), weights of the Jp columns; NULL: s = 0).
 * Error control covers the flow and its derivatives. u1, Phi, s may be NULL;
 * h_io, max_steps and stats as for washer_integrate. */
int washer_flow_variational(int law, double t0, double t1, const double *u0, const double *P,
                            const double *dir, double rtol, double atol, double *u1,
                            double *Phi, double *s, double *h_io, long max_steps, long *stats);

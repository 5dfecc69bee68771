// The washer kernel: the ground-frame system (eq 48), the rotating-frame
// system (eqs 52-59, frozen or averaged over the frame angle), analytic
// Jacobians in state and parameters, and batched evaluation.
//
// The generated code gives M(q, theta) and f(q, qd, theta, w, wd); here M a = f
// is solved numerically (Cholesky, M is SPD) and every Jacobian is assembled
// from generated derivatives with one factorization:
//   da/dx = M^-1 (df/dx - d(M a)/dx |_{a fixed}).
#include <cmath>
#include <cstring>
#include <vector>

#include "dynamics.hpp"
#include "washer.h"

namespace washer {

static constexpr double TWO_PI = 6.283185307179586476925286766559;

bool all_finite(const double *x, int n) {
    for (int i = 0; i < n; ++i)
        if (!std::isfinite(x[i])) return false;
    return true;
}

// Speed law of the basket: constant speed, or the spin-up of eq 66,
// theta_dot = Omega (1 - exp(-t / tau_s)), Omega converted from Hz to rad/s.
int speed_law(double t, const double *P, int law, Speed &s) {
    const double W = TWO_PI * P[WP_Omega];
    if (law == 0) {
        s = {W * t, W, 0.0, TWO_PI * t, TWO_PI, 0.0};
        return WASHER_OK;
    }
    if (law != 1) return WASHER_EBAD_ARGUMENT;
    const double ts = P[WP_tau_s];
    if (!(ts > 0.0)) return WASHER_EBAD_ARGUMENT;
    const double e = std::exp(-t / ts);
    const double th1 = t - ts * (1.0 - e), w1 = 1.0 - e, wd1 = e / ts;
    s = {W * th1, W * w1, W * wd1, TWO_PI * th1, TWO_PI * w1, TWO_PI * wd1};
    return WASHER_OK;
}

// The right-hand sides of da/dq (6), da/dqd (6), da/d(theta, w, wd) (3) and da/dP, row-major.
using DerivRhs = Eigen::Matrix<double, 6, 15 + WASHER_N_SYMDIFF, Eigen::RowMajor>;

// M X = B in place for X, with M = L L^T and L the lower triangle of `llt` (Eigen's
// matrixLLT()): forward, then back substitution, a row of B at a time (each row
// operation one vectorisable loop over all right-hand sides). Eigen's own solve of a
// matrix right-hand side takes its blocked path (packing, a GEMM kernel), four times
// these instructions on a 6 x 6 factor; the two round differently (the order of each
// entry's sum), each within the factor's rounding error.
static void cholesky_solve_rows(const Mat6 &llt, DerivRhs &B) {
    double inv[6];
    for (int i = 0; i < 6; ++i) inv[i] = 1.0 / llt(i, i);
    for (int i = 0; i < 6; ++i) {               // L Y = B
        for (int k = 0; k < i; ++k) B.row(i) -= llt(i, k) * B.row(k);
        B.row(i) *= inv[i];
    }
    for (int i = 5; i >= 0; --i) {              // L^T X = Y
        for (int k = i + 1; k < 6; ++k) B.row(i) -= llt(k, i) * B.row(k);
        B.row(i) *= inv[i];
    }
}

int accelerations(const double *q, const double *qd, double th, double w, double wd,
                  const double *P, bool derivs, Accel &out, unsigned pmask) {
    RowMat6 M;
    Vec6 f;
    washer_gen_mf(q, qd, th, w, wd, P, M.data(), f.data());
    if (!M.allFinite() || !f.allFinite()) return WASHER_ENONFINITE_OUTPUT;
    Eigen::LLT<Mat6> llt(M);
    if (llt.info() != Eigen::Success) return WASHER_ESINGULAR_MASS;
    // Cholesky succeeds on nearly singular matrices; refuse a tiny pivot.
    const Vec6 diag = llt.matrixLLT().diagonal();
    if (diag.minCoeff() <= 1e-12 * diag.maxCoeff()) return WASHER_ESINGULAR_MASS;
    out.a = llt.solve(f);
    if (!derivs) return out.a.allFinite() ? WASHER_OK : WASHER_ENONFINITE_OUTPUT;

    RowMat6 fq, fqd, Gq;
    Vec6 fth, fw, fwd, Gth;
    Mat6xS fp, Gp;
    washer_gen_derivs(q, qd, th, w, wd, P, out.a.data(), fq.data(), fqd.data(), fth.data(),
                      fw.data(), fwd.data(), fp.data(), Gq.data(), Gth.data(), Gp.data(),
                      pmask);
    // All derivatives' right-hand sides side by side, solved in one pass (below).
    DerivRhs B;
    B << fq - Gq, fqd, fth - Gth, fw, fwd, fp - Gp;
    cholesky_solve_rows(llt.matrixLLT(), B);
    out.a_q = B.leftCols<6>();
    out.a_qd = B.middleCols<6>(6);
    out.a_th = B.col(12);
    out.a_w = B.col(13);
    out.a_wd = B.col(14);
    out.a_p = B.rightCols<WASHER_N_SYMDIFF>();
    return WASHER_OK;
}

// Column j of a parameter Jacobian: symbolic column of the same parameter.
static inline int symbolic_column(int j) { return j < WASHER_DIFF_OMEGA_COL ? j : j - 1; }

// ---------------------------------------------------------------- ground frame (eq 48)

// Accelerations at state u = (q, qd) and time t, theta(t) from the speed law.
static int fixed_accelerations(double t, const double *u, const double *P, int law, bool derivs,
                               Speed &s, Accel &A) {
    if (!all_finite(u, 12) || !std::isfinite(t)) return WASHER_ENONFINITE_INPUT;
    int rc = speed_law(t, P, law, s);
    if (rc) return rc;
    return accelerations(u, u + 6, s.th, s.w, s.wd, P, derivs, A);
}

int rhs_fixed(double t, const double *u, const double *P, int law, double *du) {
    Speed s;
    Accel A;
    int rc = fixed_accelerations(t, u, P, law, false, s, A);
    if (rc) return rc;
    std::memcpy(du, u + 6, 6 * sizeof(double));
    Eigen::Map<Vec6>(du + 6) = A.a;
    return WASHER_OK;
}

int jac_fixed(double t, const double *u, const double *P, int law, double *J, double *Jp) {
    return rhs_jac_fixed(t, u, P, law, nullptr, J, Jp);
}

int rhs_jac_fixed(double t, const double *u, const double *P, int law, double *du, double *J,
                  double *Jp) {
    Speed s;
    Accel A;
    int rc = fixed_accelerations(t, u, P, law, true, s, A);
    if (rc) return rc;
    if (du) {
        std::memcpy(du, u + 6, 6 * sizeof(double));
        Eigen::Map<Vec6>(du + 6) = A.a;
    }
    if (J) {
        Eigen::Map<Mat12> Jm(J);
        Jm.setZero();
        Jm.block<6, 6>(0, 6).setIdentity();
        Jm.block<6, 6>(6, 0) = A.a_q;
        Jm.block<6, 6>(6, 6) = A.a_qd;
    }
    if (Jp) {
        Eigen::Map<Mat12xD> Jpm(Jp);
        Jpm.setZero();
        for (int j = 0; j < WASHER_N_DIFF; ++j)
            Jpm.block<6, 1>(6, j) = (j == WASHER_DIFF_OMEGA_COL)
                ? Vec6(A.a_th * s.th_O + A.a_w * s.w_O + A.a_wd * s.wd_O)
                : Vec6(A.a_p.col(symbolic_column(j)));
    }
    return WASHER_OK;
}

// -------------------------------------------------------- rotating frame (eqs 52-59)

// H(tau) of eq 54 and its first two tau-derivatives. H rotates (x, y) and
// (alpha, beta) by tau (eq 52 with erratum 7); H is orthogonal, H^-1 = H^T.
// H' = H K and H'' = -H D, with K the generator of the two rotations (K(b, b+1) = -1,
// K(b+1, b) = 1 for b = 0, 3) and D = K^T K (1 on the four rotated coordinates).
struct FrameMatrices {
    Mat6 H, H1, H2;
    double c, s;                          // cos(tau), sin(tau)
    FrameMatrices(double c_, double s_) : c(c_), s(s_) {
        H.setZero(); H1.setZero(); H2.setZero();
        for (int b : {0, 3}) {
            H(b, b) = c;  H(b, b + 1) = -s; H(b + 1, b) = s;  H(b + 1, b + 1) = c;
            H1(b, b) = -s; H1(b, b + 1) = -c; H1(b + 1, b) = c; H1(b + 1, b + 1) = -s;
            H2(b, b) = -c; H2(b, b + 1) = s;  H2(b + 1, b) = -s; H2(b + 1, b + 1) = -c;
        }
        H(2, 2) = H(5, 5) = 1.0;
    }
    explicit FrameMatrices(double tau) : FrameMatrices(std::cos(tau), std::sin(tau)) {}
    // X <- X H (columns b, b+1 of each rotated pair mixed)
    template <class M> void times_H(M &X) const {
        for (int b : {0, 3}) {
            for (int i = 0; i < X.rows(); ++i) {
                const double u = X(i, b), v = X(i, b + 1);
                X(i, b) = c * u + s * v;
                X(i, b + 1) = c * v - s * u;
            }
        }
    }
    // X <- H^T X (rows b, b+1 mixed)
    template <class M> void Ht_times(M &X) const {
        for (int b : {0, 3}) {
            for (int j = 0; j < X.cols(); ++j) {
                const double u = X(b, j), v = X(b + 1, j);
                X(b, j) = c * u + s * v;
                X(b + 1, j) = c * v - s * u;
            }
        }
    }
};

// The frames of the averaged system, tau_k = 2 pi k / N_AVERAGE (cos and sin once).
static const FrameMatrices &averaged_frame(int k) {
    static const auto frames = [] {
        std::vector<FrameMatrices> out;
        for (int i = 0; i < N_AVERAGE; ++i) out.emplace_back(TWO_PI * i / N_AVERAGE);
        return out;
    }();
    return frames[k];
}

// eps_ddot of eq 57 at one frame angle tau (theta = tau, constant speed):
//   M (H eps_dd + H'' w^2 eps + 2 H' w eps_d) = f(H eps, w H' eps + H eps_d, tau, w, 0).
// Accumulates `weight` times the result (and its derivatives) into the outputs.
// jp_columns: the columns of Jp computed (bit j: column j), the others left as they are.
static int rot_at(const FrameMatrices &F, double tau, const double *xi, const double *P,
                  double weight, Vec6 &dd, Mat12 *J, Mat12xD *Jp, unsigned jp_columns) {
    const double w = TWO_PI * P[WP_Omega];
    const Eigen::Map<const Vec6> eps(xi), epsd(xi + 6);
    const Vec6 q = F.H * eps;
    const Vec6 qd = w * F.H1 * eps + F.H * epsd;
    Accel A;
    unsigned pmask = 0;                     // the symbolic columns Jp's columns need
    for (int j = 0; j < WASHER_N_DIFF; ++j)
        if (Jp && j != WASHER_DIFF_OMEGA_COL && (jp_columns >> j & 1u))
            pmask |= 1u << symbolic_column(j);
    int rc = accelerations(q.data(), qd.data(), tau, w, 0.0, P, J || Jp, A, pmask);
    if (rc) return rc;
    const Mat6 Ht = F.H.transpose();
    dd += weight * Ht * (A.a - w * w * F.H2 * eps - 2.0 * w * F.H1 * epsd);
    if (!J && !Jp) return WASHER_OK;
    // With H' = H K and H'' = -H D the derivatives are rotations of rows and columns,
    // not 6 x 6 products: d/deps = H^T a_q H + w (H^T a_qd H) K + w^2 D and
    // d/deps_d = H^T a_qd H - 2 w K.
    Mat6 Y = A.a_qd;
    F.times_H(Y);
    Mat6 X = A.a_q;
    F.times_H(X);
    for (int b : {0, 3}) {                  // X + w Y K
        X.col(b) += w * Y.col(b + 1);
        X.col(b + 1) -= w * Y.col(b);
    }
    F.Ht_times(Y);                          // H^T a_qd H
    if (J) {
        F.Ht_times(X);
        Mat6 Jd = Y;
        for (int b : {0, 3}) {
            X(b, b) += w * w;
            X(b + 1, b + 1) += w * w;
            Jd(b, b + 1) += 2.0 * w;
            Jd(b + 1, b) -= 2.0 * w;
        }
        J->block<6, 6>(6, 0) += weight * X;
        J->block<6, 6>(6, 6) += weight * Jd;
    }
    if (Jp) {
        // w = 2 pi Omega enters f, qd, H' w and H'' w^2:
        //   d/dOmega = 2 pi (H^T a_w + (H^T a_qd H) K eps + 2 w D eps - 2 K eps_d)
        Vec6 a_w = A.a_w;
        F.Ht_times(a_w);
        Vec6 Keps = Vec6::Zero(), v = Vec6::Zero();
        for (int b : {0, 3}) {
            Keps(b) = -eps(b + 1);
            Keps(b + 1) = eps(b);
            v(b) = 2.0 * w * eps(b) + 2.0 * epsd(b + 1);
            v(b + 1) = 2.0 * w * eps(b + 1) - 2.0 * epsd(b);
        }
        if (jp_columns >> WASHER_DIFF_OMEGA_COL & 1u)
            Jp->block<6, 1>(6, WASHER_DIFF_OMEGA_COL) += weight * (TWO_PI * (a_w + Y * Keps + v));
        Mat6xS a_p = A.a_p;
        F.Ht_times(a_p);
        for (int j = 0; j < WASHER_N_DIFF; ++j)
            if (j != WASHER_DIFF_OMEGA_COL && (jp_columns >> j & 1u))
                Jp->block<6, 1>(6, j) += weight * a_p.col(symbolic_column(j));
    }
    return WASHER_OK;
}

static constexpr unsigned ALL_DIFF = (1u << WASHER_N_DIFF) - 1;

// f, f_u and the columns jp_columns of f_p (bit j: Jp's column j; the others are 0) of
// the rotating frame; any output may be NULL.
static int rot_eval(const double *xi, const double *P, int frame, double *dxi, double *J,
                    double *Jp, unsigned jp_columns = ALL_DIFF) {
    if (!all_finite(xi, 12)) return WASHER_ENONFINITE_INPUT;
    if (frame != 0 && frame != 1) return WASHER_EBAD_ARGUMENT;
    Vec6 dd = Vec6::Zero();
    Mat12 Jm;
    Mat12xD Jpm;
    if (J) { Jm.setZero(); Jm.block<6, 6>(0, 6).setIdentity(); }
    if (Jp) Jpm.setZero();
    int rc = WASHER_OK;
    if (frame == 0) {
        rc = rot_at(FrameMatrices(P[WP_tau0]), P[WP_tau0], xi, P, 1.0, dd, J ? &Jm : nullptr,
                    Jp ? &Jpm : nullptr, jp_columns);
    } else {
        for (int k = 0; k < N_AVERAGE && rc == WASHER_OK; ++k)
            rc = rot_at(averaged_frame(k), TWO_PI * k / N_AVERAGE, xi, P, 1.0 / N_AVERAGE, dd,
                        J ? &Jm : nullptr, Jp ? &Jpm : nullptr, jp_columns);
    }
    if (rc) return rc;
    if (dxi) {
        std::memcpy(dxi, xi + 6, 6 * sizeof(double));
        Eigen::Map<Vec6>(dxi + 6) = dd;
    }
    if (J) { Eigen::Map<Mat12> Jout(J); Jout = Jm; }
    if (Jp) { Eigen::Map<Mat12xD> Jpout(Jp); Jpout = Jpm; }
    return WASHER_OK;
}

int rhs_rot(const double *xi, const double *P, int frame, double *dxi) {
    return rot_eval(xi, P, frame, dxi, nullptr, nullptr);
}
int jac_rot(const double *xi, const double *P, int frame, double *J, double *Jp) {
    return rot_eval(xi, P, frame, nullptr, J, Jp);
}

}  // namespace washer

// --------------------------------------------------------------------------- C ABI

using namespace washer;

// Shared loop of the batched calls: stop at the first failing row.
template <class Row>
static int batch(int n, int *nfail, Row &&row) {
    if (nfail) *nfail = -1;
    if (n < 0) return WASHER_EBAD_ARGUMENT;
    for (int i = 0; i < n; ++i) {
        int rc = row(i);
        if (rc) { if (nfail) *nfail = i; return rc; }
    }
    return WASHER_OK;
}


extern "C" {

int washer_n_params(void) { return WASHER_N_PARAMS; }
int washer_n_rods(void) { return WASHER_N_RODS; }
int washer_n_diff(void) { return WASHER_N_DIFF; }
int washer_diff_param(int column) {
    if (column < 0 || column >= WASHER_N_DIFF) return -1;
    return column == WASHER_DIFF_OMEGA_COL ? WP_Omega
                                           : WASHER_SYMDIFF_INDEX[symbolic_column(column)];
}
const char *washer_param_name(int index) {
    return (index >= 0 && index < WASHER_N_PARAMS) ? WASHER_PARAM_NAMES[index] : nullptr;
}
const char *washer_inputs_hash(void) { return WASHER_INPUTS_SHA256; }

const char *washer_error_message(int code) {
    switch (code) {
        case WASHER_OK: return "success";
        case WASHER_ENONFINITE_INPUT: return "non-finite (NaN or inf) state or time";
        case WASHER_ESINGULAR_MASS: return "mass matrix is singular or not positive definite";
        case WASHER_ENONFINITE_OUTPUT: return "the model produced a non-finite value";
        case WASHER_ESTEP_TOO_SMALL: return "integrator step size fell below its minimum";
        case WASHER_EMAX_STEPS: return "integrator reached its step limit";
        case WASHER_EBAD_ARGUMENT: return "invalid argument (law, frame, tau_s, sizes or decreasing times)";
        case WASHER_EINTERRUPTED: return "interrupted (Ctrl-C)";
        default: return "unknown error";
    }
}

int washer_mass_forces(const double *q, const double *qd, double theta, double w, double wd,
                       const double *P, double *M, double *f) {
    if (!all_finite(q, 6) || !all_finite(qd, 6)) return WASHER_ENONFINITE_INPUT;
    washer_gen_mf(q, qd, theta, w, wd, P, M, f);
    return all_finite(M, 36) && all_finite(f, 6) ? WASHER_OK : WASHER_ENONFINITE_OUTPUT;
}

int washer_speed_law(double t, const double *P, int law, double *theta3) {
    Speed s;
    int rc = speed_law(t, P, law, s);
    if (rc == WASHER_OK) { theta3[0] = s.th; theta3[1] = s.w; theta3[2] = s.wd; }
    return rc;
}

int washer_rhs_fixed(double t, const double *u, const double *P, int law, double *du) {
    return rhs_fixed(t, u, P, law, du);
}
int washer_jac_fixed(double t, const double *u, const double *P, int law, double *J, double *Jp) {
    return jac_fixed(t, u, P, law, J, Jp);
}
int washer_rhs_rot(const double *xi, const double *P, int frame, double *dxi) {
    return rhs_rot(xi, P, frame, dxi);
}
int washer_jac_rot(const double *xi, const double *P, int frame, double *J, double *Jp) {
    return jac_rot(xi, P, frame, J, Jp);
}

int washer_rhs_fixed_batch(int n, const double *t, const double *u, const double *P, int pstride,
                           int law, double *du, int *nfail) {
    return batch(n, nfail, [&](int i) {
        return rhs_fixed(t[i], u + 12 * i, P + (long)i * pstride, law, du + 12 * i);
    });
}
int washer_rhs_rot_batch(int n, const double *xi, const double *P, int pstride, int frame,
                         double *dxi, int *nfail) {
    return batch(n, nfail, [&](int i) {
        return rhs_rot(xi + 12 * i, P + (long)i * pstride, frame, dxi + 12 * i);
    });
}
int washer_jac_rot_batch(int n, const double *xi, const double *P, int pstride, int frame,
                         double *J, double *Jp, int *nfail) {
    return batch(n, nfail, [&](int i) {
        return jac_rot(xi + 12 * i, P + (long)i * pstride, frame, J ? J + 144 * i : nullptr,
                       Jp ? Jp + (long)12 * WASHER_N_DIFF * i : nullptr);
    });
}
int washer_rhs_jac_rot_batch(int n, const double *xi, const double *P, int pstride, int frame,
                             double *dxi, double *J, double *Jp, unsigned jp_columns,
                             int *nfail) {
    return batch(n, nfail, [&](int i) {
        return rot_eval(xi + 12 * i, P + (long)i * pstride, frame, dxi ? dxi + 12 * i : nullptr,
                        J ? J + 144 * i : nullptr,
                        Jp ? Jp + (long)12 * WASHER_N_DIFF * i : nullptr, jp_columns & ALL_DIFF);
    });
}

}  // extern "C"

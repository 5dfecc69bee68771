// Hand-written dynamics on top of the generated M and f: the ground-frame
// system (eq 48) and the rotating-frame system (eqs 52-59), with Jacobians.
// Internal C++ interface shared by kernel.cpp and integrate.cpp.
#ifndef WASHER_DYNAMICS_HPP
#define WASHER_DYNAMICS_HPP

#include <Eigen/Dense>

#include "generated/washer_model.h"

namespace washer {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using RowMat6 = Eigen::Matrix<double, 6, 6, Eigen::RowMajor>;
using Mat12 = Eigen::Matrix<double, 12, 12, Eigen::RowMajor>;
using Mat6xS = Eigen::Matrix<double, 6, WASHER_N_SYMDIFF, Eigen::RowMajor>;
using Mat12xD = Eigen::Matrix<double, 12, WASHER_N_DIFF, Eigen::RowMajor>;

// Number of equally spaced frame angles of the averaged rotating frame
// (docs/model.md section 4: the tau-dependence is 2 Omega and 4 Omega harmonics,
// which a 16-point rectangle rule on the period integrates exactly up to order 14).
constexpr int N_AVERAGE = 16;

// Basket angle and its rates for a speed law, with their derivatives in Omega (Hz).
struct Speed {
    double th, w, wd;
    double th_O, w_O, wd_O;
};
int speed_law(double t, const double *P, int law, Speed &s);

// Accelerations a = M^-1 f at (q, qd) and, on request, their derivatives.
struct Accel {
    Vec6 a;
    Mat6 a_q, a_qd;                       // da/dq, da/dqd
    Vec6 a_th, a_w, a_wd;                 // da/dtheta, da/dw, da/dwd
    Mat6xS a_p;                           // da/dP (symbolic parameters)
};
// pmask: the columns j of a_p computed (bit j, WASHER_SYMDIFF_INDEX[j]); the others are 0.
constexpr unsigned ALL_SYMDIFF = (1u << WASHER_N_SYMDIFF) - 1;
int accelerations(const double *q, const double *qd, double th, double w, double wd,
                  const double *P, bool derivs, Accel &out, unsigned pmask = ALL_SYMDIFF);

int rhs_fixed(double t, const double *u, const double *P, int law, double *du);
int jac_fixed(double t, const double *u, const double *P, int law, double *J, double *Jp);
// rhs and Jacobians from one factorization of M; any output may be NULL.
int rhs_jac_fixed(double t, const double *u, const double *P, int law, double *du, double *J,
                  double *Jp);
int rhs_rot(const double *xi, const double *P, int frame, double *dxi);
int jac_rot(const double *xi, const double *P, int frame, double *J, double *Jp);

bool all_finite(const double *x, int n);

}  // namespace washer
#endif

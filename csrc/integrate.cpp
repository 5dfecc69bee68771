// Adaptive explicit Runge-Kutta integration inside the kernel, so that a whole
// time response is one C call (no Python per step).
//
// Dormand-Prince 5(4) with FSAL, standard error-per-unit-step control and
// Hairer's 4th-order dense output (Hairer, Norsett & Wanner, Solving ODEs I,
// 2nd ed., sec II.5 and II.6; coefficients as in their code DOPRI5).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <mutex>

#include "dynamics.hpp"
#include "washer.h"

namespace washer {
namespace {

// Step-size control constants (Hairer's defaults).
constexpr double SAFETY = 0.9;       // shrink the asymptotic step estimate by this
constexpr double MIN_FACTOR = 0.2;   // smallest allowed step decrease
constexpr double MAX_FACTOR = 10.0;  // largest allowed step increase
constexpr double ORDER_EXP = 0.2;    // 1 / (error estimator order + 1)

// Butcher tableau.
constexpr double C2 = 1.0 / 5, C3 = 3.0 / 10, C4 = 4.0 / 5, C5 = 8.0 / 9;
constexpr double A21 = 1.0 / 5;
constexpr double A31 = 3.0 / 40, A32 = 9.0 / 40;
constexpr double A41 = 44.0 / 45, A42 = -56.0 / 15, A43 = 32.0 / 9;
constexpr double A51 = 19372.0 / 6561, A52 = -25360.0 / 2187, A53 = 64448.0 / 6561,
                 A54 = -212.0 / 729;
constexpr double A61 = 9017.0 / 3168, A62 = -355.0 / 33, A63 = 46732.0 / 5247,
                 A64 = 49.0 / 176, A65 = -5103.0 / 18656;
constexpr double A71 = 35.0 / 384, A73 = 500.0 / 1113, A74 = 125.0 / 192,
                 A75 = -2187.0 / 6784, A76 = 11.0 / 84;
// Error estimate: 5th- minus 4th-order weights.
constexpr double E1 = 71.0 / 57600, E3 = -71.0 / 16695, E4 = 71.0 / 1920,
                 E5 = -17253.0 / 339200, E6 = 22.0 / 525, E7 = -1.0 / 40;
// Dense output.
constexpr double D1 = -12715105075.0 / 11282082432.0, D3 = 87487479700.0 / 32700410799.0,
                 D4 = -10690763975.0 / 1880347072.0, D5 = 701980252875.0 / 199316789632.0,
                 D6 = -1453857185.0 / 822651844.0, D7 = 69997945.0 / 29380423.0;

// ------------------------------------------------------------------ interrupts
// One process-wide flag, checked between steps: a kernel call must never keep a
// process that the user interrupts (Ctrl-C) busy for longer than a step.
std::atomic<int> g_interrupt{0};

// SIGINT is observed only while an integration runs: the first one to start installs
// a handler that sets the flag and passes the signal on to the handler installed
// before (Python's, which raises KeyboardInterrupt once the call returns); the last
// one to finish puts the previous handler back. SIG_DFL and SIG_IGN are left alone.
std::mutex g_guard_mutex;
int g_guard_depth = 0;
bool g_installed = false;
struct sigaction g_previous;

void on_sigint(int sig, siginfo_t *info, void *ctx) {
    g_interrupt.store(1, std::memory_order_relaxed);
    if (g_previous.sa_flags & SA_SIGINFO) {
        if (g_previous.sa_sigaction) g_previous.sa_sigaction(sig, info, ctx);
    } else if (g_previous.sa_handler != SIG_DFL && g_previous.sa_handler != SIG_IGN &&
               g_previous.sa_handler != nullptr) {
        g_previous.sa_handler(sig);
    }
}

class SigintGuard {
  public:
    SigintGuard() {
        std::lock_guard<std::mutex> lock(g_guard_mutex);
        if (g_guard_depth++ > 0) return;
        g_interrupt.store(0, std::memory_order_relaxed);
        struct sigaction prev;
        if (sigaction(SIGINT, nullptr, &prev) != 0) return;
        const bool has_handler = (prev.sa_flags & SA_SIGINFO)
            ? prev.sa_sigaction != nullptr
            : (prev.sa_handler != SIG_DFL && prev.sa_handler != SIG_IGN);
        if (!has_handler) return;
        g_previous = prev;
        struct sigaction mine = {};
        mine.sa_sigaction = on_sigint;
        mine.sa_flags = SA_SIGINFO | (prev.sa_flags & SA_ONSTACK);
        sigemptyset(&mine.sa_mask);
        g_installed = sigaction(SIGINT, &mine, nullptr) == 0;
    }
    ~SigintGuard() {
        std::lock_guard<std::mutex> lock(g_guard_mutex);
        if (--g_guard_depth > 0 || !g_installed) return;
        // Put the previous handler back unless someone replaced ours meanwhile.
        struct sigaction now;
        if (sigaction(SIGINT, nullptr, &now) == 0 && (now.sa_flags & SA_SIGINFO) &&
            now.sa_sigaction == on_sigint)
            sigaction(SIGINT, &g_previous, nullptr);
        g_installed = false;
    }
    SigintGuard(const SigintGuard &) = delete;
    SigintGuard &operator=(const SigintGuard &) = delete;
};

// Integrates y' = f(t, y), y of length N, from t with outputs at tout (see washer_integrate).
template <int N, class Rhs>
int dopri5(Rhs &&f, double t, Eigen::Matrix<double, N, 1> y, double rtol, double atol, int nout,
           const double *tout, double *yout, double *h_io, long max_steps, long *stats) {
    using Vec = Eigen::Matrix<double, N, 1>;
    long nfev = 0, nacc = 0, nrej = 0;
    int k_out = 0;
    Vec k1, k2, k3, k4, k5, k6, k7, ynew, yerr;
    auto eval = [&](double tt, const Vec &yy, Vec &out) { ++nfev; return f(tt, yy, out); };
    auto finish = [&](int rc) {
        stats[0] += nfev; stats[1] += nacc; stats[2] += nrej; stats[4] = k_out;
        return rc;
    };
    // Outputs at (or before) the start time.
    while (k_out < nout && tout[k_out] <= t) {
        Eigen::Map<Vec>(yout + N * k_out) = y;
        ++k_out;
    }
    if (k_out == nout) return finish(WASHER_OK);
    const double t_end = tout[nout - 1];
    int rc = eval(t, y, k1);
    if (rc) return finish(rc);

    auto scale = [&](const Vec &a, const Vec &b) {
        return (atol + rtol * a.cwiseAbs().cwiseMax(b.cwiseAbs()).array()).matrix();
    };
    double h = *h_io;
    if (!(h > 0.0)) {   // Hairer's starting-step heuristic
        const Vec sc = scale(y, y);
        const double d0 = std::sqrt(y.cwiseQuotient(sc).squaredNorm() / N);
        const double d1 = std::sqrt(k1.cwiseQuotient(sc).squaredNorm() / N);
        double h0 = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
        h0 = std::min(h0, t_end - t);
        rc = eval(t + h0, Vec(y + h0 * k1), k2);
        if (rc) return finish(rc);
        const double d2 = std::sqrt((k2 - k1).cwiseQuotient(sc).squaredNorm() / N) / h0;
        const double dm = std::max(d1, d2);
        const double h1 = dm <= 1e-15 ? std::max(1e-6, h0 * 1e-3) : std::pow(0.01 / dm, 1.0 / 5);
        h = std::min(100 * h0, h1);
    }
    bool last_rejected = false;
    while (k_out < nout) {
        if (g_interrupt.load(std::memory_order_relaxed)) return finish(WASHER_EINTERRUPTED);
        if (max_steps > 0 && nacc + nrej >= max_steps) return finish(WASHER_EMAX_STEPS);
        h = std::min(h, t_end - t);
        if (h < 1e-14 * std::max(1.0, std::fabs(t))) return finish(WASHER_ESTEP_TOO_SMALL);
        if ((rc = eval(t + C2 * h, Vec(y + h * A21 * k1), k2))) return finish(rc);
        if ((rc = eval(t + C3 * h, Vec(y + h * (A31 * k1 + A32 * k2)), k3))) return finish(rc);
        if ((rc = eval(t + C4 * h, Vec(y + h * (A41 * k1 + A42 * k2 + A43 * k3)), k4)))
            return finish(rc);
        if ((rc = eval(t + C5 * h,
                       Vec(y + h * (A51 * k1 + A52 * k2 + A53 * k3 + A54 * k4)), k5)))
            return finish(rc);
        if ((rc = eval(t + h,
                       Vec(y + h * (A61 * k1 + A62 * k2 + A63 * k3 + A64 * k4 + A65 * k5)),
                       k6)))
            return finish(rc);
        ynew = y + h * (A71 * k1 + A73 * k3 + A74 * k4 + A75 * k5 + A76 * k6);
        if ((rc = eval(t + h, ynew, k7))) return finish(rc);
        yerr = h * (E1 * k1 + E3 * k3 + E4 * k4 + E5 * k5 + E6 * k6 + E7 * k7);
        const double err = std::sqrt(yerr.cwiseQuotient(scale(y, ynew)).squaredNorm() / N);
        if (!std::isfinite(err)) return finish(WASHER_ENONFINITE_OUTPUT);
        if (err <= 1.0) {
            // Dense output on [t, t + h] for every requested time inside it.
            const Vec r2 = ynew - y;
            const Vec r3 = h * k1 - r2;
            const Vec r4 = r2 - h * k7 - r3;
            const Vec r5 = h * (D1 * k1 + D3 * k3 + D4 * k4 + D5 * k5 + D6 * k6 + D7 * k7);
            const double t_new = t + h;
            while (k_out < nout && tout[k_out] <= t_new) {
                const double s = (tout[k_out] - t) / h, s1 = 1.0 - s;
                Eigen::Map<Vec>(yout + N * k_out) = y + s * (r2 + s1 * (r3 + s * (r4 + s1 * r5)));
                ++k_out;
            }
            t = t_new;
            y = ynew;
            k1 = k7;   // first-same-as-last
            ++nacc;
            double fac = err == 0.0 ? MAX_FACTOR : SAFETY * std::pow(err, -ORDER_EXP);
            fac = std::min(MAX_FACTOR, std::max(MIN_FACTOR, fac));
            if (last_rejected) fac = std::min(1.0, fac);
            *h_io = h;
            h *= fac;
            last_rejected = false;
        } else {
            ++nrej;
            h *= std::max(MIN_FACTOR, SAFETY * std::pow(err, -ORDER_EXP));
            last_rejected = true;
        }
    }
    return finish(WASHER_OK);
}

}  // namespace
}  // namespace washer

extern "C" void washer_request_interrupt(void) {
    washer::g_interrupt.store(1, std::memory_order_relaxed);
}

extern "C" int washer_interrupt_pending(void) {
    return washer::g_interrupt.load(std::memory_order_relaxed);
}

extern "C" int washer_integrate(int system, int mode, double t0, const double *y0,
                                const double *P, double rtol, double atol, int nout,
                                const double *tout, double *yout, double *h_io, long max_steps,
                                long *stats) {
    using namespace washer;
    if (nout < 0 || !(rtol > 0) || !(atol > 0)) return WASHER_EBAD_ARGUMENT;
    // A NaN or infinite output time would never be reached: refused before any step.
    if (!all_finite(y0, 12) || !std::isfinite(t0) || !all_finite(tout, nout))
        return WASHER_ENONFINITE_INPUT;
    for (int k = 1; k < nout; ++k)
        if (!(tout[k] >= tout[k - 1])) return WASHER_EBAD_ARGUMENT;
    const Eigen::Map<const Vec12> y(y0);
    const SigintGuard guard;
    if (system == 0)
        return dopri5<12>([&](double t, const Vec12 &u, Vec12 &du) {
            return rhs_fixed(t, u.data(), P, mode, du.data());
        }, t0, y, rtol, atol, nout, tout, yout, h_io, max_steps, stats);
    if (system == 1)
        return dopri5<12>([&](double, const Vec12 &xi, Vec12 &dxi) {
            return rhs_rot(xi.data(), P, mode, dxi.data());
        }, t0, y, rtol, atol, nout, tout, yout, h_io, max_steps, stats);
    return WASHER_EBAD_ARGUMENT;
}

// ------------------------------------------------------- variational equations
// Ground-frame flow u(t1) of eq 48 together with its derivatives: the state
// transition matrix Phi = du(t1)/du(t0), Phi' = J(t, u) Phi, Phi(t0) = I
// (at constant speed over one period T = 1/Omega, the monodromy matrix), and
// the sensitivity s = du(t1)/dp along the parameter direction dir (weights of the
// Jp columns), s' = J s + Jp dir, s(t0) = 0. One augmented DOPRI5 run whose error
// control covers all 12 + 144 + 12 components, so the derivatives are as accurate
// as the flow (the variational equations are the exact derivative of the
// continuous flow, not of the discrete method: they agree with finite differences
// of the numerical flow to the integration tolerance).
extern "C" int washer_flow_variational(int law, double t0, double t1, const double *u0,
                                       const double *P, const double *dir, double rtol,
                                       double atol, double *u1, double *Phi, double *s,
                                       double *h_io, long max_steps, long *stats) {
    using namespace washer;
    constexpr int NA = 12 + 144 + 12;
    using VecA = Eigen::Matrix<double, NA, 1>;
    if (!all_finite(u0, 12) || !std::isfinite(t0) || !std::isfinite(t1))
        return WASHER_ENONFINITE_INPUT;
    if (!(rtol > 0) || !(atol > 0) || !(t1 >= t0)) return WASHER_EBAD_ARGUMENT;
    Eigen::Matrix<double, WASHER_N_DIFF, 1> w = Eigen::Matrix<double, WASHER_N_DIFF, 1>::Zero();
    if (dir) w = Eigen::Map<const Eigen::Matrix<double, WASHER_N_DIFF, 1>>(dir);
    const bool with_p = dir != nullptr;
    const SigintGuard guard;
    VecA y = VecA::Zero();
    y.head<12>() = Eigen::Map<const Vec12>(u0);
    Eigen::Map<Mat12>(y.data() + 12).setIdentity();
    VecA yend;
    double h_local = 0.0;
    long stats_local[5] = {0, 0, 0, 0, 0};
    if (!h_io) h_io = &h_local;
    if (!stats) stats = stats_local;
    const int rc = dopri5<NA>([&](double t, const VecA &x, VecA &dx) -> int {
        Mat12 J;
        Mat12xD Jp;
        const int r = rhs_jac_fixed(t, x.data(), P, law, dx.data(), J.data(),
                                    with_p ? Jp.data() : nullptr);
        if (r) return r;
        Eigen::Map<Mat12>(dx.data() + 12) = J * Eigen::Map<const Mat12>(x.data() + 12);
        Eigen::Map<Vec12> ds(dx.data() + 156);
        ds = J * Eigen::Map<const Vec12>(x.data() + 156);
        if (with_p) ds += Jp * w;
        return WASHER_OK;
    }, t0, y, rtol, atol, 1, &t1, yend.data(), h_io, max_steps, stats);
    if (rc) return rc;
    if (u1) std::copy(yend.data(), yend.data() + 12, u1);
    if (Phi) std::copy(yend.data() + 12, yend.data() + 156, Phi);
    if (s) std::copy(yend.data() + 156, yend.data() + NA, s);
    return WASHER_OK;
}

// The corrector of periodic orbits (IPS 2) in one foreign call per continuation step: the
// compiled form of washer.cont.newton.newton as washer.cont.iterator.Continuation.correct
// runs it on the plane arclength of a collocation BVP (layout and contract: cont_api.h).
//
// Each iteration is PeriodicOrbits.residual (collocation.Collocation.residual: the
// collocation equations, u(0) - u(1) (+ 2 pi NRTN), the integral phase condition), then
// up to max(NWTN, 1) iterations PeriodicOrbits.jacobian (central differences of f with
// VectorField.fu_fp's points and quotients, Collocation.local_blocks,
// Collocation.jacobian_general) factorised with the border row (cont_bvp_factor, as
// CollocationBVP.factor), chord iterations after that, the solve of [J; row] dx =
// -[G; row (x - x_ref) - ds] (cont_bvp_solve), x += dx and AUTO's NEWTONBV test
// (Continuation.correct's `converged`: EPSU on the profile, EPSL on each parameter, its
// divergence test). f is evaluated by the call back `feval` (the user's equations: one
// call for the Gauss points, one for all difference points of a Jacobian up to
// one_call_max Gauss points, else one per set of parameters, as fu_fp), or by the
// generated C of a sympy problem or a compiled user file's FUNC (and DFDU) through
// function pointers `sfunc` (f) and `sjac` (exact f_u with JAC != 0), called directly.
// A change to any of those Python functions must be made here too
// (tests/test_compiled_po.py holds the two to the same points).
#include "cont.h"
#include "numpy_sum.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

// a . b: the BLAS ddot numpy's `@` calls when given (the same rounding), else in order
double dot(cont_ddot ddot, const double *a, const double *b, int len) {
    if (ddot) {
        const int one = 1;
        return ddot(&len, a, &one, b, &one);
    }
    double s = 0.0;
    for (int i = 0; i < len; ++i) s += a[i] * b[i];
    return s;
}

// sum_q W[q * m + c] u[q * n] for q = 0 .. m in order, from 0.0: a value of u at a Gauss
// point (Collocation.at_gauss) or of u' there (the residual); with NCOL = M > 0 known to
// the compiler (the sum unrolled, the same operations in the same order), else m.
template <int M>
inline double node_sum(const double *W, const double *u, int m, int c, int n) {
    const int mm = M > 0 ? M : m;
    double s = 0.0;
    for (int q = 0; q <= mm; ++q) s += W[q * mm + c] * u[(size_t)q * n];
    return s;
}

// Whether the len values are all finite: v * 0 is 0 for a finite v and NaN for an
// infinite or NaN one, and a sum with a NaN is NaN. Eight sums side by side, without a
// test and branch per value (the Jacobian's thousands of values: a test a value was
// about 5 % of the corrector's time).
bool all_finite(const double *v, long len) {
    double s[8] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    long q = 0;
    for (; q + 8 <= len; q += 8)
        for (int r = 0; r < 8; ++r) s[r] += v[q + r] * 0.0;
    for (; q < len; ++q) s[0] += v[q] * 0.0;
    double total = 0.0;
    for (int r = 0; r < 8; ++r) total += s[r];
    return total == 0.0;
}

// The equations' evaluation and the difference Jacobian of one call (cont_po_correct's
// iterations, cont_po_jacobian's point), with their work arrays.
struct PoJacobian {
    cont_po_feval feval;
    cont_po_sym_func sfunc;
    cont_po_sym_jac sjac;
    int N, m, n, npar, k, nc, mn, kst, m0, nfp, one_call_max;
    long nb;
    int fp_index[2], slot_index[2];
    const double *WT, *WP, *dtm;
    double fd_step, hp[2] = {0.0, 0.0};
    // work arrays, each written in full by a call before it is read
    RawBuffer<double> ug, fg, parsT, pts, fst, h, A, parcols, Jp;

    PoJacobian(cont_po_feval feval_, cont_po_sym_func sfunc_, cont_po_sym_jac sjac_,
               int npar_jp, int ntst, int ncol, int ndim, int npar_, int ipa, int ipb,
               const double *WT_, const double *WP_, const double *dtm_, double fd_step_,
               int one_call_max_)
        : feval(feval_), sfunc(sfunc_), sjac(sjac_), N(ntst), m(ncol), n(ndim),
          npar(npar_), one_call_max(one_call_max_), WT(WT_), WP(WP_), dtm(dtm_),
          fd_step(fd_step_) {
        k = N * m;                                       // Gauss points
        nc = k * n;
        mn = m * n;
        nb = (long)N * mn * (m + 1) * n;                 // block values
        // the parameter stencils: the free parameters other than the period, in the order
        // of PeriodicOrbits.jacobian's slots (x[-2] = PAR(ipa + 1), then x[-1] = PAR(ipb + 1))
        nfp = 0;
        slot_index[0] = ipa;
        slot_index[1] = ipb;
        for (int s = 0; s < 2; ++s)
            if (slot_index[s] != 10) fp_index[nfp++] = slot_index[s];
        kst = 2 * n * k + 2 * nfp * k;                  // points of a Jacobian's call
        m0 = 2 * n * k;
        ug.allocate((size_t)k * n);
        fg.allocate((size_t)k * n);
        parsT.allocate(!sfunc && k <= one_call_max ? (size_t)npar * kst : 0);
        pts.allocate((size_t)kst * n);
        fst.allocate((size_t)kst * n);
        h.allocate((size_t)k * n);
        A.allocate((size_t)k * n * n);
        parcols.allocate((size_t)N * mn * 2);
        Jp.allocate(sjac ? (size_t)k * n * std::max(npar_jp, 1) : 0);
    }

    // u at the Gauss points (Collocation.at_gauss)
    void at_gauss(const double *U) {
        for (int j = 0; j < N; ++j)
            for (int c = 0; c < m; ++c) {
                double *g = &ug[((size_t)j * m + c) * n];
                for (int i = 0; i < n; ++i) {
                    const double *u = U + ((size_t)j * m) * n + i;
                    g[i] = m == 4 ? node_sum<4>(WT, u, m, c, n) : node_sum<0>(WT, u, m, c, n);
                }
            }
    }

    // f at the Gauss points into fg: 0, or 3 when f failed
    int f_gauss(const double *par) {
        if (sfunc) {
            sfunc(k, ug.data(), par, 0, fg.data());
            return 0;
        }
        return feval(k, ug.data(), par, 0, fg.data()) != 0 ? 3 : 0;
    }

    // The collocation blocks and parameter columns at ug (f there in fg) into vals
    // (Collocation.jacobian_general's order) and parcols: 0, or 3 when f failed or a
    // value is not finite
    int jacobian(const double *par, double T, double *vals) {
        // f_u and f_p by central differences (differences.u_points, par_points,
        // VectorField.fu_fp), or f_u exact (sjac: the generated Jacobian or the user's
        // DFDU, as Problem.dfdu_many gives it) and f_p by differences (VectorField.fp)
        for (int r = 0; r < k; ++r)
            for (int i = 0; i < n; ++i)
                h[(size_t)r * n + i] = fd_step * (1 + std::fabs(ug[(size_t)r * n + i]));
        for (int r = 0; r < k; ++r)
            for (int s = 0; s < 2 * n; ++s) {
                double *pt = &pts[((size_t)r * 2 * n + s) * n];
                std::copy(&ug[(size_t)r * n], &ug[(size_t)r * n] + n, pt);
                if (s < n) pt[s] += h[(size_t)r * n + s];
                else pt[s - n] -= h[(size_t)r * n + s - n];
            }
        const bool one_call = !sfunc && k <= one_call_max;
        if (one_call)
            for (int p = 0; p < npar; ++p) std::fill_n(&parsT[(size_t)p * kst], m0, par[p]);
        for (int j = 0; j < nfp; ++j) {
            const int ip = fp_index[j];
            hp[j] = fd_step * (1 + std::fabs(par[ip]));
            const double pp = par[ip] + hp[j], pm = par[ip] - hp[j];
            for (int sgn = 0; sgn < 2 && one_call; ++sgn) {
                const size_t off = (size_t)m0 + (size_t)(2 * j + sgn) * k;
                std::copy(ug.begin(), ug.end(), pts.begin() + off * n);
                for (int p = 0; p < npar; ++p)
                    std::fill_n(&parsT[(size_t)p * kst + off], k,
                                p == ip ? (sgn ? pm : pp) : par[p]);
            }
        }
        if (sfunc) {
            // one set of parameters a call (pstride 0)
            if (!sjac) sfunc(m0, pts.data(), par, 0, fst.data());
            std::vector<double> pq(par, par + npar);
            for (int j = 0; j < nfp; ++j) {
                const int ip = fp_index[j];
                for (int sgn = 0; sgn < 2; ++sgn) {
                    const size_t off = (size_t)m0 + (size_t)(2 * j + sgn) * k;
                    pq[ip] = sgn ? par[ip] - hp[j] : par[ip] + hp[j];
                    sfunc(k, ug.data(), pq.data(), 0, &fst[off * n]);
                }
                pq[ip] = par[ip];
            }
        } else if (one_call) {
            // every point in one call, the parameters point by point
            if (feval(kst, pts.data(), parsT.data(), kst, fst.data()) != 0) return 3;
        } else {
            // beyond one_call_max points a call per set of parameters (fu_fp's fu,
            // then fp's two calls for each parameter)
            bool failed = feval(m0, pts.data(), par, 0, fst.data()) != 0;
            std::vector<double> pq(par, par + npar);
            for (int j = 0; j < nfp && !failed; ++j) {
                const int ip = fp_index[j];
                for (int sgn = 0; sgn < 2 && !failed; ++sgn) {
                    const size_t off = (size_t)m0 + (size_t)(2 * j + sgn) * k;
                    pq[ip] = sgn ? par[ip] - hp[j] : par[ip] + hp[j];
                    failed = feval(k, ug.data(), pq.data(), 0, &fst[off * n]) != 0;
                }
                pq[ip] = par[ip];
            }
            if (failed) return 3;
        }
        if (sjac) {
            sjac(k, ug.data(), par, 0, A.data(), Jp.data());
        } else {
            // A[r, i, l] = (f_i(u + h_l e_l) - f_i(u - h_l e_l)) / (2 h_l)
            for (int r = 0; r < k; ++r)
                for (int l = 0; l < n; ++l) {
                    const double *fpl = &fst[((size_t)r * 2 * n + l) * n];
                    const double *fml = &fst[((size_t)r * 2 * n + n + l) * n];
                    const double d = 2 * h[(size_t)r * n + l];
                    for (int i = 0; i < n; ++i)
                        A[((size_t)r * n + i) * n + l] = (fpl[i] - fml[i]) / d;
                }
        }
        cont_coll_blocks(N, m, n, WT, WP, dtm, T, A.data(), vals);
        // the parameter columns -dtm d(T f)/dp: f for the period, T f_p otherwise
        int jf = 0;
        for (int s = 0; s < 2; ++s) {
            double *dp = vals + nb + (long)s * nc;
            if (slot_index[s] == 10) {
                for (int j = 0; j < N; ++j)
                    for (int r = 0; r < mn; ++r)
                        dp[j * mn + r] = -dtm[j] * fg[(size_t)j * mn + r];
            } else {
                const double *fpp = &fst[((size_t)m0 + (size_t)2 * jf * k) * n];
                const double *fpm = &fst[((size_t)m0 + (size_t)(2 * jf + 1) * k) * n];
                for (int j = 0; j < N; ++j)
                    for (int r = 0; r < mn; ++r) {
                        const size_t q = (size_t)j * mn + r;
                        dp[q] = -dtm[j] * (T * ((fpp[q] - fpm[q]) / (2 * hp[jf])));
                    }
                ++jf;
            }
            for (int q = 0; q < nc; ++q) parcols[(size_t)q * 2 + s] = dp[q];
        }
        return all_finite(vals, nb + 2L * nc) ? 0 : 3;
    }
};

// The phase row's values of the Jacobian (Collocation.jacobian_general: w_node *
// up_old, then the parameters' zeros) and the periodicity rows' (+1, -1) into vals.
double *po_dense_values(const PoJacobian &pj, int nodes, const double *w_node,
                        const double *up_old, double *vals) {
    const int n = pj.n, nu = nodes * n;
    double *bc_vals = vals + pj.nb + 2L * pj.nc;
    double *int_vals = bc_vals + 2 * n;
    for (int i = 0; i < n; ++i) {
        bc_vals[i] = 1.0;
        bc_vals[n + i] = -1.0;
    }
    for (int q = 0; q < nodes; ++q)
        for (int i = 0; i < n; ++i) int_vals[q * n + i] = w_node[q] * up_old[q * n + i];
    int_vals[nu] = int_vals[nu + 1] = 0.0;
    return int_vals;
}

}  // namespace

int cont_po_correct(cont_bvp *fac, cont_po_feval feval, cont_po_sym_func sfunc,
                    cont_po_sym_jac sjac, int npar_jp, cont_ddot ddot, int ntst, int ncol,
                    int ndim, int npar, int ipa, int ipb, const double *WT, const double *WP,
                    const double *dtm, const double *w_node, const double *U_old,
                    const double *up_old, const double *bc_offset, const double *par0,
                    const double *x_pred, const double *x_ref, const double *row, double ds,
                    double epsl, double epsu, int itnw, int nwtn, double divergence,
                    double fd_step, int one_call_max, double *x, double *x_J,
                    double *vals, double *P0, double *P1, int *info) {
    const int N = ntst, m = ncol, n = ndim;
    if (N < 1 || m < 1 || n < 1 || ipa < 0 || ipb < 0 || ipa >= npar || ipb >= npar
        || npar < 11 || itnw < 1 || (sjac && !sfunc) || (!sfunc && !feval))
        return 4;
    PoJacobian pj(feval, sfunc, sjac, npar_jp, N, m, n, npar, ipa, ipb, WT, WP, dtm,
                  fd_step, one_call_max);
    const int nodes = N * m + 1;
    const int nu = nodes * n, nc = pj.nc, nx = nu + 2, ne = n + 2;
    std::vector<double> par(par0, par0 + npar), extra((size_t)ne * nx, 0.0);
    RawBuffer<double> G(nc + n + 1), rhs(nx), dx(nx), xo(nx), prod(n), vsum(nodes);
    const RawBuffer<double> &fg = pj.fg;
    std::copy(x_pred, x_pred + nx, x);
    // the dense rows' constant parts: periodicity (+1 on u(0), -1 on u(1)), the border
    const int last = (nodes - 1) * n;
    for (int i = 0; i < n; ++i) {
        extra[(size_t)i * nx + i] = 1.0;
        extra[(size_t)i * nx + last + i] = -1.0;
    }
    std::copy(row, row + nx, extra.begin() + (size_t)(n + 1) * nx);
    // the phase row, the same in every Jacobian of the call
    const double *int_vals = po_dense_values(pj, nodes, w_node, up_old, vals);
    std::copy(int_vals, int_vals + nx, extra.begin() + (size_t)n * nx);

    int it_J = 0, residuals = 0, jacobians = 0;
    bool factored = false;
    double delref = -1.0;
    int status = 2;
    int it = 1;
    for (; it <= itnw; ++it) {
        par[ipa] = x[nx - 2];
        par[ipb] = x[nx - 1];
        const double T = par[10];
        const double *U = x;
        pj.at_gauss(U);
        if (pj.f_gauss(par.data()) != 0) {
            status = 3;
            break;
        }
        // the residual (Collocation.residual_general)
        for (int j = 0; j < N; ++j)
            for (int c = 0; c < m; ++c)
                for (int i = 0; i < n; ++i) {
                    const double *u = U + ((size_t)j * m) * n + i;
                    const double s = m == 4 ? node_sum<4>(WP, u, m, c, n)
                                            : node_sum<0>(WP, u, m, c, n);
                    const size_t r = ((size_t)j * m + c) * n + i;
                    G[r] = s - dtm[j] * (T * fg[r]);
                }
        for (int i = 0; i < n; ++i)
            G[nc + i] = bc_offset ? (U[i] - U[last + i]) + bc_offset[i] : U[i] - U[last + i];
        // w_node @ np.sum((U - U_old) * up_old, axis=1)
        for (int q = 0; q < nodes; ++q) {
            for (int i = 0; i < n; ++i)
                prod[i] = (U[q * n + i] - U_old[q * n + i]) * up_old[q * n + i];
            vsum[q] = pairwise_sum(prod.data(), n);
        }
        G[nc + n] = dot(ddot, w_node, vsum.data(), nodes);
        ++residuals;
        bool finite = true;
        for (int r = 0; r < nc + n + 1; ++r) finite = finite && std::isfinite(G[r]);
        if (!finite) { status = 3; break; }
        if (!factored || it <= std::max(nwtn, 1)) {
            if (pj.jacobian(par.data(), T, vals) != 0
                || cont_bvp_factor(fac, vals, pj.parcols.data(), extra.data(), nullptr, P0,
                                   P1) != 0) {
                status = 3;
                break;
            }
            factored = true;
            it_J = it;
            ++jacobians;
            std::copy(x, x + nx, x_J);
        }
        for (int q = 0; q < nx; ++q) xo[q] = x[q] - x_ref[q];
        const double c = dot(ddot, row, xo.data(), nx) - ds;
        for (int r = 0; r < nx - 1; ++r) rhs[r] = -G[r];
        rhs[nx - 1] = -c;
        cont_bvp_solve(fac, rhs.data(), dx.data());
        bool dfin = true;
        for (int q = 0; q < nx; ++q) dfin = dfin && std::isfinite(dx[q]);
        if (!dfin) { status = 3; break; }
        std::copy(x, x + nx, xo.begin());
        for (int q = 0; q < nx; ++q) x[q] += dx[q];
        // AUTO's NEWTONBV (Continuation.correct's `converged`, n_state = the profile)
        double dmax = 0.0, xmax = 0.0;
        for (int q = 0; q < nu; ++q) {
            dmax = std::max(dmax, std::fabs(dx[q]));
            xmax = std::max(xmax, std::fabs(xo[q]));
        }
        const double du = dmax / (1 + xmax);
        double dl = 0.0;
        for (int q = nu; q < nx; ++q) dl = std::max(dl, std::fabs(dx[q]) / (1 + std::fabs(x[q])));
        if (dl <= epsl && du < epsu) { status = 0; break; }
        const double size = std::max(du, dl);
        if (delref < 0) delref = divergence * std::max(size, 1e-300);
        else if (size > delref) { status = 1; break; }
    }
    info[0] = std::min(it, itnw);
    info[1] = it_J;
    info[2] = residuals;
    info[3] = jacobians;
    return status;
}

int cont_po_jacobian(cont_po_feval feval, cont_po_sym_func sfunc, cont_po_sym_jac sjac,
                     int npar_jp, int ntst, int ncol, int ndim, int npar, int ipa, int ipb,
                     const double *WT, const double *WP, const double *dtm,
                     const double *w_node, const double *up_old, const double *par0,
                     const double *x, double fd_step, int one_call_max, double *vals) {
    const int N = ntst, m = ncol, n = ndim;
    if (N < 1 || m < 1 || n < 1 || ipa < 0 || ipb < 0 || ipa >= npar || ipb >= npar
        || npar < 11 || (sjac && !sfunc) || (!sfunc && !feval))
        return 4;
    PoJacobian pj(feval, sfunc, sjac, npar_jp, N, m, n, npar, ipa, ipb, WT, WP, dtm,
                  fd_step, one_call_max);
    const int nx = (N * m + 1) * n + 2;
    std::vector<double> par(par0, par0 + npar);
    par[ipa] = x[nx - 2];
    par[ipb] = x[nx - 1];
    po_dense_values(pj, N * m + 1, w_node, up_old, vals);
    pj.at_gauss(x);
    if (pj.f_gauss(par.data()) != 0) return 3;
    return pj.jacobian(par.data(), par[10], vals);
}

int cont_bvp_factor_values(cont_bvp *fac, int ntst, int ncol, int ndim, int npar,
                           const double *vals, int ntail, const int *rows, const int *cols,
                           const double *border, double *P0, double *P1) {
    const int N = ntst, m = ncol, n = ndim, ne = ndim + npar;
    if (N < 1 || m < 1 || n < 1 || npar < 0 || ntail < 0) return 2;
    const long mn = (long)m * n, nc = N * mn, nb = nc * (m + 1) * n;
    const long nx = ((long)N * m + 1) * n + npar;
    // the parameter columns, stored column by column after the blocks, to (NTST,
    // NCOL*NDIM, NPAR) (reduction.pieces' transpose)
    std::vector<double> parcols((size_t)nc * std::max(npar, 1));
    for (int s = 0; s < npar; ++s) {
        const double *dp = vals + nb + (long)s * nc;
        for (long q = 0; q < nc; ++q) parcols[(size_t)q * npar + s] = dp[q];
    }
    // the dense rows: zero but for the tail's values at (rows, cols), then the border row
    // (reduction._dense_rows: later positions overwrite earlier ones, as numpy assigns)
    std::vector<double> extra((size_t)ne * nx, 0.0);
    const double *tail = vals + nb + (long)npar * nc;
    for (int k = 0; k < ntail; ++k) {
        if (rows[k] < 0 || rows[k] >= ne || cols[k] < 0 || cols[k] >= nx) return 2;
        extra[(size_t)rows[k] * nx + cols[k]] = tail[k];
    }
    std::copy(border, border + nx, extra.begin() + (size_t)(ne - 1) * nx);
    return cont_bvp_factor(fac, vals, parcols.data(), extra.data(), nullptr, P0, P1);
}

// Structured LU of the bordered collocation matrix: AUTO-07p's condensation of
// parameters (CONPAR), block reduction (REDUCE) and the final dense system (DIMRGE),
// as one elimination in a fixed order with pivoting inside the blocks. Layout and
// contract: cont_api.h. Every elimination step is a Gaussian step on the whole
// matrix (rows of other blocks hold structural zeros in the pivot column), so the
// determinant is the product of the pivots times the signs of the row and column
// orders, which gives the BP test of cycles from the same factorisation.
#include "cont.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <new>
#include <vector>

namespace {

using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Sign of a permutation given as the list of original indices in the new order.
double perm_sign(const std::vector<int> &p) {
    std::vector<char> seen(p.size(), 0);
    double s = 1.0;
    for (size_t i = 0; i < p.size(); ++i) {
        if (seen[i]) continue;
        size_t len = 0;
        for (size_t j = i; !seen[j]; j = static_cast<size_t>(p[j])) {
            seen[j] = 1;
            ++len;
        }
        if (len % 2 == 0) s = -s;
    }
    return s;
}

// The sign of cont_bvp_factor's row and column orders (as original indices in elimination
// order) when no pivot swaps rows: the interior rows of every interval, the rows the
// reduction pivots on, the rows left in the remaining system, the dense rows; the columns
// likewise.
double orders_sign(int N, int m, int n, int np) {
    const int mn = m * n, K = (m - 1) * n, nc = N * mn, nx = (N * m + 1) * n + np;
    std::vector<int> rows, cols, R_ids, tids(2 * n);
    rows.reserve(nx);
    cols.reserve(nx);
    for (int j = 0; j < N; ++j) {
        for (int t = 0; t < K; ++t) {
            rows.push_back(j * mn + t);
            cols.push_back(j * mn + n + t);
        }
        if (j == 0) {
            for (int r = K; r < mn; ++r) R_ids.push_back(r);
            continue;
        }
        for (int r = 0; r < n; ++r) {
            tids[r] = R_ids[r];
            tids[n + r] = j * mn + K + r;
        }
        for (int t = 0; t < n; ++t) {
            rows.push_back(tids[t]);
            cols.push_back(j * mn + t);
        }
        R_ids.assign(tids.begin() + n, tids.end());
    }
    for (int r = 0; r < n; ++r) rows.push_back(R_ids[r]);
    for (int e = 0; e < n + np; ++e) rows.push_back(nc + e);
    for (int i = 0; i < n; ++i) cols.push_back(i);
    for (int i = 0; i < n; ++i) cols.push_back(N * mn + i);
    for (int i = 0; i < np; ++i) cols.push_back(nx - np + i);
    return perm_sign(rows) * perm_sign(cols);
}

// y[k] -= l * x[k], k < len: the same operations, element by element, whichever way
// (so the same values): a plain loop for short rows, where Eigen's per-expression
// set-up dominated (NDIM 3: lengths 3 to 20), Eigen's vectorised one for long rows.
inline void sub_scaled(double *__restrict y, const double *__restrict x, double l, int len) {
    if (len >= 24) {
        Eigen::Map<Eigen::VectorXd>(y, len) -= l * Eigen::Map<const Eigen::VectorXd>(x, len);
        return;
    }
    for (int k = 0; k < len; ++k) y[k] -= l * x[k];
}


// dst[r, c] = src[r, c] for r < rows, c < cols (row strides ds, ss).
inline void copy_block(double *__restrict dst, int ds, const double *__restrict src, int ss,
                       int rows, int cols) {
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) dst[(size_t)r * ds + c] = src[(size_t)r * ss + c];
}

// dst[r, c] = 0 for r < rows, c < cols (row stride ds).
inline void zero_block(double *dst, int ds, int rows, int cols) {
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c) dst[(size_t)r * ds + c] = 0.0;
}

// One dense row `ex` (nx) through interior pivot t of interval j (pivot row wt of W(j),
// pivot d, `tail` columns of nodes right of the pivot column): its multiplier, stored in
// E1. cont_bvp_factor and cont_bvp_reborder take every dense row through the same calls
// (a row's eliminations involve only itself and the final pivot rows), so a row
// replaced later comes out as it would in a new factorisation.
inline double dense_step_interior(double *ex, const double *wt, double d, int j, int t,
                                  int n, int mn, int cw, int np, int nx, int tail) {
    const int c = n + t, gc = j * mn + c;
    const double l = ex[gc] / d;
    ex[gc] = 0.0;
    if (l == 0.0) return l;
    sub_scaled(ex + j * mn, wt, l, n);
    sub_scaled(ex + gc + 1, wt + c + 1, l, tail);
    sub_scaled(ex + nx - np, wt + cw - np, l, np);
    return l;
}

// The same through pivot t of the reduction at end node j (pivot row tt of T(j)): its
// multiplier, stored in E2.
inline double dense_step_end(double *ex, const double *tt, double d, int j, int t, int n,
                             int mn, int np, int nx) {
    const int gc = j * mn + t;
    const double l = ex[gc] / d;
    ex[gc] = 0.0;
    if (l == 0.0) return l;
    sub_scaled(ex + gc + 1, tt + t + 1, l, n - t - 1);
    sub_scaled(ex, tt + n, l, n);
    sub_scaled(ex + (j + 1) * mn, tt + 2 * n, l, n);
    sub_scaled(ex + nx - np, tt + 3 * n, l, np);
    return l;
}

}  // namespace

struct cont_bvp {
    int N, m, n, np, ne, K, nx, nc;   // NTST, NCOL, NDIM, NPAR, dense rows, interior, sizes
    // Interval j (condensation): W(j) (m n x (m+1) n + np) eliminated in place (multipliers
    // below the pivots in the interior columns n..n+K-1), row swaps piv1(j), the dense
    // rows' multipliers E1(j) (ne x K).
    // Node k = 1..N-1 (reduction): T(k) (2n x 3n + np), columns (U_k, U_0, U_k+1, par),
    // swaps piv2(k), dense-row multipliers E2(k) (ne x n). Index 0 unused.
    // All of them in buffers allocated once with the object (a factorisation allocates
    // nothing per interval).
    int cw = 0, tw = 0;
    bool factored = false;
    RawBuffer<double> Wb, E1b, Tb, E2b;
    RawBuffer<int> piv1b, piv2b;
    Eigen::Map<Mat> W(int j) { return Eigen::Map<Mat>(Wb.data() + (size_t)j * m * n * cw, m * n, cw); }
    Eigen::Map<const Mat> W(int j) const {
        return Eigen::Map<const Mat>(Wb.data() + (size_t)j * m * n * cw, m * n, cw);
    }
    Eigen::Map<Mat> E1(int j) { return Eigen::Map<Mat>(E1b.data() + (size_t)j * ne * K, ne, K); }
    Eigen::Map<const Mat> E1(int j) const {
        return Eigen::Map<const Mat>(E1b.data() + (size_t)j * ne * K, ne, K);
    }
    Eigen::Map<Mat> T(int j) { return Eigen::Map<Mat>(Tb.data() + (size_t)j * 2 * n * tw, 2 * n, tw); }
    Eigen::Map<const Mat> T(int j) const {
        return Eigen::Map<const Mat>(Tb.data() + (size_t)j * 2 * n * tw, 2 * n, tw);
    }
    Eigen::Map<Mat> E2(int j) { return Eigen::Map<Mat>(E2b.data() + (size_t)j * ne * n, ne, n); }
    Eigen::Map<const Mat> E2(int j) const {
        return Eigen::Map<const Mat>(E2b.data() + (size_t)j * ne * n, ne, n);
    }
    int *piv1(int j) { return piv1b.data() + (size_t)j * K; }
    const int *piv1(int j) const { return piv1b.data() + (size_t)j * K; }
    int *piv2(int j) { return piv2b.data() + (size_t)j * n; }
    const int *piv2(int j) const { return piv2b.data() + (size_t)j * n; }
    // The remaining (U_0, U_N, par) system, and its first n rows (the collocation rows
    // reduced: P0 U_0 + P1 U_N + Ppar par) for cont_bvp_schur.
    Eigen::PartialPivLU<Mat> lu;
    Mat Rfin;
    // The matrix itself (blocks, parameter columns, dense rows), for the residual of
    // the refinement step in cont_bvp_solve.
    std::vector<double> blocks0, parcols0, extra0;
    // The pivots in elimination order (the remaining system's in `lu`), the sign of the
    // determinant and whether a pivot was zero: log|det| is summed on request
    // (cont_bvp_sign_logdet), in the order the factorisation met the pivots.
    std::vector<double> pivots;
    double sign = 1.0;
    bool singular = false;
    // The remaining system before its LU, and what the eliminations before it leave for
    // the determinant (the sign of their pivots and of the row and column orders, the
    // number of their pivots, whether one was zero): a new border row (cont_bvp_reborder)
    // redoes only that LU.
    Mat D;
    double sign_chain = 1.0;
    size_t n_chain = 0;
    bool singular_chain = false;
    // The sign of the elimination's row and column orders when no pivoting swaps rows
    // (the orders depend on the sizes alone): each swap a factorisation makes transposes
    // two rows of its order, so its sign is this one times (-1)^swaps.
    double sign_orders = 1.0;
    // Work arrays, allocated once with the object: the dense rows during a factorisation
    // (Ex, NE x nx) and the rows carried along the chain (R); a solve's right-hand sides
    // (rc, re, the reduction's t2, tR, the remaining system's d, z) and the refinement's
    // residual and correction (rr, dd). A solve writes them (mutable): one factorisation
    // is not solved with from two threads at once.
    RawBuffer<double> Exb;
    Mat R;
    mutable RawBuffer<double> rc, re, t2, tR, rr, dd;
    mutable Eigen::VectorXd dv, zv;
};

namespace {

// Dense row e, eliminated through the chain (ex, nx), into the remaining system D.
void final_row(cont_bvp *f, const double *ex, int e) {
    const int n = f->n, np = f->np, nx = f->nx, gN = f->nc;
    for (int i = 0; i < n; ++i) {
        f->D(n + e, i) = ex[i];
        f->D(n + e, n + i) = ex[gN + i];
    }
    for (int i = 0; i < np; ++i) f->D(n + e, 2 * n + i) = ex[nx - np + i];
}

// The LU of the remaining system D, its pivots after the chain's, the determinant's sign.
void factor_final(cont_bvp *f) {
    const int nd = 2 * f->n + f->np;
    f->pivots.resize(f->n_chain);
    double sign = f->sign_chain;
    bool singular = f->singular_chain;
    f->lu.compute(f->D);
    const Mat &U = f->lu.matrixLU();
    for (int i = 0; i < nd; ++i) {
        const double p = U(i, i);
        if (p == 0.0) {
            singular = true;
            continue;
        }
        if (p < 0) sign = -sign;
        f->pivots.push_back(p);
    }
    f->sign = sign * f->lu.permutationP().determinant();
    f->singular = singular;
    f->factored = true;
}

}  // namespace

cont_bvp *cont_bvp_new(int ntst, int ncol, int ndim, int npar) {
    if (ntst < 1 || ncol < 1 || ndim < 1 || npar < 0) return nullptr;
    cont_bvp *f = new (std::nothrow) cont_bvp;
    if (!f) return nullptr;
    f->N = ntst;
    f->m = ncol;
    f->n = ndim;
    f->np = npar;
    f->ne = ndim + npar;
    f->K = (ncol - 1) * ndim;
    f->nc = ntst * ncol * ndim;
    f->nx = (ntst * ncol + 1) * ndim + npar;
    f->cw = (ncol + 1) * ndim + npar;
    f->tw = 3 * ndim + npar;
    try {
        f->Wb.allocate((size_t)ntst * ncol * ndim * f->cw);
        f->E1b.allocate((size_t)ntst * f->ne * f->K);
        f->Tb.allocate((size_t)ntst * 2 * ndim * f->tw);
        f->E2b.allocate((size_t)ntst * f->ne * ndim);
        f->piv1b.allocate((size_t)ntst * f->K);
        f->piv2b.allocate((size_t)ntst * ndim);
        f->Exb.allocate((size_t)f->ne * f->nx);
        f->R.resize(ndim, 2 * ndim + npar);
        f->rc.allocate((size_t)f->nc);
        f->re.allocate((size_t)f->ne);
        f->t2.allocate((size_t)ntst * 2 * ndim);
        f->tR.allocate((size_t)ndim);
        f->rr.allocate((size_t)f->nx);
        f->dd.allocate((size_t)f->nx);
        f->dv.resize(2 * ndim + npar);
        f->zv.resize(2 * ndim + npar);
        f->sign_orders = orders_sign(ntst, ncol, ndim, npar);
    } catch (const std::bad_alloc &) {
        delete f;
        return nullptr;
    }
    return f;
}

void cont_bvp_free(cont_bvp *f) { delete f; }

namespace {

// cont_bvp_factor with NDIM = NN, NPAR = NP and NCOL = NM where they are positive / not
// negative / positive, else f's: with the sizes known to the compiler, the row updates of
// NDIM and NPAR terms (most of them, at NDIM 2 to 4) and the loops over an interval's rows
// and pivots are straight-line code without a loop's set-up; the same operations on the
// same values.
template <int NN, int NP, int NM>
int factor_sized(cont_bvp *f, const double *blocks, const double *parcols,
                 const double *extra, double *sign_logdet, double *P0, double *P1) {
    const int N = f->N, nx = f->nx;
    const int n = NN > 0 ? NN : f->n, np = NP >= 0 ? NP : f->np, ne = n + np;
    const int m = NM > 0 ? NM : f->m, K = (m - 1) * n;
    const int mn = m * n, cw = (m + 1) * n + np;
    std::copy(extra, extra + (size_t)ne * nx, f->Exb.data());
    Eigen::Map<Mat> Ex(f->Exb.data(), ne, nx);
    f->blocks0.assign(blocks, blocks + (size_t)N * mn * (m + 1) * n);
    f->parcols0.assign(parcols, parcols + (size_t)N * mn * np);
    f->extra0.assign(extra, extra + (size_t)ne * nx);
    double sign = 1.0;
    bool singular = false;
    int swaps = 0;                   // row swaps: each changes the sign of the row order
    std::vector<double> &pivots = f->pivots;
    pivots.clear();
    pivots.reserve(nx);
    auto pivot_step = [&](double p) {
        if (p == 0.0) {
            singular = true;
            return;
        }
        if (p < 0) sign = -sign;
        pivots.push_back(p);
    };

    // ---- condensation of the interior nodes of every interval: first each interval's
    // own rows (independent of the other intervals: one after the other without waiting
    // for the chain), then the dense rows through those pivots and the reduction, in the
    // elimination's order (the same operations on every value as interval by interval)
    for (int j = 0; j < N; ++j) {
        Eigen::Map<Mat> W = f->W(j);
        copy_block(W.data(), cw, blocks + (size_t)j * mn * (m + 1) * n, (m + 1) * n, mn,
                   (m + 1) * n);
        copy_block(W.data() + (m + 1) * n, cw, parcols + (size_t)j * mn * np, np, mn, np);
        int *piv = f->piv1(j);
        // (unrolled where NCOL and NDIM are known: every row update of fixed length)
#pragma GCC unroll 16
        for (int t = 0; t < K; ++t) {
            const int c = n + t;
            int p = t;
            for (int r = t + 1; r < mn; ++r)
                if (std::fabs(W(r, c)) > std::fabs(W(p, c))) p = r;
            piv[t] = p;
            if (p != t) {
                W.row(t).swap(W.row(p));
                ++swaps;
            }
            const double d = W(t, c);
            if (d == 0.0) continue;     // no elimination
            // the columns still to eliminate: U_j (0..n-1) and everything right of c
            const double *wt = &W(t, 0);
            for (int r = t + 1; r < mn; ++r) {
                double *wr = &W(r, 0);
                const double l = wr[c] / d;
                wr[c] = l;
                if (l == 0.0) continue;
                sub_scaled(wr, wt, l, n);
                sub_scaled(wr + c + 1, wt + c + 1, l, cw - c - 1);
            }
        }
    }
    Mat &R = f->R;              // the rows carried along the chain: (U_0, U_k, par)
    for (int j = 0; j < N; ++j) {
        Eigen::Map<Mat> W = f->W(j);
        Eigen::Map<Mat> E = f->E1(j);
        for (int t = 0; t < K; ++t) {
            const int c = n + t;
            const double d = W(t, c);   // the pivot row t is final once it has pivoted
            pivot_step(d);
            if (d == 0.0) {             // no elimination: the dense rows' multipliers 0
                E.col(t).setZero();
                continue;
            }
            const int tail = (m + 1) * n - c - 1;
            const double *wt = &W(t, 0);
            for (int e = 0; e < ne; ++e)
                E(e, t) = dense_step_interior(&Ex(e, 0), wt, d, j, t, n, mn, cw, np, nx, tail);
        }
        // the n condensed rows of interval j: (U_j, U_j+1, par)
        // (plain copies of blocks of NDIM and NPAR columns: Eigen's block assignment costs
        // more than the copying at these sizes)
        const int rw = 2 * n + np, tw = 3 * n + np;
        double *Rp = R.data();
        const double *WK = W.data() + (size_t)K * cw;           // the condensed rows
        if (j == 0) {
            copy_block(Rp, rw, WK, cw, n, n);
            copy_block(Rp + n, rw, WK + n + K, cw, n, n);
            copy_block(Rp + 2 * n, rw, WK + (m + 1) * n, cw, n, np);
            continue;
        }
        // ---- reduction: eliminate U_j from R (U_0, U_j, par) and interval j's rows
        Eigen::Map<Mat> T = f->T(j);
        double *Tp = T.data();
        zero_block(Tp + 2 * n, tw, n, n);                      // what is not copied in
        zero_block(Tp + (size_t)n * tw + n, tw, n, n);
        copy_block(Tp, tw, Rp + n, rw, n, n);                   // U_j
        copy_block(Tp + n, tw, Rp, rw, n, n);                   // U_0
        copy_block(Tp + 3 * n, tw, Rp + 2 * n, rw, n, np);
        copy_block(Tp + (size_t)n * tw, tw, WK, cw, n, n);                  // U_j
        copy_block(Tp + (size_t)n * tw + 2 * n, tw, WK + n + K, cw, n, n);  // U_j+1
        copy_block(Tp + (size_t)n * tw + 3 * n, tw, WK + (m + 1) * n, cw, n, np);
        Eigen::Map<Mat> E2 = f->E2(j);
        int *piv2 = f->piv2(j);
        for (int t = 0; t < n; ++t) {
            int p = t;
            for (int r = t + 1; r < 2 * n; ++r)
                if (std::fabs(T(r, t)) > std::fabs(T(p, t))) p = r;
            piv2[t] = p;
            if (p != t) {
                std::swap_ranges(Tp + (size_t)t * tw, Tp + (size_t)(t + 1) * tw,
                                 Tp + (size_t)p * tw);
                ++swaps;
            }
            const double d = T(t, t);
            pivot_step(d);
            if (d == 0.0) {
                E2.col(t).setZero();
                continue;
            }
            const double *tt = &T(t, 0);
            for (int r = t + 1; r < 2 * n; ++r) {
                double *tr = &T(r, 0);
                const double l = tr[t] / d;
                tr[t] = l;
                if (l == 0.0) continue;
                sub_scaled(tr + t + 1, tt + t + 1, l, tw - t - 1);
            }
            for (int e = 0; e < ne; ++e)
                E2(e, t) = dense_step_end(&Ex(e, 0), tt, d, j, t, n, mn, np, nx);
        }
        copy_block(Rp, rw, Tp + (size_t)n * tw + n, tw, n, n);
        copy_block(Rp + n, rw, Tp + (size_t)n * tw + 2 * n, tw, n, n);
        copy_block(Rp + 2 * n, rw, Tp + (size_t)n * tw + 3 * n, tw, n, np);
    }
    // R: P0 U_0 + P1 U_N + S par = ... (the collocation rows, reduced)
    f->Rfin = R;
    Eigen::Map<Mat>(P0, n, n) = R.leftCols(n);
    Eigen::Map<Mat>(P1, n, n) = R.middleCols(n, n);
    // ---- the remaining system in (U_0, U_N, par)
    const int nd = 2 * n + np;
    f->D.resize(nd, nd);
    f->D.topRows(n) = R;
    for (int e = 0; e < ne; ++e) final_row(f, &Ex(e, 0), e);
    const double orders = swaps % 2 ? -f->sign_orders : f->sign_orders;
    f->sign_chain = sign * orders;
    f->singular_chain = singular;
    f->n_chain = pivots.size();
    factor_final(f);
    if (sign_logdet) cont_bvp_sign_logdet(f, sign_logdet);
    return f->singular ? 1 : 0;
}

}  // namespace

int cont_bvp_factor(cont_bvp *f, const double *blocks, const double *parcols,
                    const double *extra, double *sign_logdet, double *P0, double *P1) {
    if (f->np == 2 && f->m == 4) {  // periodic orbits ((PERIOD, a parameter), NCOL 4)
        switch (f->n) {
        case 2: return factor_sized<2, 2, 4>(f, blocks, parcols, extra, sign_logdet, P0, P1);
        case 3: return factor_sized<3, 2, 4>(f, blocks, parcols, extra, sign_logdet, P0, P1);
        case 4: return factor_sized<4, 2, 4>(f, blocks, parcols, extra, sign_logdet, P0, P1);
        default: break;
        }
    }
    if (f->np == 2) {
        switch (f->n) {
        case 2: return factor_sized<2, 2, 0>(f, blocks, parcols, extra, sign_logdet, P0, P1);
        case 3: return factor_sized<3, 2, 0>(f, blocks, parcols, extra, sign_logdet, P0, P1);
        case 4: return factor_sized<4, 2, 0>(f, blocks, parcols, extra, sign_logdet, P0, P1);
        default: break;
        }
    }
    return factor_sized<0, -1, 0>(f, blocks, parcols, extra, sign_logdet, P0, P1);
}

int cont_bvp_reborder(cont_bvp *f, const double *row) {
    const int N = f->N, m = f->m, n = f->n, np = f->np, ne = f->ne, K = f->K, nx = f->nx;
    const int mn = m * n, cw = (m + 1) * n + np, e = ne - 1;
    if (!f->factored) return 2;
    if (f->singular_chain) return 3;
    std::copy(row, row + nx, f->extra0.begin() + (size_t)e * nx);
    std::vector<double> ex(row, row + nx);
    const cont_bvp *cf = f;
    // the row through the factorisation's eliminations, by the calls that took the
    // other dense rows through them (dense_step_interior, dense_step_end)
    for (int j = 0; j < N; ++j) {
        const Eigen::Map<const Mat> W = cf->W(j);
        Eigen::Map<Mat> E = f->E1(j);
        for (int t = 0; t < K; ++t) {
            const int c = n + t;
            E(e, t) = dense_step_interior(ex.data(), W.data() + (size_t)t * cw, W(t, c), j, t, n, mn, cw, np,
                                          nx, (m + 1) * n - c - 1);
        }
        if (j == 0) continue;
        const Eigen::Map<const Mat> T = cf->T(j);
        Eigen::Map<Mat> E2 = f->E2(j);
        for (int t = 0; t < n; ++t)
            E2(e, t) = dense_step_end(ex.data(), T.data() + (size_t)t * (3 * n + np), T(t, t), j, t, n, mn, np, nx);
    }
    final_row(f, ex.data(), e);
    factor_final(f);
    return f->singular ? 1 : 0;
}

int cont_bvp_sign_logdet(const cont_bvp *f, double *sign_logdet) {
    double logdet = 0.0;
    for (double p : f->pivots) logdet += std::log(std::fabs(p));
    sign_logdet[0] = f->singular ? 0.0 : f->sign;
    sign_logdet[1] = f->singular ? -INFINITY : logdet;
    return f->singular ? 1 : 0;
}

int cont_bvp_schur(const cont_bvp *f, const double *extra, double *Sc) {
    const int N = f->N, m = f->m, n = f->n, np = f->np, ne = f->ne, K = f->K, nx = f->nx;
    const int mn = m * n;
    if (!f->factored || f->Rfin.rows() != n) return 2;
    Mat Ex = Eigen::Map<const Mat>(extra, ne, nx);
    // the dense rows through the eliminations of cont_bvp_factor, as they went there
    // (each pivot row is final once it has pivoted), by the calls that took its dense
    // rows through them (dense_step_interior, dense_step_end)
    const int cw = (m + 1) * n + np;
    for (int j = 0; j < N; ++j) {
        const Eigen::Map<const Mat> W = f->W(j);
        for (int t = 0; t < K; ++t) {
            const int c = n + t;
            const double d = W(t, c);
            if (d == 0.0) return 1;
            for (int e = 0; e < ne; ++e)
                dense_step_interior(&Ex(e, 0), W.data() + (size_t)t * cw, d, j, t, n, mn, cw,
                                    np, nx, (m + 1) * n - c - 1);
        }
        if (j == 0) continue;
        const Eigen::Map<const Mat> T = f->T(j);
        for (int t = 0; t < n; ++t) {
            const double d = T(t, t);
            if (d == 0.0) return 1;
            for (int e = 0; e < ne; ++e)
                dense_step_end(&Ex(e, 0), T.data() + (size_t)t * (3 * n + np), d, j, t, n, mn,
                               np, nx);
        }
    }
    // eliminate U_N with the reduced collocation rows: Sc = E_S - E_N P1^-1 [P0 Ppar]
    const int gN = N * mn, ns = n + np;
    const Mat &R = f->Rfin;
    Eigen::FullPivLU<Mat> p1(R.middleCols(n, n));
    if (!p1.isInvertible()) return 1;
    Mat RS(n, ns);
    RS.leftCols(n) = R.leftCols(n);
    if (np) RS.rightCols(np) = R.rightCols(np);
    const Mat Y = p1.solve(RS);                           // P1^-1 [P0 Ppar]
    Eigen::Map<Mat> out(Sc, ne, ns);
    for (int e = 0; e < ne; ++e) {
        for (int i = 0; i < n; ++i) out(e, i) = Ex(e, i);
        for (int i = 0; i < np; ++i) out(e, n + i) = Ex(e, nx - np + i);
    }
    out -= Ex.block(0, gN, ne, n) * Y;
    return 0;
}

int cont_bvp_bp_test(const cont_bvp *f, void *getrf, void *ddot, const double *tail,
                     const int *rows, const int *cols, int ntail, int phase,
                     const double *w_node, double T, const double *F, const double *theta,
                     const double *tangent, double *Sc, double *out) {
    const int n = f->n, ne = f->ne, nx = f->nx, nu = (f->N * f->m + 1) * n;
    if (phase < 0 || phase >= ne - 1 || ntail < 0) return -1;
    // the dense rows as reduction.dense_rows scatters them, the own-phase row
    // (PeriodicOrbits._own_phase_row: T f first, then the node weight) and the border
    std::vector<double> extra((size_t)ne * nx, 0.0);
    for (int q = 0; q < ntail; ++q) {
        if (rows[q] < 0 || rows[q] >= ne || cols[q] < 0 || cols[q] >= nx) return -1;
        extra[(size_t)rows[q] * nx + cols[q]] = tail[q];
    }
    double *ph = &extra[(size_t)phase * nx];
    for (int c = 0; c < nu; ++c) ph[c] = w_node[c / n] * (T * F[c]);
    for (int c = nu; c < nx; ++c) ph[c] = 0.0;
    double *border = &extra[(size_t)(ne - 1) * nx];
    for (int c = 0; c < nx; ++c) border[c] = theta[c] * tangent[c];
    const int rc = cont_bvp_schur(f, extra.data(), Sc);
    if (rc != 0) return 10 + rc;
    RawBuffer<double> work(2 * (size_t)ne * ne);
    RawBuffer<int64_t> ipiv(ne);
    return cont_scaled_slogdet(getrf, ddot, ne, Sc, work.data(), ipiv.data(), out);
}

namespace {

// The back substitution of the interior nodes of the L intervals j0 .. j0 + L - 1 (their
// end nodes and the parameters par known), interleaved: each interval's values take the
// operations of one interval alone, in its order (the same values); side by side, the
// divisions and the chains of subtractions of one interval overlap another's instead of
// waiting for each other. NN, NP as in factor_sized.
template <int NN, int NP, int NM, int L>
inline void back_interior(const cont_bvp *f, const double *rc, double *x, const double *par,
                          int j0) {
    const int n = NN > 0 ? NN : f->n, np = NP >= 0 ? NP : f->np;
    const int m = NM > 0 ? NM : f->m, K = (m - 1) * n, mn = m * n, cw = (m + 1) * n + np;
    const double *W[L], *rb[L], *uL[L], *uR[L];
    double *uI[L];
    for (int l = 0; l < L; ++l) {
        const int j = j0 + l;
        W[l] = f->Wb.data() + (size_t)j * mn * cw;
        rb[l] = rc + (size_t)j * mn;
        uL[l] = x + (size_t)j * mn;
        uR[l] = x + (size_t)(j + 1) * mn;
        uI[l] = x + (size_t)j * mn + n;
    }
    for (int t = K - 1; t >= 0; --t) {
        double s[L];
        for (int l = 0; l < L; ++l) s[l] = rb[l][t];
        for (int w = t + 1; w < K; ++w)
            for (int l = 0; l < L; ++l) s[l] -= W[l][(size_t)t * cw + n + w] * uI[l][w];
        for (int i = 0; i < n; ++i)
            for (int l = 0; l < L; ++l)
                s[l] -= W[l][(size_t)t * cw + i] * uL[l][i]
                        + W[l][(size_t)t * cw + n + K + i] * uR[l][i];
        for (int i = 0; i < np; ++i)
            for (int l = 0; l < L; ++l) s[l] -= W[l][(size_t)t * cw + (m + 1) * n + i] * par[i];
        for (int l = 0; l < L; ++l) uI[l][t] = s[l] / W[l][(size_t)t * cw + n + t];
    }
}

// The forward substitution of the L intervals j0 .. j0 + L - 1 through their own rows
// (rc: their right-hand sides, in place), interleaved as in back_interior. The factor
// swapped whole rows (multipliers included, as LAPACK's getrf): all interchanges first,
// then the unit lower triangle row by row: each rb[r] takes its updates in the pivots'
// order, as column by column (the same operations), from a contiguous row of multipliers.
template <int NN, int NP, int NM, int L>
inline void forward_interior(const cont_bvp *f, double *rc, int j0) {
    const int n = NN > 0 ? NN : f->n, np = NP >= 0 ? NP : f->np;
    const int m = NM > 0 ? NM : f->m, K = (m - 1) * n, mn = m * n, cw = (m + 1) * n + np;
    const double *W[L];
    double *rb[L];
    for (int l = 0; l < L; ++l) {
        const int j = j0 + l;
        W[l] = f->Wb.data() + (size_t)j * mn * cw + n;
        rb[l] = rc + (size_t)j * mn;
        const int *piv = f->piv1(j);
        for (int t = 0; t < K; ++t)
            if (piv[t] != t) std::swap(rb[l][t], rb[l][piv[t]]);
    }
    for (int r = 1; r < mn; ++r) {
        double s[L];
        for (int l = 0; l < L; ++l) s[l] = rb[l][r];
        for (int t = 0, tn = std::min(r, K); t < tn; ++t)
            for (int l = 0; l < L; ++l) s[l] -= W[l][(size_t)r * cw + t] * rb[l][t];
        for (int l = 0; l < L; ++l) rb[l][r] = s[l];
    }
}

// One solve with the factorisation; NN, NP, NM as in factor_sized.
template <int NN, int NP, int NM>
void solve_sized(const cont_bvp *f, const double *rhs, double *x) {
    const int N = f->N, nx = f->nx;
    const int n = NN > 0 ? NN : f->n, np = NP >= 0 ? NP : f->np, ne = n + np;
    const int m = NM > 0 ? NM : f->m, K = (m - 1) * n;
    const int mn = m * n;
    RawBuffer<double> &rc = f->rc, &re = f->re;
    std::copy(rhs, rhs + f->nc, rc.data());
    std::copy(rhs + f->nc, rhs + nx, re.data());
    RawBuffer<double> &t2all = f->t2;               // the reduction's right-hand sides
    // forward: condensation (the intervals' own rows four intervals at a time,
    // forward_interior; the dense rows interval after interval)
    for (int j = 0; j < N; ++j) {
        double *rb = rc.data() + (size_t)j * mn;
        if (j % 4 == 0) {
            if (j + 4 <= N) forward_interior<NN, NP, NM, 4>(f, rc.data(), j);
            else
                for (int i = j; i < N; ++i) forward_interior<NN, NP, NM, 1>(f, rc.data(), i);
        }
        const double *E1 = f->E1b.data() + (size_t)j * ne * K;
        for (int e = 0; e < ne; ++e) {
            double s = re[e];
            for (int t = 0; t < K; ++t) s -= E1[(size_t)e * K + t] * rb[t];
            re[e] = s;
        }
    }
    // forward: reduction
    RawBuffer<double> &tR = f->tR;
    std::copy(rc.begin() + K, rc.begin() + mn, tR.data());
    for (int j = 1; j < N; ++j) {
        const Eigen::Map<const Mat> T = f->T(j);
        double *tv = t2all.data() + (size_t)j * 2 * n;
        for (int r = 0; r < n; ++r) {
            tv[r] = tR[r];
            tv[n + r] = rc[(size_t)j * mn + K + r];
        }
        for (int t = 0; t < n; ++t) {
            const int p = f->piv2(j)[t];
            if (p != t) std::swap(tv[t], tv[p]);
        }
        for (int r = 1; r < 2 * n; ++r) {            // row by row, as above
            const double *tr = T.data() + (size_t)r * T.cols();
            double s = tv[r];
            for (int t = 0, tn = std::min(r, n); t < tn; ++t) s -= tr[t] * tv[t];
            tv[r] = s;
        }
        const double *E2 = f->E2b.data() + (size_t)j * ne * n;
        for (int e = 0; e < ne; ++e) {
            double s = re[e];
            for (int t = 0; t < n; ++t) s -= E2[(size_t)e * n + t] * tv[t];
            re[e] = s;
        }
        for (int r = 0; r < n; ++r) tR[r] = tv[n + r];
    }
    // the (U_0, U_N, par) system
    const int gN = N * mn;
    Eigen::VectorXd &d = f->dv, &z = f->zv;
    for (int r = 0; r < n; ++r) d(r) = tR[r];
    for (int e = 0; e < ne; ++e) d(n + e) = re[e];
    z = f->lu.solve(d);
    for (int i = 0; i < n; ++i) {
        x[i] = z(i);
        x[gN + i] = z(n + i);
    }
    for (int i = 0; i < np; ++i) x[nx - np + i] = z(2 * n + i);
    const double *par = x + nx - np;
    // back: the end nodes U_N-1 .. U_1
    for (int j = N - 1; j >= 1; --j) {
        const Eigen::Map<const Mat> T = f->T(j);
        const double *tv = t2all.data() + (size_t)j * 2 * n;
        const double *u0 = x, *u1 = x + (size_t)(j + 1) * mn;
        double *uj = x + (size_t)j * mn;
        for (int t = n - 1; t >= 0; --t) {
            double s = tv[t];
            for (int w = t + 1; w < n; ++w) s -= T(t, w) * uj[w];
            for (int i = 0; i < n; ++i) s -= T(t, n + i) * u0[i] + T(t, 2 * n + i) * u1[i];
            for (int i = 0; i < np; ++i) s -= T(t, 3 * n + i) * par[i];
            uj[t] = s / T(t, t);
        }
    }
    // back: the interior nodes of every interval (independent of each other once the
    // end nodes are known), four intervals at a time
    int j = 0;
    for (; j + 4 <= N; j += 4) back_interior<NN, NP, NM, 4>(f, rc.data(), x, par, j);
    for (; j < N; ++j) back_interior<NN, NP, NM, 1>(f, rc.data(), x, par, j);
}

void solve_once(const cont_bvp *f, const double *rhs, double *x) {
    if (f->np == 2 && f->m == 4) {
        switch (f->n) {
        case 2: return solve_sized<2, 2, 4>(f, rhs, x);
        case 3: return solve_sized<3, 2, 4>(f, rhs, x);
        case 4: return solve_sized<4, 2, 4>(f, rhs, x);
        default: break;
        }
    }
    if (f->np == 2) {
        switch (f->n) {
        case 2: return solve_sized<2, 2, 0>(f, rhs, x);
        case 3: return solve_sized<3, 2, 0>(f, rhs, x);
        case 4: return solve_sized<4, 2, 0>(f, rhs, x);
        default: break;
        }
    }
    solve_sized<0, -1, 0>(f, rhs, x);
}

// r = rhs - M x with the matrix as given to cont_bvp_factor.
// s[l] -= A[l, k] v[k] for k = 0 .. len - 1 in order, for the L rows of A (row stride
// `stride`) side by side: each row's sum is taken in its own order (the same values as one
// row at a time), and the L chains of subtractions overlap instead of waiting for each other.
template <int L>
inline void minus_dots(const double *A, size_t stride, const double *v, int len, double *s) {
    for (int k = 0; k < len; ++k)
        for (int l = 0; l < L; ++l) s[l] -= A[l * stride + k] * v[k];
}

// r[i] = rhs[i] - A[i, :len] v for the `rows` rows of A (row stride `stride`), and, where
// C is given, minus C[i, :clen] c after that: four rows at a time (minus_dots).
void rows_residual(const double *rhs, const double *A, size_t stride, const double *v, int len,
                   const double *C, const double *c, int clen, int rows, double *r) {
    int i = 0;
    for (; i + 4 <= rows; i += 4) {
        double s[4] = {rhs[i], rhs[i + 1], rhs[i + 2], rhs[i + 3]};
        minus_dots<4>(A + (size_t)i * stride, stride, v, len, s);
        if (C) minus_dots<4>(C + (size_t)i * clen, clen, c, clen, s);
        std::copy(s, s + 4, r + i);
    }
    for (; i < rows; ++i) {
        double s[1] = {rhs[i]};
        minus_dots<1>(A + (size_t)i * stride, stride, v, len, s);
        if (C) minus_dots<1>(C + (size_t)i * clen, clen, c, clen, s);
        r[i] = s[0];
    }
}

void residual(const cont_bvp *f, const double *rhs, const double *x, double *r) {
    const int N = f->N, m = f->m, n = f->n, np = f->np, ne = f->ne, nx = f->nx;
    const int mn = m * n, w = (m + 1) * n;
    const double *par = x + nx - np;
    for (int j = 0; j < N; ++j) {
        const size_t o = (size_t)j * mn;
        rows_residual(rhs + o, f->blocks0.data() + o * w, w, x + o, w,
                      np ? f->parcols0.data() + o * np : nullptr, par, np, mn, r + o);
    }
    rows_residual(rhs + f->nc, f->extra0.data(), nx, x, nx, nullptr, nullptr, 0, ne,
                  r + f->nc);
}

}  // namespace

// One solve and one step of iterative refinement: the pivoting is confined to the
// rows of one interval (or two, in the reduction), which lets the elimination grow
// more than LAPACK's; the refinement brings the backward error back to rounding level
// (near homoclinic orbits the corrector needs it: ab's seventh family stalled otherwise).
int cont_bvp_solve(const cont_bvp *f, const double *rhs, double *x) {
    solve_once(f, rhs, x);
    RawBuffer<double> &r = f->rr, &d = f->dd;
    residual(f, rhs, x, r.data());
    solve_once(f, r.data(), d.data());
    for (int i = 0; i < f->nx; ++i) x[i] += d[i];
    return 0;
}

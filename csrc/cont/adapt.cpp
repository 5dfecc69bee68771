// ADAPT's interpolation (AUTO's INTERP, washer.cont.collocation.evaluator): the piecewise
// polynomial of degree NCOL through a profile's node values, evaluated at given times.
// The arithmetic is numpy's in washer/cont/collocation.py, operation for operation
// (compiled with -ffp-contract=off: no fused multiply-adds), so the values are the same
// to the bit:
//   j = searchsorted(tm, t, 'right') - 1 clipped to [0, NTST - 1], z = (t - tm[j]) / dtm[j];
//   the Lagrange basis on the nodes k / NCOL at z: 1.0 times (z - x_k) over the other
//   nodes in increasing order, divided by the product of (x_b - x_k) (_lagrange);
//   each value the sum over the interval's NCOL + 1 nodes in order from 0.0 (numpy's
//   einsum "tk,tk...->t..." sums in that order when the values have two or more columns).
#include "cont.h"

#include <algorithm>
#include <cmath>

namespace {

// The count of a[k] <= x in a non-decreasing array without NaN (numpy's searchsorted
// 'right', the search np.interp makes): std::upper_bound's place of x.
int count_not_above(const double *a, int len, double x)
{
    return (int)(std::upper_bound(a, a + len, x) - a);
}

}  // namespace

extern "C" int cont_mesh_weights(int ntst, int ncol, const double *tm, const double *dtm,
                                 int nt, const double *t, const double *others,
                                 const double *denom, int *j, double *W)
{
    const int nb = ncol + 1;
    if (ntst < 1 || ncol < 1 || nt < 0)
        return 2;
    // numpy's binary search is that of a sorted array only without NaN: otherwise the
    // caller computes it with numpy
    for (int i = 0; i <= ntst; ++i)
        if (std::isnan(tm[i]) || (i > 0 && !(tm[i - 1] <= tm[i])))
            return 1;
    for (int i = 0; i < nt; ++i)
        if (std::isnan(t[i]))
            return 1;
    // The count of tm[k] <= t[i] by a walk on from the previous time's count where the
    // times increase (node times: ADAPT's; a search's branches are unpredictable), else
    // by the search: the same count either way.
    int count = 0;
    for (int i = 0; i < nt; ++i) {
        const double ti = t[i];
        if (i > 0 && t[i - 1] <= ti) {
            while (count <= ntst && tm[count] <= ti)
                ++count;
        } else {
            count = count_not_above(tm, ntst + 1, ti);
        }
        int jj = count - 1;
        if (jj < 0)
            jj = 0;
        if (jj > ntst - 1)
            jj = ntst - 1;
        j[i] = jj;
        const double z = (ti - tm[jj]) / dtm[jj];
        for (int b = 0; b < nb; ++b) {
            double L = 1.0;
            for (int s = 0; s < ncol; ++s)
                L *= z - others[s * nb + b];
            W[(size_t)b * nt + i] = L / denom[b];
        }
    }
    return 0;
}

extern "C" void cont_mesh_apply(int nt, int ncol, const int *j, const double *W,
                                const double *U, int width, double *out)
{
    const int nb = ncol + 1;
    // Each value's sum is a chain of dependent additions; kept in a register until it is
    // stored, the chains of successive values overlap in the processor (summed in place
    // in out, every addition waited for the store before it: 4.3 us at NTPL 281, NDIM 2)
    for (int i = 0; i < nt; ++i) {
        const double *u = U + (size_t)j[i] * ncol * width;
        double *o = out + (size_t)i * width;
        for (int c = 0; c < width; ++c) {
            double s = 0.0;
            for (int k = 0; k < nb; ++k)
                s = s + W[(size_t)k * nt + i] * u[(size_t)k * width + c];
            o[c] = s;
        }
    }
}

// ADAPT's new mesh (AUTO's EQDF and NEWMSH, washer.cont.collocation.eqdf and new_mesh),
// numpy's operations in numpy's order: each power by numpy's own loop for doubles (on this
// machine an SVML kernel that differs from libm's pow in the last bit for some arguments),
// called once on the whole array as numpy calls it; the sums over the components by
// numpy's pairwise sum from 0.0; einsum's sum over the interval's nodes in order from 0.0;
// cumsum in order; np.interp's search and its slope formula.
#include "numpy_sum.h"

#include <vector>

typedef void np_loop_t(char **args, const ptrdiff_t *n, const ptrdiff_t *steps, void *data);

namespace {

// out[i] = a[i] ** e (numpy's power loop, the exponent a scalar: stride 0, as numpy passes
// a Python number)
void np_power(void *loop, void *data, const double *a, double e, double *out, ptrdiff_t len)
{
    if (len <= 0)
        return;
    char *args[3] = {(char *)a, (char *)&e, (char *)out};
    const ptrdiff_t n[1] = {len};
    const ptrdiff_t steps[3] = {8, 0, 8};
    ((np_loop_t *)loop)(args, n, steps, data);
}

// np.interp(x, xp, fp) at one x for xp non-decreasing without NaN (left fp[0], right fp[-1])
double np_interp(double x, const double *xp, const double *fp, int len)
{
    if (x > xp[len - 1])
        return fp[len - 1];
    if (x < xp[0])
        return fp[0];
    const int j = count_not_above(xp, len, x) - 1;
    if (j == len - 1 || xp[j] == x)
        return fp[j];
    const double slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j]);
    double r = slope * (x - xp[j]) + fp[j];
    if (std::isnan(r)) {
        r = slope * (x - xp[j + 1]) + fp[j + 1];
        if (std::isnan(r) && fp[j] == fp[j + 1])
            r = fp[j];
    }
    return r;
}

}  // namespace

extern "C" int cont_new_mesh(int ntst, int ncol, int ndim, const double *tm, const double *dtm,
                             const double *U, int periodic, const double *cntdif, double small,
                             void *pow_loop, void *pow_data, int ntst_new, double *tm_new)
{
    const int N = ntst, m = ncol, n = ndim;
    if (N < 1 || m < 1 || n < 1 || ntst_new < 1 || pow_loop == nullptr)
        return 2;
    std::vector<double> hd((size_t)N * n), pj(N), q(N), v((size_t)N * n);
    // hd = ((m / dtm) ** m)[:, None] * einsum("k,jkn->jn", CNTDIF, U at each interval's nodes)
    for (int j = 0; j < N; ++j)
        q[j] = (double)m / dtm[j];
    np_power(pow_loop, pow_data, q.data(), (double)m, pj.data(), N);
    bool all_small = true;
    for (int j = 0; j < N; ++j) {
        const double *u = U + (size_t)j * m * n;
        for (int c = 0; c < n; ++c) {
            double s = 0.0;
            for (int k = 0; k <= m; ++k)
                s = s + cntdif[k] * u[(size_t)k * n + c];
            const double h = pj[j] * s;
            hd[(size_t)j * n + c] = h;
            if (!(std::fabs(h) <= small))
                all_small = false;
        }
    }
    const double pwr = 1.0 / (m + 1);
    std::vector<double> eqf(N + 1, 0.0);
    if (N > 1) {
        for (int j = 0; j < N - 1; ++j)
            for (int c = 0; c < n; ++c)
                v[(size_t)j * n + c] = std::fabs(2 * (hd[(size_t)(j + 1) * n + c] - hd[(size_t)j * n + c])
                                                 / (dtm[j] + dtm[j + 1]));
        std::vector<double> w((size_t)(N - 1) * n);
        np_power(pow_loop, pow_data, v.data(), pwr, w.data(), (ptrdiff_t)(N - 1) * n);
        double acc = 0.0;
        for (int j = 0; j < N - 1; ++j) {
            const double ej = 0.0 + pairwise_sum(w.data() + (size_t)j * n, n);
            const double x = dtm[j] * ej;
            acc = (j == 0) ? x : acc + x;
            eqf[j + 1] = acc;
        }
    }
    const int jj = periodic ? 0 : (N - 2 > 0 ? N - 2 : 0);
    const double dtav = periodic ? (dtm[N - 1] + dtm[0]) / 2 : dtm[N - 1];
    std::vector<double> a(n), b(n);
    for (int c = 0; c < n; ++c)
        a[c] = std::fabs((hd[(size_t)jj * n + c] - hd[(size_t)(N - 1) * n + c]) / dtav);
    np_power(pow_loop, pow_data, a.data(), pwr, b.data(), n);
    eqf[N] = eqf[N - 1] + dtm[N - 1] * (0.0 + pairwise_sum(b.data(), n));
    if (all_small)
        for (int i = 0; i <= N; ++i)
            eqf[i] = (double)i;
    // NEWMSH: what numpy's comparisons and search order alone (a NaN, an infinity) is left
    // to numpy
    for (int i = 0; i <= N; ++i)
        if (!std::isfinite(eqf[i]))
            return 1;
    bool increasing = true;
    for (int i = 0; i < N; ++i)
        if (!(eqf[i + 1] - eqf[i] > 0))
            increasing = false;
    if (!increasing) {
        const double s = 1e-12 * eqf[N];
        const double den = (double)(N > 1 ? N : 1);
        for (int i = 0; i <= N; ++i)
            eqf[i] = eqf[i] + s * (double)i / den;
        for (int i = 0; i < N; ++i)
            if (!(eqf[i] <= eqf[i + 1]))
                return 1;
    }
    tm_new[0] = tm[0];
    for (int k = 1; k < ntst_new; ++k)
        tm_new[k] = np_interp(eqf[N] * (double)k / (double)ntst_new, eqf.data(), tm, N + 1);
    tm_new[ntst_new] = tm[N];
    return 0;
}

// ADAPT in one call (washer.cont.collocation.adapt): NEWMSH's mesh of the same NTST
// (cont_new_mesh), the new mesh's interval lengths (np.diff), node times
// (Mesh.node_times: tm[j] + dtm[j] * (k / NCOL), then tm[NTST]) and quadrature weights
// (Mesh.node_weights: dtm[j] WI[k] at node j NCOL + k, an interval's first node plus the
// previous interval's last term), and the interpolation from the old mesh onto the new
// nodes (cont_mesh_weights).
extern "C" int cont_adapt_mesh(int ntst, int ncol, int ndim, const double *tm, const double *dtm,
                               const double *U, int periodic, const double *cntdif, double small,
                               void *pow_loop, void *pow_data, const double *others,
                               const double *denom, const double *wi, double *tm_new,
                               double *dtm_new, double *t_new, double *w_new, int *j, double *W)
{
    const int N = ntst, m = ncol;
    int status = cont_new_mesh(N, m, ndim, tm, dtm, U, periodic, cntdif, small, pow_loop,
                               pow_data, N, tm_new);
    if (status != 0)
        return status;
    for (int i = 0; i < N; ++i)
        dtm_new[i] = tm_new[i + 1] - tm_new[i];
    for (int i = 0; i < N; ++i)
        for (int k = 0; k < m; ++k) {
            t_new[(size_t)i * m + k] = tm_new[i] + dtm_new[i] * ((double)k / (double)m);
            w_new[(size_t)i * m + k] = dtm_new[i] * wi[k];
        }
    t_new[(size_t)N * m] = tm_new[N];
    for (int i = 1; i < N; ++i)
        w_new[(size_t)i * m] = w_new[(size_t)i * m] + dtm_new[i - 1] * wi[m];
    w_new[(size_t)N * m] = dtm_new[N - 1] * wi[m];
    return cont_mesh_weights(N, m, tm, dtm, N * m + 1, t_new, others, denom, j, W);
}

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

#include <cmath>

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
    for (int i = 0; i < nt; ++i) {
        const double ti = t[i];
        int lo = 0, hi = ntst + 1;                 // the count of tm[k] <= t[i]
        while (lo < hi) {
            const int mid = lo + ((hi - lo) >> 1);
            if (tm[mid] <= ti)
                lo = mid + 1;
            else
                hi = mid;
        }
        int jj = lo - 1;
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
    for (int i = 0; i < nt; ++i) {
        const double *u = U + (size_t)j[i] * ncol * width;
        double *o = out + (size_t)i * width;
        for (int c = 0; c < width; ++c)
            o[c] = 0.0;
        for (int k = 0; k < nb; ++k) {
            const double wk = W[(size_t)k * nt + i];
            const double *uk = u + (size_t)k * width;
            for (int c = 0; c < width; ++c)
                o[c] = o[c] + wk * uk[c];
        }
    }
}

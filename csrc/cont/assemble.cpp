// The collocation blocks of a boundary-value problem's Jacobian, assembled from the
// Jacobians of the (scaled) right-hand side at the Gauss points (layout and contract:
// cont_api.h). The same operations in the same order as the numpy expression of
// washer.cont.collocation.Collocation.local_blocks, so the values are identical.
#include "cont.h"

namespace {

// NDIM = NN where it is positive, else ndim: with the size known to the compiler the
// innermost loop is straight-line code (the same operations).
template <int NN>
void blocks_sized(int ntst, int ncol, int ndim, const double *WT, const double *WP,
                  const double *dtm, double T, const double *A, double *blocks) {
    const int m = ncol, n = NN > 0 ? NN : ndim;
    const long w = (long)(m + 1) * n;               // a block's row length
    for (int j = 0; j < ntst; ++j) {
        const double s = dtm[j] * T;
        for (int c = 0; c < m; ++c) {
            const double *Ac = A + ((long)j * m + c) * n * n;
            for (int i = 0; i < n; ++i) {
                double *row = blocks + (((long)j * m + c) * n + i) * w;
                for (int k = 0; k <= m; ++k) {
                    const double wp = WP[k * m + c], wt = s * WT[k * m + c];
                    double *out = row + (long)k * n;
                    for (int l = 0; l < n; ++l)
                        out[l] = (l == i ? wp * 1.0 : wp * 0.0) - wt * Ac[i * n + l];
                }
            }
        }
    }
}

}  // namespace

int cont_coll_blocks(int ntst, int ncol, int ndim, const double *WT, const double *WP,
                     const double *dtm, double T, const double *A, double *blocks) {
    if (ntst < 1 || ncol < 1 || ndim < 1) return 2;
    switch (ndim) {
    case 2: blocks_sized<2>(ntst, ncol, ndim, WT, WP, dtm, T, A, blocks); break;
    case 3: blocks_sized<3>(ntst, ncol, ndim, WT, WP, dtm, T, A, blocks); break;
    case 4: blocks_sized<4>(ntst, ncol, ndim, WT, WP, dtm, T, A, blocks); break;
    default: blocks_sized<0>(ntst, ncol, ndim, WT, WP, dtm, T, A, blocks); break;
    }
    return 0;
}

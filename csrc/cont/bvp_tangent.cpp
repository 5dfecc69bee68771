// The unit tangent of a BVP's point from the factorisation of its bordered Jacobian
// (washer.cont.iterator.Continuation.tangent with CollocationBVP's inner product, one call
// where it was a solve and a dozen numpy operations): z = M^-1 e_n by cont_bvp_solve, its
// norm sqrt|<z, theta z>| with <a, b> as numpy's dot of two vectors sums it (0.0 plus
// numpy's own CBLAS ddot of a and theta * b), then z / norm: the same doubles.
#include "cont.h"
#include "numpy_sum.h"

#include <cmath>
#include <vector>

extern "C" int cont_bvp_unit_tangent(const cont_bvp *f, int nx, const double *theta, double big,
                                     void *ddot, double *t)
{
    if (nx < 1 || ddot == nullptr)
        return 2;
    std::vector<double> e(nx, 0.0), wz(nx);
    e[nx - 1] = 1.0;
    cont_bvp_solve(f, e.data(), t);
    for (int i = 0; i < nx; ++i)
        if (!std::isfinite(t[i]))
            return 1;
    for (int i = 0; i < nx; ++i)
        wz[i] = theta[i] * t[i];
    double s = 0.0;
    s += ((numpy_cblas_ddot_t)ddot)(nx, t, 1, wz.data(), 1);
    const double nz = std::sqrt(std::fabs(s));
    if (!std::isfinite(nz) || nz == 0.0 || nz > big)
        return 1;
    for (int i = 0; i < nx; ++i)
        t[i] = t[i] / nz;
    return 0;
}

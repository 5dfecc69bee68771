// numpy's absolute value of a complex number, the same double: the engine's C decides on
// the values numpy's np.abs gives (floquet.cpp's multiplier order, fold_tests.cpp's
// complex eigenvalues).
#ifndef WASHER_NUMPY_CABS_H
#define WASHER_NUMPY_CABS_H
#include <cmath>

// numpy's absolute value of a complex number (its SIMD loop, which contiguous arrays take
// on this machine): the larger part times sqrt(fma(r, r, 1)), r the smaller over the
// larger; inf if a part is infinite, else nan if one is nan, 0 where both are 0. It is
// not libm's hypot (they differ in the last bit for about a third of random numbers).
inline double numpy_cabs(double re, double im) {
    re = std::fabs(re);
    im = std::fabs(im);
    if (std::isinf(re) || std::isinf(im)) return INFINITY;
    if (std::isnan(re) || std::isnan(im)) return NAN;
    double big = re > im ? re : im, small = re > im ? im : re;
    if (big == 0.0) return 0.0;
    double r = small / big;
    return big * std::sqrt(std::fma(r, r, 1.0));
}

#endif

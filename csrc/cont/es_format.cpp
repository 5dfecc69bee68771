// Fortran's ESw.d and ESw.dE3 edit descriptors as gfortran writes them, for one value
// (es_field, es_format.h) and for rows of doubles (cont_format_es in cont_api.h): the
// numbers of AUTO-07p's b-, s- and d-files, whose lines auto_point.cpp lays out.
//
// The decimal digits are the correctly rounded ones (ties to even, as C's printf and
// Python's float formatting): a value whose scaled mantissa x * 10^s (or x / 10^-s) is
// formed exactly with an exact power of ten (10^0 .. 10^22 are doubles) and one fused
// multiply-add is rounded here, by exact comparisons with the half; any other value
// (magnitudes beyond those powers' reach, subnormals) goes through snprintf.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "cont.h"
#include "es_format.h"

namespace {

// 10^0 .. 10^22: every one a double exactly (5^22 < 2^53).
const double POW10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                          1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
const uint64_t IPOW10[19] = {1ull,
                             10ull,
                             100ull,
                             1000ull,
                             10000ull,
                             100000ull,
                             1000000ull,
                             10000000ull,
                             100000000ull,
                             1000000000ull,
                             10000000000ull,
                             100000000000ull,
                             1000000000000ull,
                             10000000000000ull,
                             100000000000000ull,
                             1000000000000000ull,
                             10000000000000000ull,
                             100000000000000000ull,
                             1000000000000000000ull};

// y = a * 10^s (s >= 0) or a / 10^-s (s < 0) for a > 0 finite and |s| <= 22, when y is
// below 2^52: its floor (*fl) and the integer nearest to it, ties to even (*n); false
// otherwise (or for a remainder near the subnormals, where the fma below may be inexact).
// Exact: with p = 10^|s| a double, a * p = hi + lo exactly (lo by a fused multiply-add),
// and a = q * p + r exactly for q = fl(a / p) (r again by one fma). hi (q) lies within
// half an ulp of y, and an integer is a multiple of that ulp below 2^52: y's floor is
// floor(hi) less one when hi is an integer and lo (r) negative, else floor(hi). The
// fraction against 1/2 is decided by the sign of one sum rounded once, which is the sign
// of the exact sum.
bool scaled_round(double a, int s, uint64_t *fl, uint64_t *n) {
    if (s > 22 || s < -22)
        return false;
    double p = POW10[s < 0 ? -s : s];
    double whole, frac, tail, side;    // floor(hi), hi - floor(hi), lo, the sign of y - whole - 1/2
    if (s >= 0) {
        double hi = a * p;
        if (!(hi < 4503599627370496.0))     // 2^52
            return false;
        tail = std::fma(a, p, -hi);
        whole = std::floor(hi);
        frac = hi - whole;                  // exact
        side = (frac - 0.5) + tail;         // frac - 0.5 exact: one rounding
    } else {
        double q = a / p;
        if (!(q < 4503599627370496.0))
            return false;
        tail = std::fma(-q, p, a);
        if (tail != 0.0 && std::fabs(tail) < 2.2250738585072014e-308 * 4503599627370496.0)
            return false;
        whole = std::floor(q);
        frac = q - whole;
        side = std::fma(frac - 0.5, p, tail);   // the sign of (frac - 1/2) p + r
    }
    uint64_t w = (uint64_t)whole;
    *fl = (frac == 0.0 && tail < 0.0) ? w - 1 : w;
    if (side > 0.0 || (side == 0.0 && (w & 1u)))
        w += 1;
    *n = w;
    return true;
}

// The digits of x's ES text: mantissa digits m (d + 1 of them, m in [10^d, 10^(d+1))) and
// the decimal exponent e, correctly rounded; x finite, |x| >= the smallest normal double,
// d <= 15. False when scaled_round cannot decide (the caller uses snprintf).
bool es_digits(double x, int d, uint64_t *m, int *e) {
    double a = std::fabs(x);
    int b2;
    std::frexp(a, &b2);                     // a in [2^(b2-1), 2^b2)
    // floor(log10(a)) is e0 or e0 + 1 with e0 = floor((b2 - 1) log10(2))
    int e0 = (int)std::floor((b2 - 1) * 0.30102999566398120);
    const uint64_t lower = IPOW10[d], upper = IPOW10[d + 1];
    for (int k = e0 + 1; k >= e0 - 1; --k) {
        uint64_t fl, n;
        if (!scaled_round(a, d - k, &fl, &n))
            return false;
        if (fl >= upper)
            return false;                   // the exponent guessed too low: not expected
        if (fl >= lower) {                  // 10^k <= a < 10^(k+1): k is a's exponent
            if (n == upper) {               // rounded up to the next power of ten
                *m = lower;
                *e = k + 1;
            } else {
                *m = n;
                *e = k;
            }
            return true;
        }
    }
    return false;
}

// gfortran's text of NaN and the infinities in a field of width w; 0 for finite x.
int special(double x, int w, char *out) {
    const char *t;
    if (std::isnan(x))
        t = "NaN";
    else if (std::isinf(x))
        t = x > 0 ? "Infinity" : "-Infinity";
    else
        return 0;
    int len = (int)std::strlen(t);
    int pad = w > len ? w - len : 0;
    std::memset(out, ' ', pad);
    std::memcpy(out + pad, t, len);
    return pad + len;
}

}  // namespace

int es_field(double x, int w, int d, int exp3, char *out) {
    int sp = special(x, w, out);
    if (sp)
        return sp;
    uint64_t m;
    int e;
    bool neg = std::signbit(x);
    if (x == 0.0) {
        m = 0;
        e = 0;
    } else if (!(std::fabs(x) >= 2.2250738585072014e-308) || d > 15 || !es_digits(x, d, &m, &e)) {
        // snprintf's correctly rounded digits ("-d.dddE+xx")
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.*E", d, x);
        const char *p = buf + (buf[0] == '-');
        m = (uint64_t)(p[0] - '0');
        for (int i = 0; i < d; ++i)
            m = 10 * m + (uint64_t)(p[2 + i] - '0');
        e = std::atoi(p + (d > 0 ? 3 + d : 2));
    }
    char t[48];
    int len = 0;
    if (neg)
        t[len++] = '-';
    char dig[24];
    for (int i = d; i >= 0; --i) {
        dig[i] = (char)('0' + m % 10);
        m /= 10;
    }
    t[len++] = dig[0];
    if (d > 0) {
        t[len++] = '.';
        std::memcpy(t + len, dig + 1, d);
        len += d;
    }
    int ae = e < 0 ? -e : e;
    bool three = exp3 || ae > 99;
    if (exp3 || ae <= 99)
        t[len++] = 'E';
    t[len++] = e < 0 ? '-' : '+';
    if (three)
        t[len++] = (char)('0' + ae / 100);
    t[len++] = (char)('0' + ae / 10 % 10);
    t[len++] = (char)('0' + ae % 10);
    int pad = w > len ? w - len : 0;
    std::memset(out, ' ', pad);
    std::memcpy(out + pad, t, len);
    return pad + len;
}

extern "C" int cont_format_es(const double *v, int k, int m, int per_line, int indent,
                              int width, int digits, int exp3, char *out) {
    if (k < 0 || m < 0 || per_line < 1 || indent < 0 || width < 0 || digits < 0 || digits > 17)
        return -1;
    int len = 0;
    for (int i = 0; i < k; ++i) {
        for (int j = 0; j < m; ++j) {
            if (j % per_line == 0) {
                if (i > 0 || j > 0)
                    out[len++] = '\n';
                std::memset(out + len, ' ', indent);
                len += indent;
            }
            len += es_field(v[(size_t)i * m + j], width, digits, exp3, out + len);
        }
    }
    out[len] = '\0';
    return len;
}

// A continuation point's lines in AUTO-07p's b- and d-files (io.f90 WRLINE, ae.f90
// PRINTEIG, bvp.f90 PVSPBV's Floquet block): see cont_auto_point in cont_api.h. The
// numbers' text is es_format.cpp's.
#include <cmath>
#include <cstring>

#include "cont.h"
#include "es_format.h"

namespace {

// C's %*d (Python's {:wd}): the decimal text of i right-justified in w, never cut.
int put_int(char *out, int i, int w) {
    char t[16];
    int len = 0;
    unsigned u = i < 0 ? 0u - (unsigned)i : (unsigned)i;
    do {
        t[len++] = (char)('0' + u % 10);
        u /= 10;
    } while (u);
    if (i < 0)
        t[len++] = '-';
    int pad = w > len ? w - len : 0;
    std::memset(out, ' ', pad);
    for (int k = 0; k < len; ++k)
        out[pad + k] = t[len - 1 - k];
    return pad + len;
}

int put_str(char *out, const char *s) {
    int len = (int)std::strlen(s);
    std::memcpy(out, s, len);
    return len;
}

// The start of a line of a point's block in the d-file: I4 br, I6 pt, then `label`.
int block_line(char *out, int br, int pt, const char *label) {
    int len = put_int(out, br, 4);
    len += put_int(out + len, pt, 6);
    return len + put_str(out + len, label);
}

}  // namespace

extern "C" int cont_auto_point(int br, int pt, int ty, int lab, const char *name, const double *v,
                               int n, const char *dhead, int ebr, int ept, const double *eig,
                               int neig, int cplx, int nstable, char *out, int *blen) {
    int len = 0;
    if (n >= 0) {
        // b-file (WRLINE): I4, I6, I4, I5, ES19.10E3 each value
        len += put_int(out + len, br, 4);
        len += put_int(out + len, pt, 6);
        len += put_int(out + len, ty, 4);
        len += put_int(out + len, lab, 5);
        for (int j = 0; j < n; ++j)
            len += es_field(v[j], 19, 10, 1, out + len);
        out[len++] = '\n';
    }
    *blen = len;
    if (n >= 0) {
        // d-file: the caller's bar and heading, then the screen line (I4, I6, 1X, A3, I5,
        // ES14.5 of the first 8 values)
        len += put_str(out + len, dhead);
        len += put_int(out + len, br, 4);
        len += put_int(out + len, pt, 6);
        out[len++] = ' ';
        int nl = (int)std::strlen(name);
        for (int k = nl; k < 3; ++k)
            out[len++] = ' ';
        len += put_str(out + len, name);
        len += put_int(out + len, lab, 5);
        for (int j = 0; j < n && j < 8; ++j)
            len += es_field(v[j], 14, 5, 0, out + len);
        out[len++] = '\n';
    }
    if (neig >= 0 && nstable >= 0) {
        // PVSPBV's Floquet multipliers: the stable count given, then each multiplier's Re,
        // Im and modulus (ES14.5; the modulus is Python's abs of a complex, libm's hypot)
        len += block_line(out + len, ebr, ept, "         Multipliers:     Stable:");
        len += put_int(out + len, nstable, 4);
        for (int k = 0; k < neig; ++k) {
            const double re = cplx ? eig[2 * k] : eig[k], im = cplx ? eig[2 * k + 1] : 0.0;
            out[len++] = '\n';
            len += block_line(out + len, ebr, ept, "         Multiplier");
            len += put_int(out + len, k + 1, 3);
            out[len++] = ' ';
            len += es_field(re, 14, 5, 0, out + len);
            len += es_field(im, 14, 5, 0, out + len);
            len += put_str(out + len, "  Abs. Val.");
            len += es_field(std::hypot(re, im), 14, 5, 0, out + len);
        }
        out[len++] = '\n';
    } else if (neig >= 0) {
        // PRINTEIG: the stable count (Re < 0), then each eigenvalue's Re and Im (ES14.5)
        int stable = 0;
        for (int k = 0; k < neig; ++k)
            stable += (cplx ? eig[2 * k] : eig[k]) < 0.0;
        out[len++] = '\n';
        len += block_line(out + len, ebr, ept, "         Eigenvalues  :   Stable:");
        len += put_int(out + len, stable, 4);
        for (int k = 0; k < neig; ++k) {
            out[len++] = '\n';
            len += block_line(out + len, ebr, ept, "         Eigenvalue");
            len += put_int(out + len, k + 1, 3);
            out[len++] = ':';
            len += es_field(cplx ? eig[2 * k] : eig[k], 14, 5, 0, out + len);
            len += es_field(cplx ? eig[2 * k + 1] : 0.0, 14, 5, 0, out + len);
        }
        out[len++] = '\n';
    }
    out[len] = '\0';
    return len;
}

// One value in Fortran's ESw.d (exp3 = 0: 'E' and 2 exponent digits, 3 digits without the
// 'E' beyond 99) or ESw.dE3 (exp3 = 1: 'E' and 3 digits), right-justified in w characters
// (never cut) at out, as gfortran writes it: the field of cont_format_es (es_format.cpp),
// which auto_point.cpp's lines use too. Returns its length (at most max(w, d + 8)).
// Internal to washer._cont (hidden: a direct call, not the cffi API of cont_api.h).
#ifndef WASHER_CONT_ES_FORMAT_H
#define WASHER_CONT_ES_FORMAT_H

__attribute__((visibility("hidden"))) int es_field(double x, int w, int d, int exp3, char *out);

#endif

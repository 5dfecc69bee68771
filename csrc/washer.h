#ifndef WASHER_H
#define WASHER_H
/* C++ view of the C ABI: the prototypes of washer_api.h with C linkage. */
#ifdef __cplusplus
extern "C" {
#endif
#include "washer_api.h"
#ifdef __cplusplus
}
#endif

/* Error codes returned by every washer_* function. */
enum {
    WASHER_OK = 0,
    WASHER_ENONFINITE_INPUT = 1,
    WASHER_ESINGULAR_MASS = 2,
    WASHER_ENONFINITE_OUTPUT = 3,
    WASHER_ESTEP_TOO_SMALL = 4,
    WASHER_EMAX_STEPS = 5,
    WASHER_EBAD_ARGUMENT = 6,
    WASHER_EINTERRUPTED = 7
};
#endif

#ifndef WASHER_CONT_H
#define WASHER_CONT_H
#ifdef __cplusplus
extern "C" {
#endif
#include "cont_api.h"
#ifdef __cplusplus
}
#endif
#endif

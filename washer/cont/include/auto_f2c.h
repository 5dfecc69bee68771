/* auto_f2c.h: the declarations AUTO-07p's C user files expect (washer's own header).
 *
 * A user file includes this header and defines the static functions func, stpnt,
 * bcnd, icnd, fopt and pvls with AUTO's C signatures (0-based arrays, Jacobians
 * column-major: dfdu[i + j*ndim] = d f_i / d u_j). The header collects them in
 * the table `user`, which washer's shim calls. getp() is AUTO's PVLS support
 * routine (solution measures, see washer/cont/user_problem/user_files_native.py).
 */
#ifndef WASHER_AUTO_F2C_H
#define WASHER_AUTO_F2C_H
#include <stdlib.h>
#include <string.h>
#include <stdio.h>
#include <math.h>

typedef int integer;
typedef float real;
typedef double doublereal;
typedef struct { real r, i; } complex;
typedef struct { doublereal r, i; } doublecomplex;
typedef integer logical;
#define TRUE_ (1)
#define FALSE_ (0)
#define VOID void

#ifndef abs
#define abs(x) ((x) >= 0 ? (x) : -(x))
#endif
#ifndef min
#define min(a,b) ((a) <= (b) ? (a) : (b))
#endif
#ifndef max
#define max(a,b) ((a) >= (b) ? (a) : (b))
#endif
#define dmin(a,b) (doublereal)min(a,b)
#define dmax(a,b) (doublereal)max(a,b)
#define ARRAY2D(array,i,j) array[(i) + (j) * array ## _dim1]
#define ARRAY3D(array,i,j,k) array[(i) + ((j)  + (k) * array ## _dim2) * array ## _dim1]

/* HomCont's constants (ITWIST, ISTART, IEQUIB, NFIXED, NPSI, NUNSTAB, NSTAB, NREV): a C file
 * declares `extern struct {...} blhom_1;` and AUTO's header names it the Fortran COMMON
 * /BLHOM/, blhom_ (the fnb and kdv demos' STPNT read IEQUIB and ISTART from it). */
#define blhom_1 blhom_

typedef int user_func_t(integer ndim, const doublereal *u, const integer *icp,
                        const doublereal *par, integer ijac,
                        doublereal *f, doublereal *dfdu, doublereal *dfdp);
typedef int user_stpnt_t(integer ndim, doublereal t, doublereal *u, doublereal *par);
typedef int user_bcnd_t(integer ndim, const doublereal *par, const integer *icp, integer nbc,
                        const doublereal *u0, const doublereal *u1, integer ijac,
                        doublereal *f, doublereal *dbc);
typedef int user_icnd_t(integer ndim, const doublereal *par, const integer *icp, integer nint,
                        const doublereal *u, const doublereal *uold, const doublereal *udot,
                        const doublereal *upold, integer ijac,
                        doublereal *fi, doublereal *dint);
typedef int user_fopt_t(integer ndim, const doublereal *u, const integer *icp,
                        const doublereal *par, integer ijac,
                        doublereal *fs, doublereal *dfdu, doublereal *dfdp);
typedef int user_pvls_t(integer ndim, const doublereal *u, doublereal *par);

typedef struct {
  user_func_t *func;
  user_stpnt_t *stpnt;
  user_bcnd_t *bcnd;
  user_icnd_t *icnd;
  user_fopt_t *fopt;
  user_pvls_t *pvls;
  int uses_fortran;
} user_function_list;

extern const user_function_list user;
extern doublereal getp(const char *code, integer ic, const doublereal *u);

#ifndef WRAPPER
static int func();
static int stpnt();
static int bcnd();
static int icnd();
static int fopt();
static int pvls();
const user_function_list user = { func, stpnt, bcnd, icnd, fopt, pvls, 0 };
#endif
#endif

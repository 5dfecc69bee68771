/* AUTO-07p's demo ab with AUTO's C user-file conventions (auto_f2c.h). */
#include "auto_f2c.h"

int func(integer ndim, const doublereal *u, const integer *icp, const doublereal *par,
         integer ijac, doublereal *f, doublereal *dfdu, doublereal *dfdp)
{
    doublereal e = exp(u[1]);
    f[0] = -u[0] + par[0] * (1 - u[0]) * e;
    f[1] = -u[1] + par[0] * par[1] * (1 - u[0]) * e - par[2] * u[1];
    return 0;
}

int stpnt(integer ndim, doublereal t, doublereal *u, doublereal *par)
{
    par[0] = 0.; par[1] = 8.; par[2] = 3.;
    u[0] = 0.; u[1] = 0.;
    return 0;
}

int bcnd(integer ndim, const doublereal *par, const integer *icp, integer nbc,
         const doublereal *u0, const doublereal *u1, integer ijac, doublereal *fb,
         doublereal *dbc) { return 0; }
int icnd(integer ndim, const doublereal *par, const integer *icp, integer nint,
         const doublereal *u, const doublereal *uold, const doublereal *udot,
         const doublereal *upold, integer ijac, doublereal *fi, doublereal *dint) { return 0; }
int fopt(integer ndim, const doublereal *u, const integer *icp, const doublereal *par,
         integer ijac, doublereal *fs, doublereal *dfdu, doublereal *dfdp) { return 0; }
int pvls(integer ndim, const doublereal *u, doublereal *par) { return 0; }

! Hopf normal form as a user BVP: x' = T (p x - y - x r2), y' = T (x + p y - y r2)
      SUBROUTINE FUNC(NDIM,U,ICP,PAR,IJAC,F,DFDU,DFDP)
      IMPLICIT NONE
      INTEGER NDIM, ICP(*), IJAC
      DOUBLE PRECISION U(NDIM), PAR(*), F(NDIM), DFDU(*), DFDP(*)
      DOUBLE PRECISION R2
      R2 = U(1)**2 + U(2)**2
      F(1) = PAR(11) * (PAR(1)*U(1) - U(2) - U(1)*R2)
      F(2) = PAR(11) * (U(1) + PAR(1)*U(2) - U(2)*R2)
      END
      SUBROUTINE STPNT(NDIM,U,PAR,T)
      IMPLICIT NONE
      INTEGER NDIM
      DOUBLE PRECISION U(NDIM), PAR(*), T, PI
      PI = 4*ATAN(1.D0)
      PAR(1) = 1.0
      PAR(11) = 2*PI
      U(1) = COS(2*PI*T)
      U(2) = SIN(2*PI*T)
      END
      SUBROUTINE BCND(NDIM,PAR,ICP,NBC,U0,U1,FB,IJAC,DBC)
      IMPLICIT NONE
      INTEGER NDIM, ICP(*), NBC, IJAC
      DOUBLE PRECISION PAR(*), U0(NDIM), U1(NDIM), FB(NBC), DBC(NBC,*)
      FB(1) = U0(1) - U1(1)
      FB(2) = U0(2) - U1(2)
      END
      SUBROUTINE ICND(NDIM,PAR,ICP,NINT,U,UOLD,UDOT,UPOLD,FI,IJAC,DINT)
      IMPLICIT NONE
      INTEGER NDIM, ICP(*), NINT, IJAC
      DOUBLE PRECISION PAR(*), U(NDIM), UOLD(NDIM), UDOT(NDIM), UPOLD(NDIM), FI(NINT), DINT(NINT,*)
      FI(1) = (U(1)-UOLD(1))*UPOLD(1) + (U(2)-UOLD(2))*UPOLD(2)
      END
      SUBROUTINE FOPT
      END
      SUBROUTINE PVLS
      END

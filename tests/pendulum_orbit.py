"""The pendulum theta'' = -a sin(theta) + mu theta' as a washer Problem whose stpnt is its
orbit at mu = 0, theta = 4 arctan(e^(sqrt(a) t)) - pi from the saddle (-pi, 0) to (pi, 0)
(the same equilibrium of the angle: an orbit whose angle turns once), at a = 1 on a
truncation interval T (PAR(11)), the equilibrium in PAR(12), PAR(13) (IEQUIB = 1)."""
import numpy as np

from washer.cont.problem import Problem


def pendulum(T: float) -> Problem:
    """The Problem (PAR(1) = a, PAR(2) = mu) starting from the orbit on [-T/2, T/2]."""
    def func(u, par):
        return np.array([u[1], -par[0] * np.sin(u[0]) + par[1] * u[1]])

    def dfdu(u, par):
        return np.array([[0.0, 1.0], [-par[0] * np.cos(u[0]), par[1]]])

    def stpnt(u, par, s):
        par[0], par[1], par[10] = 1.0, 0.0, T
        par[11], par[12] = -np.pi, 0.0
        z = (s - 0.5) * T
        u[0] = 4 * np.arctan(np.exp(z)) - np.pi
        u[1] = 2 / np.cosh(z)
    return Problem(2, func, stpnt=stpnt, dfdu=dfdu, name="pendulum", jac=-1)

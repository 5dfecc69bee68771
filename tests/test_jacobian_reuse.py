"""The corrector's Jacobians on the hot path: what is reused or taken from the user must
be what a fresh evaluation gives.

* Small finite-difference stencils are evaluated call by call with the stencil built in
  Python floats (`Problem._jacobian_by_calls`): bit for bit the quotients of the array
  stencil that a batched func gets.
* The collocation's f_p comes from the user's batched dfdp when JAC = 1 (the washer's
  kernel returns it with f_u): exactly that column, and within the difference
  quotient's error of central differences.
* On BVPs the last Newton iteration's Jacobian serves as the Jacobian at the converged
  point (tangent, Floquet multipliers): the points differ by the last correction, within
  EPSU, so the multipliers and the tangent agree with a fresh evaluation to that order.
"""
import math

import numpy as np

from washer.cont import collocation as col
from washer.cont import floquet
from washer.cont.iterator import Continuation
from washer.cont.problem import Problem
from washer.cont.settings import Settings
from washer.cont.system import StartData
from washer.cont.systems.bvp import VectorField
from washer.cont.systems.periodic import PeriodicOrbits


def ab(u, par):
    e = np.exp(u[1])
    return np.array([-u[0] + par[0] * (1 - u[0]) * e,
                     -u[1] + par[0] * par[1] * (1 - u[0]) * e - par[2] * u[1]])


def test_small_stencil_jacobian_equals_the_batched_stencil_bit_for_bit():
    plain = Problem(2, ab, npar=3)
    batched = Problem(2, ab, npar=3,
                      func_batch=lambda us, ps: np.array([ab(u, p) for u, p in zip(us, ps)]))
    rng = np.random.default_rng(7)
    for _ in range(50):
        u = rng.normal(size=2) * 10 ** rng.uniform(-3, 1)
        par = rng.normal(size=3) * 5
        for idx in ([1], [2, 1], [3]):
            assert np.array_equal(plain.jacobian(u, par, idx), batched.jacobian(u, par, idx))
        assert np.array_equal(plain.dfdu(u, par), batched.dfdu(u, par))


def lw(u, par):
    x, y = u[0], u[1]
    mu, om, b, c = par[0], par[1], par[2], par[3]
    r2 = x * x + y * y
    th = om + b * r2 + c * x
    return np.array([x * (mu - r2) - y * th, y * (mu - r2) + x * th])


def lw_dfdp_batch(us, pars):
    """d f / d PAR at k points, (k, 2, NPAR): only PAR(1) = mu and PAR(2) = omega enter
    linearly (the others through th, not needed here)."""
    us, pars = np.asarray(us), np.asarray(pars)
    out = np.zeros((len(us), 2, pars.shape[1]))
    x, y = us[:, 0], us[:, 1]
    out[:, 0, 0], out[:, 1, 0] = x, y                 # d/d mu
    out[:, 0, 1], out[:, 1, 1] = -y, x                # d/d omega
    return out


def test_collocation_fp_takes_the_batched_dfdp_with_jac_1():
    rng = np.random.default_rng(3)
    U = rng.normal(size=(40, 2))
    par = np.r_[0.3, 1.0, 0.5, 0.8, np.zeros(8)]
    analytic = VectorField(Problem(2, lw, dfdp_batch=lw_dfdp_batch, jac=1), 2)
    differenced = VectorField(Problem(2, lw, dfdp_batch=lw_dfdp_batch, jac=0), 2)
    for index in (1, 2):
        exact = lw_dfdp_batch(U, np.broadcast_to(par, (40, 12)))[:, :, index - 1]
        assert np.array_equal(analytic.fp(U, par, index), exact)
        # JAC = 0 keeps AUTO's central differences (error ~1e-9 relative here)
        assert np.allclose(differenced.fp(U, par, index), exact, rtol=0, atol=1e-7)


def test_reused_jacobian_gives_the_fresh_tangent_and_multipliers():
    """The lambda-omega family from its Hopf point (mu = r^2, multipliers 1 and
    exp(-2 mu T)): at every point the multipliers from the reused Jacobian equal a fresh
    condensation at the converged point to 1e-7 (EPSU = 1e-7, the multipliers are
    well conditioned), the tangent to 1e-6; and the reuse did happen: no Jacobian was
    evaluated at any of the converged points (each converges within NWTN iterations
    here; without the reuse 7 of the 10 are, the other 3 being moved by the mesh
    adaptation after they were accepted)."""
    par = np.r_[0.0, 1.0, 0.5, 0.8, np.zeros(8)]
    par[10] = 2 * math.pi
    s = Settings(IPS=2, ICP=(1, 11), NDIM=2, NPAR=12, NTST=20, NCOL=4, THL={11: 0.0},
                 DS=0.05, DSMAX=0.5, DSMIN=1e-6)
    sysm = PeriodicOrbits(StartData(Problem(2, lw, name="lw"), s, np.zeros(2), par, None,
                                    "HB"))
    at = []
    jacobian = sysm.jacobian

    def counted(x):
        at.append(x.tobytes())
        return jacobian(x)
    sysm.jacobian = counted
    it = Continuation(sysm, s)
    points = []
    for step in it:
        assert step.kind != "failed", step.text
        if step.kind == "point":
            p = step.point
            # multipliers of a fresh Jacobian at p.x, condensed without the factor
            blocks = sysm.coll.local_blocks(sysm.period(sysm.unpack(p.x)[1]), sysm.field.fu(
                sysm.coll.at_gauss(sysm.unpack(p.x)[0]).reshape(-1, 2),
                sysm.unpack(p.x)[1]).reshape(20, 4, 2, 2))
            fresh = floquet.pencil_multipliers(*col.condense_blocks(blocks, 2))
            assert np.max(np.abs(np.sort_complex(fresh) -
                                 np.sort_complex(p.stability.values))) < 1e-7
            # the unit null vector of a fresh Jacobian, oriented along the point's own
            t_fresh = it.tangent(jacobian(p.x), p.tangent)[0]
            assert np.max(np.abs(t_fresh - p.tangent)) < 1e-6
            points.append(p)
        if len(points) == 10:
            break
    reused = sum(p.x.tobytes() not in at for p in points)
    assert reused == len(points), reused
    mus = [sysm.params(p.x)[0] for p in points]
    assert mus[-1] > 0.05


def test_washer_batched_dfdp_is_the_pointwise_kernel_jp():
    """e='washer': dfdp_batch (the kernel's Jp from the jac_rot_batch call that gives
    f_u) equals the per-point dfdp (jac_rot's Jp, the tied dampers summed into C_p) and
    central differences of f in C_p to the quotient's error; f_u from the shared call is
    the per-point one."""
    from washer.problems.rotating import rotating_problem
    prob = rotating_problem().with_jac(1)
    u0, par0 = prob.start(17)
    rng = np.random.default_rng(5)
    us = u0 + 1e-3 * rng.normal(size=(6, 12))
    pars = np.repeat(par0[None, :], 6, axis=0)
    pars[:, 0] += np.linspace(0.0, 0.05, 6)
    Jp = prob.dfdp_many(us, pars, 1)
    fu = prob.dfdu_many(us, pars)
    for k in range(6):
        assert np.allclose(Jp[k], prob.dfdp(us[k], pars[k], [1])[:, 0], rtol=1e-12, atol=1e-12)
        assert np.allclose(fu[k], prob.dfdu(us[k], pars[k]), rtol=1e-12, atol=1e-12)
        h = 1e-6 * (1 + abs(pars[k, 0]))
        pp, pm = pars[k].copy(), pars[k].copy()
        pp[0] += h
        pm[0] -= h
        fd = (prob.func(us[k], pp) - prob.func(us[k], pm)) / (2 * h)
        assert np.allclose(Jp[k], fd, rtol=1e-6, atol=1e-6 * np.max(np.abs(fd)))

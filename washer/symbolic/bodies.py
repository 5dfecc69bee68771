"""The machine's structure as symbolic data: tub bodies, spinning bodies, rods.

The paper's general form (section 2.1.4) has N1 bodies fixed to the tub
("first category") and N2 bodies spinning about axes parallel to Z_b with
theta_i = p_i * theta ("second category"). `default_structure()` builds the
reference machine of docs/model.md section 1 (one lumped tub, the basket, the
imbalance, four rods) with every quantity a symbol of `washer.machine.layout`.
A user extension (a motor rotor with gear ratio p_i, a second imbalance, six
rods) is another `Structure`; the generated kernel is then rebuilt.
"""
from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from washer.machine import layout


@dataclass(frozen=True)
class TubBody:
    """First-category body: mass m (kg), mass centre r (tub frame, m),
    principal inertia J = (Jx, Jy, Jz) about the mass centre along tub axes (kg m^2)."""
    m: sp.Expr
    r: tuple
    J: tuple


@dataclass(frozen=True)
class SpinningBody:
    """Second-category body (eqs 10-15): axis at (px, py) in the tub frame,
    mass-centre height pz, eccentricity R, principal inertia J = (Jx, Jy, Jz)
    in its own frame, and speed ratio p (theta_c = p * theta)."""
    m: sp.Expr
    axis: tuple
    R: sp.Expr
    J: tuple
    ratio: sp.Expr = sp.Integer(1)


@dataclass(frozen=True)
class Rod:
    """Suspension rod: upper joint P (ground frame) and lower joint O (tub frame), m."""
    P: tuple
    O: tuple


@dataclass(frozen=True)
class Structure:
    tub_bodies: tuple
    spinning_bodies: tuple
    rods: tuple
    K_s: sp.Expr
    C_a: sp.Expr
    C_p: sp.Expr
    C_ox: sp.Expr
    C_oz: sp.Expr
    l0: sp.Expr
    g: sp.Expr


def param_symbols() -> dict[str, sp.Symbol]:
    """One real sympy symbol per kernel parameter, keyed by its layout name."""
    return {n: sp.Symbol(n, real=True) for n in layout.PARAM_NAMES}


def default_structure(P: dict[str, sp.Symbol] | None = None) -> Structure:
    """The reference machine (docs/model.md section 1) in terms of layout symbols."""
    P = P or param_symbols()
    zero = sp.Integer(0)
    tub = TubBody(P["m_t"], (P["r_tx"], P["r_ty"], P["r_tz"]), (P["J_tx"], P["J_ty"], P["J_tz"]))
    basket = SpinningBody(P["m_b"], (zero, zero, P["h_b"]), zero, (P["J_bt"], P["J_bt"], P["J_bz"]))
    imbalance = SpinningBody(P["m_u"], (zero, zero, P["h_u"]), P["R_u"], (zero, zero, zero))
    rods = tuple(
        Rod(tuple(P[layout.rod_param(f, k)] for f in ("Px", "Py", "Pz")),
            tuple(P[layout.rod_param(f, k)] for f in ("Ox", "Oy", "Oz")))
        for k in range(layout.N_RODS)
    )
    return Structure((tub,), (basket, imbalance), rods, P["K_s"], P["C_a"], P["C_p"],
                     P["C_ox"], P["C_oz"], P["l0"], P["g"])

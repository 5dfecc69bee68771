"""The kernel's parameter vector: names, order, units (single source of truth).

The compiled kernel, the code generator, `washer.machine.params` and the AUTO problem
all index parameters through this table; a test checks that the compiled
kernel was generated from the same table.

No sympy here: this module is imported at run time.
"""
from __future__ import annotations

#: Number of suspension rods the generated kernel was built for.
N_RODS = 4

#: (name, unit, meaning) of the scalar parameters, in kernel order.
SCALARS: tuple[tuple[str, str, str], ...] = (
    ("C_p", "N m s/rad", "damping of joint P (and of C_ox, C_oz when tied)"),
    ("Omega", "Hz", "basket speed at steady state"),
    ("m_u", "kg", "imbalance mass"),
    ("R_u", "m", "imbalance eccentricity ('radius of gyration')"),
    ("h_u", "m", "imbalance height above plane A"),
    ("C_a", "N s/m", "axial damping of a rod"),
    ("K_s", "N/m", "rod spring stiffness"),
    ("C_ox", "N m s/rad", "damping of joint O about e1"),
    ("C_oz", "N m s/rad", "damping of joint O about e2, e3 (C_oy = C_oz)"),
    ("l0", "m", "rod spring free length"),
    ("tau_s", "s", "spin-up time constant of eq 66"),
    ("tau0", "rad", "frozen rotating-frame phase"),
    ("J_bz", "kg m^2", "basket polar inertia"),
    ("J_bt", "kg m^2", "basket transverse inertia"),
    ("m_b", "kg", "basket mass"),
    ("h_b", "m", "basket mass-centre height above plane A"),
    ("m_t", "kg", "tub (first-category) mass"),
    ("r_tx", "m", "tub mass centre, x (tub frame)"),
    ("r_ty", "m", "tub mass centre, y (tub frame)"),
    ("r_tz", "m", "tub mass centre, z (tub frame)"),
    ("J_tx", "kg m^2", "tub principal inertia about x"),
    ("J_ty", "kg m^2", "tub principal inertia about y"),
    ("J_tz", "kg m^2", "tub principal inertia about z"),
    ("g", "m/s^2", "gravitational acceleration"),
)

#: Per-rod parameters: upper joint P (ground frame) and lower joint O (tub frame).
ROD_FIELDS: tuple[str, ...] = ("Px", "Py", "Pz", "Ox", "Oy", "Oz")


def rod_param(field: str, k: int) -> str:
    """Name of rod k's parameter `field`, e.g. rod_param('Px', 0) == 'Px0'."""
    return f"{field}{k}"


PARAM_NAMES: tuple[str, ...] = tuple(n for n, _, _ in SCALARS) + tuple(
    rod_param(f, k) for k in range(N_RODS) for f in ROD_FIELDS
)
N_PARAMS = len(PARAM_NAMES)
INDEX = {name: i for i, name in enumerate(PARAM_NAMES)}
UNITS = {n: u for n, u, _ in SCALARS} | {
    rod_param(f, k): "m" for k in range(N_RODS) for f in ROD_FIELDS
}

#: Parameters the kernel returns analytic derivatives for, in column order of
#: every parameter Jacobian. Omega enters through theta(t) and is handled by
#: the chain rule in C++; the others are differentiated symbolically.
DIFF_PARAMS: tuple[str, ...] = (
    "C_p", "Omega", "m_u", "R_u", "h_u", "C_a", "K_s", "C_ox", "C_oz",
    "l0", "J_bz", "J_bt", "m_b", "h_b", "m_t",
)
SYMBOLIC_DIFF_PARAMS: tuple[str, ...] = tuple(p for p in DIFF_PARAMS if p != "Omega")

#: State names of the ground-frame system (eq 48), u = (q, q_dot).
Q_NAMES = ("x", "y", "z", "alpha", "beta", "gamma")
#: State names of the rotating-frame system (eq 59), xi = (eps, eps_dot).
EPS_NAMES = tuple(f"eps{i}" for i in range(1, 7))


# ------------------------------------------------------------------ the parameter map
#: The tie rule: with tied dampings (the paper's C_ox = C_oy = C_oz = C_p, a parameter set
#: that gives neither C_ox nor C_oz) these parameters follow the one named.
TIED_TO = {"C_ox": "C_p", "C_oz": "C_p"}


def moved_by(name: str, tied: bool) -> tuple[str, ...]:
    """The kernel parameters that change when the user changes `name`: itself, and with
    tied dampings the parameters tied to it (C_p moves C_ox and C_oz)."""
    return (name,) + (tuple(k for k, v in TIED_TO.items() if v == name) if tied else ())


#: AUTO's PAR(i) -> kernel parameter name, for the washer as a continuation problem
#: (e='washer'): the one map between PAR indices and names. PAR(11) and PAR(12) are
#: AUTO's: the period, and the torus angle written at TR points of periodic orbits (a
#: model parameter there would be overwritten in the s-file).
PAR_NAMES = {1: "C_p", 2: "Omega", 3: "m_u", 4: "R_u", 5: "h_u", 6: "C_a", 7: "K_s",
             8: "C_ox", 9: "C_oz", 10: "l0", 13: "J_bz", 14: "J_bt", 15: "m_b", 16: "h_b",
             17: "m_t"}
#: PAR index of each name in PAR_NAMES.
PAR_INDEX = {n: i for i, n in PAR_NAMES.items()}

"""washer: nonlinear vibration and stability of a vertical-axis washing machine.

Public API (see README.md):
    load_params(path=None) -> Params      # TOML parameter set (default: shipped reference)
    Model(params)                         # right-hand sides, Jacobians, equilibria, simulate
"""
from washer.machine.params import Params, ParameterError, load_params
from washer.machine.model import EquilibriumError, Model
from washer.machine.kernel import KernelError

__all__ = ["Params", "ParameterError", "load_params", "Model", "EquilibriumError", "KernelError"]

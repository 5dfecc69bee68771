"""washer: nonlinear vibration and stability of a vertical-axis washing machine.

Public API (see README.md):
    load_params(path=None) -> Params      # TOML parameter set (default: shipped reference)
    Model(params)                         # right-hand sides, Jacobians, equilibria, simulate
"""
import importlib

#: The public names and the modules holding them. They are imported on first use
#: (PEP 562), so that `python -m washer.run` on a user's problem does not load the
#: washer's model, its parameter files and compiled kernel.
_PUBLIC = {"Params": "washer.machine.params", "ParameterError": "washer.machine.params",
           "load_params": "washer.machine.params", "Model": "washer.machine.model",
           "EquilibriumError": "washer.machine.model", "KernelError": "washer.machine.kernel"}

__all__ = list(_PUBLIC)


def __getattr__(name: str):
    if name in _PUBLIC:
        value = getattr(importlib.import_module(_PUBLIC[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'washer' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(_PUBLIC))

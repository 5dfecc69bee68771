"""The tolerances the tests judge located points by, from the engine's own definitions."""
from pathlib import Path
from types import SimpleNamespace
from collections.abc import Mapping

from washer.auto.constants_file import read_constants
from washer.cont.events import location_tolerance as _engine_location_tolerance


def location_tolerance(constants: Path | str | Mapping, **overrides) -> float:
    """The location's stopping tolerance on the arclength, EPSS (1 + sqrt|DS DSMAX|)
    (washer.cont.events.location_tolerance), of a constants file or of constants already
    read, with the overrides a run passes (EPSS, DS, DSMAX). The tangent is unit in the
    THL/THU norm, so a located parameter of weight 1 is within this of the zero."""
    c = constants if isinstance(constants, Mapping) else read_constants(constants)
    c = {k: float(overrides.get(k, c[k])) for k in ("EPSS", "DS", "DSMAX")}
    return _engine_location_tolerance(SimpleNamespace(**c))

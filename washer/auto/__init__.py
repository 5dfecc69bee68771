"""AUTO-07p compatibility: constants files, b./s./d. files and the sinks that write a run
into them (the type codes and the record they hold are the engine's: washer.cont.codes,
washer.cont.record), and AUTO's command language (`from washer.auto import run, load,
save, ...`; `python -m washer.auto NAME.auto`)."""
import importlib

_OBJECTS = {"Diagram": "diagram", "Solution": "diagram", "SolutionList": "diagram",
            "AutoError": "script_constants", "AutoConstants": "script_constants", "auto": "script"}


def __getattr__(name):
    # The CLUI's commands and objects, imported on first use (the file modules stay light).
    if name.startswith("__"):
        raise AttributeError(name)
    clui = importlib.import_module("washer.auto.clui")
    if name in clui.COMMANDS:
        return clui.COMMANDS[name]
    if name in _OBJECTS:
        return getattr(importlib.import_module(f"washer.auto.{_OBJECTS[name]}"), name)
    raise AttributeError(f"module 'washer.auto' has no attribute {name!r}")

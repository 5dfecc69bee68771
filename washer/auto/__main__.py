"""`python -m washer.auto [NAME.auto ...]`: run AUTO scripts in the current folder
(or, without arguments, AUTO's interactive prompt)."""
from __future__ import annotations

import os
import sys


def main(argv: list[str] | None = None) -> int:
    from washer.auto.script_constants import AutoError
    from washer.auto.script import ScriptError, interact, run_script
    argv = sys.argv[1:] if argv is None else argv
    if argv and argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0
    if not argv:
        interact()
        return 0
    from washer.auto import clui
    import warnings
    # A warning names its file and line itself: the screen shows it as such.
    warnings.formatwarning = lambda message, category, *a, **k: f"warning: {message}\n"
    for path in argv:
        try:
            run_script(path)
        except (ScriptError, AutoError) as exc:
            print(f"error: {exc}", file=sys.stderr)
            if os.environ.get("WASHER_TRACEBACK") and exc.__cause__ is not None:
                import traceback
                traceback.print_exception(exc.__cause__)
            return 1
        except KeyboardInterrupt:
            print("interrupted", file=sys.stderr)
            return 130
    if clui._runner.refused:
        print(f"error: {len(clui._runner.refused)} run(s) not done (see above)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

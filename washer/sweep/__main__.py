"""`python -m washer.sweep SPEC.toml --out DIR` and `python -m washer.sweep plot DIR`."""
from washer.sweep.cli import main

if __name__ == "__main__":
    raise SystemExit(main())

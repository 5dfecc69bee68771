# cffi cannot be configured from pyproject.toml (python-cffi/cffi#55): the
# extension is declared here, everything else lives in pyproject.toml.
import shutil
from pathlib import Path

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = Path(__file__).resolve().parent


class build_py_with_constants(build_py):
    """Also ship the AUTO constants files of auto_constants/ as washer/auto_constants/,
    and the examples (examples/*.toml, AUTO's ab demo) as washer/examples/.

    They stay at the top of the source tree (where the README, the tests and
    users of a checkout run them); a wheel carries a copy inside the package so
    that `python -m washer.run --copy-examples DIR` and washer.paper find them
    without a checkout. An editable install reads the checkout's folder instead.
    """

    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            return
        dst = Path(self.build_lib) / "washer" / "auto_constants"
        dst.mkdir(parents=True, exist_ok=True)
        for f in sorted((HERE / "auto_constants").glob("c.*")):
            shutil.copy2(f, dst / f.name)
        # The sweep specs and AUTO's ab demo, for `--copy-examples` (washer.auto.constants_file.
        # shipped_examples reads them from washer/examples/ in an installed copy).
        ex = Path(self.build_lib) / "washer" / "examples"
        ex.mkdir(parents=True, exist_ok=True)
        for f in sorted((HERE / "examples").glob("*.toml")):
            shutil.copy2(f, ex / f.name)
        for rel in ("tests/data/ab/ab.py", "tests/data/ab/c.ab"):
            shutil.copy2(HERE / rel, ex / Path(rel).name)


setup(cffi_modules=["build.py:ffibuilder", "build.py:contbuilder"],
      cmdclass={"build_py": build_py_with_constants})

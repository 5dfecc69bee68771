# cffi cannot be configured from pyproject.toml (python-cffi/cffi#55): the
# extension is declared here, everything else lives in pyproject.toml.
from setuptools import setup

setup(cffi_modules=["build.py:ffibuilder"])

"""fluid's Python package: pip install ./python (see docs/python.md)."""
from setuptools import setup

setup(cffi_modules=["build_ffi.py:ffibuilder"])

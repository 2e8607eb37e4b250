#!/usr/bin/env bash
# The python tests' fixture (ctest python.install): a venv in the build tree made from Debian's
# Python with its site packages (python3-cffi, python3-numpy, python3-pygame, python3-pytest:
# scripts/deps.sh), and the package python/ installed into it against this build's
# libfluid_c.so, offline (pip install --no-build-isolation --no-index).
#
#   bash tests/python/setup_venv.sh PYTHON VENV SOURCE_DIR BUILD_DIR
set -euo pipefail
python=$1 venv=$2 source=$3 build=$4

if ! "$python" -c "import cffi, numpy, pygame, pytest, setuptools" 2>/dev/null; then
    echo "setup_venv.sh: $python lacks cffi, numpy, pygame, pytest or setuptools:" >&2
    echo "    run: sudo bash scripts/deps.sh" >&2
    PYGAME_HIDE_SUPPORT_PROMPT=1 "$python" -c "import cffi, numpy, pygame, pytest, setuptools" \
        >&2 || true
    exit 1
fi
if [[ ! -x "$venv/bin/python" ]]; then
    "$python" -m venv --system-site-packages "$venv"
fi
# A copy of python/ in the build tree: the build leaves its build/ and egg-info there, not in
# the sources.
copy="$venv/../package"
rm -rf "$copy"
cp -r "$source/python" "$copy"
rm -rf "$copy/build" "$copy"/*.egg-info "$copy"/src/*.egg-info
FLUID_BUILD_DIR="$build" FLUID_SOURCE_DIR="$source" PIP_DISABLE_PIP_VERSION_CHECK=1 \
    "$venv/bin/python" -m pip install --quiet --no-build-isolation --no-index "$copy"
PYGAME_HIDE_SUPPORT_PROMPT=1 "$venv/bin/python" -c "import fluid; \
print('setup_venv.sh: fluid', fluid.__version__, 'C API', fluid.C_API_VERSION, 'in', '$venv')"

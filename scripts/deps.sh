#!/usr/bin/env bash
# Install the Debian 12 packages fluid needs (library, tests, bench, examples, demo, CI under Xvfb;
# python3 drives libfluid_c.so through ctypes in a test; the Python package python/ is built with
# python3-cffi against it and tested in a venv of Debian's python3 with numpy, pygame and pytest).
# Idempotent: does nothing when every package is already installed. Needs root only to install.
# Works without a terminal or standard input. The list follows shared docs/PLATFORM.md.
#
#   bash scripts/deps.sh            the list below
#   bash scripts/deps.sh PKG...     those packages instead (scripts/web.sh's)
set -euo pipefail

PACKAGES=(
    build-essential cmake ninja-build pkg-config ccache
    libbox2d-dev libsfml-dev libglm-dev catch2 libglew-dev libimgui-dev
    nlohmann-json3-dev libbenchmark-dev libcli11-dev
    xvfb xauth x11-utils mesa-utils
    clang-14 libclang-rt-14-dev
    glslang-tools
    python3 python3-dev python3-venv python3-setuptools
    python3-cffi python3-numpy python3-pygame python3-pytest
)
if [[ $# -gt 0 ]]; then
    PACKAGES=("$@")
fi

missing=()
for pkg in "${PACKAGES[@]}"; do
    status=$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)
    if [[ "$status" != "installed" ]]; then
        missing+=("$pkg")
    fi
done

if [[ ${#missing[@]} -eq 0 ]]; then
    echo "deps.sh: all ${#PACKAGES[@]} packages already installed"
    exit 0
fi

if [[ $(id -u) -ne 0 ]]; then
    echo "deps.sh: missing Debian packages: ${missing[*]}" >&2
    echo "deps.sh: run this script as root (e.g. sudo bash scripts/deps.sh) to install them," >&2
    echo "         or: sudo apt-get install ${missing[*]}" >&2
    exit 1
fi

echo "deps.sh: installing ${#missing[@]} missing package(s): ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
# Do not name Mesa packages here: xvfb pulls in the llvmpipe driver by itself.
apt-get update -qq </dev/null
apt-get install -y -qq --no-install-recommends "${missing[@]}" </dev/null >/dev/null
echo "deps.sh: done"

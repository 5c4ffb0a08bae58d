#!/usr/bin/env bash
# Idempotent set-up for a fresh Debian 12 machine: system packages (only those missing), a
# virtual environment in .venv, and the package with its test extras. Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

# What `pip install .` needs to build the package (the README's "Installing with pip" names
# these, and CMakeLists.txt names each one it misses).
BUILD_PACKAGES=(g++ make cmake pkg-config python3-venv python3-dev
                libembree-dev libtbb-dev libeigen3-dev libopenimageio-dev)
# What only the tests and benchmarks need: doctest for tests/cpp; libllvm19 for Mitsuba 3.9's
# llvm_ad_rgb variant (a reference renderer in tests and benchmarks), which needs LLVM >= 16.
TEST_PACKAGES=(libllvm19 doctest-dev)
PACKAGES=("${BUILD_PACKAGES[@]}" "${TEST_PACKAGES[@]}")
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "setup: missing Debian packages: ${missing[*]}; run as root or: sudo apt-get install ${missing[*]}" >&2
    exit 1
  fi
  echo "setup: installing ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

PYTHON=${PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
# Build requirements live in the venv so rebuilds can skip build isolation (and reuse build/).
.venv/bin/python -m pip install -q --disable-pip-version-check --upgrade pip >/dev/null
.venv/bin/python -m pip install -q --disable-pip-version-check \
  "scikit-build-core>=0.11.1" "pybind11>=2.12" "numpy>=1.24" "tqdm>=4.60" "trimesh>=4.0" \
  "pytest>=7" "colour-science>=0.4.3" "mitsuba>=3.5" "ruff>=0.4" "matplotlib>=3.7" "atheris>=2.3" \
  "jupytext>=1.16" "nbclient>=0.7" "ipykernel>=6" "pybind11-stubgen>=2.5" "dask[distributed]>=2024.1"

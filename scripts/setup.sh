#!/usr/bin/env bash
# Sets up fetorsion on a fresh Debian/Ubuntu machine: the system libraries that the gmsh
# and VTK wheels load (X11/GLU for gmsh, EGL + Mesa for off-screen rendering), then a
# virtual environment in .venv with fetorsion and its test tools. Safe to run again.
#
# The FE modal solver factorises with CHOLMOD (scikit-sparse) when it is there: SuiteSparse
# headers (libsuitesparse-dev) to build scikit-sparse 0.4.16 from source (~15 s; 0.5 does not
# build against Debian's SuiteSparse 5), and OpenBLAS (libopenblas0-pthread) behind it: with
# the reference BLAS the issue-4 trial took 226 s instead of 39 s. Without them fetorsion falls back to
# scipy's SuperLU (fine up to ~100 k DOF, 5x slower factorisation at 80 k DOF).
set -euo pipefail
cd "$(dirname "$0")/.."

system_pkgs=(libglu1-mesa libxft2 libxcursor1 libxinerama1 libxrender1 libfontconfig1
             libegl1 libegl-mesa0 libgl1-mesa-dri libgl1
             libsuitesparse-dev libopenblas0-pthread)
missing=()
if command -v dpkg >/dev/null 2>&1; then
  for p in "${system_pkgs[@]}"; do
    dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
  done
fi
if [ ${#missing[@]} -gt 0 ]; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "setup: installing system libraries: ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# Debian's chromium: a real headless browser for the test that opens report.html. Optional:
# without it that one test skips with a message.
if ! command -v chromium >/dev/null 2>&1 && command -v apt-get >/dev/null 2>&1; then
  sudo=""; [ "$(id -u)" -ne 0 ] && sudo="sudo"
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq chromium >/dev/null 2>&1 \
    || echo "setup: chromium not installed; the browser test of report.html will skip"
fi

python3 -m venv .venv
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e ".[test]"
if [ -e /usr/include/suitesparse/cholmod.h ]; then
  .venv/bin/python -m pip install -q -e ".[fast]" \
    || echo "setup: scikit-sparse did not build; the modal solver will use SuperLU (slower)"
else
  echo "setup: no SuiteSparse headers; the modal solver will use SuperLU (slower)"
fi
.venv/bin/python -m pip install -q -e ".[mkl]" \
  || echo "setup: MKL did not install; the modal solver will use CHOLMOD"
.venv/bin/python -c "from fetorsion.fe import pardiso; print('setup: MKL PARDISO', 'found' if pardiso.available() else 'not found (x86-64 only): CHOLMOD is used')"
echo "setup: done (.venv)"

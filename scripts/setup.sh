#!/usr/bin/env bash
# Sets up fetorsion on a fresh Debian/Ubuntu machine: the system libraries that the gmsh
# and VTK wheels load (X11/GLU for gmsh, EGL + Mesa for off-screen rendering), then a
# virtual environment in .venv with fetorsion and its test tools. Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."

system_pkgs=(libglu1-mesa libxft2 libxcursor1 libxinerama1 libxrender1 libfontconfig1
             libegl1 libegl-mesa0 libgl1-mesa-dri libgl1)
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

python3 -m venv .venv
.venv/bin/python -m pip install -q --upgrade pip
.venv/bin/python -m pip install -q -e ".[test]"
echo "setup: done (.venv)"

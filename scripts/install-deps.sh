#!/usr/bin/env bash
# Installs every Debian package wefm needs to build, test and run its bindings.
set -euo pipefail
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends \
  build-essential cmake pkg-config gfortran abigail-tools \
  libeigen3-dev libsuitesparse-dev libopenblas-dev libopenmesh-dev doctest-dev nlohmann-json3-dev zlib1g-dev \
  python3 python3-numpy python3-pytest python3-setuptools python3-wheel gcovr >/dev/null
# Reading written meshes back in the tests (meshio) and running faces on Dask (dask, distributed).
$SUDO apt-get install -y -qq --no-install-recommends python3-meshio python3-dask python3-distributed >/dev/null
# CAD import (wefm model, WEFM_WITH_OCCT): Open CASCADE 7.6; its CMake targets also need TBB's dev files.
$SUDO apt-get install -y -qq --no-install-recommends \
  libocct-foundation-dev libocct-modeling-data-dev libocct-modeling-algorithms-dev libocct-data-exchange-dev \
  libtbb-dev >/dev/null
# bench/compare_gmsh.py (scripts/cad_results.sh) runs the gmsh program side by side; never linked.
$SUDO apt-get install -y -qq --no-install-recommends gmsh >/dev/null

#!/usr/bin/env bash
# The whole test suite: the CHOLMOD build and the permissive (Eigen-only) build, each with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
for preset in release permissive; do
  echo "== $preset build"
  cmake --preset "$preset" >/dev/null
  cmake --build --preset "$preset" -j"$jobs"
  ctest --preset "$preset" -j"$jobs"
done

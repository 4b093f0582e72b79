#!/usr/bin/env bash
# Fresh Debian machine: install dependencies, build, and flatten the bundled example.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j"$(nproc)"
mkdir -p out
./build/release/apps/wefm flatten examples/data/vessel_patch.obj -o out/vessel_patch.obj \
  --report out/vessel_patch.json --svg out/vessel_patch.svg
echo "outputs: out/vessel_patch.obj (3D + UV), out/vessel_patch.json (report), out/vessel_patch.svg (domain picture)"

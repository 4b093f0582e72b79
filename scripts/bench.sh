#!/usr/bin/env bash
# The benchmark of docs/PERFORMANCE.md in one command:
#   scripts/bench.sh [wefm-bench options]       e.g. scripts/bench.sh --s 0,1 --4m
# Builds a Release tree with WEFM_BUILD_BENCH=ON (and the CGAL peer when libcgal-dev is installed),
# runs wefm-bench (each case in a fresh process), writes $OUT/bench-results.{json,md} and replaces
# the table between the "bench:begin/end" markers of docs/PERFORMANCE.md with the new one.
#   BUILD_DIR  build tree (default build/bench)      OUT  results directory (default $BUILD_DIR)
#   WEFM_BENCH_UPDATE_DOC=0  leaves docs/PERFORMANCE.md alone
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build/bench}
out=${OUT:-$build}
mkdir -p "$out"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DWEFM_WITH_SUITESPARSE=ON -DWEFM_BUILD_BENCH=ON \
  -DWEFM_BUILD_TESTS=OFF -DWEFM_BUILD_BINDINGS=OFF >/dev/null
cmake --build "$build" -j"$(nproc)"  # library, tool, wefm-bench and (with CGAL) wefm-bench-cgal
"$build/bench/wefm-bench" --json "$out/bench-results.json" --markdown "$out/bench-results.md" "$@"
if [ "${WEFM_BENCH_UPDATE_DOC:-1}" = 1 ]; then
  awk -v table="$out/bench-results.md" '
    /<!-- bench:begin -->/ { print; while ((getline line < table) > 0) print line; skip = 1; next }
    /<!-- bench:end -->/ { skip = 0 }
    !skip { print }' docs/PERFORMANCE.md > docs/PERFORMANCE.md.new && mv docs/PERFORMANCE.md.new docs/PERFORMANCE.md
  echo "docs/PERFORMANCE.md updated from $out/bench-results.md"
fi

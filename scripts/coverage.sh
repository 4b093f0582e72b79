#!/usr/bin/env bash
# Line and branch coverage of the test suite (docs/COVERAGE.md):
#   1. builds the whole tree with gcc --coverage into build/coverage (-O1: -O0 makes the Eigen-heavy
#      tests too slow; NDEBUG as in a release build, so assert() branches are not counted);
#   2. removes the counters of any earlier run and runs the ctest suite there;
#   3. prints line and branch coverage per folder (core/, capi/, apps/, bindings/) and per file
#      with gcovr (Debian package gcovr, scripts/install-deps.sh).
# Usage: scripts/coverage.sh [extra ctest arguments, e.g. -R cli]
#        scripts/coverage.sh --report-only     (step 3 again, from the counters of the last run)
# Environment: WEFM_COVERAGE_DIR (default build/coverage), WEFM_COVERAGE_JOBS (default nproc),
#   WEFM_COVERAGE_EXCLUDE (ctest -E regex of tests left out; default: none, see docs/COVERAGE.md).
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${WEFM_COVERAGE_DIR:-build/coverage}
jobs=${WEFM_COVERAGE_JOBS:-$(nproc)}
command -v gcovr >/dev/null || { echo "coverage.sh: gcovr not found (apt-get install gcovr)" >&2; exit 2; }

status=0
if [ "${1:-}" != "--report-only" ]; then
  # Threads update the same counters (OpenMP in CHOLMOD, the library's worker threads): atomic updates
  # keep the counts exact.
  flags="-O1 -g -DNDEBUG --coverage -fprofile-update=atomic"
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="$flags" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$flags" \
    -DCMAKE_Fortran_FLAGS_RELWITHDEBINFO="-O1 -g" \
    -DCMAKE_EXE_LINKER_FLAGS=--coverage -DCMAKE_SHARED_LINKER_FLAGS=--coverage \
    -DCMAKE_MODULE_LINKER_FLAGS=--coverage >/dev/null
  cmake --build "$dir" -j"$jobs"

  find "$dir" -name '*.gcda' -delete
  t0=$(date +%s)
  ctest --test-dir "$dir" -j"$jobs" --output-on-failure ${WEFM_COVERAGE_EXCLUDE:+-E "$WEFM_COVERAGE_EXCLUDE"} "$@" \
    || status=$?
  echo "coverage.sh: ctest took $(( $(date +%s) - t0 )) s (exit $status)"
fi

# Throw branches (the exception edges of every call that may throw) and branches the compiler
# proved unreachable are left out: they are not decisions of our code. gcov prints a few branch
# counts as negative ("taken -2", counters of code run in several processes at once); gcovr skips
# those lines and names them on stderr instead of stopping. No -j: gcovr 5.2's worker pool hangs
# when a worker fails.
mkdir -p "$dir/coverage-html"
gcovr --root . --object-directory "$dir" \
  --filter 'core/' --filter 'capi/' --filter 'apps/' --filter 'bindings/' \
  --exclude-throw-branches --exclude-unreachable-branches --gcov-ignore-parse-errors \
  --json-summary "$dir/coverage-summary.json" --json-summary-pretty \
  --txt "$dir/coverage-files.txt" --html-details "$dir/coverage-html/index.html" >/dev/null
python3 scripts/coverage_folders.py "$dir/coverage-summary.json" | tee "$dir/coverage-folders.txt"
echo "per file: $dir/coverage-files.txt; annotated sources: $dir/coverage-html/index.html"
exit "$status"

#!/usr/bin/env bash
# Run every fuzz target for SECONDS each, as many at once as there are cores (scripts/fuzz.sh
# builds and runs one; CI runs each for 30 s). Prints executions and findings per target and exits
# non-zero if any target found something.
#   scripts/fuzz_all.sh [SECONDS]            (default 600)
# Environment: as scripts/fuzz.sh (WEFM_FUZZ_BUILD_DIR, WEFM_FUZZ_TARGETS, ...), and
# WEFM_FUZZ_MERGE=1: afterwards minimise each target's grown corpus with the committed one
# (libFuzzer -merge=1) into tests/fuzz/corpus/<target>, to be reviewed and committed.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-600}
dir=${WEFM_FUZZ_BUILD_DIR:-build/fuzz}
slots=$(nproc)

WEFM_FUZZ_BUILD_ONLY=1 WEFM_FUZZ_BUILD_DIR="$dir" scripts/fuzz.sh
targets=${WEFM_FUZZ_TARGETS:-$(cmake --build "$dir" --target help | sed -n 's/^\.\.\. wefm_fuzz_\([a-z_]*\)$/\1/p' | grep -v '_static$' | sort | tr '\n' ' ')}

status=0
running=()
for t in $targets; do
  WEFM_FUZZ_NO_BUILD=1 WEFM_FUZZ_TARGETS="$t" WEFM_FUZZ_BUILD_DIR="$dir" scripts/fuzz.sh "$secs" >"$dir/fuzz_all_$t.out" 2>&1 &
  running+=($!)
  if [ "${#running[@]}" -ge "$slots" ]; then
    wait "${running[0]}" || status=1
    running=("${running[@]:1}")
  fi
done
for p in "${running[@]}"; do wait "$p" || status=1; done
for t in $targets; do grep -v '^==' "$dir/fuzz_all_$t.out" || true; done

if [ "${WEFM_FUZZ_MERGE:-0}" = 1 ]; then
  for t in $targets; do
    merged="$dir/merged/$t"
    rm -rf "$merged" && mkdir -p "$merged"
    "$dir/tests/fuzz/wefm_fuzz_$t" -merge=1 "$merged" "tests/fuzz/corpus/$t" "$dir/corpus/$t" >"$dir/merge_$t.log" 2>&1
    rm -rf "tests/fuzz/corpus/$t" && cp -r "$merged" "tests/fuzz/corpus/$t"
    echo "   $t: corpus $(ls "tests/fuzz/corpus/$t" | wc -l) files, $(du -sk "tests/fuzz/corpus/$t" | cut -f1) KB"
  done
fi
exit $status

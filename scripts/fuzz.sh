#!/usr/bin/env bash
# Build the libFuzzer targets (clang-14, ASan+UBSan, tests/fuzz) and run each for SECONDS (default 60).
#   scripts/fuzz.sh [SECONDS]
# Environment: WEFM_FUZZ_BUILD_DIR (default build/fuzz), WEFM_FUZZ_TARGETS (default: every target
# in tests/fuzz/CMakeLists.txt), WEFM_FUZZ_JOBS (build parallelism, default nproc),
# WEFM_FUZZ_BUILD_ONLY=1 / WEFM_FUZZ_NO_BUILD=1 (scripts/fuzz_all.sh builds once, then runs several).
# New corpus entries go to $WEFM_FUZZ_BUILD_DIR/corpus/<target> (the committed seeds in
# tests/fuzz/corpus are read, never written); crashes, leaks and timeouts to .../artifacts/<target>/.
# Prints executions per target; exits non-zero if any target found something. A finding becomes a
# regression input: copy it to tests/fuzz/regressions/<target>/ (replayed by ctest in every build).
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-60}
dir=${WEFM_FUZZ_BUILD_DIR:-build/fuzz}
targets=${WEFM_FUZZ_TARGETS:-}
jobs=${WEFM_FUZZ_JOBS:-$(nproc)}
cc=${WEFM_FUZZ_CC:-clang-14}
cxx=${WEFM_FUZZ_CXX:-clang++-14}

if [ ! -f "$dir/CMakeCache.txt" ]; then
  CC=$cc CXX=$cxx cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DWEFM_BUILD_FUZZ=ON \
    -DWEFM_BUILD_APPS=OFF -DWEFM_BUILD_BINDINGS=OFF >/dev/null
fi
# Default: every libFuzzer target this build defines (cad_import only where Open CASCADE is found).
if [ -z "$targets" ]; then
  targets=$(cmake --build "$dir" --target help | sed -n 's/^\.\.\. wefm_fuzz_\([a-z_]*\)$/\1/p' | grep -v '_static$' | sort | tr '\n' ' ')
fi
[ "${WEFM_FUZZ_NO_BUILD:-0}" = 1 ] || cmake --build "$dir" -j"$jobs" --target $(for t in $targets; do printf 'wefm_fuzz_%s ' "$t"; done)
[ "${WEFM_FUZZ_BUILD_ONLY:-0}" = 1 ] && exit 0

status=0
for t in $targets; do
  mkdir -p "$dir/corpus/$t" "$dir/artifacts/$t"
  case $t in
    capi | map | domain_mesh) max_len=2048 rss=2048 ;;
    cad_import) max_len=65536 rss=4096 ;;
    *) max_len=16384 rss=2048 ;;
  esac
  seeds=("tests/fuzz/corpus/$t")
  [ -d "tests/fuzz/regressions/$t" ] && seeds+=("tests/fuzz/regressions/$t")
  log="$dir/fuzz_$t.log"
  before=$(find "$dir/artifacts/$t" -type f | wc -l)
  echo "== fuzz $t for ${secs}s (log $log)"
  set +e
  ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1} \
    "$dir/tests/fuzz/wefm_fuzz_$t" "$dir/corpus/$t" "${seeds[@]}" \
    -max_total_time="$secs" -timeout=10 -rss_limit_mb="$rss" -max_len="$max_len" -print_final_stats=1 \
    -artifact_prefix="$dir/artifacts/$t/" >"$log" 2>&1
  rc=$?
  set -e
  execs=$(grep -m1 'stat::number_of_executed_units' "$log" | awk '{print $2}')
  cov=$(grep -E '^#[0-9]+' "$log" | tail -1 | grep -oE 'cov: [0-9]+' || true)
  found=$(( $(find "$dir/artifacts/$t" -type f | wc -l) - before ))
  echo "   $t: ${execs:-?} executions, ${cov:-cov ?}, exit $rc, $found new artifact(s) in $dir/artifacts/$t"
  if [ "$rc" -ne 0 ] || [ "$found" -ne 0 ]; then
    status=1
    grep -m8 -E "^==[0-9]+==ERROR|^ERROR: libFuzzer|^SUMMARY|invariant violated|runtime error|Test unit written|deadly signal" "$log" || true
  fi
done
exit $status

#!/usr/bin/env bash
# The whole test suite (README "Quick start"):
#   1. release      CHOLMOD build, ctest
#   2. permissive   Eigen-only build, ctest
#   3. sanitize     ASan + UBSan build (Debug at -O1: -O0 ran the suite three times slower), the whole
#                   ctest suite under it but cad.model_mesh
#   4. tsan         ThreadSanitizer build of the library and the concurrency test, run
#   5. fuzz         each libFuzzer target for WEFM_FUZZ_SECONDS (default 30) with clang (scripts/fuzz.sh)
# WEFM_TEST_STAGES selects stages (default "release permissive sanitize tsan fuzz"); stages whose
# tools are missing (clang-14 for fuzz) are skipped with a note. Build directories: build/<stage>.
# Timings per stage are printed at the end (2-core machine: see tests/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
stages=${WEFM_TEST_STAGES:-"release permissive sanitize tsan fuzz"}
summary=()

stage_time() {  # name start
  summary+=("$(printf '%-11s %5ds' "$1" $(( $(date +%s) - $2 )))")
}

for stage in $stages; do
  t0=$(date +%s)
  case $stage in
    release|permissive)
      echo "== $stage build"
      cmake --preset "$stage" >/dev/null
      cmake --build --preset "$stage" -j"$jobs"
      ctest --preset "$stage" -j"$jobs"
      ;;
    sanitize)
      echo "== sanitize build (ASan + UBSan)"
      cmake --preset sanitize >/dev/null
      cmake --build --preset sanitize -j"$jobs"
      # Programs linked with the sanitized library run as they are. The Python tests load it into
      # an uninstrumented interpreter: the ASan runtime must be preloaded, and the interpreter's own
      # allocations at exit are not ours (leak checking stays on for everything else).
      export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
      export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
      # cad.model_mesh (whole models: by far the slowest test under ASan) runs in the release and permissive
      # stages; here mesh-model is exercised by cad.import_repair and cad.cli_model.
      ctest --preset sanitize -j"$jobs" -LE python -E '^cad\.model_mesh$'
      # libstdc++ is preloaded too: python does not link it, and without it ASan's __cxa_throw
      # interceptor finds no real __cxa_throw when the library throws (a CHECK failure, not a bug).
      asan_rt=$(${CC:-gcc} -print-file-name=libasan.so)
      cxx_rt=$(${CXX:-g++} -print-file-name=libstdc++.so)
      LD_PRELOAD="$asan_rt $cxx_rt" ASAN_OPTIONS=detect_leaks=0 ctest --preset sanitize -L python
      unset UBSAN_OPTIONS LSAN_OPTIONS
      ;;
    tsan)
      echo "== ThreadSanitizer: concurrency test"
      cmake -S . -B build/tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWEFM_SANITIZE=thread \
        -DWEFM_BUILD_APPS=OFF -DWEFM_BUILD_BINDINGS=OFF >/dev/null
      cmake --build build/tsan -j"$jobs" --target wefm_concurrency_test
      # BLAS/OpenMP threads inside CHOLMOD are not instrumented: keep them to one.
      # libgomp (CHOLMOD's OpenMP) is not instrumented either: tests/robustness/tsan.supp.
      OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 \
        TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/tests/robustness/tsan.supp" \
        build/tsan/tests/robustness/wefm_concurrency_test
      ;;
    fuzz)
      if command -v "${WEFM_FUZZ_CXX:-clang++-14}" >/dev/null; then
        scripts/fuzz.sh "${WEFM_FUZZ_SECONDS:-30}"
      else
        echo "== fuzz: ${WEFM_FUZZ_CXX:-clang++-14} not found, skipped"
      fi
      ;;
    *) echo "unknown stage '$stage'" >&2; exit 2 ;;
  esac
  stage_time "$stage" "$t0"
done
echo "== stage times"
printf '%s\n' "${summary[@]}"

#!/usr/bin/env bash
# Builds the scenario-parser fuzzer (tests/fuzz/) with clang and runs it.
#
#   tools/fuzz.sh build   [DIR]           configure and build it in DIR (default build-fuzz)
#   tools/fuzz.sh regress [DIR]           run every input of tests/fuzz/corpus once
#   tools/fuzz.sh fuzz SECONDS [DIR] [-- LIBFUZZER_OPTIONS...]
#                                         fuzz for SECONDS, starting from tests/fuzz/corpus
#
# regress and fuzz build first (nothing to do when it is up to date). Inputs that reach new
# code go to DIR/corpus, not into the source tree; an input that fails stops the run and is
# written to DIR/artifacts/. Copy it to tests/fuzz/corpus/ once the bug is fixed, so that
# regress keeps checking it. The compiler is $SWEMPS_FUZZ_CXX, or clang++.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
usage() {
  sed -n '2,8s/^# \{0,1\}//p' "$0" >&2
  exit 2
}

mode="${1:-}"
[ $# -gt 0 ] && shift
seconds=""
if [ "$mode" = fuzz ]; then
  [ $# -gt 0 ] || usage
  seconds="$1"
  shift
  [[ "$seconds" =~ ^[1-9][0-9]*$ ]] || usage
fi
dir="build-fuzz"
if [ $# -gt 0 ] && [ "$1" != "--" ]; then
  dir="$1"
  shift
fi
if [ $# -gt 0 ]; then
  [ "$1" = "--" ] || usage
  shift
fi
case "$dir" in /*) ;; *) dir="$PWD/$dir" ;; esac

build() {
  if [ ! -f "$dir/CMakeCache.txt" ]; then
    cmake -S "$root/tests/fuzz" -B "$dir" -DCMAKE_BUILD_TYPE= \
      -DCMAKE_CXX_COMPILER="${SWEMPS_FUZZ_CXX:-clang++}" >/dev/null
  fi
  cmake --build "$dir" -j 2
}

# A hang or a leak is a bug as much as a crash is; stack traces make the report useful.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:detect_stack_use_after_return=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
common=(-timeout=10 -rss_limit_mb=2048 -artifact_prefix="$dir/artifacts/")

case "$mode" in
  build)
    build
    ;;
  regress)
    build
    mkdir -p "$dir/artifacts"
    # -runs=0: run the given inputs, make no new ones; no -max_len, which would cut long ones.
    "$dir/swemps-fuzz-scenario" "${common[@]}" -runs=0 "$root/tests/fuzz/corpus"
    ;;
  fuzz)
    build
    mkdir -p "$dir/artifacts" "$dir/corpus"
    # The first folder receives what the fuzzer finds; the second only seeds it.
    "$dir/swemps-fuzz-scenario" "${common[@]}" -max_len=8192 -dict="$root/tests/fuzz/scenario.dict" \
      -max_total_time="$seconds" -print_final_stats=1 "$@" "$dir/corpus" "$root/tests/fuzz/corpus"
    ;;
  *)
    usage
    ;;
esac

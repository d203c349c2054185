#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) and runs each for a
# fixed number of executions on its corpus in fuzz/corpus/<target>/.
#
#   scripts/fuzz.sh                 # both targets, default run counts
#   scripts/fuzz.sh parser          # one target (parser or options)
#   UNIPARAM_FUZZ_RUNS=100000 scripts/fuzz.sh
#
# Environment: UNIPARAM_FUZZ_DIR (build dir, default build-fuzz),
# UNIPARAM_FUZZ_RUNS (executions per target; default 20000 for the parser,
# 3000 for the options), UNIPARAM_JOBS (build parallelism, default 2),
# CXX / CC (default clang++ / clang).
#
# New inputs that reach new code are written to a scratch directory, not to
# the repository's corpus; copy the interesting ones into fuzz/corpus/ by
# hand (or `<target> -merge=1 fuzz/corpus/<target> <scratch>`). A crash, a
# sanitizer report, a leak or a hang (-timeout) stops the run, leaves the
# reproducer (crash-*, leak-*, timeout-*) in the scratch directory and makes
# the script exit non-zero. Reproduce with: build-fuzz/fuzz/fuzz_<target> FILE
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
build="${UNIPARAM_FUZZ_DIR:-build-fuzz}"
jobs="${UNIPARAM_JOBS:-2}"
targets=("$@")
[ "${#targets[@]}" -gt 0 ] || targets=(parser options)

bash scripts/install-deps.sh --fuzz
export CXX="${CXX:-clang++}" CC="${CC:-clang}"
command -v "$CXX" >/dev/null || { echo "fuzz.sh: $CXX not found (Debian: apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }

echo "== configure ($build, $CXX, libFuzzer + ASan + UBSan)"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUNIPARAM_FUZZ=ON \
  -DUNIPARAM_BUILD_TESTS=OFF -DUNIPARAM_BUILD_BENCH=OFF >/dev/null
echo "== build (-j$jobs)"
cmake --build "$build" --parallel "$jobs" --target $(printf 'fuzz_%s ' "${targets[@]}")

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
case "$build" in /*) build_abs="$build" ;; *) build_abs="$root/$build" ;; esac
scratch="$build_abs/fuzz-work"
for t in "${targets[@]}"; do
  case "$t" in
    parser) runs="${UNIPARAM_FUZZ_RUNS:-20000}"; max_len=512 ;;
    options) runs="${UNIPARAM_FUZZ_RUNS:-3000}"; max_len=256 ;;
    *) echo "fuzz.sh: unknown target '$t' (parser or options)" >&2; exit 2 ;;
  esac
  corpus="fuzz/corpus/$t"
  work="$scratch/$t"
  rm -rf "$work"
  mkdir -p "$work"
  dict=()
  [ -f "fuzz/$t.dict" ] && dict=(-dict="fuzz/$t.dict")
  echo "== fuzz_$t: $runs runs on $corpus ($(ls "$corpus" | wc -l) seeds)"
  start=$(date +%s)
  # -timeout: one input taking longer than 20 s is a hang; -rss_limit_mb: a
  # memory blow-up is a finding too.
  (cd "$work" && "$build_abs/fuzz/fuzz_$t" -runs="$runs" -max_len="$max_len" -timeout=20 \
     -rss_limit_mb=2048 -print_final_stats=1 "${dict[@]/#-dict=/-dict=$root/}" \
     "$work" "$root/$corpus" 2>"$work/log") || {
    tail -n 60 "$work/log" >&2
    echo "fuzz.sh: fuzz_$t FAILED; reproducer and log in $work" >&2
    exit 1
  }
  grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|Done)" "$work/log" || true
  echo "== fuzz_$t: clean ($(( $(date +%s) - start )) s)"
done

#!/bin/bash
# Default threads against one thread, paired: every certified 15-digit row
# of uniparam_bench, each run its own process. For each row, PAIR_RUNS pairs
# (default 9) of one run with the default thread count and one with
# UNIPARAM_THREADS=1, the order inside each pair drawn at random, so that a
# drift of the machine's speed hits both kinds alike. Then a Markdown table
# (scripts/bench-pairs-report.py): the fastest run of each kind, the median
# of the pairs' ratios (above 1: the default was slower) with a
# distribution-free confidence interval, and a verdict: "slower" only when
# the whole interval lies above 1. Where the two kinds are equal, the
# interval of 9 pairs (96%) lies above 1 by chance in about one row of
# fifty, and there are 72 rows: the rows judged "slower" are paired again
# (PAIR_CONFIRM_RUNS pairs, default 15, into OUT.confirm) and judged on the
# new pairs alone: a second table, whose "slower" rows are the findings.
#
#   bash scripts/bench-pairs.sh [BENCH_BINARY] [OUT]
#
# BENCH_BINARY defaults to build/bench/uniparam_bench (build it first, in
# Release: scripts/bench.sh does); OUT (default build/bench-pairs.txt) gets
# the raw times in ms, one line per row (the default runs, the one-thread
# runs in the same pair order, the load average after the row).
# The default runs get UNIPARAM_PADDING=1 in their environment, as long as
# the one-thread runs' UNIPARAM_THREADS=1: the size of the environment moves
# the initial stack, which can change a process's speed by itself.
# PAIR_FILTER (a grep -E pattern on the benchmark names) selects rows.
# PAIR_LOAD=N (default 0) keeps N busy loops running beside the benchmark
# (a busy machine: with N equal to the cores, every core is taken); they are
# stopped on every exit path.
# About 15 minutes for all 72 rows on 2 cores with nothing else running.
set -euo pipefail
B=${1:-build/bench/uniparam_bench}
OUT=${2:-build/bench-pairs.txt}
FILTER=${PAIR_FILTER:-.}
RUNS=${PAIR_RUNS:-9}
CONFIRM=${PAIR_CONFIRM_RUNS:-15}
LOAD=${PAIR_LOAD:-0}
[ -x "$B" ] || { echo "bench-pairs.sh: no benchmark binary at $B (build it first)" >&2; exit 2; }
[[ $RUNS =~ ^[1-9][0-9]*$ ]] || { echo "bench-pairs.sh: PAIR_RUNS must be a positive integer, got '$RUNS'" >&2; exit 2; }
[[ $CONFIRM =~ ^[1-9][0-9]*$ ]] || { echo "bench-pairs.sh: PAIR_CONFIRM_RUNS must be a positive integer, got '$CONFIRM'" >&2; exit 2; }
[[ $LOAD =~ ^[0-9]+$ ]] || { echo "bench-pairs.sh: PAIR_LOAD must be a non-negative integer, got '$LOAD'" >&2; exit 2; }
loaders=()
stop_load() { for p in "${loaders[@]}"; do kill "$p" 2>/dev/null || true; done; }
trap stop_load EXIT
trap 'exit 130' INT TERM
for _ in $(seq "$LOAD"); do
  (while :; do :; done) &
  loaders+=($!)
done
: > "$OUT"
time_of() {  # time_of ROW THREADS: the run's real time in ms (exit 3 when the run fails)
  local r label how
  if [ "$2" = default ]; then
    label="default threads"; how=(env -u UNIPARAM_THREADS UNIPARAM_PADDING=1)
  else
    label="one thread"; how=(env UNIPARAM_THREADS=1)
  fi
  r=$("${how[@]}" "$B" --benchmark_filter="^$1\$" --benchmark_min_time=0.3 --benchmark_format=csv 2>/dev/null | grep '^"cert') || true
  [ -n "$r" ] || { echo "bench-pairs.sh: $1 ($label) gave no time: the benchmark failed or does not exist" >&2; exit 3; }
  echo "$r" | awk -F, '{ t = $3; if ($5 == "us") t /= 1000; if ($5 == "s") t *= 1000; printf "%.6g", t }'
}
pairs() {  # pairs OUT RUNS ROW...: RUNS pairs of each row, appended to OUT
  local out=$1 runs=$2 row d o td to
  shift 2
  for row in "$@"; do
    d=""; o=""
    for _ in $(seq "$runs"); do
      if [ $((RANDOM % 2)) = 0 ]; then
        td=$(time_of "$row" default); to=$(time_of "$row" one)
      else
        to=$(time_of "$row" one); td=$(time_of "$row" default)
      fi
      d="$d $td"; o="$o $to"
    done
    echo "$row |$d |$o | $(cut -d' ' -f1 /proc/loadavg)" >> "$out"
  done
}
REPORT="$(dirname "$0")/bench-pairs-report.py"
mapfile -t rows < <("$B" --benchmark_list_tests 2>/dev/null | grep '^cert/.*/15$' | grep -E "$FILTER" || true)
[ "${#rows[@]}" -gt 0 ] || { echo "bench-pairs.sh: no certified 15-digit row of $B matches PAIR_FILTER='$FILTER'" >&2; exit 2; }
pairs "$OUT" "$RUNS" "${rows[@]}"
python3 "$REPORT" "$OUT"
mapfile -t slower < <(python3 "$REPORT" --slower "$OUT")
: > "$OUT.confirm"
if [ "${#slower[@]}" -gt 0 ]; then
  pairs "$OUT.confirm" "$CONFIRM" "${slower[@]}"
  echo
  echo "Paired again ($CONFIRM pairs each), the rows judged slower above:"
  echo
  python3 "$REPORT" "$OUT.confirm"
fi

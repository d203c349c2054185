#!/bin/bash
# Default threads against one thread, paired: every certified 15-digit row
# of uniparam_bench, each run its own process, the default thread count and
# UNIPARAM_THREADS=1 alternating (PAIR_RUNS runs of each, default 3 at
# degrees 6 and 12, 2 above), then a Markdown table of the fastest and median
# run of each kind and their ratios (above 1: the default was slower).
#
#   bash scripts/bench-pairs.sh [BENCH_BINARY] [OUT]
#
# BENCH_BINARY defaults to build/bench/uniparam_bench (build it first, in
# Release: scripts/bench.sh does); OUT (default build/bench-pairs.txt) gets
# the raw times, one line per row, with the load average after the row.
# PAIR_FILTER (a grep -E pattern on the benchmark names) selects rows.
# About 12 minutes for all 72 rows on 2 cores; run it on a quiet machine.
set -euo pipefail
B=${1:-build/bench/uniparam_bench}
OUT=${2:-build/bench-pairs.txt}
FILTER=${PAIR_FILTER:-.}
[ -x "$B" ] || { echo "bench-pairs.sh: no benchmark binary at $B (build it first)" >&2; exit 2; }
: > "$OUT"
time_of() {  # time_of ROW THREADS: the run's real time in ms
  local r
  if [ "$2" = default ]; then
    r=$(env -u UNIPARAM_THREADS "$B" --benchmark_filter="^$1\$" --benchmark_min_time=0.3 --benchmark_format=csv 2>/dev/null | grep '^"cert')
  else
    r=$(UNIPARAM_THREADS=1 "$B" --benchmark_filter="^$1\$" --benchmark_min_time=0.3 --benchmark_format=csv 2>/dev/null | grep '^"cert')
  fi
  echo "$r" | awk -F, '{ t = $3; if ($5 == "us") t /= 1000; if ($5 == "s") t *= 1000; printf "%.6g", t }'
}
for row in $("$B" --benchmark_list_tests 2>/dev/null | grep '^cert/.*/15$' | grep -E "$FILTER"); do
  deg=$(echo "$row" | cut -d/ -f3)
  runs=${PAIR_RUNS:-$([ "$deg" -le 12 ] && echo 3 || echo 2)}
  d=""; o=""
  for _ in $(seq "$runs"); do
    d="$d $(time_of "$row" default)"
    o="$o $(time_of "$row" one)"
  done
  echo "$row |$d |$o | $(cut -d' ' -f1 /proc/loadavg)" >> "$OUT"
done
python3 - "$OUT" <<'EOF'
import statistics, sys
ops = {"uniformity": "uniformity", "radical": "radical", "pieces3": "reparam --pieces 3",
       "target99": "reparam --target 0.99"}
def ms(x):
    return f"{x:.3g} ms" if x < 1000 else f"{x / 1000:.3g} s"
print("| curve | degree | operation | runs of each | default threads (fastest, median) "
      "| one thread (fastest, median) | ratio of the fastest | ratio of the medians |")
print("|---|---|---|---|---|---|---|---|")
for line in open(sys.argv[1]):
    name, d, o, _ = [f.strip() for f in line.split("|")]
    d = [float(x) for x in d.split()]
    o = [float(x) for x in o.split()]
    _, fam, deg, op, _ = name.split("/")
    print(f"| {fam} | {deg} | {ops.get(op, op)} | {len(d)} | {ms(min(d))}, {ms(statistics.median(d))} "
          f"| {ms(min(o))}, {ms(statistics.median(o))} | {min(d) / min(o):.3f} "
          f"| {statistics.median(d) / statistics.median(o):.3f} |")
EOF

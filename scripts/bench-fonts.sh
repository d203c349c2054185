#!/usr/bin/env bash
# scripts/bench-fonts.sh -- font workloads through `uniparam batch`, end to end
# (one process, JSON lines in and out, certified to 15 digits):
#   * the arc length (uniformity --speed parametric) of every TrueType quadratic
#     segment of DejaVu Sans (tests/data/font_quadratics.jsonl, made by
#     scripts/extract_font_segments.py): segments per second;
#   * every letter contour of tests/data/glyphs.jsonl as one composite curve
#     (an SVG path): milliseconds per contour, on one thread (--jobs 1) and on
#     the default threads.
# Each measurement is the fastest of BENCH_RUNS (default 3) runs; every result
# line is checked to have status 0. Prints a Markdown table.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
RUNS=${BENCH_RUNS:-3}
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j2 --target uniparam_cli >/dev/null
U="$BUILD/cli/uniparam"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# The data files as batch lines: glyph and contour become the line's id.
/usr/bin/python3 - tests/data/font_quadratics.jsonl tests/data/glyphs.jsonl "$tmp" <<'PY'
import json, sys
quads, glyphs, out = sys.argv[1:4]
with open(quads) as f, open(out + "/quads.jsonl", "w") as g:
    for line in f:
        d = json.loads(line)
        g.write(json.dumps({"id": [d["glyph"], d["contour"]], "control": d["control"]}) + "\n")
with open(glyphs) as f, open(out + "/glyphs.jsonl", "w") as g:
    for line in f:
        d = json.loads(line)
        g.write(json.dumps({"id": [d["glyph"], d["contour"]], "svg": d["svg"]}) + "\n")
PY

# best NAME ARGS...: the fastest of $RUNS runs of `uniparam batch ARGS` on
# $tmp/NAME.jsonl, in seconds; fails if a line did not succeed.
best() {
  local name=$1 b=""
  shift
  for _ in $(seq "$RUNS"); do
    local t0 t1
    t0=$(date +%s.%N)
    "$U" batch "$@" --no-progress <"$tmp/$name.jsonl" >"$tmp/$name.out" 2>/dev/null || true
    t1=$(date +%s.%N)
    local n_ok n_all
    n_ok=$(grep -c '"status":0,' "$tmp/$name.out" || true)
    n_all=$(grep -c . "$tmp/$name.jsonl")
    if [[ $n_ok -ne $n_all ]]; then
      echo "bench-fonts: $name: $n_ok of $n_all lines succeeded" >&2
      exit 1
    fi
    local d
    d=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.6f", b - a }')
    if [[ -z $b ]] || awk -v d="$d" -v b="$b" 'BEGIN { exit !(d < b) }'; then b=$d; fi
  done
  echo "$b"
}

nq=$(grep -c . "$tmp/quads.jsonl")
ng=$(grep -c . "$tmp/glyphs.jsonl")
q=$(best quads uniformity --speed parametric)
g1=$(best glyphs uniformity --speed parametric --jobs 1)
g=$(best glyphs uniformity --speed parametric)
echo "| workload | items | time | rate |"
echo "|---|---|---|---|"
printf '| arc length of DejaVu Sans quadratics, batch, default threads | %d segments | %.3f s | %.0f segments/s |\n' \
  "$nq" "$q" "$(awk -v n="$nq" -v t="$q" 'BEGIN { print n / t }')"
printf '| arc length of each letter contour as one composite curve, batch, 1 thread | %d contours | %.3f s | %.2f ms per contour |\n' \
  "$ng" "$g1" "$(awk -v n="$ng" -v t="$g1" 'BEGIN { print 1000 * t / n }')"
printf '| the same, default threads | %d contours | %.3f s | %.2f ms per contour |\n' \
  "$ng" "$g" "$(awk -v n="$ng" -v t="$g" 'BEGIN { print 1000 * t / n }')"

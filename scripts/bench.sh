#!/usr/bin/env bash
# scripts/bench.sh -- builds Release, runs the benchmark table
# (bench/bench_table.cpp, Google Benchmark) one process per benchmark, and
# prints a Markdown table: curve, degree, operation, digits, certified time,
# double time, ratio, correct digits of double, memory.
#
#   scripts/bench.sh                      # everything (long: degree 300 included)
#   BENCH_DEGREES="6 12 50" BENCH_FAMILIES="bez-plane" BENCH_OPS="radical" scripts/bench.sh
#
# Environment: BENCH_DEGREES, BENCH_FAMILIES, BENCH_OPS (uniformity radical
# pieces3 target99; target99 = reparam_c1 to u >= 0.99, 15 digits only, no
# double baseline), BENCH_DIGITS ("15 50"), BENCH_TIMEOUT (seconds per benchmark
# process, default 600), BENCH_MIN_TIME (Google Benchmark min time, default
# 0.2), BENCH_REPETITIONS (default 1: each benchmark runs that many times in its
# process, and the table reports the fastest repetition, the certified and the
# double rows alike: on a VM whose speed varies from one second to the next,
# the minimum of a few short runs is steadier than one run), BENCH_OUT (results folder, default build/bench-results; results.csv
# there feeds scripts/plot-scaling). BENCH_REPORT_ONLY=1 prints the table of
# the results already in BENCH_OUT without running anything. The double column is the UNCERTIFIED
# baseline of bench/float_baseline.hpp. BENCH_PIECES="3 10 30 100 300" (default: unset, skipped)
# adds a second table: reparam --pieces N on bez-plane degree 50 at 15 digits, time and peak
# memory against N (build/bench/uniparam_probe under /usr/bin/time), to show that nothing grows
# quadratically with the number of breakpoints. BENCH_ONE_THREAD=1 (the default; 0 to skip)
# also runs every certified 15-digit row with UNIPARAM_THREADS=1 and adds its time as a column,
# so the table shows whether the default thread count is ever slower than one thread.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${BUILD:-build}
DEGREES=${BENCH_DEGREES:-"6 12 50 100 150 300"}
FAMILIES=${BENCH_FAMILIES:-"bez-plane bez-rat-space dense-plane"}
OPS=${BENCH_OPS:-"uniformity radical pieces3 target99"}
DIGITS=${BENCH_DIGITS:-"15 50"}
TIMEOUT=${BENCH_TIMEOUT:-600}
MIN_TIME=${BENCH_MIN_TIME:-0.2}
REPS=${BENCH_REPETITIONS:-1}
OUT=${BENCH_OUT:-$BUILD/bench-results}
ONE_THREAD=${BENCH_ONE_THREAD:-1}

cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j2 --target uniparam_bench >/dev/null
mkdir -p "$OUT"
BIN="$BUILD/bench/uniparam_bench"

run() {  # run NAME: one benchmark in its own process, JSON to $OUT/NAME.json
  local name=$1 file="$OUT/$(echo "$1" | tr '/' '_').json"
  if timeout "$TIMEOUT" "$BIN" --benchmark_filter="^${name}\$" --benchmark_min_time="$MIN_TIME" --benchmark_repetitions="$REPS" \
      --benchmark_format=json >"$file.tmp" 2>/dev/null; then
    mv "$file.tmp" "$file"
  elif [[ $name == float/* ]] && UNIPARAM_BENCH_NO_REF=1 timeout "$TIMEOUT" "$BIN" --benchmark_filter="^${name}\$" \
      --benchmark_min_time="$MIN_TIME" --benchmark_repetitions="$REPS" --benchmark_format=json >"$file.tmp" 2>/dev/null; then
    mv "$file.tmp" "$file"  # the double run without its certified reference: "no ref" digits
  else
    echo '{"timeout": true}' >"$file"
    rm -f "$file.tmp"
  fi
}

# run_one_thread NAME: NAME again with UNIPARAM_THREADS=1, JSON to $OUT/NAME.t1.json.
run_one_thread() {
  local file="$OUT/$(echo "$1" | tr '/' '_').t1.json"
  if UNIPARAM_THREADS=1 timeout "$TIMEOUT" "$BIN" --benchmark_filter="^${1}\$" --benchmark_min_time="$MIN_TIME" \
      --benchmark_repetitions="$REPS" --benchmark_format=json >"$file.tmp" 2>/dev/null; then
    mv "$file.tmp" "$file"
  else
    echo '{"timeout": true}' >"$file"
    rm -f "$file.tmp"
  fi
}

# run_pair CERT FLOAT: with BENCH_REPETITIONS > 1, the certified 15-digit row
# and its double baseline in one process, their repetitions interleaved in
# random order (Google Benchmark's --benchmark_enable_random_interleaving), so
# that both are timed in the same minutes of the VM and the ratio compares like
# with like; each one's JSON is then split out as run() writes it. false (no
# file written) when that run fails, and the caller runs them apart.
run_pair() {
  local tmp="$OUT/pair.json.tmp"
  [[ $REPS -gt 1 ]] || return 1
  timeout "$TIMEOUT" "$BIN" --benchmark_filter="^(${1}|${2})\$" --benchmark_min_time="$MIN_TIME" \
    --benchmark_repetitions="$REPS" --benchmark_enable_random_interleaving=true \
    --benchmark_format=json >"$tmp" 2>/dev/null || { rm -f "$tmp"; return 1; }
  python3 - "$tmp" "$OUT" "$1" "$2" <<'PY' || { rm -f "$tmp"; return 1; }
import json, os, sys
tmp, out, names = sys.argv[1], sys.argv[2], sys.argv[3:]
j = json.load(open(tmp))
for n in names:
    runs = [b for b in j['benchmarks'] if b.get('run_name', b['name']).split('/repeats')[0] == n
            and b.get('run_type', 'iteration') == 'iteration']
    if not runs:
        sys.exit(1)
    json.dump({'context': j.get('context', {}), 'benchmarks': runs},
              open(os.path.join(out, n.replace('/', '_') + '.json'), 'w'))
PY
  rm -f "$tmp"
}

for fam in $FAMILIES; do
  [[ -n ${BENCH_REPORT_ONLY:-} ]] && break  # only print the table of what $OUT holds
  for d in $DEGREES; do
    for op in $OPS; do
      if [[ $ONE_THREAD == 1 && " $DIGITS " == *" 15 "* ]]; then run_one_thread "cert/$fam/$d/$op/15"; fi
      if [[ $op == target99 ]]; then run "cert/$fam/$d/$op/15"; echo "done $fam $d $op" >&2; continue; fi
      paired=
      if [[ " $DIGITS " == *" 15 "* ]] && run_pair "cert/$fam/$d/$op/15" "float/$fam/$d/$op"; then paired=1; fi
      for dg in $DIGITS; do [[ -n $paired && $dg == 15 ]] || run "cert/$fam/$d/$op/$dg"; done
      [[ -n $paired ]] || run "float/$fam/$d/$op"
      echo "done $fam $d $op" >&2
    done
  done
done

python3 - "$OUT" "$TIMEOUT" "$FAMILIES" "$DEGREES" "$OPS" "$DIGITS" <<'PY'
import json, os, sys
out, timeout = sys.argv[1], sys.argv[2]
fams, degs, ops, digs = (s.split() for s in sys.argv[3:7])
def load(name, suffix=''):
    p = os.path.join(out, name.replace('/', '_') + suffix + '.json')
    if not os.path.exists(p):
        return None
    j = json.load(open(p))
    if j.get('timeout'):
        return 'timeout'
    runs = [b for b in j['benchmarks'] if b.get('run_type', 'iteration') == 'iteration']
    b = min(runs, key=lambda r: r['real_time'])  # the fastest repetition (BENCH_REPETITIONS)
    scale = {'ns': 1e-9, 'us': 1e-6, 'ms': 1e-3, 's': 1.0}[b['time_unit']]
    b['seconds'] = b['real_time'] * scale
    return b
def fmt_t(s):
    return f'{s*1e3:.3g} ms' if s < 1 else f'{s:.3g} s'
names = {'uniformity': 'uniformity', 'radical': 'radical', 'pieces3': 'reparam --pieces 3',
         'target99': 'reparam --target 0.99'}
rows, csv = [], ['family,degree,op,digits,cert_s,one_thread_s,double_s,correct_digits,maxrss_mb']
print('| curve | degree | operation | digits | certified time | one thread | double time | ratio | correct digits of double | memory (peak RSS) |')
print('|---|---|---|---|---|---|---|---|---|---|')
for f in fams:
    for d in degs:
        for op in ops:
            fl = load(f'float/{f}/{d}/{op}')
            for dg in (['15'] if op == 'target99' else digs):
                c = load(f'cert/{f}/{d}/{op}/{dg}')
                if c is None:
                    continue
                if c == 'timeout':
                    ct, ratio, mem, cs = f'> {timeout} s (timeout)', '', '', ''
                else:
                    cs = c['seconds']
                    ct, mem = fmt_t(cs), f"{c.get('maxrss_MB', 0):.0f} MB"
                    if op == 'target99':
                        ct += f" ({c.get('pieces', 0):.0f} pieces{'' if c.get('reached', 1) else ', target not reached'})"
                ft, ratio_s, dig, fs = ('n/a (no double C1)' if op == 'target99' else 'timeout'), '', '', ''
                if isinstance(fl, dict):
                    fs = fl['seconds']
                    ft = fmt_t(fs)
                    cd = fl.get('correct_digits', -1)
                    dig = 'no ref (timeout)' if cd < 0 else f'{cd:.1f}'
                    if fl.get('structure_ok', 1) == 0:
                        dig += ' (wrong breakpoints)'
                    if fl.get('converged', 1) == 0:
                        dig += ' (not converged)'
                    if cs != '':
                        ratio_s = f'{cs / fs:.2g}x'
                one = load(f'cert/{f}/{d}/{op}/{dg}', '.t1')
                ot, os1 = '', ''
                if one == 'timeout':
                    ot = 'timeout'
                elif isinstance(one, dict):
                    os1 = one['seconds']
                    ot = fmt_t(os1)
                print(f'| {f} | {d} | {names[op]} | {dg} | {ct} | {ot} | {ft} | {ratio_s} | {dig} | {mem} |')
                csv.append(f'{f},{d},{op},{dg},{cs},{os1},{fs},{dig.split(" ")[0] if dig else ""},{mem.split(" ")[0] if mem else ""}')
open(os.path.join(out, 'results.csv'), 'w').write('\n'.join(csv) + '\n')
PY

if [[ -n ${BENCH_PIECES:-} ]]; then
  cmake --build "$BUILD" -j2 --target uniparam_probe >/dev/null
  echo
  echo '| pieces N | certified u after | time | memory (peak RSS) |'
  echo '|---|---|---|---|'
  for n in $BENCH_PIECES; do
    if res=$(timeout "$TIMEOUT" /usr/bin/time -f '%e %M' "$BUILD/bench/uniparam_probe" bez-plane 50 "pieces$n" 2>&1); then
      u=$(echo "$res" | head -1 | cut -d' ' -f1-3)
      read -r secs kb <<<"$(echo "$res" | tail -1)"
      echo "| $n | $u | $secs s | $((kb / 1024)) MB |"
    else
      echo "| $n | timeout (> $TIMEOUT s) | | |"
    fi
  done
fi

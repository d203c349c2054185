#!/usr/bin/env python3
"""The Markdown table of scripts/bench-pairs.sh's raw times.

    python3 scripts/bench-pairs-report.py RAW [RAW...]
    python3 scripts/bench-pairs-report.py --slower RAW [RAW...]   # the names of the rows judged slower

Each line of RAW: `cert/FAMILY/DEGREE/OP/15 | d1 d2 ... | o1 o2 ... | load`,
times in ms, d_j the default thread count and o_j one thread, run as the
j-th pair. A row that appears in several files keeps all its pairs.

For each row: the fastest run of each kind, the median m of the pairs'
ratios d_j / o_j, and an interval that holds the median of the ratios'
distribution with probability >= 90% whatever that distribution is (the
order statistics r_(k) and r_(n+1-k) of the n ratios, with the largest k
for which 1 - 2 P(Binomial(n, 1/2) <= k - 1) >= 0.9, the sign test's
interval; its coverage is printed with it: 96% for 9 pairs). Verdict:
"slower" when the whole interval lies above 1, "faster" when it lies below
1, "same" otherwise (no difference shown). Pairs, not
the fastest runs, carry the verdict: a machine whose speed drifts slows
both runs of a pair alike. Fewer than 5 pairs cannot give a 90% interval:
the verdict is then "too few pairs".
"""
import math
import statistics
import sys

OPS = {"uniformity": "uniformity", "radical": "radical", "pieces3": "reparam --pieces 3",
       "target99": "reparam --target 0.99"}


def ms(x):
    return f"{x:.3g} ms" if x < 1000 else f"{x / 1000:.3g} s"


def sign_interval(ratios, level=0.9):
    """(low, high, coverage) of the median, or None when no k reaches level."""
    n = len(ratios)
    r = sorted(ratios)
    best = None
    cdf = 0.0
    for k in range(1, n // 2 + 1):
        cdf += math.comb(n, k - 1) / 2 ** n  # P(Binomial(n, 1/2) <= k - 1)
        coverage = 1 - 2 * cdf
        if coverage < level:
            break
        best = (r[k - 1], r[n - k], coverage)
    return best


def verdict_of(ratios):
    """(interval text, verdict) of a row's pair ratios."""
    ci = sign_interval(ratios)
    if ci is None:
        return "", "too few pairs"
    lo, hi, coverage = ci
    return f"{lo:.3f}–{hi:.3f} ({100 * coverage:.0f}%)", "slower" if lo > 1 else "faster" if hi < 1 else "same"


def read(paths):
    rows = {}
    for path in paths:
        try:
            lines = open(path).read().splitlines()
        except OSError as e:
            sys.exit(f"bench-pairs-report: cannot read {path}: {e.strerror}")
        for number, line in enumerate(lines, 1):
            if not line.strip():
                continue
            try:
                name, d, o, _ = [f.strip() for f in line.split("|")]
                d = [float(x) for x in d.split()]
                o = [float(x) for x in o.split()]
                name.split("/")[4]
            except (ValueError, IndexError):
                sys.exit(f"bench-pairs-report: {path}:{number}: not a line of bench-pairs.sh "
                         "(cert/FAMILY/DEGREE/OP/DIGITS | times | times | load)")
            if len(d) != len(o):
                sys.exit(f"bench-pairs-report: {path}: {name}: {len(d)} default runs, {len(o)} one-thread runs")
            rd, ro = rows.setdefault(name, ([], []))
            rd.extend(d)
            ro.extend(o)
    return rows


def main(paths, slower_only):
    rows = read(paths)
    if slower_only:
        for name, (d, o) in rows.items():
            if verdict_of([a / b for a, b in zip(d, o)])[1] == "slower":
                print(name)
        return
    print("| curve | degree | operation | pairs | default threads (fastest) | one thread (fastest) "
          "| median ratio | interval (coverage) | verdict |")
    print("|---|---|---|---|---|---|---|---|---|")
    verdicts = {}
    for name, (d, o) in rows.items():
        _, fam, deg, op, _ = name.split("/")
        ratios = [a / b for a, b in zip(d, o)]
        interval, verdict = verdict_of(ratios)
        verdicts[verdict] = verdicts.get(verdict, 0) + 1
        print(f"| {fam} | {deg} | {OPS.get(op, op)} | {len(d)} | {ms(min(d))} | {ms(min(o))} "
              f"| {statistics.median(ratios):.3f} | {interval} | {verdict} |")
    print()
    print("Verdicts: " + ", ".join(f"{v} {n}" for v, n in sorted(verdicts.items())))


if __name__ == "__main__":
    args = sys.argv[1:]
    slower_only = bool(args) and args[0] == "--slower"
    if slower_only:
        args = args[1:]
    if not args:
        sys.exit("usage: bench-pairs-report.py [--slower] RAW [RAW...]")
    main(args, slower_only)

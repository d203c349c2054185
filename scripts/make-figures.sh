#!/usr/bin/env bash
# Regenerates the pictures of docs/plots.md (docs/img/*.svg) with the built
# uniparam binary. The SVGs are deterministic: rerunning on an unchanged tree
# changes nothing (git diff stays empty).
#
#   scripts/make-figures.sh            # uses build/cli/uniparam
#   scripts/make-figures.sh BUILD_DIR  # uses BUILD_DIR/cli/uniparam
#   UNIPARAM_BIN=/path/to/uniparam scripts/make-figures.sh
#
# Build first: cmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake --build build -j2
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
case "${1:-}" in
  -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
esac
build="${1:-$root/build}"
bin="${UNIPARAM_BIN:-$build/cli/uniparam}"
[ -x "$bin" ] || { echo "make-figures.sh: no uniparam binary at $bin (build first, see --help)" >&2; exit 1; }
out="$root/docs/img"
mkdir -p "$out"

# ImUp's slide curve (ASCM 2012 slides, "Plot with C0 / C1 piecewise reparameterization").
slide="((t^3-6t^2+9t-2)/(2t^4-16t^3+40t^2-32t+9), (t^2-4t+4)/(2t^4-16t^3+40t^2-32t+9))"

fig() {  # fig NAME ARGS... : one picture, reported
  local name="$1"
  shift
  "$bin" plot "$@" -o "$out/$name.svg"
  echo "make-figures.sh: wrote docs/img/$name.svg"
}

# Hong, Wang, Yang 2023, Example 16: the running example under the radical method.
fig example16-radical "(t, t^3)" --method radical --points 40
# The slides' C0 figure: N = 3 pieces, 40 points.
fig slide-c0-n3 "$slide" --method c0 --pieces 3 --points 40
# The slides' C1 figure: target 0.99, 40 points.
fig slide-c1-u099 "$slide" --method c1 --target 0.99 --points 40
# A space curve (a projection is drawn) and the parametric speed.
fig space-c0-n2 "((1-t^2)/(1+t^2), 2t/(1+t^2), t)" --method c0 --pieces 2 --points 30
fig example16-parametric "(t, t^3)" --method radical --speed parametric --points 40

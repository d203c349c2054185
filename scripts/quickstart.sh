#!/usr/bin/env bash
# The first command to run: installs the dependencies (Debian 12), builds
# uniparam (Release) and runs the main job on the built-in example:
#
#   build/cli/uniparam uniformity "(t, t^3)"
#
#   scripts/quickstart.sh                        # the example above
#   scripts/quickstart.sh uniformity "(t, t^2)"  # any other uniparam command
#
# Environment: UNIPARAM_BUILD_DIR (default: build), UNIPARAM_JOBS (default: nproc).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
build="${UNIPARAM_BUILD_DIR:-build}"
jobs="${UNIPARAM_JOBS:-$(nproc 2>/dev/null || echo 2)}"

bash scripts/install-deps.sh

echo "== configure ($build, Release)"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release
echo "== build uniparam (-j$jobs)"
cmake --build "$build" --target uniparam_cli --parallel "$jobs"

cli="$build/cli/uniparam"
if [ "$#" -eq 0 ]; then
  set -- uniformity "(t, t^3)"
fi
shown="$cli"
for a in "$@"; do
  if [[ "$a" =~ ^[A-Za-z0-9_./=:-]+$ ]]; then shown+=" $a"; else shown+=" \"$a\""; fi
done
echo "== $shown"
exec "$cli" "$@"

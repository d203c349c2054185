#!/usr/bin/env bash
# The test command: installs the dependencies (Debian 12), configures and
# builds everything (libraries, CLI, tests, benchmarks) in Release, then runs
# the whole CTest suite -- which includes installing uniparam into a scratch
# prefix and building and running examples/ against it, and the Python
# package's pytest suite (UNIPARAM_PYTHON, python/tests). Exits non-zero when
# anything fails.
#
#   scripts/test.sh               # everything
#   scripts/test.sh -R Radical    # extra arguments go to ctest (GoogleTest names)
#
# Environment: UNIPARAM_BUILD_DIR (default: build), UNIPARAM_JOBS (default:
# nproc), UNIPARAM_TEST_TIMEOUT (seconds per test without its own TIMEOUT;
# default 900).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
build="${UNIPARAM_BUILD_DIR:-build}"
jobs="${UNIPARAM_JOBS:-$(nproc 2>/dev/null || echo 2)}"
timeout="${UNIPARAM_TEST_TIMEOUT:-900}"

bash scripts/install-deps.sh

echo "== configure ($build, Release, tests + benchmarks + Python)"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release \
  -DUNIPARAM_BUILD_TESTS=ON -DUNIPARAM_BUILD_BENCH=ON -DUNIPARAM_OCCT_TESTS=ON -DUNIPARAM_PYTHON=ON
echo "== build (-j$jobs)"
cmake --build "$build" --parallel "$jobs"
echo "== test (-j$jobs)"
ctest --test-dir "$build" --output-on-failure --parallel "$jobs" \
  --timeout "$timeout" --no-tests=error "$@"

#!/usr/bin/env bash
# The whole CTest suite under AddressSanitizer + UndefinedBehaviorSanitizer.
#
#   scripts/sanitize.sh              # configure, build, run every test
#   scripts/sanitize.sh -R Hostile   # extra arguments go to ctest
#
# Builds in its own directory (UNIPARAM_SANITIZE_DIR, default build-sanitize)
# with -DUNIPARAM_SANITIZE=ON (RelWithDebInfo, benchmarks off), so it never
# disturbs the Release build. Any ASan report (overflow, use after free,
# leak) or UBSan report makes the test that hit it fail: UBSan does not
# recover (-fno-sanitize-recover) and ASan aborts. Exits non-zero when
# anything fails. UNIPARAM_JOBS (default 2) sets build and test parallelism.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
build="${UNIPARAM_SANITIZE_DIR:-build-sanitize}"
jobs="${UNIPARAM_JOBS:-2}"

# Leak checking at exit; UBSan prints a stack and exits non-zero; the
# detect_stack_use_after_return check is cheap enough here.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"

bash scripts/install-deps.sh
start=$(date +%s)
echo "== configure ($build, ASan + UBSan)"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DUNIPARAM_SANITIZE=ON -DUNIPARAM_BUILD_TESTS=ON -DUNIPARAM_BUILD_BENCH=OFF -DUNIPARAM_OCCT_TESTS=OFF \
  -DUNIPARAM_PYTHON=OFF >/dev/null
echo "== build (-j$jobs)"
cmake --build "$build" --parallel "$jobs"
echo "== test (-j$jobs)"
ctest --test-dir "$build" --output-on-failure --parallel "$jobs" --no-tests=error "$@"
echo "== sanitize.sh: all tests clean under ASan + UBSan ($(( $(date +%s) - start )) s)"

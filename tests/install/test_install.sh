#!/usr/bin/env bash
# test_install.sh CMAKE BUILD_DIR EXAMPLES_DIR WORK_DIR
#
# Installs the uniparam build in BUILD_DIR into WORK_DIR/stage, moves it to
# WORK_DIR/prefix (the package must be relocatable), then configures, builds
# and runs the consumer project EXAMPLES_DIR against it with
# find_package(uniparam) and checks that it prints "u = ...".
# Optional environment: UNIPARAM_TEST_GENERATOR, UNIPARAM_TEST_CXX,
# UNIPARAM_TEST_BUILD_TYPE (set by tests/install/CMakeLists.txt).
set -euo pipefail

if [ "$#" -ne 4 ]; then
  echo "usage: $0 CMAKE BUILD_DIR EXAMPLES_DIR WORK_DIR" >&2
  exit 2
fi
cmake="$1" build="$2" examples="$3" work="$4"

rm -rf "$work"
mkdir -p "$work"
stage="$work/stage" prefix="$work/prefix" ebuild="$work/build-examples"

echo "== install $build -> $stage"
"$cmake" --install "$build" --prefix "$stage"
mv "$stage" "$prefix"

config="$(find "$prefix" -name uniparamConfig.cmake -print -quit)"
[ -n "$config" ] || { echo "FAIL: no uniparamConfig.cmake installed under $prefix" >&2; exit 1; }
[ -f "$prefix/include/uniparam/uniparam.hpp" ] \
  || { echo "FAIL: public header uniparam/uniparam.hpp not installed" >&2; exit 1; }
# The public headers and nothing else: no engine header, no FLINT/Arb include.
headers="$(cd "$prefix/include" && find . -type f | sort | tr '\n' ' ')"
[ "$headers" = "./uniparam/error.hpp ./uniparam/uniparam.hpp " ] \
  || { echo "FAIL: installed headers are '$headers', not the public uniparam/uniparam.hpp and uniparam/error.hpp" >&2; exit 1; }
if grep -nE '#include *[<"](flint/|arb|acb|arf|mag|fmpz|fmpq)' "$prefix/include/uniparam/"*.hpp; then
  echo "FAIL: a public header includes a FLINT/Arb header" >&2; exit 1
fi

args=(-S "$examples" -B "$ebuild" -DCMAKE_PREFIX_PATH="$prefix"
      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
      -DCMAKE_BUILD_TYPE="${UNIPARAM_TEST_BUILD_TYPE:-Release}")
[ -z "${UNIPARAM_TEST_GENERATOR:-}" ] || args+=(-G "$UNIPARAM_TEST_GENERATOR")
[ -z "${UNIPARAM_TEST_CXX:-}" ] || args+=(-DCMAKE_CXX_COMPILER="$UNIPARAM_TEST_CXX")

echo "== configure examples against $prefix"
"$cmake" "${args[@]}"
found="$(sed -n 's/^uniparam_DIR:PATH=//p' "$ebuild/CMakeCache.txt")"
case "$found" in
  "$prefix"/*) ;;
  *) echo "FAIL: find_package(uniparam) found '$found', not the package in $prefix" >&2; exit 1 ;;
esac

echo "== build examples"
"$cmake" --build "$ebuild" --parallel 2

echo "== run examples/uniformity"
out="$("$ebuild/uniformity")" || { rc=$?; echo "$out"; echo "FAIL: uniformity exited $rc" >&2; exit 1; }
echo "$out"
grep -q '^u = ' <<<"$out" || { echo "FAIL: no 'u = ' line in the output" >&2; exit 1; }
echo "== run examples/toolbox"
out="$("$ebuild/toolbox")" || { rc=$?; echo "$out"; echo "FAIL: toolbox exited $rc" >&2; exit 1; }
echo "$out"
grep -q '^C1, rational: u = ' <<<"$out" || { echo "FAIL: no 'C1, rational' line in the output" >&2; exit 1; }
grep -q '^path: length ' <<<"$out" || { echo "FAIL: no 'path: length' line in the output" >&2; exit 1; }
echo "PASS: installed package found, examples built and ran"

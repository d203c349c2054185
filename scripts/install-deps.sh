#!/usr/bin/env bash
# Installs what a bare Debian 12 (bookworm) machine needs to build and test
# uniparam: the C++ toolchain, CMake, GMP, MPFR, FLINT 2.9, Arb 2.23,
# GoogleTest and Google Benchmark; rsvg-convert (librsvg2-bin), which
# 'uniparam plot -o FILE.png' runs to turn its SVG into PNG; and OpenCASCADE's
# STEP reader (libocct-data-exchange-dev), which only the tests use, to read
# back the STEP files uniparam writes (the library never depends on it); and,
# for the Python package (python/, docs/python.md) and its tests, Debian's
# python3 with pybind11, numpy, pytest, mpmath and Dask distributed, plus
# pip, setuptools, wheel and venv for installing it offline.
#
#   scripts/install-deps.sh        # quiet; prints nothing when all is present
#   scripts/install-deps.sh -v     # (or UNIPARAM_VERBOSE=1) show apt's output
#   scripts/install-deps.sh --fuzz # also clang + libFuzzer (scripts/fuzz.sh)
#
# Idempotent: when every package is already installed (checked with
# dpkg-query) it does not call apt at all. Runs apt as root, or through sudo
# when not root.
set -euo pipefail

PACKAGES=(
  g++ cmake make
  libgmp-dev libmpfr-dev
  libflint-dev libflint-arb-dev
  libgtest-dev googletest
  libbenchmark-dev
  librsvg2-bin
  libocct-data-exchange-dev
  python3-dev python3-pybind11 python3-numpy python3-pytest python3-mpmath python3-distributed
  python3-pip python3-setuptools python3-wheel python3-venv
)

verbose="${UNIPARAM_VERBOSE:-0}"
for arg in "$@"; do
  case "$arg" in
    -v|--verbose) verbose=1 ;;
    --fuzz) PACKAGES+=(clang libclang-rt-14-dev) ;;
    -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "install-deps.sh: unknown argument '$arg' (try --help)" >&2; exit 2 ;;
  esac
done

die() { echo "install-deps.sh: error: $*" >&2; exit 1; }
say() { if [ "$verbose" = 1 ]; then echo "install-deps.sh: $*"; fi; }

if ! command -v dpkg-query >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
  die "this script needs a Debian system with apt-get and dpkg-query (Debian 12 \"bookworm\").
On another system install by hand: a C++17 compiler, CMake >= 3.20, make, GMP, MPFR,
FLINT 2.9, Arb 2.23, GoogleTest and Google Benchmark (Debian names: ${PACKAGES[*]})."
fi

# Only Debian 12 has exactly FLINT 2.9 + a separate Arb 2.23 (libflint-arb-dev);
# elsewhere warn, and let apt say what it cannot find.
if [ -r /etc/os-release ]; then
  # shellcheck disable=SC1091
  read -r os_id os_ver < <(. /etc/os-release && echo "${ID:-unknown} ${VERSION_ID:-?}")
  if [ "$os_id" != debian ] || [ "$os_ver" != 12 ]; then
    echo "install-deps.sh: warning: made for Debian 12; this is $os_id $os_ver" >&2
  fi
fi

missing=()
for p in "${PACKAGES[@]}"; do
  status="$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)"
  if [ "$status" != installed ]; then
    missing+=("$p")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  say "all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

if [ "$(id -u)" -eq 0 ]; then
  as_root=(env)
elif command -v sudo >/dev/null 2>&1; then
  as_root=(sudo env)
else
  die "missing packages (${missing[*]}) and not root, and sudo is not available.
Run as root: apt-get update && apt-get install -y --no-install-recommends ${missing[*]}"
fi

echo "install-deps.sh: installing ${missing[*]}" >&2
apt_env=(DEBIAN_FRONTEND=noninteractive)
apt_opts=(-o DPkg::Lock::Timeout=300)
log="$(mktemp "${TMPDIR:-/tmp}/uniparam-install-deps.XXXXXX")"
trap 'rm -f "$log"' EXIT

run() {
  if [ "$verbose" = 1 ]; then
    "${as_root[@]}" "${apt_env[@]}" "$@"
  elif ! "${as_root[@]}" "${apt_env[@]}" "$@" >"$log" 2>&1; then
    cat "$log" >&2
    return 1
  fi
}

run apt-get "${apt_opts[@]}" update -q \
  || die "'apt-get update' failed (see above)"
run apt-get "${apt_opts[@]}" install -y -q --no-install-recommends "${missing[@]}" \
  || die "'apt-get install ${missing[*]}' failed (see above)"

# Confirm, so a silently half-done install is caught here and not in CMake.
for p in "${missing[@]}"; do
  status="$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)"
  [ "$status" = installed ] || die "package $p is still not installed after apt-get install"
done
say "installed ${missing[*]}"

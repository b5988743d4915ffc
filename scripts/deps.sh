#!/usr/bin/env bash
# Installs what skinslide needs to build and test, from Debian's packages.
# A no-op (no apt-get call) when everything is already installed.
# Usage: scripts/deps.sh             the build's and the tests' packages
#        scripts/deps.sh PACKAGE...  only these: the tools some tests and benchmarks drive
#                                    (blender; slurm-wlm munge), never needed to build
# Installs as root, or through sudo; exits non-zero, naming why, when it cannot (the callers
# that may skip say so with that reason).
set -euo pipefail

if [ $# -gt 0 ]; then
  packages=("$@")
else
  packages=(
    build-essential cmake pkg-config
    libopenmesh-dev libeigen3-dev libcli11-dev libtinygltf-dev libopenexr-dev openexr
    libstb-dev libgtest-dev libsuitesparse-dev
    python3-numpy python3-scipy
    pybind11-dev python3-dev python3-pytest
    strace  # tests/cli/scale.sh counts a run's stat calls
  )
  # The Khronos glTF validator (scripts/gltf_validate.sh) runs on node; the tests skip it, saying
  # so, only where npm cannot reach its registry.
  if ! command -v npm >/dev/null 2>&1; then packages+=(nodejs npm); fi
  # scripts/fuzz.sh only (not the main build): clang with libFuzzer and the sanitizer runtimes.
  if [ "${SKINSLIDE_FUZZ_DEPS:-0}" = 1 ]; then
    packages+=(clang libclang-rt-14-dev)
  fi
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "deps.sh: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  if ! command -v sudo >/dev/null 2>&1; then
    echo "deps.sh: cannot install ${missing[*]}: not root and no sudo" >&2
    exit 1
  fi
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
# One apt-get at a time: tests that install their tools may start together (ctest -j), and a
# second apt-get would fail on dpkg's lock rather than wait for it. The lock is this script's own
# file: no lock file left in /tmp (nor in a test run's TMPDIR).
exec 9<"${BASH_SOURCE[0]}"
flock 9
# The package lists first: a fresh image has none, and stale ones name versions long gone.
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2

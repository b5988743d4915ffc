#!/usr/bin/env bash
# Installs the dependencies (if missing), builds skinslide with warnings as errors, and runs the
# whole test suite (unit tests, end-to-end CLI tests, conformance with the reference). After
# scripts/demo.sh (same configuration, the command only) the build is incremental.
# Usage: scripts/test.sh [extra cmake -D options, e.g. -DSKINSLIDE_SANITIZE=address,undefined]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" -DSKINSLIDE_WERROR=ON -DSKINSLIDE_BUILD_TESTS=ON "$@"
cd "${SKINSLIDE_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j"$(nproc)"

#!/usr/bin/env bash
# Installs the dependencies (if missing), builds skinslide and slides the sample elbow in data/.
# The build tree is configured exactly as scripts/test.sh configures it (warnings as errors, tests
# on), but only the command is built: test.sh afterwards compiles the rest, nothing twice.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" --target skinslide -DSKINSLIDE_WERROR=ON -DSKINSLIDE_BUILD_TESTS=ON
cd "$root"
"${SKINSLIDE_BUILD_DIR:-$root/build}/skinslide" --patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/frames/*.obj -o slid/elbow
echo "slid frames: $root/slid/elbow/"

#!/usr/bin/env bash
# Installs the dependencies (if missing), builds skinslide and slides the sample elbow in data/.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/build.sh" -DSKINSLIDE_BUILD_TESTS=OFF
cd "$root"
build/skinslide --patch data/elbow/patch.txt data/elbow/bind.obj data/elbow/frames/*.obj -o slid/elbow
echo "slid frames: $root/slid/elbow/"

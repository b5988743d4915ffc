#!/usr/bin/env bash
# The Blender add-on (scripts/blender/skinslide_addon) baked headless in Debian's Blender 3.4 and
# played back equal to the command line (bake_test.py), or its live preview (live_test.py).
# Installs Blender when missing (as root); skips (exit 77), saying why, only where it cannot, and
# fails instead with SKINSLIDE_REQUIRE_SHARED=1 (CI).
# Usage: SKINSLIDE=path/to/skinslide SKINSLIDE_MODULE_DIR=build/python tests/blender/bake.sh [TEST]
#   TEST: bake_test.py (the default) or live_test.py
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
# shellcheck source=../cli/require.sh
. "$root/tests/cli/require.sh"
require_program SKINSLIDE
require_folder SKINSLIDE_MODULE_DIR
# shellcheck source=../cli/cannot.sh
. "$root/tests/cli/cannot.sh"
if ! command -v blender >/dev/null 2>&1; then
  if [ "$(id -u)" -ne 0 ]; then cannot "no blender, and not root to install it (apt-get install blender)"; fi
  echo "bake.sh: installing blender (Debian)" >&2
  # scripts/deps.sh: the one installer, one apt-get at a time (tests/cli/blender_cache.sh may be
  # installing Blender at the same moment).
  install_or_cannot blender
fi
script=${1:-bake_test.py}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
blender -b --factory-startup -noaudio --python-exit-code 1 --python "$here/$script" -- \
  "$root/scripts/blender" "$SKINSLIDE_MODULE_DIR" "$SKINSLIDE" "$work" >"$work/log" 2>&1
status=$?
grep -E "${script%.py}|Error|error|Traceback" "$work/log" | grep -v "^$" | head -40
if [ $status -ne 0 ]; then tail -n 30 "$work/log"; fi
# Blender's own count of memory left allocated at its exit: data the add-on left half-removed.
if [ $status -eq 0 ] && grep -q "Not freed memory blocks" "$work/log"; then
  echo "${script%.py}: Blender reports memory left allocated at its exit" >&2
  status=1
fi
exit $status

#!/usr/bin/env bash
# What the build and README's steps make inside the clone is ignored by git (.gitignore), so
# `git status` shows only what a person changed: the build folders, the Python module copied into
# the Blender add-on (README "In Python and Blender", step 1), the command's default outputs and
# Python's caches. Skips (exit 77) outside a git checkout.
# Usage: tests/cli/ignored.sh
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
# shellcheck source=cannot.sh
. "$root/tests/cli/cannot.sh"
command -v git >/dev/null 2>&1 || cannot "git is not installed"
git -C "$root" rev-parse --git-dir >/dev/null 2>&1 || cannot "$root is not a git checkout"
products=(
  build/skinslide
  build-sanitize/skinslide
  build/python/skinslide.cpython-311-x86_64-linux-gnu.so
  scripts/blender/skinslide_addon/skinslide.cpython-311-x86_64-linux-gnu.so
  slid/elbow.0001.obj
  out/elbow.0001.obj
  scripts/blender/skinslide_addon/__pycache__/point_cache.cpython-311.pyc
)
failed=0
for path in "${products[@]}"; do
  if git -C "$root" check-ignore -q --no-index "$path"; then
    echo "ignored: $path"
  else
    echo "FAIL: $path is not ignored by git (.gitignore)" >&2
    failed=1
  fi
done
# The add-on's own files stay tracked.
for path in scripts/blender/skinslide_addon/__init__.py scripts/blender/skinslide_addon/point_cache.py; do
  git -C "$root" check-ignore -q --no-index "$path" && { echo "FAIL: $path is ignored" >&2; failed=1; }
done
exit $failed

#!/usr/bin/env bash
# Installs the dependencies (if missing), builds skinslide with warnings as errors, and runs the
# whole test suite (unit tests, end-to-end CLI tests, conformance with the reference). After
# scripts/demo.sh (same configuration, the command only) the build is incremental.
# Some tests drive real clients and install them when missing, as root (scripts/deps.sh): Blender
# (cli_blender_cache, blender_addon, blender_live) and Slurm (cli_slurm). Before anything is
# installed this script says which are missing and which tests need them.
# Usage: scripts/test.sh [extra cmake -D options, e.g. -DSKINSLIDE_SANITIZE=address,undefined]
#        SKINSLIDE_NO_INSTALL=1 scripts/test.sh   install none of those clients: their tests skip,
#                                                 naming what is missing (the build's packages
#                                                 are still installed when missing)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

# The clients tests install, one a line: "packages|a command each provides|the tests and why".
clients=(
  "blender|blender|cli_blender_cache, blender_addon, blender_live (Blender 3.4 plays our caches, bakes the add-on, previews it live)"
  "slurm-wlm munge|sbatch munged|cli_slurm (a one-node Slurm cluster runs a farm shot)"
)

# announce: one notice, before the build, of the clients missing here and what becomes of them.
announce() {
  local line packages commands tests missing=() command count
  for line in "${clients[@]}"; do
    IFS='|' read -r packages commands tests <<<"$line"
    for command in $commands; do
      if ! command -v "$command" >/dev/null 2>&1; then
        # apt-get's own count from the package lists here (none without them).
        # shellcheck disable=SC2086
        count=$(apt-get install -s --no-install-recommends $packages 2>/dev/null | grep -c '^Inst ' || true)
        [ "${count:-0}" -gt 0 ] || count=""
        missing+=("  $packages${count:+ ($count packages with what they need)}: $tests")
        break
      fi
    done
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local what="installed by those tests when they run (scripts/deps.sh, as root)"
  if [ "${SKINSLIDE_NO_INSTALL:-0}" = 1 ]; then
    what="not installed (SKINSLIDE_NO_INSTALL=1): those tests skip, naming what is missing"
  fi
  {
    echo "test.sh: missing here, $what:"
    printf '%s\n' "${missing[@]}"
    [ "${SKINSLIDE_NO_INSTALL:-0}" = 1 ] ||
      echo "test.sh: SKINSLIDE_NO_INSTALL=1 scripts/test.sh runs without installing them."
  } >&2
}

announce
"$root/scripts/build.sh" -DSKINSLIDE_WERROR=ON -DSKINSLIDE_BUILD_TESTS=ON "$@"
cd "${SKINSLIDE_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j"$(nproc)"

#!/usr/bin/env bash
# Every test script refuses to start without what it needs (tests/cli/require.sh): run with
# SKINSLIDE unset, or naming no file, or (tests/blender/bake.sh) without SKINSLIDE_MODULE_DIR,
# each must exit 2 at once, naming what is missing, having created nothing (not even its scratch
# folder). Before require.sh, tests/cli/slurm.sh with SKINSLIDE unset started a Slurm cluster
# and submitted its jobs, failing 549 s later. The scripts run with stubs first on the PATH (id
# says "not root"; blender, apt-get, sudo, the Slurm daemons fail), so that one which does not
# refuse cannot install or start anything here either. Needs nothing itself.
# Usage: tests/cli/scripts_refuse.sh
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0

mkdir -p "$tmp/stubs" "$tmp/scratch"
for tool in blender apt-get sudo munged slurmctld slurmd sbatch squeue scancel scontrol sinfo; do
  printf '#!/bin/sh\necho "stub %s: not run by this test" >&2\nexit 1\n' "$tool" >"$tmp/stubs/$tool"
done
printf '#!/bin/sh\n[ "$1" = -u ] && echo 1000 || /usr/bin/id "$@"\n' >"$tmp/stubs/id"
chmod +x "$tmp/stubs"/*

# refuses WHAT PATTERN SCRIPT [VAR=VALUE...] [-- ARG...]: the script, in a clean environment but
# for the variables given, exits 2 within 60 s, its output holds PATTERN, and it made no scratch
# folder.
refuses() {
  local what=$1 pattern=$2 script=$3
  shift 3
  local vars=()
  while [ $# -gt 0 ] && [ "$1" != -- ]; do vars+=("$1") && shift; done
  [ $# -gt 0 ] && shift
  rm -rf "$tmp/scratch" && mkdir "$tmp/scratch"
  env -i PATH="$tmp/stubs:/usr/sbin:/usr/bin:/sbin:/bin" HOME="$HOME" TMPDIR="$tmp/scratch" \
    ${vars[@]+"${vars[@]}"} timeout 60 bash "$root/$script" "$@" >"$tmp/out" 2>&1
  local rc=$?
  if [ "$rc" -eq 2 ] && grep -qF -- "$pattern" "$tmp/out" && [ -z "$(ls -A "$tmp/scratch")" ]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $script $what: exit $rc (expected 2), output:" >&2
    sed 's/^/    /' "$tmp/out" >&2
    [ -z "$(ls -A "$tmp/scratch")" ] || echo "    and it left $(ls -A "$tmp/scratch") in TMPDIR" >&2
  fi
}

scripts=()
for f in "$root"/tests/cli/*.sh "$root"/tests/blender/*.sh "$root"/tests/bad_inputs/run.sh; do
  case $(basename "$f") in
    harness.sh | cannot.sh | require.sh) ;;                  # sourced by the others
    scripts_refuse.sh | demo_build.sh | install_notice.sh | ignored.sh) ;; # need nothing
    slurm_task.sh) ;;                                        # below
    *) scripts+=("${f#"$root"/}") ;;
  esac
done
for s in "${scripts[@]}"; do
  refuses "with SKINSLIDE unset" "SKINSLIDE is not set" "$s"
  refuses "with SKINSLIDE naming no file" "$tmp/none/skinslide" "$s" SKINSLIDE="$tmp/none/skinslide"
done
refuses "without SKINSLIDE_MODULE_DIR" "SKINSLIDE_MODULE_DIR is not set" tests/blender/bake.sh \
  SKINSLIDE=/bin/true
refuses "without its arguments" "OUT LAST_FRAME SHOT_DIR expected" tests/cli/slurm_task.sh \
  SKINSLIDE=/bin/true
refuses "outside sbatch" "SLURM_ARRAY_TASK_ID is not set" tests/cli/slurm_task.sh \
  SKINSLIDE=/bin/true -- "$tmp/out" 24 "$tmp"
echo "scripts_refuse: ${#scripts[@]} scripts; $passed passed, $failed failed"
[ "$failed" -eq 0 ]

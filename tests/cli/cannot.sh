# cannot REASON...: ends a test script that cannot run here, naming why: exit 77 (ctest: skipped),
# or 1 (failed) when SKINSLIDE_REQUIRE_SHARED=1 (CI, which has ../shared and root, must run
# every test). Sourced by harness.sh and by the scripts that install their tools (Blender,
# Slurm).
cannot() {
  if [ "${SKINSLIDE_REQUIRE_SHARED:-0}" = 1 ]; then
    echo "FAIL: $* (SKINSLIDE_REQUIRE_SHARED=1: $(basename "$0") must run)" >&2
    exit 1
  fi
  echo "SKIP: $*"
  exit 77
}

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

# install_or_cannot PACKAGE...: installs the Debian packages a test drives (Blender, Slurm) through
# scripts/deps.sh, the one installer; or ends the test with cannot, naming what is missing and
# why: SKINSLIDE_NO_INSTALL=1 (scripts/test.sh run without installing them), or the install failed
# (not root and no sudo, no network: deps.sh's last line).
install_or_cannot() {
  if [ "${SKINSLIDE_NO_INSTALL:-0}" = 1 ]; then
    cannot "$* not installed, and SKINSLIDE_NO_INSTALL=1 (scripts/deps.sh $* installs it)"
  fi
  local deps log
  deps="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)/scripts/deps.sh"
  log=$("$deps" "$@" 2>&1) || cannot "cannot install $*: $(tail -n 1 <<<"$log")"
}

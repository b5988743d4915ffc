# The shared frame of the end-to-end scripts, sourced by each: SKINSLIDE checked first (require.sh),
# paths, a scratch folder removed on exit, `check NAME COMMAND...` (counts a pass when COMMAND
# succeeds), `require_shared FILE...` (skips the script when ../shared lacks a file) and `finish NAME`.
here=$(cd "$(dirname "${BASH_SOURCE[1]}")" && pwd)
root=$(cd "$here/../.." && pwd)
# shellcheck source=require.sh
. "$root/tests/cli/require.sh"
require_program SKINSLIDE
require_tools /usr/bin/python3
bin=$SKINSLIDE
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passed=0
failed=0
# The real test data checked out beside the repository (a clone elsewhere has none).
shared=${SKINSLIDE_SHARED_DIR:-$(cd "$root/.." && pwd)/shared}

# shellcheck source=cannot.sh
. "$here/cannot.sh"

require_shared() {  # require_shared FILE...: ends the script when a file is missing, naming it
  local f
  for f in "$@"; do
    [ -e "$f" ] || cannot "missing $f"
  done
}

check() {  # check NAME COMMAND...
  local name=$1
  shift
  if "$@"; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL: $name" >&2
  fi
}

expect_exit() {  # expect_exit CODE OUTDIR ARGS...: runs skinslide -q -o OUTDIR ARGS, checks the exit code
  # and that stderr holds an error line
  local code=$1 out=$2
  shift 2
  "$bin" -q -o "$out" "$@" 2>"$tmp/stderr"
  local rc=$?
  if [ "$rc" -ne "$code" ]; then
    echo "exit $rc, expected $code: $(cat "$tmp/stderr")" >&2
    return 1
  fi
  grep -q "skinslide: error: " "$tmp/stderr"
}

finish() {  # finish NAME: the tally, and the script's exit status
  echo "$1: $passed passed, $failed failed"
  [ "$failed" -eq 0 ]
}

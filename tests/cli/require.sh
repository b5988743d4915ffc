# What a test script needs before it starts, checked at once (sourced first by every script of
# tests/cli, tests/blender and tests/bad_inputs): a missing one ends the script with exit 2,
# naming it, before anything is installed, started or submitted. Unlike cannot.sh's skip, a
# missing variable or tool is a mistake in how the script was called, never a reason to skip.
#   require_program VAR  $VAR is set and names an executable file (SKINSLIDE: the command)
#   require_folder VAR   $VAR is set and names a folder (SKINSLIDE_MODULE_DIR: build/python)
#   require_tools CMD... each command is on the PATH (scripts/deps.sh installs the build's)
refuse() {
  echo "$(basename "$0"): cannot start: $*" >&2
  exit 2
}

require_program() {
  local name=$1 value=${!1:-}
  [ -n "$value" ] || refuse "$name is not set (Usage: $name=path/to/skinslide $0)"
  [ -f "$value" ] && [ -x "$value" ] || refuse "$name=$value is not an executable file"
}

require_folder() {
  local name=$1 value=${!1:-}
  [ -n "$value" ] || refuse "$name is not set (see the Usage line of $0)"
  [ -d "$value" ] || refuse "$name=$value is not a folder"
}

require_tools() {
  local tool
  for tool in "$@"; do
    command -v "$tool" >/dev/null 2>&1 || refuse "$tool is not installed (scripts/deps.sh installs it)"
  done
}

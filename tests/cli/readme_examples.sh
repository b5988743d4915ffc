#!/usr/bin/env bash
# README's commands run as written, on the repository's own files, so that README cannot drift
# from them: every `skinslide ...` line of README's ```sh blocks (continuation lines joined;
# synopses with "..." and lines using shell variables, the Slurm task's, left out) runs with
# `skinslide` on the PATH and must exit 0. The commands of one block run one after the other in
# a fresh scratch folder of their own holding a link to data/ and what the examples assume
# beyond it (below). The conversion of an OBJ sequence into a cache (`--no-slide --format pc2`)
# joins README's Usage once the command can write one.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/readme_examples.sh
set -u
source "$(dirname "$0")/harness.sh"

# What the examples assume beyond data/: approved/, a previous accepted output of data/elbow (the
# CI step in README "Tests" compares a new run with it).
mkdir -p "$tmp/bin" "$tmp/assumed"
ln -s "$(readlink -f "$bin")" "$tmp/bin/skinslide"
(cd "$root" && "$bin" -q -o "$tmp/assumed/approved" --patch data/elbow/patch.txt \
  data/elbow/bind.obj data/elbow/frames/*.obj)

mapfile -d '' commands < <(/usr/bin/python3 - "$root/README.md" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
for n, block in enumerate(re.findall(r"^```sh\n(.*?)^```", text, re.S | re.M)):
    block = re.sub(r"\\\n\s*", "", block)  # continuation lines
    for line in block.splitlines():
        command = re.sub(r"\s+#.*$", "", line).strip()
        synopsis = "..." in command or "[options]" in command
        if command.startswith("skinslide ") and not synopsis and "$" not in command:
            sys.stdout.write("%d\t%s\0" % (n, command))
PY
)
check "README has its examples (at least 9 skinslide commands)" test "${#commands[@]}" -ge 9

runs() {  # runs FOLDER COMMAND: README's command in FOLDER; its stderr shown if it fails
  (cd "$1" && PATH="$tmp/bin:$PATH" bash -c "$2") </dev/null 2>"$tmp/said" ||
    { sed 's/^/    /' "$tmp/said" >&2; return 1; }
}
for entry in "${commands[@]}"; do
  block=${entry%%$'\t'*} command=${entry#*$'\t'}
  folder=$tmp/block$block
  if [ ! -d "$folder" ]; then
    cp -r "$tmp/assumed" "$folder"
    ln -s "$root/data" "$folder/data"
  fi
  echo "README (block $block): $command"
  check "README's command runs: $command" runs "$folder" "$command"
done
finish readme_examples

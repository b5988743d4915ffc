#!/usr/bin/env bash
# Runs the Khronos glTF validator (npm package gltf-validator) on glTF/GLB files; installs it
# first when it is missing. Prints one summary line per file; exit 0 when no file has an error,
# 1 when one has, 2 when the validator cannot be installed or run (no node, npm unreachable).
#   scripts/gltf_validate.sh FILE...
# The validator goes to $SKINSLIDE_TOOLS_DIR (default ~/.cache/skinslide), outside the source tree.
set -euo pipefail

tools="${SKINSLIDE_TOOLS_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/skinslide}"
version="2.0.0-dev.3.10"
if [ $# -eq 0 ]; then
  echo "usage: $0 FILE..." >&2
  exit 2
fi
if ! command -v node >/dev/null 2>&1; then
  echo "gltf_validate: node is not installed" >&2
  exit 2
fi
if [ ! -f "$tools/node_modules/gltf-validator/package.json" ]; then
  if ! command -v npm >/dev/null 2>&1; then
    echo "gltf_validate: npm is not installed" >&2
    exit 2
  fi
  mkdir -p "$tools"
  echo "gltf_validate: installing gltf-validator $version into $tools" >&2
  if ! npm install --silent --no-audit --no-fund --prefix "$tools" "gltf-validator@$version" >&2; then
    echo "gltf_validate: npm could not install gltf-validator (offline?)" >&2
    exit 2
  fi
fi

# External resources (.bin, images) are resolved beside each file.
NODE_PATH="$tools/node_modules" node - "$@" <<'JS'
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');
(async () => {
  let failed = false;
  for (const file of process.argv.slice(2)) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: path.basename(file),
      maxIssues: 0,
      externalResourceFunction: (uri) => new Promise((resolve, reject) => {
        fs.readFile(path.join(path.dirname(file), decodeURIComponent(uri)),
                    (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
      }),
    });
    const i = report.issues;
    console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos`);
    for (const m of i.messages)
      if (m.severity === 0) console.log(`  error ${m.code} at ${m.pointer || '-'}: ${m.message}`);
    if (i.numErrors > 0) failed = true;
  }
  process.exit(failed ? 1 : 0);
})().catch((e) => { console.error(`gltf_validate: ${e}`); process.exit(2); });
JS

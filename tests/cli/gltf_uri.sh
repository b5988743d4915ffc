#!/usr/bin/env bash
# Which files a glTF reads (lib/io/README.md "Which files a glTF reads"), end to end: a buffer URI
# leading out of the glTF's folder (climbing, through a symbolic link, absolute, file:,
# percent-encoded) stops the run with exit 3 and nothing written, whether the glTF is the BIND, a
# FRAME or an --animation character; a URI with `..` that stays inside is read;
# --allow-uri-outside (or its --config key) admits a sibling tree; images are never opened, only rebased.
# Writes its own glTFs (python3); needs nothing from ../shared.
# Usage: SKINSLIDE=path/to/skinslide tests/cli/gltf_uri.sh
set -u
source "$(dirname "$0")/harness.sh"
command -v python3 >/dev/null || cannot "python3 is needed to write the glTFs"

asset=$tmp/asset
mkdir -p "$asset/meshes" "$tmp/tree/chars" "$tmp/tree/shared" "$tmp/tree/other"
secret="not for the farm: $RANDOM$RANDOM"
printf '%s\n' "$secret" >"$tmp/secret.txt"
patch=$tmp/grid.txt
printf '0-17\n' >"$patch"

# make.py bin OUT: the buffer of a 4x4 grid bent along x (18 triangles, 4 inner vertices).
# make.py gltf OUT URI [--extra URI LENGTH] [--image URI]...: its glTF, buffer 0 at URI ("data":
# embedded), and an unused buffer 1 of LENGTH bytes at the --extra URI (the leak as reported).
cat >"$tmp/make.py" <<'PY'
import argparse, base64, json, struct
def grid():
    pos = [(x, y, 0.1 * x * x) for y in range(4) for x in range(4)]
    idx = []
    for y in range(3):
        for x in range(3):
            a = 4 * y + x
            idx += [a, a + 1, a + 5, a, a + 5, a + 4]
    return pos, struct.pack("<48f", *sum(pos, ())) + struct.pack("<54H", *idx) + b"\0\0"
ap = argparse.ArgumentParser()
ap.add_argument("what")
ap.add_argument("out")
ap.add_argument("uri", nargs="?")
ap.add_argument("--extra", nargs=2)
ap.add_argument("--image", action="append", default=[])
a = ap.parse_args()
pos, data = grid()
if a.what == "bin":
    open(a.out, "wb").write(data)
    raise SystemExit
uri = a.uri
if uri == "data":
    uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
buffers = [{"byteLength": len(data), "uri": uri}]
if a.extra:
    buffers.append({"byteLength": int(a.extra[1]), "uri": a.extra[0]})
doc = {"asset": {"version": "2.0"}, "buffers": buffers,
       "bufferViews": [{"buffer": 0, "byteLength": 192, "target": 34962},
                       {"buffer": 0, "byteOffset": 192, "byteLength": 108, "target": 34963}],
       "accessors": [{"bufferView": 0, "componentType": 5126, "count": 16, "type": "VEC3",
                      "min": [min(p[i] for p in pos) for i in range(3)],
                      "max": [max(p[i] for p in pos) for i in range(3)]},
                     {"bufferView": 1, "componentType": 5123, "count": 54, "type": "SCALAR"}],
       "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
       "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
if a.image:
    doc["images"] = [{"uri": u} for u in a.image]
json.dump(doc, open(a.out, "w"))
PY
make() { python3 "$tmp/make.py" "$@"; }

refused() {  # refused CODE OUTDIR TEXT ARGS...: exit CODE, stderr holds TEXT, no output folder
  local code=$1 out=$2 text=$3
  shift 3
  expect_exit "$code" "$out" "$@" || return 1
  grep -qF -- "$text" "$tmp/stderr" || { echo "stderr lacks '$text': $(cat "$tmp/stderr")" >&2; return 1; }
  [ ! -e "$out" ] || { echo "$out was made: $(ls -A "$out")" >&2; return 1; }
}
rule="a glTF's buffers are read only from data: URIs and from files inside its own folder"
size=$(stat -c %s "$tmp/secret.txt")

# The leak as first reported: an unused second buffer climbing to /etc/hostname; before, the run
# exited 0 and wrote out/bind_1.bin, a copy of it.
if [ -r /etc/hostname ]; then
  make gltf "$asset/bind.gltf" data --extra ../../../../../../../../etc/hostname "$(stat -c %s /etc/hostname)"
  (cd "$asset" && "$bin" --patch "$patch" -o out bind.gltf bind.gltf) >"$tmp/stdout" 2>"$tmp/stderr"
  check "the repro (/etc/hostname) exits 3" [ $? -eq 3 ]
  check "the repro writes nothing" [ ! -e "$asset/out" ]
  check "the repro names the file, the URI and the rule" \
    grep -qF "bind.gltf: buffer 1 uri \"../../../../../../../../etc/hostname\": resolves to /etc/hostname, outside the glTF's folder $(cd "$asset" && pwd -P); $rule" "$tmp/stderr"
fi
up=../../../../../../../../../../../../..
make gltf "$asset/climb.gltf" data --extra "$up$tmp/secret.txt" "$size"
check "a URI climbing out of the folder is refused (BIND)" \
  refused 3 "$tmp/o1" "climb.gltf: buffer 1 uri \"$up$tmp/secret.txt\": resolves to" --patch "$patch" "$asset/climb.gltf" "$asset/climb.gltf"
make gltf "$asset/clean.gltf" data
"$bin" -q -o "$tmp/o2" --patch "$patch" "$asset/clean.gltf" "$asset/climb.gltf" 2>"$tmp/stderr"
check "... as a FRAME: exit 3" [ $? -eq 3 ]
check "... as a FRAME: no file written" [ -z "$(find "$tmp/o2" -type f 2>/dev/null)" ]
check "... as an --animation character" \
  refused 3 "$tmp/o3" "climb.gltf: buffer 1 uri" --patch "$patch" --animation 0 "$asset/climb.gltf"
check "... with --weights-from-gltf-attribute" \
  refused 3 "$tmp/o4" "climb.gltf: buffer 1 uri" --weights-from-gltf-attribute _W --patch "$patch" "$asset/climb.gltf" "$asset/clean.gltf"
ln -s "$tmp" "$asset/up"
make gltf "$asset/link.gltf" data --extra up/secret.txt "$size"
check "a URI through a symbolic link leading out is refused" \
  refused 3 "$tmp/o5" "buffer 1 uri \"up/secret.txt\": resolves to $(cd "$tmp" && pwd -P)/secret.txt, outside" --patch "$patch" "$asset/link.gltf" "$asset/link.gltf"
make gltf "$asset/abs.gltf" data --extra "$tmp/secret.txt" "$size"
check "an absolute path is refused" \
  refused 3 "$tmp/o6" "buffer 1 uri \"$tmp/secret.txt\": an absolute path; $rule" --patch "$patch" "$asset/abs.gltf" "$asset/abs.gltf"
check "... also from the working folder" \
  bash -c "cd '$asset' && '$bin' -q -o '$tmp/o7' --patch '$patch' abs.gltf abs.gltf 2>/dev/null; [ \$? -eq 3 ] && [ ! -e '$tmp/o7' ]"
make gltf "$asset/file.gltf" data --extra "file://$tmp/secret.txt" "$size"
check "a file: URI is refused" \
  refused 3 "$tmp/o8" "buffer 1 uri \"file://$tmp/secret.txt\": the scheme file:" --patch "$patch" "$asset/file.gltf" "$asset/file.gltf"
make gltf "$asset/pct.gltf" data --extra "%2e%2e/secret.txt" "$size"
check "a percent-encoded ../ is refused" \
  refused 3 "$tmp/o9" "buffer 1 uri \"%2e%2e/secret.txt\": resolves to" --patch "$patch" "$asset/pct.gltf" "$asset/pct.gltf"

# Inside the folder, `..` is fine; a sibling tree needs --allow-uri-outside.
make bin "$asset/grid.bin"
make gltf "$asset/inside.gltf" meshes/../grid.bin
check "a URI with .. that stays inside is read" \
  "$bin" -q -o "$tmp/in" --patch "$patch" "$asset/inside.gltf" "$asset/inside.gltf"
check "... and its buffer written beside the output" cmp "$tmp/in/inside.bin" "$asset/grid.bin"
make bin "$tmp/tree/shared/grid.bin"
make gltf "$tmp/tree/chars/hero.gltf" ../shared/grid.bin
check "a sibling tree is refused by default" \
  refused 3 "$tmp/s1" "hero.gltf: buffer 0 uri \"../shared/grid.bin\": resolves to" --patch "$patch" "$tmp/tree/chars/hero.gltf" "$tmp/tree/chars/hero.gltf"
check "--allow-uri-outside admits it" \
  "$bin" -q -o "$tmp/s2" --allow-uri-outside "$tmp/tree/shared" --patch "$patch" "$tmp/tree/chars/hero.gltf" "$tmp/tree/chars/hero.gltf"
check "... and its buffer is written" cmp "$tmp/s2/hero.bin" "$tmp/tree/shared/grid.bin"
check "--allow-uri-outside another tree does not" \
  refused 3 "$tmp/s3" "resolves to" --allow-uri-outside "$tmp/tree/other" --patch "$patch" "$tmp/tree/chars/hero.gltf" "$tmp/tree/chars/hero.gltf"
check "--allow-uri-outside a missing folder is a usage error" \
  refused 2 "$tmp/s4" "--allow-uri-outside" --allow-uri-outside "$tmp/tree/none" --patch "$patch" "$tmp/tree/chars/hero.gltf" "$tmp/tree/chars/hero.gltf"
printf 'allow-uri-outside = ["%s", "%s"]\n' "$tmp/tree/other" "$tmp/tree/shared" >"$tmp/trees.toml"
check "--allow-uri-outside as a --config key (a list of folders) admits it too" \
  "$bin" -q -o "$tmp/s5" --config "$tmp/trees.toml" --patch "$patch" "$tmp/tree/chars/hero.gltf" "$tmp/tree/chars/hero.gltf"
check "... and its buffer is written" cmp "$tmp/s5/hero.bin" "$tmp/tree/shared/grid.bin"

# Images are rebased, never opened: one is a FIFO (opening it would block), one outside.
mkfifo "$asset/pipe.png"
make gltf "$asset/img.gltf" grid.bin --image pipe.png --image ../secret.txt
timeout 60 "$bin" -q -o "$tmp/img" --patch "$patch" "$asset/img.gltf" "$asset/img.gltf" 2>"$tmp/stderr"
check "images are not opened (a FIFO image does not block the run)" [ $? -eq 0 ]
check "... and keep reaching their files from the output" \
  python3 -c "import json,sys; d=json.load(open('$tmp/img/img.gltf')); sys.exit(d['images'] != [{'uri': '../asset/pipe.png'}, {'uri': '../secret.txt'}])"
check "no file the runs wrote holds the secret" \
  bash -c "[ -z \"\$(grep -rlF -D skip '$secret' '$tmp' | grep -vxF '$tmp/secret.txt')\" ]"

finish gltf_uri

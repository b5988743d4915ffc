#!/usr/bin/env bash
# The bad-input catalogue: each case runs skinslide on a small broken (or tricky but valid) input
# and checks the exit code (README "Exit codes"), a substring of the message (file, line, what is
# wrong), that a failed run leaves no output for what failed, and that nothing written holds a
# NaN or an infinity. Inputs are the files beside this script and variants of grid.obj made here.
# Usage: SKINSLIDE=path/to/skinslide tests/bad_inputs/run.sh
set -u
here=$(cd "$(dirname "$0")" && pwd)
# shellcheck source=../cli/require.sh
. "$here/../cli/require.sh"
require_program SKINSLIDE
require_tools /usr/bin/python3
bin=$SKINSLIDE
tmp=$(mktemp -d)
mkdir -p "$tmp/out"
trap 'chmod -R u+rwx "$tmp" 2>/dev/null; rm -rf "$tmp"' EXIT
passed=0
runner=()  # a command prefix for skinslide (set for the permission cases)
failed=0
skipped=0
cd "$here"

fail() {
  failed=$((failed + 1))
  echo "FAIL: $*" >&2
}

# expect NAME CODE SUBSTRING ARGS...: runs `skinslide -o OUT ARGS` with OUT a fresh folder (unless
# ARGS set -o), checks the exit code and that stderr contains SUBSTRING; on an error, that no
# frame was written (unless --keep-going); always, that every output is finite.
expect() {
  local name=$1 code=$2 text=$3
  shift 3
  local out=$tmp/out/$name
  if [ "$1" = -o ]; then
    out=$2
  elif [ "$1" = join ]; then  # `skinslide join [-o DIR] CHUNK...`
    shift
    set -- join -o "$out" "$@"
  elif [ "$1" = compare ]; then  # `skinslide compare A B`: its report is the output
    shift
    mkdir -p "$out"
    set -- compare --report "$out/report.json" "$@"
  else
    set -- -o "$out" "$@"
  fi
  "${runner[@]}" "$bin" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  local ok=1
  if [ "$rc" -ne "$code" ]; then
    fail "$name: exit $rc, expected $code"
    ok=0
  elif ! grep -qF -- "$text" "$tmp/stderr"; then
    fail "$name: stderr lacks '$text'"
    ok=0
  elif [ -s "$tmp/stdout" ]; then
    fail "$name: wrote to stdout"
    ok=0
  elif [ "$code" -ne 0 ] && [ -d "$out" ] && ! grep -q -- "--keep-going" <<<"$*" &&
    ! { [ "$1" = compare ] && [ "$code" -eq 1 ]; } && [ -n "$(find "$out" -type f)" ]; then
    fail "$name: a failed run left files: $(ls -A "$out")"
    ok=0
  elif [ -d "$out" ] && grep -rqiIE '(^|[ /])[-+]?(nan|inf)' "$out"; then
    fail "$name: an output holds a NaN or an infinity"
    ok=0
  fi
  if [ "$ok" -eq 1 ]; then
    passed=$((passed + 1))
  else
    sed 's/^/    /' "$tmp/stderr" >&2
  fi
}

# variant NAME SED-SCRIPT [SOURCE]: a copy of SOURCE (grid.obj) edited by sed, as $tmp/NAME.
variant() {
  sed -e "$2" "${3:-grid.obj}" >"$tmp/$1"
}

B=grid.obj
F=grid.0001.obj
P=all.txt
# grid.obj: line 1 a comment, lines 2-17 the 16 vertices (vertex k on line k+1), lines 18-26 the
# 9 quads (face k on line k+18); vertices 5, 6, 9 and 10 (0-based) are inside the patch.

# --- OBJ: empty, truncated, garbage -------------------------------------------------------------
: >"$tmp/empty.obj"
expect obj_empty 3 "empty.obj: the file is empty (0 bytes)" --patch $P "$tmp/empty.obj" $F
head -c 47 $F >"$tmp/cut_vertex.0001.obj"  # ends inside line 3, "v 1.2 0 0.1"
expect obj_cut_in_vertex 3 "cut_vertex.0001.obj:3: vertex has 2 coordinates; 3 needed (the last line has no end of line: is the file truncated?)" --patch $P $B "$tmp/cut_vertex.0001.obj"
head -n 10 $F >"$tmp/cut_lines.0001.obj"
expect obj_cut_at_line 3 "cut_lines.0001.obj: has 9 vertices; the bind (grid.obj) has 16" --patch $P $B "$tmp/cut_lines.0001.obj"
head -c 298 $F >"$tmp/cut_face.0001.obj"  # ends inside the last face line: "f 11 1"
expect obj_cut_in_face 3 "cut_face.0001.obj:26: face has 2 vertices; at least 3 needed (the last line has no end of line: is the file truncated?)" --patch $P $B "$tmp/cut_face.0001.obj"
printf '\x7fELF\x02\x01\x01\x00\x00\x00\x00\x00\x03\x00>\x00\x01\x00\x00\x00v 1 2 3\n' >"$tmp/garbage.obj"
expect obj_binary_garbage 3 "garbage.obj:1: binary data (NUL byte): not a text OBJ file" --patch $P "$tmp/garbage.obj" $F
printf '\x89PNG\r\n\x1a\n\xff\xfe\xfd junk\n' >"$tmp/png.obj"
expect obj_not_obj_text 3 "png.obj: no vertices (\`v\` lines): not an OBJ mesh" --patch $P "$tmp/png.obj" $F

# --- OBJ: coordinates --------------------------------------------------------------------------
variant nonnumeric.obj '7s/.*/v 1 one 0/'
expect obj_nonnumeric_coordinate 3 "nonnumeric.obj:7: vertex coordinate 'one' is not a number" --patch $P "$tmp/nonnumeric.obj" $F
variant comma.obj '7s/.*/v 1,0 1,0 0/'
expect obj_decimal_comma 3 "comma.obj:7: vertex coordinate '1,0' is not a number" --patch $P "$tmp/comma.obj" $F
variant missing.obj '7s/.*/v 1 1/'
expect obj_missing_coordinate 3 "missing.obj:7: vertex has 2 coordinates; 3 needed" --patch $P "$tmp/missing.obj" $F
variant nan.0001.obj '7s/.*/v nan 1 0/' $F
expect obj_nan 3 "nan.0001.obj:7: vertex coordinate 'nan' is not finite" --patch $P $B "$tmp/nan.0001.obj"
variant inf.0001.obj '7s/.*/v 1 -inf 0/' $F
expect obj_inf 3 "inf.0001.obj:7: vertex coordinate '-inf' is not finite" --patch $P $B "$tmp/inf.0001.obj"
variant huge.0001.obj '7s/.*/v 1e999 1 0/' $F
expect obj_overflowing_number 3 "huge.0001.obj:7: vertex coordinate '1e999' is not finite (beyond the largest double, 1.8e308)" --patch $P $B "$tmp/huge.0001.obj"
# A number nearer 0 than the smallest double (1e-400) is one: read as 0, as strtod reads it.
variant tiny.obj '7s/.*/v 1 1 1e-400/'
expect obj_underflowing_number_valid 0 "1 frame slid" --patch $P "$tmp/tiny.obj" $F
"$bin" -q -o "$tmp/out/untiny" --patch $P $B $F
cmp -s "$tmp/out/obj_underflowing_number_valid/$F" "$tmp/out/untiny/$F" ||
  fail "obj_underflowing_number_valid: not the slide of the bind with a 0 there"
# After x y z: a w or a colour r g b [a] (numbers, at most 4), kept byte for byte in the frame
# written; a word there is refused.
variant word_tail.obj '7s/.*/v 1 1 0 abc/'
expect obj_vertex_word_after_coordinates 3 "word_tail.obj:7: vertex entry 'abc' after x y z is not a number" --patch $P "$tmp/word_tail.obj" $F
variant five.obj '7s/.*/v 1 1 0 1 1 1 1 1/'
expect obj_vertex_too_many_numbers 3 "five.obj:7: vertex has 8 numbers; at most 7" --patch $P "$tmp/five.obj" $F
variant colour.0001.obj '7s/$/ 0.5 0.25 0.125 1/' $F
expect obj_vertex_colour_valid 0 "1 frame slid" --patch $P $B "$tmp/colour.0001.obj"
sed -n 7p "$tmp/out/obj_vertex_colour_valid/colour.0001.obj" | grep -q ' 0.5 0.25 0.125 1$' ||
  fail "obj_vertex_colour_valid: the slid vertex lost its colour"
# Slide weights from a colour channel: r g b, or r g b a with the alpha ignored (the weights, so
# the slide, of the same colours without it); a vertex with a w only has no colour.
awk '/^v /{print $0, "0.5 0.25 1"; next} {print}' $B >"$tmp/rgb.obj"
awk '/^v /{print $0, "0.5 0.25 1 0.75"; next} {print}' $B >"$tmp/rgba.obj"
expect obj_colour_weights_rgb_valid 0 "1 frame slid" --weights-from-obj-color g --patch $P "$tmp/rgb.obj" $F
expect obj_colour_weights_alpha_ignored_valid 0 "1 frame slid" --weights-from-obj-color g --patch $P "$tmp/rgba.obj" $F
cmp -s "$tmp/out/obj_colour_weights_rgb_valid/$F" "$tmp/out/obj_colour_weights_alpha_ignored_valid/$F" ||
  fail "obj_colour_weights_alpha_ignored_valid: not the slide of the same colours without alpha"
awk '/^v /{print $0, "1"; next} {print}' $B >"$tmp/w_only.obj"
expect obj_colour_weights_w_only 3 "w_only.obj:2: vertex 0 has no colour: expected 'v x y z r g b' or 'v x y z r g b a' for slide weights from vertex colours" --weights-from-obj-color r --patch $P "$tmp/w_only.obj" $F

# A statement meant as a vertex but misspelt would be skipped and shift every later index.
variant upper.obj '7s/^v /V /'
expect obj_upper_case_keyword 3 "upper.obj:7: unknown statement 'V': OBJ keywords are lower case" --patch $P "$tmp/upper.obj" $F
variant nospace.obj '7s/^v /v/'
expect obj_keyword_without_space 3 "nospace.obj:7: unknown statement 'v" --patch $P "$tmp/nospace.obj" $F
# A UTF-8 byte-order mark (Windows tools) is not the first statement: the same slide as without,
# and the rewritten frame keeps its mark.
printf '\xEF\xBB\xBF' | cat - $B >"$tmp/bom.obj"
printf '\xEF\xBB\xBF' | cat - $F >"$tmp/bom.0001.obj"
printf '\xEF\xBB\xBF' | cat - $P >"$tmp/bom.txt"
expect obj_byte_order_mark 0 "1 frame slid" --patch "$tmp/bom.txt" "$tmp/bom.obj" "$tmp/bom.0001.obj"
expect obj_no_byte_order_mark 0 "1 frame slid" -o "$tmp/out/nobom" --patch $P $B "$tmp/bom.0001.obj"
if ! cmp -s <(tail -c +4 "$tmp/out/obj_byte_order_mark/bom.0001.obj") <(tail -c +4 "$tmp/out/nobom/bom.0001.obj") ||
  [ "$(head -c 3 "$tmp/out/obj_byte_order_mark/bom.0001.obj" | od -An -tx1 | tr -d ' ')" != efbbbf ]; then
  fail "obj_byte_order_mark: not the slide without the mark, or the mark lost"
fi

# --- OBJ: faces --------------------------------------------------------------------------------
variant zero.obj '18s/.*/f 0 2 6 5/'
expect obj_face_index_0 3 "zero.obj:18: face index 0 (OBJ indices start at 1)" --patch $P "$tmp/zero.obj" $F
variant far.obj '26s/.*/f 11 12 17 15/'
expect obj_face_index_out_of_range 3 "far.obj:26: face index 17 is out of range (the file has 16 vertices)" --patch $P "$tmp/far.obj" $F
variant before.obj '18s/.*/f -1 -2 -17/'
expect obj_relative_before_first 3 "before.obj:18: relative face index -17 reaches before vertex 1" --patch $P "$tmp/before.obj" $F
variant two.obj '20s/.*/f 3 4/'
expect obj_face_two_vertices 3 "two.obj:20: face has 2 vertices; at least 3 needed" --patch $P "$tmp/two.obj" $F
variant one.obj '20s/.*/f 3/'
expect obj_face_one_vertex 3 "one.obj:20: face has 1 vertex; at least 3 needed" --patch $P "$tmp/one.obj" $F
variant repeat.obj '20s/.*/f 3 4 8 4/'
expect obj_face_repeats_vertex 3 "repeat.obj:20: face uses vertex 4 twice (degenerate face)" --patch $P "$tmp/repeat.obj" $F
variant word.obj '20s/.*/f 3 4 eight 7/'
expect obj_face_entry_not_index 3 "word.obj:20: face entry 'eight' is not a vertex index" --patch $P "$tmp/word.obj" $F
variant vast_index.obj '20s/.*/f 3 4 99999999999999999999 7/'
expect obj_face_index_beyond_an_integer 3 "vast_index.obj:20: face index '99999999999999999999' is too large" --patch $P "$tmp/vast_index.obj" $F
variant vast_relative.obj '20s/.*/f 3 4 -99999999999999999999 7/'
expect obj_relative_index_beyond_an_integer 3 "vast_relative.obj:20: relative face index '-99999999999999999999' reaches before vertex 1" --patch $P "$tmp/vast_relative.obj" $F
variant corner.obj '20s|.*|f 3 4/1/1/1 8 7|'
expect obj_face_corner_four_parts 3 "corner.obj:20: face corner '4/1/1/1' has more than 3 parts" --patch $P "$tmp/corner.obj" $F
# A corner's texture and normal parts are not read, but each is empty or a whole number.
variant corner_vt.obj '20s|.*|f 3/x/1 4/y/2 8/z/3 7/w/4|'
expect obj_face_corner_texture_not_a_number 3 "corner_vt.obj:20: face corner '3/x/1': texture index 'x' is not a whole number (a corner is v, v/vt, v//vn or v/vt/vn, each a whole number)" --patch $P "$tmp/corner_vt.obj" $F
variant corner_vn.0001.obj '20s|.*|f 3//1 4//1 8//1.5 7//1|' $F
expect obj_face_corner_normal_not_a_number 3 "corner_vn.0001.obj:20: face corner '8//1.5': normal index '1.5' is not a whole number" --patch $P $B "$tmp/corner_vn.0001.obj"
variant corner_vt0.obj '20s|.*|f 3/1 4/0 8/1 7/1|'
expect obj_face_corner_texture_index_0 3 "corner_vt0.obj:20: face corner '4/0': texture index 0 (OBJ indices start at 1)" --patch $P "$tmp/corner_vt0.obj" $F
# Valid: an empty part (1//3), relative parts, vt and vn that no line defines (they are not read).
variant corner_parts.obj '20s|.*|f 3//1 4/-1/-1 8/2/ 7/+3/3|'
expect obj_face_corner_parts_valid 0 "1 patch, 4 sliding vertices" --patch $P "$tmp/corner_parts.obj" $F
variant cont.obj '20s/.*/f 3 4 \\/'
expect obj_line_continuation 3 "cont.obj:20: line continuation" --patch $P "$tmp/cont.obj" $F
# Valid: relative indices, v lines after the faces, slashes and extra statements.
awk 'BEGIN{n=0} /^v /{n++} /^f /{printf "f"; for(i=2;i<=NF;i++) printf " %d/%d", $i-n-1, 1; print ""; next} {print}' $B >"$tmp/relative.obj"
expect obj_relative_indices_valid 0 "1 patch, 4 sliding vertices" --patch $P "$tmp/relative.obj" $F
{ grep '^f ' $B; grep -v '^f ' $B; } >"$tmp/faces_first.obj"
expect obj_v_after_f_valid 0 "1 patch, 4 sliding vertices" --patch $P "$tmp/faces_first.obj" $F

# --- patch files -------------------------------------------------------------------------------
printf '0-4\nselect -r pBody\n' >"$tmp/token.txt"
expect patch_unknown_token 3 "token.txt:2: unknown token 'select': expected a face id (12), a range (12-40)" --patch "$tmp/token.txt" $B $F
printf '# all\n0-9\n' >"$tmp/range.txt"
expect patch_index_out_of_range 3 "range.txt:2: face 9 is out of range (the bind has 9 faces, numbered 0 to 8)" --patch "$tmp/range.txt" $B $F
printf '# nothing selected yet\n\n' >"$tmp/none.txt"
expect patch_empty_selection 3 "none.txt: selects no faces" --patch "$tmp/none.txt" $B $F
: >"$tmp/zero.txt"
expect patch_empty_file 3 "zero.txt: selects no faces" --patch "$tmp/zero.txt" $B $F
printf 'pBody.f[0:3]\npHead.f[4:8]\n' >"$tmp/maya.txt"
expect patch_maya_two_objects 3 "maya.txt:2: names object 'pHead' but line 1 names 'pBody'" --patch "$tmp/maya.txt" $B $F
printf '8-0\n' >"$tmp/back.txt"
expect patch_backward_range 3 "back.txt:1: range '8-0' runs backwards" --patch "$tmp/back.txt" $B $F
printf '0-8\n\x00\x01\x02' >"$tmp/bin.txt"
expect patch_binary 3 "bin.txt:2: binary data (NUL byte)" --patch "$tmp/bin.txt" $B $F
printf 'pBody.f[0:8]\n' >"$tmp/maya_ok.txt"
expect patch_maya_one_object_valid 0 "1 patch, 4 sliding vertices" --patch "$tmp/maya_ok.txt" $B $F

# --- patch topology ----------------------------------------------------------------------------
printf '0-5\n' >"$tmp/cube.txt"
expect topo_closed_patch 3 "has no boundary: it is a closed surface; leave at least one face out" --patch "$tmp/cube.txt" cube.obj cube.obj
printf '0-2\n' >"$tmp/fin.txt"
expect topo_edge_three_faces 3 "edge (0, 1) is shared by 3 selected faces" --patch "$tmp/fin.txt" fin.obj fin.obj
expect topo_bowtie_vertex 3 "vertex 9 is non-manifold" --patch bowtie.txt $B $F
printf '0-5\n' >"$tmp/moebius.txt"
expect topo_moebius 3 "not consistently oriented (a flipped face, or a non-orientable patch such as a Moebius strip)" --patch "$tmp/moebius.txt" moebius.obj moebius.obj
variant flipped.obj '22s/.*/f 10 11 7 6/'
expect topo_flipped_face 3 "traverse edge" --patch $P "$tmp/flipped.obj" $F
printf '0-4\n' >"$tmp/left.txt"
printf '4-8\n' >"$tmp/right.txt"
expect topo_face_in_two_patches 3 "face 4 (grid.obj:22) is selected by --patch $tmp/left.txt and by --patch $tmp/right.txt; a face belongs to one patch" --patch "$tmp/left.txt" --patch "$tmp/right.txt" $B $F

# --- frames that are not the bind deformed ------------------------------------------------------
variant more.0001.obj '17a v 9 9 9' $F
expect frame_vertex_count 3 "more.0001.obj: has 17 vertices; the bind (grid.obj) has 16" --patch $P $B "$tmp/more.0001.obj"
variant fewer.0001.obj '17d' $F  # the last vertex gone: the faces that use it now point past the end
expect frame_vertex_missing 3 "fewer.0001.obj:25: face index 16 is out of range (the file has 15 vertices)" --patch $P $B "$tmp/fewer.0001.obj"
variant faces.0001.obj '22s/.*/f 6 7 11 9/' $F
expect frame_face_differs 3 "faces.0001.obj:22: face 4 differs from the bind's (grid.obj:22)" --patch $P $B "$tmp/faces.0001.obj"
variant extra.0001.obj '$a f 1 2 3' $F
expect frame_face_count 3 "has 10 faces; the bind (grid.obj) has 9" --patch $P $B "$tmp/extra.0001.obj"

# --- degenerate geometry: handled (exit 0, finite) or refused with a message --------------------
variant zero_edge.obj '7s/.*/v 2 1 0/'  # vertex 5 on vertex 6: zero-length edge, zero-area fans
expect degenerate_bind_zero_length_edge 0 "sliding vertices" --patch $P "$tmp/zero_edge.obj" $F
variant sliver.obj '7s/.*/v 0.5 0 0/'  # vertex 5 on the border edge 0-1: zero-area triangle
expect degenerate_bind_zero_area 0 "sliding vertices" --patch $P "$tmp/sliver.obj" $F
# Degenerate frames, with each method: the paper's log line counts its locator's fallbacks, the
# elastic one its relaxation.
variant collapsed_edge.0001.obj '7s/.*/v 2.2 1 0.4/' $F
expect degenerate_frame_zero_length_edge 0 "1 patch, elastic" --patch $P $B "$tmp/collapsed_edge.0001.obj"
expect degenerate_frame_zero_length_edge_paper 0 "fallbacks" --method paper --patch $P $B "$tmp/collapsed_edge.0001.obj"
variant folded.0001.obj '7s/.*/v 2.8 1.5 -0.5/' $F  # vertex 5 pulled across its neighbours
expect degenerate_frame_folded 0 "1 patch, elastic" --patch $P $B "$tmp/folded.0001.obj"
expect degenerate_frame_folded_paper 0 "fallbacks" --method paper --patch $P $B "$tmp/folded.0001.obj"
# The paper's nets fold where the frame's bars cross: its log and report count the slid triangles
# turned against the frame's (they said only "net flips 0"); the elastic search turns none (its
# holds: lib/elastic/README.md), the map counts the one it turns (its shares bound each pass's
# strain, not a fold: rule M4).
expect noisy_frame_paper_flips_told 0 "0 fallbacks, flips 2 ->" --method paper --patch noisy.txt noisy_bind.obj noisy.0001.obj
expect noisy_frame_search_turns_none 0 "flips 0," --solver search --patch noisy.txt noisy_bind.obj noisy.0001.obj
expect noisy_frame_map_flips_told 0 "flips 1," --patch noisy.txt noisy_bind.obj noisy.0001.obj
awk '/^v /{print "v 1 1 1"; next} {print}' $B >"$tmp/point.0001.obj"
# Every vertex on one point: the paper's bar net has no length to work with (refused); to the
# elastic method it is the bind scaled to nothing, at rest: written unchanged.
expect degenerate_frame_all_collapsed 0 "1 frame slid" --patch $P $B "$tmp/point.0001.obj"
cmp -s "$tmp/point.0001.obj" "$tmp/out/degenerate_frame_all_collapsed/point.0001.obj" ||
  fail "degenerate_frame_all_collapsed: the frame was not written unchanged"
expect degenerate_frame_all_collapsed_paper 3 "point.0001.obj: patch 0: every bar of the patch has zero (or non-finite) length" --method paper --patch $P $B "$tmp/point.0001.obj"
awk '/^v /{print "v", $2, 0, 0; next} {print}' $B >"$tmp/flat.obj"
expect degenerate_bind_all_collapsed_to_a_line 0 "1 frame slid" --patch $P "$tmp/flat.obj" $F
expect degenerate_bind_all_collapsed_to_a_line_paper 0 "1 frame slid" --method paper --patch $P "$tmp/flat.obj" $F
# Coordinates near 1e300: lengths overflow a double (they read as "zero length" once); refused,
# naming the vertex, in the bind and in a frame.
awk '/^v /{print "v", $2 "e300", $3 "e300", $4 "e300"; next} {print}' $B >"$tmp/vast.obj"
expect degenerate_bind_overflowing_coordinates 3 "patch 0 (face 0 ($tmp/vast.obj:18), 9 faces): vertex 3 at (3e+300, 0, 0): coordinates too large" --patch $P "$tmp/vast.obj" $F
awk '/^v /{print "v", $2 "e300", $3 "e300", $4 "e300"; next} {print}' $F >"$tmp/vast.0001.obj"
expect degenerate_frame_overflowing_coordinates_paper 3 "vast.0001.obj: patch 0: vertex 3 at (3e+300, 0, 9e+299): coordinates too large" --method paper --patch $P $B "$tmp/vast.0001.obj"
# Coordinates near 1e-300: lengths' squares underflow (they read as "zero length" once), and under
# 1e-38 float32 (the at-rest comparison, caches) loses precision; a span under 1e-30 is refused,
# naming the vertex, in the bind and in a frame. Millimetres in kilometres (1e-6) slide as ever.
awk '/^v /{print "v", $2 "e-300", $3 "e-300", $4 "e-300"; next} {print}' $B >"$tmp/speck.obj"
awk '/^v /{print "v", $2 "e-300", $3 "e-300", $4 "e-300"; next} {print}' $F >"$tmp/speck.0001.obj"
expect degenerate_bind_underflowing_coordinates 3 "patch 0 (face 0 ($tmp/speck.obj:18), 9 faces): vertex 3 at (3e-300, 0, 0): coordinates too small: the patch spans 4.243e-300, under the smallest span of 1e-30" --patch $P "$tmp/speck.obj" "$tmp/speck.0001.obj"
expect degenerate_frame_underflowing_coordinates_paper 3 "speck.0001.obj: patch 0: vertex 3 at (3e-300, 0, 9e-301): coordinates too small" --method paper --patch $P $B "$tmp/speck.0001.obj"
awk '/^v /{print "v", $2 "e-6", $3 "e-6", $4 "e-6"; next} {print}' $B >"$tmp/milli.obj"
awk '/^v /{print "v", $2 "e-6", $3 "e-6", $4 "e-6"; next} {print}' $F >"$tmp/milli.0001.obj"
expect small_scale_valid 0 "1 frame slid" --patch $P "$tmp/milli.obj" "$tmp/milli.0001.obj"
expect small_scale_valid_paper 0 "1 frame slid" --method paper --patch $P "$tmp/milli.obj" "$tmp/milli.0001.obj"
expect degenerate_bind_zero_length_edge_paper 0 "sliding vertices" --method paper --patch $P "$tmp/zero_edge.obj" $F
expect degenerate_bind_zero_area_paper 0 "sliding vertices" --method paper --patch $P "$tmp/sliver.obj" $F

# --- glTF (read through --animation, which reads the mesh before looking for a skin) ----------
# quad.gltf: one indexed quad, positions and indices in a data: URI buffer; valid but not skinned.
G=quad.gltf
expect gltf_valid_but_not_skinned 3 "quad.gltf: mesh 0: is not skinned: no node gives it a skin" --patch $P --animation 0 $G
gltf_variant() {
  sed -e "$2" $G >"$tmp/$1"
}
gltf_variant nobuffer.gltf 's|"uri":"data:[^"]*"|"uri":"quad.bin"|'
expect gltf_missing_buffer 3 "nobuffer.gltf: not a readable glTF 2.0 file: File not found : quad.bin" --patch $P --animation 0 "$tmp/nobuffer.gltf"
gltf_variant badbuffer.gltf 's|"byteLength":60|"byteLength":600|'
expect gltf_buffer_shorter_than_declared 3 "badbuffer.gltf: not a readable glTF 2.0 file: Failed to decode 'uri'" --patch $P --animation 0 "$tmp/badbuffer.gltf"
gltf_variant noaccessor.gltf 's|"POSITION":0|"POSITION":7|'
expect gltf_missing_accessor 3 "noaccessor.gltf: mesh 0 primitive 0: POSITION accessor 7: does not exist" --patch $P --animation 0 "$tmp/noaccessor.gltf"
gltf_variant overrun.gltf 's|"count":4,"type":"VEC3"|"count":40,"type":"VEC3"|'
expect gltf_accessor_past_its_view 3 "overrun.gltf: mesh 0 primitive 0: POSITION accessor 0: 40 elements from byte 0 run past the end of buffer view 0 (48 bytes)" --patch $P --animation 0 "$tmp/overrun.gltf"
gltf_variant noview.gltf 's|"buffer":0,"byteOffset":48|"buffer":3,"byteOffset":48|'
expect gltf_view_of_missing_buffer 3 "noview.gltf: mesh 0 primitive 0: indices accessor 1: its buffer view 1: buffer 3 does not exist" --patch $P --animation 0 "$tmp/noview.gltf"
gltf_variant vec2.gltf 's|"count":4,"type":"VEC3"|"count":4,"type":"VEC2"|'
expect gltf_position_wrong_type 3 "vec2.gltf: mesh 0 primitive 0: POSITION accessor 0: is VEC2, expected VEC3" --patch $P --animation 0 "$tmp/vec2.gltf"
gltf_variant u32pos.gltf 's|"bufferView":0,"componentType":5126|"bufferView":0,"componentType":5125|'
expect gltf_position_wrong_component_type 3 "u32pos.gltf: mesh 0 primitive 0: POSITION accessor 0: has component type 5125; positions are float (5126)" --patch $P --animation 0 "$tmp/u32pos.gltf"
gltf_variant floatidx.gltf 's|"componentType":5123,"count":6|"componentType":5126,"count":6|'
expect gltf_float_indices 3 "floatidx.gltf: mesh 0 primitive 0: indices accessor 1: must be SCALAR unsigned byte/short/int" --patch $P --animation 0 "$tmp/floatidx.gltf"
gltf_variant count.gltf 's|"count":4,"type":"VEC3"|"count":4294967295,"type":"VEC3"|'
expect gltf_accessor_count_huge 3 "count.gltf: mesh 0 primitive 0: POSITION accessor 0: 4294967295 elements from byte 0 run past the end of buffer view 0 (48 bytes)" --patch $P --animation 0 "$tmp/count.gltf"
# Integer properties (offsets, counts, indices) that are not whole numbers: tinygltf reads them as
# absent (a byteOffset as 0); refused, naming the element.
gltf_variant negoffset.gltf 's|"buffer":0,"byteOffset":48|"buffer":0,"byteOffset":-12|'
expect gltf_negative_byte_offset 3 "negoffset.gltf: bufferViews[1].byteOffset: -12 is not a whole number >= 0" --patch $P --animation 0 "$tmp/negoffset.gltf"
gltf_variant halfoffset.gltf 's|"bufferView":0,"componentType":5126|"bufferView":0,"byteOffset":1.5,"componentType":5126|'
expect gltf_fractional_byte_offset 3 "halfoffset.gltf: accessors[0].byteOffset: 1.5 is not a whole number >= 0" --patch $P --animation 0 "$tmp/halfoffset.gltf"
gltf_variant bigindex.gltf 's|"POSITION":0|"POSITION":4294967296|'
expect gltf_index_past_int 3 "bigindex.gltf: meshes[0].primitives[0].attributes.POSITION: 4294967296 is past the largest index read (2147483647)" --patch $P --animation 0 "$tmp/bigindex.gltf"
head -c 300 $G >"$tmp/cut.gltf"
expect gltf_truncated_json 3 "cut.gltf: not a readable glTF 2.0 file: [json.exception.parse_error.101] parse error at line 1, column 301" --patch $P --animation 0 "$tmp/cut.gltf"
printf 'glTF\x02\x00\x00\x00\xff\xff\x00\x00JSON' >"$tmp/cut.glb"
expect gltf_truncated_glb 3 "cut.glb: not a readable glTF 2.0 file" --patch $P --animation 0 "$tmp/cut.glb"
# Buffer URIs (lib/io/README.md "Which files a glTF reads"): a second buffer, used by nothing, as
# in the report that found the leak, leading out of the glTF's folder ($tmp) is refused before any
# byte is read; one with .. that stays inside is read (the error is then the missing skin).
gltf_uri_variant() {  # gltf_uri_variant NAME URI: quad.gltf with an unused buffer 1 at URI
  sed -e 's|}\],"bufferViews"|},{"byteLength":6,"uri":"'"$2"'"}],"bufferViews"|' $G >"$tmp/$1"
}
uri_rule="a glTF's buffers are read only from data: URIs and from files inside its own folder"
gltf_uri_variant climb.gltf ../../../../../../../../etc/hostname
expect gltf_uri_climbs_out 3 "climb.gltf: buffer 1 uri \"../../../../../../../../etc/hostname\": resolves to /etc/hostname, outside the glTF's folder $(cd "$tmp" && pwd -P); $uri_rule" --patch $P --animation 0 "$tmp/climb.gltf"
ln -s / "$tmp/root_link"
gltf_uri_variant link.gltf root_link/etc/hostname
expect gltf_uri_through_symlink 3 "link.gltf: buffer 1 uri \"root_link/etc/hostname\": resolves to /etc/hostname, outside" --patch $P --animation 0 "$tmp/link.gltf"
gltf_uri_variant pct.gltf %2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/etc/hostname
expect gltf_uri_percent_encoded 3 "pct.gltf: buffer 1 uri \"%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/%2e%2e/etc/hostname\": resolves to /etc/hostname" --patch $P --animation 0 "$tmp/pct.gltf"
gltf_uri_variant abs.gltf /etc/hostname
expect gltf_uri_absolute 3 "abs.gltf: buffer 1 uri \"/etc/hostname\": an absolute path; $uri_rule" --patch $P --animation 0 "$tmp/abs.gltf"
gltf_uri_variant scheme.gltf file:///etc/hostname
expect gltf_uri_file_scheme 3 "scheme.gltf: buffer 1 uri \"file:///etc/hostname\": the scheme file: (no scheme but data: is read)" --patch $P --animation 0 "$tmp/scheme.gltf"
gltf_uri_variant escape.gltf 'quad.bin%zz'
expect gltf_uri_bad_percent_escape 3 "escape.gltf: buffer 1 uri \"quad.bin%zz\": malformed percent-encoding" --patch $P --animation 0 "$tmp/escape.gltf"
printf '123456' >"$tmp/six.bin"
mkdir -p "$tmp/sub"
gltf_uri_variant inside.gltf sub/../six.bin
expect gltf_uri_dotdot_inside_read 3 "inside.gltf: mesh 0: is not skinned" --patch $P --animation 0 "$tmp/inside.gltf"

# --- point caches (PC2, MDD: lib/io/README.md "Point caches") ----------------------------------
# cache NAME EDIT: grid.0001.obj and grid.0002.obj as a cache of two samples (NAME ending .pc2:
# frames 1-2; .mdd: 0 and 1/24 s), written as Blender's exporters write them, then EDIT (Python
# on its bytes `b`) applied, as $tmp/NAME.
cache() {
  /usr/bin/python3 - "$tmp/$1" "$2" $F grid.0002.obj <<'PY'
import struct, sys
out, edit = sys.argv[1], sys.argv[2]
frames = [[tuple(map(float, l.split()[1:4])) for l in open(p) if l.startswith("v ")]
          for p in sys.argv[3:]]
n = len(frames[0])
if out.endswith(".pc2"):
    b = struct.pack("<12siiffi", b"POINTCACHE2\0", 1, n, 1.0, 1.0, len(frames))
    b += b"".join(struct.pack("<3f", *p) for v in frames for p in v)
else:
    b = struct.pack(">2i", len(frames), n) + struct.pack(">2f", 0.0, 1 / 24)
    b += b"".join(struct.pack(">3f", *p) for v in frames for p in v)
b = bytearray(b)
exec(edit)
open(out, "wb").write(bytes(b))
PY
}
cache shot.pc2 ''
cache shot.mdd ''
expect cache_pc2_valid 0 "2 frames slid" --patch $P $B "$tmp/shot.pc2"
expect cache_mdd_valid 0 "2 frames slid" --patch $P $B "$tmp/shot.mdd"
expect cache_output_other_format 2 "x.mdd: names a mdd cache, but $tmp/shot.pc2 is a pc2 cache" -o "$tmp/x.mdd" --patch $P $B "$tmp/shot.pc2"
[ -e "$tmp/x.mdd" ] && fail "cache_output_other_format: made $tmp/x.mdd"
: >"$tmp/empty.pc2"
expect cache_empty 3 "empty.pc2: the file is empty (0 bytes)" --patch $P $B "$tmp/empty.pc2"
cache magic.pc2 'b[0:11] = b"POINTCACHE3"'
expect cache_pc2_wrong_magic 3 'magic.pc2: not a PC2 point cache: it does not start with "POINTCACHE2\0"' --patch $P $B "$tmp/magic.pc2"
cache version.pc2 'b[12:16] = struct.pack("<i", 2)'
expect cache_pc2_wrong_version 3 "version.pc2: byte 12: PC2 version 2; only version 1 exists" --patch $P $B "$tmp/version.pc2"
cache header.pc2 'del b[20:]'
expect cache_pc2_cut_in_header 3 "header.pc2: truncated: a PC2 header is 32 bytes; the file has 20" --patch $P $B "$tmp/header.pc2"
cache cut.pc2 'del b[300:]'
expect cache_pc2_cut_in_sample 3 "cut.pc2: truncated: the header says 2 samples of 16 points; the file has 300 bytes, which hold 1 of them (sample 1 is cut at byte 300)" --patch $P $B "$tmp/cut.pc2"
cache long.pc2 'b += bytes(12)'
expect cache_pc2_bytes_past_the_end 3 "long.pc2: the header says 2 samples of 16 points (416 bytes); the file has 428: 12 bytes past the last sample" --patch $P $B "$tmp/long.pc2"
cache zero.pc2 'b[28:32] = struct.pack("<i", 0); del b[32:]'
expect cache_pc2_zero_samples 3 "zero.pc2: byte 28: the sample count is 0: the cache holds no samples" --patch $P $B "$tmp/zero.pc2"
cache huge.pc2 'b[16:20] = struct.pack("<i", 2**31 - 1); b[28:32] = struct.pack("<i", 2**31 - 1)'
expect cache_pc2_huge_counts 3 "huge.pc2: truncated: the header says 2147483647 samples of 2147483647 points; the file has 416 bytes, which hold 0 of them" --patch $P $B "$tmp/huge.pc2"
cache rate.pc2 'b[24:28] = struct.pack("<f", 0)'
expect cache_pc2_zero_rate 3 "rate.pc2: byte 24: sampleRate 0: the frames from one sample to the next must be a finite number above 0" --patch $P $B "$tmp/rate.pc2"
cache points.pc2 'b[16:20] = struct.pack("<i", 15); del b[32 + 2 * 15 * 12:]'
expect cache_points_not_the_binds 3 "points.pc2: has 15 points; the bind (grid.obj) has 16 vertices: a cache must hold one point per bind vertex, in the bind's order" --patch $P $B "$tmp/points.pc2"
cache nan.pc2 'b[288:292] = struct.pack("<f", float("nan"))'
expect cache_pc2_nan 3 "nan.pc2: byte 288: sample 1, point 5: coordinate y is NaN" --patch $P $B "$tmp/nan.pc2"
cache inf.mdd 'b[24:28] = struct.pack(">f", float("-inf"))'
expect cache_mdd_inf 3 "inf.mdd: byte 24: sample 0, point 0: coordinate z is infinite" --patch $P $B "$tmp/inf.mdd"
cache times.mdd 'b[12:16] = struct.pack(">f", 0.0)'
expect cache_mdd_times_not_increasing 3 "times.mdd: byte 12: the time of sample 1 (0 s) is not after sample 0's (0 s): MDD times must increase" --patch $P $B "$tmp/times.mdd"
cache none.mdd 'b[0:4] = struct.pack(">i", 0); del b[8:]'
expect cache_mdd_zero_samples 3 "none.mdd: byte 0: the sample count is 0: the cache holds no samples" --patch $P $B "$tmp/none.mdd"
cache cut_times.mdd 'b[0:4] = struct.pack(">i", 1000)'
expect cache_mdd_times_past_the_end 3 "cut_times.mdd: truncated: the header says 1000 samples of 16 points, whose header alone is 4008 bytes; the file has 400" --patch $P $B "$tmp/cut_times.mdd"
cache cut.mdd 'del b[7:]'
expect cache_mdd_cut_in_counts 3 "cut.mdd: truncated: an MDD file starts with two 4-byte counts; the file has 7 bytes" --patch $P $B "$tmp/cut.mdd"
expect cache_among_frames 2 "a point cache is a whole shot: give it as the only FRAME" --patch $P $B "$tmp/shot.pc2" $F
expect cache_frames_none 2 "--frames 5-9 selects none of the cache's 2 samples (frames 1 to 2)" --frames 5-9 --patch $P $B "$tmp/shot.pc2"
expect cache_format_other_cache 2 "--format mdd: $tmp/shot.pc2 is a pc2 cache" --format mdd --patch $P $B "$tmp/shot.pc2"
expect cache_format_glb_obj_bind 2 "glb from a point cache needs a .gltf or .glb BIND" --format glb --patch $P $B "$tmp/shot.pc2"
expect format_without_cache_or_animation 2 "--format: obj or glb applies to --animation or a point cache FRAME" --format obj --patch $P $B $F
# FRAME files as one cache (--format pc2|mdd): the header the files' numbers make, or none.
mkdir -p "$tmp/seq"
for n in 0001 0002 0004; do cp $F "$tmp/seq/s.$n.obj"; done
cp $F "$tmp/seq/unnumbered.obj"
cp $F "$tmp/seq/t.1000000000.obj" && cp $F "$tmp/seq/t.1000000001.obj"
cp "$tmp/cut_lines.0001.obj" "$tmp/seq/grid.0002.obj"
expect sequence_pc2_uneven 2 "$tmp/seq/s.0004.obj (frame 4) follows $tmp/seq/s.0002.obj (frame 2): a PC2 cache's frames rise by one step" --format pc2 --patch $P $B "$tmp"/seq/s.*.obj
expect sequence_numbered_and_not 2 "--format pc2: some FRAMEs have a frame number in their file names and some have not" --format pc2 --patch $P $B $F "$tmp/seq/unnumbered.obj"
expect sequence_mdd_without_fps 2 "--format mdd: an MDD cache holds each sample's time in seconds: give the frames' rate with --fps" --format mdd --patch $P $B $F
expect sequence_fps_without_mdd 2 "--fps: applies to --animation, or to FRAME files written as one MDD cache" --fps 24 --format pc2 --patch $P $B $F
expect sequence_mdd_one_time 2 "--format mdd: frames 1000000000 and 1000000001 have one time in float32 at --fps 1" --format mdd --fps 1 --patch $P $B "$tmp"/seq/t.*.obj
expect sequence_bad_frame_no_cache 3 "grid.0002.obj: has 9 vertices; the bind (grid.obj) has 16" --format pc2 --patch $P $B $F "$tmp/seq/grid.0002.obj"
# The bind forgotten: the first frame taken for it.
expect bind_named_as_frame 2 "BIND grid.0001.obj is named as a frame of the sequence it comes with (grid.0002.obj): is the bind mesh missing?" --patch $P grid.0001.obj grid.0002.obj
# An output that is its input: refused before anything is written, the input untouched.
mkdir -p "$tmp/cache_in"
cp "$tmp/shot.pc2" "$tmp/cache_in/"
"$bin" -o "$tmp/cache_in" --patch $P $B "$tmp/cache_in/shot.pc2" >"$tmp/stdout" 2>"$tmp/stderr"
rc=$?
if [ "$rc" -ne 2 ] || ! grep -qF "output $tmp/cache_in/shot.pc2 would overwrite input $tmp/cache_in/shot.pc2" "$tmp/stderr"; then
  fail "cache_output_is_input: exit $rc"
elif ! cmp -s "$tmp/shot.pc2" "$tmp/cache_in/shot.pc2" || [ "$(ls -A "$tmp/cache_in" | wc -l)" -ne 1 ]; then
  fail "cache_output_is_input: the folder of the input changed"
else
  passed=$((passed + 1))
fi
# Farm chunks and their join (`skinslide join`): a three-sample cache, frames 1-3.
cache shot3.pc2 'b[28:32] = struct.pack("<i", 3); b += b[32 + 16 * 12:]'
mkdir -p "$tmp/chunks"
for range in 1 2-3 3; do "$bin" -q --frames $range -o "$tmp/chunks" --patch $P $B "$tmp/shot3.pc2"; done
"$bin" -q -o "$tmp/whole" --patch $P $B "$tmp/shot3.pc2"
expect cache_frames_with_a_step 2 "--frames selects samples with gaps between them (frames 1 to 3, 2 samples)" --frames 1-3:2 --patch $P $B "$tmp/shot3.pc2"
expect join_valid 0 "2 chunks, 3 samples of 16 points" join "$tmp/chunks/shot3.0002-0003.pc2" "$tmp/chunks/shot3.0001-0001.pc2"
cmp -s "$tmp/out/join_valid/shot3.pc2" "$tmp/whole/shot3.pc2" || fail "join_valid: not the one-task cache"
expect join_a_gap 3 "shot3.0003-0003.pc2: starts at frame 3 but the chunks before it end one sample before frame 2: the samples between are missing" join "$tmp/chunks/shot3.0001-0001.pc2" "$tmp/chunks/shot3.0003-0003.pc2"
expect join_an_overlap 3 "shot3.0003-0003.pc2: frames 3-3 overlap $tmp/chunks/shot3.0002-0003.pc2's frames 2-3" join "$tmp/chunks/shot3.0002-0003.pc2" "$tmp/chunks/shot3.0003-0003.pc2"
expect join_not_a_chunk 3 "shot.pc2: not a chunk's name: expected <shot>.<first>-<last>.pc2 or .mdd" join "$tmp/shot.pc2"

# --- `skinslide compare A B`: what it refuses (its report, the output, is then not written) ------
mkdir -p "$tmp/cmp/a" "$tmp/cmp/b" "$tmp/cmp/fewer" "$tmp/cmp/empty" "$tmp/cmp/face"
"$bin" -q -o "$tmp/cmp/a" --patch $P $B $F grid.0002.obj
cp "$tmp/cmp/a/"* "$tmp/cmp/b/"
cp "$tmp/cmp/a/$F" "$tmp/cmp/fewer/"
variant cmp/face/$F '20s/.*/f 4 8 7 3/' "$tmp/cmp/a/$F"
expect compare_same 0 "2 frames, the same" compare "$tmp/cmp/a" "$tmp/cmp/b"
expect compare_different 1 "1 differ" compare "$tmp/cmp/a/$F" grid.0002.obj
expect compare_missing_frame 3 "$tmp/cmp/a has 2 frames, $tmp/cmp/fewer 1; missing from $tmp/cmp/fewer: grid.0002.obj" compare "$tmp/cmp/a" "$tmp/cmp/fewer"
expect compare_sample_counts 3 "shot3.pc2: has 3 samples; $tmp/shot.pc2 has 2" compare "$tmp/shot.pc2" "$tmp/shot3.pc2"
expect compare_vertex_counts 3 "cut_lines.0001.obj: has 9 vertices; $tmp/cmp/a/$F has 16" compare "$tmp/cmp/a/$F" "$tmp/cut_lines.0001.obj"
expect compare_other_faces 3 "$tmp/cmp/face/$F:20: face 2 differs from $tmp/cmp/a/$F:20: the two are not one mesh" compare "$tmp/cmp/a/$F" "$tmp/cmp/face/$F"
expect compare_cache_formats 3 "shot.mdd: is a mdd cache, $tmp/shot.pc2 a pc2 one: compare caches of one format" compare "$tmp/shot.pc2" "$tmp/shot.mdd"
expect compare_bind_vertices 3 "has 16 vertices; the bind (cube.obj) has 8" compare --bind cube.obj "$tmp/shot.pc2" "$tmp/shot.pc2"
expect compare_empty_folder 3 "$tmp/cmp/empty: holds no frame (no .obj, .gltf, .glb, .pc2 or .mdd file)" compare "$tmp/cmp/empty" "$tmp/cmp/a"
expect compare_no_such_output 3 "$tmp/cmp/none: no such file or folder" compare "$tmp/cmp/a" "$tmp/cmp/none"
expect compare_unlike_outputs 2 "are not alike: compare two folders, two meshes or two caches" compare "$tmp/cmp/a" "$tmp/shot.pc2"
expect compare_one_output 2 "B is required" compare "$tmp/cmp/a"
mkdir -p "$tmp/cmp/later" && cp "$tmp/cmp/a/grid.0002.obj" "$tmp/cmp/later/grid.0003.obj"
expect compare_common_none 3 "$tmp/cmp/a and $tmp/cmp/later have no frame in common" compare --common "$tmp/cmp/a" "$tmp/cmp/later"

# --- files and folders -------------------------------------------------------------------------
expect file_missing_bind 3 "nothere.obj: cannot read: No such file or directory" --patch $P "$tmp/nothere.obj" $F
expect file_missing_frame 3 "nothere.0002.obj: cannot read: No such file or directory" --patch $P $B "$tmp/nothere.0002.obj"
expect file_missing_patch 3 "nothere.txt: cannot read: No such file or directory" --patch "$tmp/nothere.txt" $B $F
mkdir -p "$tmp/folder.obj"
expect file_bind_is_folder 3 "folder.obj: cannot read: it is a directory" --patch $P "$tmp/folder.obj" $F
echo x >"$tmp/afile"
expect file_path_through_a_file 3 "afile/grid.obj: cannot read: Not a directory" --patch $P "$tmp/afile/grid.obj" $F
# Permission cases: root reads and writes whatever the mode bits say, so run them as nobody, in
# a folder nobody can reach: $tmp may be under TMPDIR in a clone whose folders only their owner
# may enter (mktemp -d makes them 0700), where every path of $tmp fails for nobody whatever its
# own mode says. So these cases get a folder of their own in /tmp, with a copy of the program.
as_user=()
if [ "$(id -u)" -eq 0 ]; then
  if command -v setpriv >/dev/null && setpriv --reuid=65534 --regid=65534 --clear-groups true 2>/dev/null; then
    as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  else
    as_user=(none)
  fi
fi
if [ "${as_user[0]:-}" = none ]; then
  echo "SKIP file_unreadable_bind, out_folder_read_only, file_folder_not_enterable: root without setpriv" >&2
  skipped=$((skipped + 3))
else
  perm=$(TMPDIR=/tmp mktemp -d)
  trap 'chmod -R u+rwx "$tmp" "$perm" 2>/dev/null; rm -rf "$tmp" "$perm"' EXIT
  chmod 755 "$perm"
  cp "$bin" "$perm/skinslide" && chmod 755 "$perm/skinslide"
  cp $B "$perm/locked.obj"
  chmod 000 "$perm/locked.obj"
  mkdir -p "$perm/ro" "$perm/out"
  chmod 555 "$perm/ro"
  chmod 1777 "$perm/out"
  cp -r . "$perm/inputs" && chmod -R a+rwX "$perm/inputs"
  # A folder nobody may enter: each path through it is "cannot read", never one file with
  # another (two lookups that both fail are not the same file).
  mkdir -p "$perm/d/frames"
  cp $B "$perm/d/bind.obj" && cp $P "$perm/d/patch.txt" && cp grid.0002.obj "$perm/d/frames/"
  chmod 700 "$perm/d"
  runner=("${as_user[@]}")
  saved_bin=$bin
  bin=$perm/skinslide
  cd "$perm/inputs"
  expect file_unreadable_bind 3 "locked.obj: cannot read: Permission denied" -o "$perm/out/unreadable" \
    --patch $P "$perm/locked.obj" $F
  expect out_folder_read_only 4 "grid.0001.obj: cannot write: Permission denied" -o "$perm/ro" --patch $P $B $F
  expect file_folder_not_enterable 3 "$perm/d/frames/grid.0002.obj: cannot read: Permission denied" -o "$perm/d/out" \
    --patch "$perm/d/patch.txt" "$perm/d/bind.obj" "$perm/d/frames/grid.0002.obj"
  cd "$here"
  bin=$saved_bin
  runner=()
fi
expect out_folder_is_file 4 "afile: cannot write: exists and is not a folder" -o "$tmp/afile" --patch $P $B $F
expect out_parent_is_file 4 "cannot create the output folder" -o "$tmp/afile/sub" --patch $P $B $F
expect out_unwritable_path 4 "cannot create the output folder" -o /proc/skinslide-out --patch $P $B $F
mkdir -p "$tmp/hasdir/grid.0001.obj"
expect out_target_is_folder 4 "grid.0001.obj: cannot write: it is a directory" -o "$tmp/hasdir" --patch $P $B $F
# An output that is an input: refused before anything is opened for writing, inputs untouched.
mkdir -p "$tmp/inplace"
cp $B $F $P "$tmp/inplace/"
touch -d 2000-01-01 "$tmp/inplace/"*
(cd "$tmp/inplace" && "$bin" -o . --patch $P $B $F >"$tmp/stdout" 2>"$tmp/stderr")
rc=$?
if [ "$rc" -ne 2 ] || ! grep -qF "output ./grid.0001.obj would overwrite input grid.0001.obj" "$tmp/stderr"; then
  fail "out_overwrites_input: exit $rc"
elif ! cmp -s $F "$tmp/inplace/$F" || [ -n "$(find "$tmp/inplace" -type f -newermt 2000-01-02)" ] ||
  [ "$(ls -A "$tmp/inplace" | wc -l)" -ne 3 ]; then
  fail "out_overwrites_input: the folder of inputs changed"
else
  passed=$((passed + 1))
fi
# Side outputs (a glTF frame's buffer, dumps, previews) and outputs onto a --config file: an input
# is never replaced, whichever output would land on it (io/run_inputs.h); exit 4, nothing of the
# frame written. expect_kept NAME TEXT KEPT ARGS...: runs `skinslide ARGS`, KEPT is an input.
expect_kept() {
  local name=$1 text=$2 kept=$3
  shift 3
  cp "$kept" "$tmp/kept.bak"
  "$bin" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  if [ "$rc" -ne 4 ] || ! grep -qF -- "$text" "$tmp/stderr"; then
    fail "$name: exit $rc, stderr: $(cat "$tmp/stderr")"
  elif ! cmp -s "$kept" "$tmp/kept.bak"; then
    fail "$name: input $kept was replaced"
  elif [ -n "$(find "$tmp/side" -name '.*.tmp.*')" ]; then
    fail "$name: a temporary was left"
  else
    passed=$((passed + 1))
  fi
}
mkdir -p "$tmp/side/cfg" "$tmp/side/dump" "$tmp/side/preview" "$tmp/side/X" "$tmp/side/Y"
echo 'method = "elastic"' >"$tmp/side/cfg/grid.0001.obj"
expect_kept output_onto_config "$tmp/side/cfg/grid.0001.obj: cannot write: it is an input of this run" \
  "$tmp/side/cfg/grid.0001.obj" --config "$tmp/side/cfg/grid.0001.obj" -o "$tmp/side/cfg" --patch $P $B $F
cp $P "$tmp/side/dump/bind.patch000.id.exr"
expect_kept dump_onto_patch_file "$tmp/side/dump/bind.patch000.id.exr: cannot write: it is an input of this run" \
  "$tmp/side/dump/bind.patch000.id.exr" -o "$tmp/side/out1" --dump "$tmp/side/dump" \
  --patch "$tmp/side/dump/bind.patch000.id.exr" $B $F
cp $P "$tmp/side/preview/grid.0001.patch000.png"
expect_kept preview_onto_patch_file "$tmp/side/preview/grid.0001.patch000.png: cannot write: it is an input of this run" \
  "$tmp/side/preview/grid.0001.patch000.png" -o "$tmp/side/out2" --preview "$tmp/side/preview" \
  --patch "$tmp/side/preview/grid.0001.patch000.png" $B $F
# The bind X/bind.gltf reads its buffer X/shared.bin; the frame Y/shared.gltf slid into X would
# write X/shared.gltf and its buffer X/shared.bin.
/usr/bin/python3 - quad.gltf "$tmp/side" <<'PY'
import base64, json, sys
g = json.load(open(sys.argv[1]))
data = base64.b64decode(g["buffers"][0]["uri"].split(",", 1)[1])
open(sys.argv[2] + "/X/shared.bin", "wb").write(data)
json.dump(g, open(sys.argv[2] + "/Y/shared.gltf", "w"))
g["buffers"][0]["uri"] = "shared.bin"
json.dump(g, open(sys.argv[2] + "/X/bind.gltf", "w"))
PY
echo 0 1 >"$tmp/side/quad.txt"
expect_kept gltf_buffer_onto_bind_buffer "$tmp/side/X/shared.bin: cannot write: it is an input of this run" \
  "$tmp/side/X/shared.bin" -o "$tmp/side/X" --patch "$tmp/side/quad.txt" "$tmp/side/X/bind.gltf" "$tmp/side/Y/shared.gltf"
if [ -e "$tmp/side/X/shared.gltf" ]; then fail "gltf_buffer_onto_bind_buffer: half a frame written"; fi
# A report or an output that is a pipe (or a device: /dev/null as root) is not replaced by a file.
mkfifo "$tmp/side/fifo.json"
expect report_onto_fifo 2 "--report $tmp/side/fifo.json is not a regular file" --report "$tmp/side/fifo.json" --patch $P $B $F
if [ ! -p "$tmp/side/fifo.json" ]; then fail "report_onto_fifo: the pipe was replaced"; fi
mkdir -p "$tmp/side/out3"
mkfifo "$tmp/side/out3/grid.0001.obj"
"$bin" -o "$tmp/side/out3" --patch $P $B $F >"$tmp/stdout" 2>"$tmp/stderr"
rc=$?
if [ "$rc" -ne 4 ] || ! grep -qF "grid.0001.obj: cannot write: it is not a regular file" "$tmp/stderr" ||
  [ ! -p "$tmp/side/out3/grid.0001.obj" ]; then
  fail "output_onto_fifo: exit $rc, stderr: $(cat "$tmp/stderr")"
else
  passed=$((passed + 1))
fi
expect frame_unknown_format 2 "unknown mesh format '.ply'" --patch $P $B frame.0001.ply
# Every input is looked at before the bind is set up (pipeline/input_checks.h): frame 900 of
# 1,000 missing fails at once, nothing written; --keep-going names each missing frame before the
# bind's line and slides the rest.
mkdir -p "$tmp/long"
for k in $(seq 1000); do ln -s "$here/$F" "$(printf '%s/long/seq.%04d.obj' "$tmp" "$k")"; done
rm "$tmp/long/seq.0900.obj" "$tmp/long/seq.0300.obj"
expect frames_missing_of_many 3 "seq.0300.obj: cannot read: No such file or directory (and 1 more of the 1000 FRAMEs, $tmp/long/seq.0900.obj" \
  --patch $P $B "$tmp"/long/seq.0{001..999}.obj "$tmp/long/seq.1000.obj"
expect frames_missing_keep_going 3 "998 frames slid, 2 failed" --keep-going \
  --patch $P $B "$tmp"/long/seq.0{001..999}.obj "$tmp/long/seq.1000.obj"
first_bad=$(grep -n "seq.0300.obj: cannot read" "$tmp/stderr" | head -1 | cut -d: -f1)
second_bad=$(grep -n "seq.0900.obj: cannot read" "$tmp/stderr" | head -1 | cut -d: -f1)
bind_line=$(grep -n "1 patch, 4 sliding vertices" "$tmp/stderr" | cut -d: -f1)
if [ -z "$first_bad" ] || [ -z "$second_bad" ] || [ -z "$bind_line" ] ||
  [ "$second_bad" -gt "$bind_line" ] || [ "$(grep -c "cannot read" "$tmp/stderr")" -ne 2 ]; then
  fail "frames_missing_keep_going: the missing frames are not named once each before the bind's line"
fi
# An unusable -o stops the run before the bind's set-up: no bind line told.
expect out_checked_before_set_up 4 "afile: cannot write: exists and is not a folder" -o "$tmp/afile" --patch $P $B $F
if grep -q "sliding vertices" "$tmp/stderr"; then fail "out_checked_before_set_up: the bind was set up"; fi
# -o is a folder: a mesh file's name is refused; a cache's name writes that cache.
expect out_named_like_a_mesh 2 "-o $tmp/out/shot.obj: -o is a folder, not a mesh file" -o "$tmp/out/shot.obj" --patch $P $B $F
expect out_named_like_a_gltf 2 "-o is a folder, not a mesh file" -o "$tmp/out/shot.GLB" --patch $P $B $F
expect out_named_like_a_cache_valid 0 "2 frames slid" -o "$tmp/out/named/shot.pc2" --patch $P $B $F grid.0002.obj
expect out_cache_format_valid 0 "2 frames slid" -o "$tmp/out/formatted/shot.pc2" --format pc2 --patch $P $B $F grid.0002.obj
cmp -s "$tmp/out/named/shot.pc2" "$tmp/out/formatted/shot.pc2" ||
  fail "out_named_like_a_cache_valid: not the cache --format pc2 writes"
expect out_named_like_mdd_needs_fps 2 "--format mdd: an MDD cache holds each sample's time" -o "$tmp/out/shot.mdd" --patch $P $B $F
cp $F "$tmp/grid.0001.obj"
expect frames_same_name 2 "two frames are named 'grid.0001.obj'" --patch $P $B $F "$tmp/grid.0001.obj"

# --- --frames and --keep-going ------------------------------------------------------------------
cp $B "$tmp/rest.obj"
expect frames_without_number 2 "--frames: $tmp/rest.obj has no frame number in its file name" --frames 1-10 --patch $P $B $F "$tmp/rest.obj"
expect frames_bad_spec 2 "--frames: '10-1' runs backwards" --frames 10-1 --patch $P $B $F
expect frames_none_selected 2 "--frames 5-9 selects none of the 2 frames (numbered 1 to 2)" --frames 5-9 --patch $P $B $F grid.0002.obj
expect frames_clamped_valid 0 "1 frame slid" --frames 2-100 --patch $P $B $F grid.0002.obj
cp $F "$tmp/good.0001.obj"
cp grid.0002.obj "$tmp/good.0003.obj"
expect fail_fast_bad_frame 3 "nan.0001.obj:7: vertex coordinate 'nan' is not finite" -j 1 --patch $P $B "$tmp/nan.0001.obj" "$tmp/good.0001.obj"
expect keep_going_bad_frames 3 "2 frames slid, 2 failed" --keep-going --patch $P $B "$tmp/good.0001.obj" "$tmp/nan.0001.obj" "$tmp/fewer.0001.obj" "$tmp/good.0003.obj"
ls "$tmp/out/keep_going_bad_frames" 2>/dev/null | tr '\n' ' ' >"$tmp/written"
[ "$(cat "$tmp/written")" = "good.0001.obj good.0003.obj " ] || fail "keep_going_bad_frames wrote: $(cat "$tmp/written")"
grep -qF "nan.0001.obj:7:" "$tmp/stderr" && grep -qF "fewer.0001.obj:25: face index 16" "$tmp/stderr" ||
  fail "keep_going_bad_frames does not name both bad frames"
expect keep_going_exit_code_of_first 4 "2 failed" -o "$tmp/hasdir" --keep-going --patch $P $B $F "$tmp/nan.0001.obj"

# --- --window: a frame written with its neighbours ----------------------------------------------
expect window_paper 2 "--window: applies to --method elastic only, not to --method paper" --window 2 --method paper --patch $P $B $F
expect window_not_a_number 2 "--window" --window two --patch $P $B $F
expect window_too_wide 2 "--window" --window 101 --patch $P $B $F
expect window_frame_without_number 2 "--window 1: $tmp/rest.obj has no frame number (name.0042.obj), and a window takes each frame's neighbours by their numbers" --window 1 --patch $P $B $F "$tmp/rest.obj"
if grep -q "sliding vertices" "$tmp/stderr"; then fail "window_frame_without_number: told after the bind's set-up"; fi
mkdir -p "$tmp/other"
cp $F "$tmp/other/shot.0001.obj"
expect window_one_number_twice 2 "are both frame 1: a window takes each frame's neighbours by their numbers" --window 1 --patch $P $B $F "$tmp/other/shot.0001.obj"
cp $F "$tmp/win.0001.obj"
cp "$tmp/nan.0001.obj" "$tmp/win.0002.obj"
cp grid.0002.obj "$tmp/win.0003.obj"
cp $F "$tmp/win.0005.obj"
# A broken frame fails itself and every frame whose window holds it, naming both; frame 5 is two
# frames of the sequence given away (frame 4 is not given) and is written.
expect window_broken_neighbour 3 "win.0001.obj: its --window neighbour $tmp/win.0002.obj:7: vertex coordinate 'nan' is not finite" --keep-going --window 1 -j 1 --patch $P $B "$tmp/win.0001.obj" "$tmp/win.0002.obj" "$tmp/win.0003.obj" "$tmp/win.0005.obj"
ls "$tmp/out/window_broken_neighbour" 2>/dev/null | tr '\n' ' ' >"$tmp/written"
[ "$(cat "$tmp/written")" = "win.0005.obj " ] || fail "window_broken_neighbour wrote: $(cat "$tmp/written")"
# (win.0005's window, win.0003 and itself, costs it ten points: counted between the two.)
grep -qE "1 frame slid( \([^)]*\))?, 3 failed" "$tmp/stderr" || fail "window_broken_neighbour: not '1 frame slid, 3 failed'"
# --window-ends without a window, another word, or with the paper method: usage errors. A loop's
# windows wrap around: a broken frame 1 fails frame 5 too (beside it in the loop); frame 3 (its
# neighbours 2 and 5) is written.
expect window_ends_without_window 2 "--window-ends: says where --window's frames end: give --window N too" --window-ends cycle --patch $P $B $F
expect window_ends_unknown_word 2 "--window-ends: loop not in {one-sided,cycle}" --window 1 --window-ends loop --patch $P $B $F
expect window_ends_paper 2 "--window-ends: applies to --method elastic only, not to --method paper" --method paper --window-ends cycle --patch $P $B $F
cp "$tmp/nan.0001.obj" "$tmp/cyc.0001.obj"
cp $F "$tmp/cyc.0002.obj"
cp grid.0002.obj "$tmp/cyc.0003.obj"
cp $F "$tmp/cyc.0005.obj"
expect window_cycle_broken_neighbour 3 "cyc.0005.obj: its --window neighbour $tmp/cyc.0001.obj:7: vertex coordinate 'nan' is not finite" --keep-going --window 1 --window-ends cycle -j 1 --patch $P $B "$tmp/cyc.0001.obj" "$tmp/cyc.0002.obj" "$tmp/cyc.0003.obj" "$tmp/cyc.0005.obj"
ls "$tmp/out/window_cycle_broken_neighbour" 2>/dev/null | tr '\n' ' ' >"$tmp/written"
[ "$(cat "$tmp/written")" = "cyc.0003.obj " ] || fail "window_cycle_broken_neighbour wrote: $(cat "$tmp/written")"

# --- config files (--config): every key an option, every value checked as on the command line ---
printf '# a shot\nmethd = "paper"\npatch = ["all.txt"]\n' >"$tmp/typo.toml"
expect config_unknown_key 2 "typo.toml:2: unknown key 'methd'; the nearest option is 'method'" --config "$tmp/typo.toml" $B $F
printf '; farm defaults\ntolerence = 0.5\npatch = all.txt\n' >"$tmp/typo.ini"
expect config_unknown_key_ini 2 "typo.ini:2: unknown key 'tolerence'; the nearest option is 'tolerance'" --config "$tmp/typo.ini" $B $F
printf 'patches = ["all.txt"]\n' >"$tmp/required.toml"
expect config_unknown_key_not_a_missing_option 2 "required.toml:1: unknown key 'patches'; the nearest option is 'patch'" --config "$tmp/required.toml" $B $F
printf 'patch = ["all.txt"]\n[run]\nthreads = 2\n' >"$tmp/section.toml"
expect config_key_in_a_section 2 "section.toml:3: unknown key 'run.threads'; the nearest option is 'threads'" --config "$tmp/section.toml" $B $F
printf 'patch = ["all.txt",\n         "all.txt"]\nq_floor = 0.01\n' >"$tmp/array.toml"
expect config_key_after_an_array 2 "array.toml:3: unknown key 'q_floor'; the nearest option is 'q-floor'" --config "$tmp/array.toml" $B $F
printf 'patch = ["all.txt"]\ntolerance = 5\n' >"$tmp/range.toml"
expect config_value_out_of_range 2 "range.toml:2: key 'tolerance': --tolerance: Value 5 not in range 0.000000 to 1.000000" --config "$tmp/range.toml" $B $F
# A value of the wrong type names the file, line and key (CLI11's message names the option only).
printf 'patch = ["all.txt"]\n# farm\nthreads = "two"\n' >"$tmp/type.toml"
expect config_value_wrong_type 2 "type.toml:3: key 'threads': --threads: Value two not in range 0 to 1024" --config "$tmp/type.toml" $B $F
printf 'patch = ["all.txt"]\nkeep-going = "maybe"\n' >"$tmp/flag.toml"
expect config_flag_not_a_boolean 2 "flag.toml:2: key 'keep-going': --keep-going = maybe: a flag takes true or false (or on/off, yes/no, 1/0, enable/disable), or the key alone for true" --config "$tmp/flag.toml" $B $F
# A flag takes true/false (on/off, yes/no, 1/0, enable/disable) or its key alone; CLI11 read any
# other number as on (5) or off (-1), and an empty value as on. A flag given on the command line
# wins, and the file's value is not read.
printf 'patch = ["all.txt"]\n# farm\nkeep-going = 5\n' >"$tmp/flag5.toml"
expect config_flag_a_number 2 "flag5.toml:3: key 'keep-going': --keep-going = 5: a flag takes true or false (or on/off, yes/no, 1/0, enable/disable), or the key alone for true" --config "$tmp/flag5.toml" $B $F
printf 'patch = ["all.txt"]\nq = -1\n' >"$tmp/flag_short.toml"
expect config_flag_negative_short_key 2 "flag_short.toml:2: key 'q': --quiet = -1: a flag takes true or false" --config "$tmp/flag_short.toml" $B $F
printf 'patch = ["all.txt"]\nno-slide =\n' >"$tmp/flag_empty.toml"
expect config_flag_empty_value 2 "flag_empty.toml:2: key 'no-slide': --no-slide has an empty value: a flag takes true or false" --config "$tmp/flag_empty.toml" $B $F
printf 'patch = ["all.txt"]\nkeep-going = Yes\nquiet = "false"\nrequire-converged = 0\nbind-is-frame = OFF\n' >"$tmp/flag_words.toml"
expect config_flag_documented_forms_valid 0 "1 frame slid" --config "$tmp/flag_words.toml" $B $F
expect config_flag_overridden_valid 0 "1 frame slid" --keep-going --config "$tmp/flag5.toml" $B $F
# --quiet and --verbose exclude each other when both are on; a flag set off is no conflict.
printf 'patch = ["all.txt"]\nquiet = false\n' >"$tmp/quiet_off.toml"
expect config_quiet_off_beside_verbose_valid 0 "1 frame slid" -v --config "$tmp/quiet_off.toml" $B $F
printf 'patch = ["all.txt"]\nquiet = true\nverbose = true\n' >"$tmp/quiet_verbose.toml"
# A conflict the file has a part in names its key and line (the first such key of the file).
expect config_quiet_and_verbose 2 "quiet_verbose.toml:2: key 'quiet': --quiet excludes --verbose" --config "$tmp/quiet_verbose.toml" $B $F
printf 'patch = ["all.txt"]\n# shot\nverbose = true\n' >"$tmp/verbose.toml"
expect config_verbose_beside_quiet 2 "verbose.toml:3: key 'verbose': --quiet excludes --verbose" -q --config "$tmp/verbose.toml" $B $F
expect quiet_and_verbose 2 "--quiet excludes --verbose" -q -v --patch $P $B $F
# The same for the flags that need another option: off, they need nothing.
printf 'patch = ["all.txt"]\nkeyframes = false\nreport-no-timings = off\n' >"$tmp/flags_off.toml"
expect config_flags_off_need_nothing_valid 0 "1 frame slid" --config "$tmp/flags_off.toml" $B $F
expect report_no_timings_off_valid 0 "1 frame slid" --report-no-timings=false --patch $P $B $F
expect keyframes_without_animation 2 "--keyframes requires --animation" --keyframes --patch $P $B $F
printf 'patch = ["all.txt"]\nreport-no-timings = on\n' >"$tmp/no_timings.toml"
expect config_report_no_timings_without_report 2 "no_timings.toml:2: key 'report-no-timings': --report-no-timings requires --report" --config "$tmp/no_timings.toml" $B $F
# CLI11's ranges let NaN through; bands narrower than round-off read as converged: refused.
expect option_nan 2 "--convergence: Value nan is not a number" --convergence nan --patch $P $B $F
expect option_nan_blend 2 "--blend: Value NaN is not a number" --blend NaN --patch $P $B $F
expect blend_below_round_off 2 "--blend 1e-100: bands this narrow are below round-off; use 0 (the facets) or 0.001 to 2" --solver search --blend 1e-100 --patch $P $B $F
printf 'patch = ["all.txt"]\nmethod = "paper"\ndensity = "papr"\n' >"$tmp/word.toml"
expect config_value_not_a_word 2 "--density: papr not in {paper,inverse,length,uniform}" --config "$tmp/word.toml" $B $F
printf 'patch = ["all.txt"]\nmethod = "paper"\ntolerance = 0.1\n' >"$tmp/other.toml"
expect config_other_methods_option 2 "other.toml:3: key 'tolerance': --tolerance: applies to --method elastic only, not to --method paper" --config "$tmp/other.toml" $B $F
printf '# every key an option\npatch = ["all.txt"]\nkeep-going\n[default]\nstrength = 0.5\n' >"$tmp/good.toml"
expect config_keys_all_options 0 "1 frame slid" --config "$tmp/good.toml" $B $F
printf '\xEF\xBB\xBF' | cat - "$tmp/good.toml" >"$tmp/bom.toml"
expect config_byte_order_mark 2 "bom.toml:1: the file starts with a UTF-8 byte-order mark" --config "$tmp/bom.toml" $B $F
# A misspelt option on the command line: named, with the nearest, as a config file's key is.
expect option_misspelt 2 "--pach: unknown option; the nearest option is --patch" --pach $P $B $F
expect option_misspelt_with_value 2 "--rotation-fit: unknown option; the nearest option is --rotation-fits" --rotation-fit=2 --patch $P $B $F

echo "bad_inputs: $passed passed, $failed failed, $skipped skipped"
[ "$failed" -eq 0 ]

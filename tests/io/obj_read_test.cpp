#include "io/obj_read.h"

#include <gtest/gtest.h>

#include "core/error.h"

namespace skinslide {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_obj("t.obj", text);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return "";
}

TEST(ObjRead, ReadsVerticesFacesAndTheirLines) {
  const ObjMesh obj = parse_obj("t.obj",
                                "# header\r\nv 0 0 0\r\nv 1 0 0 1.0\nvt 0 0\nv 1 1 0 # c\n"
                                "v 0 1 0\ng grp\nf 1/1 2/1 3/1 4/1\nf -4 -3 -1\n");
  EXPECT_EQ(obj.mesh.vertex_count(), 4);
  ASSERT_EQ(obj.mesh.face_count(), 2);
  EXPECT_EQ(obj.mesh.face_size(0), 4);
  EXPECT_EQ(obj.mesh.face_begin(1)[0], 0);  // -4 of 4 = vertex 1
  EXPECT_EQ(obj.mesh.face_begin(1)[2], 3);
  EXPECT_EQ(obj.face_lines, (std::vector<long>{8, 9}));
  EXPECT_EQ(obj.mesh.positions[2], Vec3(1, 1, 0));
}

TEST(ObjRead, FindsEachCoordinateTokenWhateverTheSpacing) {
  const std::string text = "v 0 0 0\nv\t1.5  -2\t\t3e1 1.0 # w\nv 1 1 0# c\n";
  const ObjMesh obj = parse_obj("t.obj", text);
  ASSERT_EQ(obj.text.coordinate_spans.size(), 3u);
  auto tokens = [&](size_t v) {
    const auto span = coordinate_tokens(obj.text, v);
    std::vector<std::string> out;
    for (int k = 0; k < 6; k += 2) out.push_back(text.substr(span[k], span[k + 1] - span[k]));
    return out;
  };
  EXPECT_EQ(tokens(0), (std::vector<std::string>{"0", "0", "0"}));
  EXPECT_EQ(tokens(1), (std::vector<std::string>{"1.5", "-2", "3e1"}));
  EXPECT_EQ(tokens(2), (std::vector<std::string>{"1", "1", "0"}));
  // A span runs from x's first byte to z's last: the w and the comment are outside it.
  EXPECT_EQ(obj.text.coordinate_spans[1][0], 10u);
  EXPECT_EQ(text.substr(obj.text.coordinate_spans[1][0],
                        obj.text.coordinate_spans[1][1] - obj.text.coordinate_spans[1][0]),
            "1.5  -2\t\t3e1");
}

TEST(ObjRead, VerticesAfterFacesAndForwardReferencesAreValid) {
  const ObjMesh obj = parse_obj("t.obj", "v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n");
  EXPECT_EQ(obj.mesh.face_count(), 1);
  EXPECT_EQ(obj.mesh.vertex_count(), 3);
}

TEST(ObjRead, RejectsBadInputWithFileAndLine) {
  EXPECT_EQ(error_of("v 0 0\n"), "t.obj:1: vertex has 2 coordinates; 3 needed");
  EXPECT_EQ(error_of("v 0 x 0\n"), "t.obj:1: vertex coordinate 'x' is not a number");
  EXPECT_EQ(error_of("v 0 nan 0\n"), "t.obj:1: vertex coordinate 'nan' is not finite");
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nf 1 2\n"),
            "t.obj:3: face has 2 vertices; at least 3 needed");
  EXPECT_EQ(error_of("v 0 0 0\nf 0 1 1\n"), "t.obj:2: face index 0 (OBJ indices start at 1)");
  EXPECT_EQ(error_of("v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 4\n"),
            "t.obj:4: face index 4 is out of range (the file has 3 vertices)");
  EXPECT_EQ(error_of("v 0 0 0\nf -1 -2 -3\n"),
            "t.obj:2: relative face index -2 reaches before vertex 1 (1 vertices defined so far)");
  EXPECT_EQ(error_of("v 0 0 0\nv 0 0 0\nf 1 2 1\n"),
            "t.obj:3: face uses vertex 1 twice (degenerate face)");
  EXPECT_EQ(error_of(""), "t.obj: the file is empty (0 bytes): not an OBJ mesh");
  EXPECT_EQ(error_of("# nothing\nvt 0 0\n"), "t.obj: no vertices (`v` lines): not an OBJ mesh");
  // A bad last line without an end of line: the file was most likely cut short.
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0"),
            "t.obj:2: vertex has 2 coordinates; 3 needed (the last line has no end of line: is the "
            "file truncated?)");
  EXPECT_EQ(
      error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4"),
      "t.obj:4: face index 4 is out of range (the file has 3 vertices; its last line has no end "
      "of line: is the file truncated?)");
  EXPECT_EQ(error_of(std::string("v 0 0 0\n\x01\x00\x02", 11)),
            "t.obj:2: binary data (NUL byte): not a text OBJ file");
  EXPECT_EQ(error_of("v 0 0 0\nf 1 a 3\n"), "t.obj:2: face entry 'a' is not a vertex index");
  // A whole number beyond a long long is an index out of range, not a word.
  EXPECT_EQ(error_of("v 0 0 0\nf 1 99999999999999999999 3\n"),
            "t.obj:2: face index '99999999999999999999' is too large");
  EXPECT_EQ(error_of("v 0 0 0\nf 1 -99999999999999999999/1 3\n"),
            "t.obj:2: relative face index '-99999999999999999999' reaches before vertex 1 (1 "
            "vertices defined so far)");
}

// After x y z a vertex line may hold a w or a colour r g b [a]: numbers, at most 4 of them.
TEST(ObjRead, AVertexTakesUpToFourNumbersAfterItsCoordinates) {
  const ObjMesh obj = parse_obj("t.obj", "v 0 0 0 1\nv 1 0 0 0.5 0.2 0.1\nv 0 1 0 1 0 0 1\n");
  EXPECT_EQ(obj.mesh.positions[1], Vec3(1, 0, 0));
  EXPECT_EQ(error_of("v 0 0 0 abc\n"),
            "t.obj:1: vertex entry 'abc' after x y z is not a number (a vertex is x y z, then w "
            "or a colour r g b [a])");
  EXPECT_EQ(error_of("v 0 0 0\nv 0 0 0 1 1 nan\n"),
            "t.obj:2: vertex entry 'nan' after x y z is not finite (a vertex is x y z, then w or "
            "a colour r g b [a])");
  EXPECT_EQ(error_of("v 0 0 0 1 1 1 1 1\n"),
            "t.obj:1: vertex has 8 numbers; at most 7 (x y z, then w or a colour r g b [a])");
}

TEST(ObjRead, AFaceCornerHasAtMostThreeParts) {
  const ObjMesh obj = parse_obj("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2//1 3/1/1\n");
  EXPECT_EQ(obj.mesh.face_count(), 1);
  EXPECT_EQ(error_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/1/1/1\n"),
            "t.obj:4: face corner '3/1/1/1' has more than 3 parts; a corner is v, v/vt, v//vn or "
            "v/vt/vn");
}

// A corner's texture and normal parts are not read, but each is empty or a whole number but 0:
// `1//3` is standard, relative (negative) ones are valid, and no vt or vn need exist.
TEST(ObjRead, ACornersTextureAndNormalPartsAreWholeNumbers) {
  const ObjMesh obj = parse_obj(
      "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1/1 2//2 3/-1/-1 4/+7/\nf -4/9 -3//1 -1\n");
  EXPECT_EQ(obj.mesh.face_count(), 2);
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  EXPECT_EQ(error_of(tri + "f 1/x/1 2/y/2 3/z/3\n"),
            "t.obj:4: face corner '1/x/1': texture index 'x' is not a whole number (a corner is "
            "v, v/vt, v//vn or v/vt/vn, each a whole number)");
  EXPECT_EQ(error_of(tri + "f 1//1 2//2 3//n\n"),
            "t.obj:4: face corner '3//n': normal index 'n' is not a whole number (a corner is v, "
            "v/vt, v//vn or v/vt/vn, each a whole number)");
  EXPECT_EQ(error_of(tri + "f 1/1/1 2/1.5/1 3/1/1\n"),
            "t.obj:4: face corner '2/1.5/1': texture index '1.5' is not a whole number (a corner "
            "is v, v/vt, v//vn or v/vt/vn, each a whole number)");
  EXPECT_EQ(error_of(tri + "f 1/1 2/0 3/1\n"),
            "t.obj:4: face corner '2/0': texture index 0 (OBJ indices start at 1)");
  EXPECT_EQ(error_of(tri + "f 1/1/99999999999999999999 2 3\n"),
            "t.obj:4: face corner '1/1/99999999999999999999': normal index "
            "'99999999999999999999' is too large (a corner is v, v/vt, v//vn or v/vt/vn, each a "
            "whole number)");
  // Cut short: the file's last line has no end of line.
  EXPECT_EQ(error_of(tri + "f 1/1 2/1 3/"), "");
  EXPECT_EQ(error_of(tri + "f 1/1 2/1 3/-"),
            "t.obj:4: face corner '3/-': texture index '-' is not a whole number (a corner is v, "
            "v/vt, v//vn or v/vt/vn, each a whole number) (the last line has no end of line: is "
            "the file truncated?)");
}

// The first bad line decides the message, whatever comes after it.
TEST(ObjRead, TheFirstBadLineIsTheOneReported) {
  EXPECT_EQ(error_of(std::string("v 0 0 0\nv 0 x 0\nv \x00\n", 20)),
            "t.obj:2: vertex coordinate 'x' is not a number");
  EXPECT_EQ(error_of(std::string("v 0 0 0\n\x00\nv 0 x 0\n", 18)),
            "t.obj:2: binary data (NUL byte): not a text OBJ file");
  // Statements kept as text are not split, but a continuation on any of them is still refused.
  EXPECT_EQ(error_of("v 0 0 0\nvt 0 0 \\\n0\n"),
            "t.obj:2: line continuation '\\' is not supported; join the lines");
  EXPECT_EQ(error_of("v 0 0 0\n\\\n"),
            "t.obj:2: line continuation '\\' is not supported; join the lines");
  EXPECT_EQ(error_of("v 0 0 0\nvt 0 0 # \\\ng a\\ \t\n"), "");
  // The smallest vertex used twice, in faces of a few corners and of many.
  EXPECT_EQ(error_of("v 0 0 0\nv 0 0 0\nv 0 0 0\nf 3 2 1 2 3\n"),
            "t.obj:4: face uses vertex 2 twice (degenerate face)");
  EXPECT_EQ(error_of("v 0 0 0\nv 0 0 0\nv 0 0 0\nf 3 1 2 3 1 2 3 1 2 3\n"),
            "t.obj:4: face uses vertex 1 twice (degenerate face)");
}

TEST(ObjRead, EveryPrefixOfAValidFileParsesOrFailsCleanly) {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1 4/1\nf 1 3 4\n";
  for (size_t n = 0; n <= text.size(); ++n) {
    try {
      const ObjMesh obj = parse_obj("t.obj", text.substr(0, n));
      EXPECT_GE(obj.mesh.vertex_count(), 1);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << n;
    }
  }
}

}  // namespace
}  // namespace skinslide

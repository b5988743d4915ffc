#include "io/vertex_list.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "io/obj_read.h"

namespace skinslide {
namespace {

std::string weights_error(const std::string& text, Index vertices = 4) {
  try {
    parse_weights("w.txt", text, vertices);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return "";
}

std::string list_error(const std::string& text, Index vertices = 100) {
  try {
    parse_vertex_list("pins.txt", text, vertices);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return "";
}

TEST(Weights, OneALineInVertexOrder) {
  EXPECT_EQ(parse_weights("w.txt", "# painted\n0\n0.25\n\n1 # full\n0.5\n", 4),
            (std::vector<double>{0, 0.25, 1, 0.5}));
}

TEST(Weights, PairsLeaveUnlistedVerticesAtZero) {
  EXPECT_EQ(parse_weights("w.txt", "3 0.5\n# comment\n1, 1\n", 5),
            (std::vector<double>{0, 1, 0, 0.5, 0}));
}

TEST(Weights, RejectsBadLinesWithTheirLine) {
  EXPECT_EQ(weights_error("0\n0.5\nhalf\n1\n"), "w.txt:3: 'half' is not a number");
  EXPECT_EQ(weights_error("0\n1.5\n0\n0\n"), "w.txt:2: weight 1.5 is outside [0, 1]");
  EXPECT_EQ(weights_error("0\n-0.1\n0\n0\n"), "w.txt:2: weight -0.1 is outside [0, 1]");
  EXPECT_EQ(weights_error("0\nnan\n0\n0\n"), "w.txt:2: weight nan is outside [0, 1]");
  EXPECT_EQ(weights_error("0\n0\n0\n"),
            "w.txt: has 3 weights; the bind has 4 vertices (one weight a line in vertex order, or "
            "'index weight' pairs)");
  EXPECT_EQ(weights_error("0\n0\n0\n0\n0\n"), "w.txt:5: more weights than the bind's 4 vertices");
  EXPECT_EQ(weights_error("1 0.5\n4 0.5\n"),
            "w.txt:2: vertex 4 is out of range (the bind has 4 vertices, numbered 0 to 3)");
  EXPECT_EQ(weights_error("1 0.5\n-1 0.5\n"), "w.txt:2: '-1' is not a vertex id");
  EXPECT_EQ(weights_error("1 0.5\n2 0.5\n1 1\n"),
            "w.txt:3: vertex 1 is already given a weight on line 1");
  EXPECT_EQ(weights_error("1 0.5\n0.5\n"),
            "w.txt:2: has 1 numbers; line 1 starts an 'index weight' file");
  EXPECT_EQ(weights_error("# x\n0.5\n1 0.5\n"),
            "w.txt:3: has 2 numbers; line 2 starts a one-weight-a-line file (vertex order)");
  EXPECT_EQ(weights_error("1 2 3\n"),
            "w.txt:1: expected one weight a line or 'index weight' pairs; found 3 numbers");
  EXPECT_EQ(weights_error("# nothing\n"), "w.txt: holds no weights");
}

TEST(Weights, EveryPrefixOfAFileParsesOrIsRejected) {
  const std::string text = "# w\n0 0.125\n2 1 # x\n3 0.5\n";
  for (size_t n = 0; n <= text.size(); ++n) {
    try {
      const std::vector<double> w = parse_weights("w.txt", text.substr(0, n), 4);
      EXPECT_EQ(w.size(), 4u);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << n;
    }
  }
}

TEST(VertexList, ReadsIdsRangesAndMayaComponents) {
  EXPECT_EQ(parse_vertex_list("pins.txt",
                              "# pins\n7 3, 3\n10-12 # range\npBody.vtx[20:21] vtx[30]\n", 100),
            (std::vector<Index>{3, 7, 10, 11, 12, 20, 21, 30}));
  EXPECT_TRUE(parse_vertex_list("pins.txt", "# none\n", 100).empty());
}

TEST(VertexList, RejectsBadTokensWithTheirLine) {
  EXPECT_EQ(list_error("1\nx\n"),
            "pins.txt:2: unknown token 'x': expected a vertex id (12), a range (12-40) or a Maya "
            "component (pBody.vtx[12:40])");
  EXPECT_EQ(list_error("5-3\n"), "pins.txt:1: range '5-3' runs backwards");
  EXPECT_EQ(list_error("1\n\n90-100\n"),
            "pins.txt:3: vertex 100 is out of range (the bind has 100 vertices, numbered 0 to 99)");
  EXPECT_NE(list_error("-3\n").find("unknown token '-3'"), std::string::npos);
  EXPECT_NE(list_error("pBody.f[3]\n").find("unknown token"), std::string::npos);
}

TEST(ObjColorWeights, ReadsOneChannel) {
  const ObjMesh obj =
      parse_obj("c.obj",
                "# coloured\nv 0 0 0 0.1 0.2 0.3\nv 1 0 0 1 0 0.5 # red\r\nv 0 1 0 0 0 0\n"
                "f 1 2 3\n");
  EXPECT_EQ(obj_color_weights("c.obj", obj.text, 0), (std::vector<double>{0.1, 1, 0}));
  EXPECT_EQ(obj_color_weights("c.obj", obj.text, 2), (std::vector<double>{0.3, 0.5, 0}));
}

// An alpha after r g b is ignored: the weights are those of the same file without it.
TEST(ObjColorWeights, AnAlphaIsIgnored) {
  const ObjMesh obj = parse_obj("c.obj",
                                "v 0 0 0 0.1 0.2 0.3 1\nv 1 0 0 1 0 0.5 0.25 # red\r\n"
                                "v 0 1 0 0 0 0\nf 1 2 3\n");
  EXPECT_EQ(obj_color_weights("c.obj", obj.text, 0), (std::vector<double>{0.1, 1, 0}));
  EXPECT_EQ(obj_color_weights("c.obj", obj.text, 1), (std::vector<double>{0.2, 0, 0}));
  EXPECT_EQ(obj_color_weights("c.obj", obj.text, 2), (std::vector<double>{0.3, 0.5, 0}));
  // Not even an alpha outside [0, 1] is looked at.
  EXPECT_EQ(obj_color_weights("c.obj", parse_obj("c.obj", "v 0 0 0 0.5 0.5 0.5 255\n").text, 1),
            (std::vector<double>{0.5}));
}

TEST(ObjColorWeights, RejectsMissingOrOutOfRangeColours) {
  auto error_of = [](const std::string& text) -> std::string {
    try {
      obj_color_weights("c.obj", parse_obj("c.obj", text).text, 1);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error_of("v 0 0 0 1 1 1\n\nv 1 0 0\nv 0 1 0 1 1 1\nf 1 2 3\n"),
            "c.obj:3: vertex 1 has no colour: expected 'v x y z r g b' or 'v x y z r g b a' for "
            "slide weights from vertex colours");
  EXPECT_EQ(error_of("v 0 0 0 1\nv 1 0 0 1 1 1\nv 0 1 0 1 1 1\nf 1 2 3\n"),
            "c.obj:1: vertex 0 has no colour: expected 'v x y z r g b' or 'v x y z r g b a' for "
            "slide weights from vertex colours");
  EXPECT_EQ(error_of("v 0 0 0 1 1 1\nv 1 0 0 0 255 0\nv 0 1 0 1 1 1\nf 1 2 3\n"),
            "c.obj:2: colour 255 is outside [0, 1] (slide weights are colours in 0..1)");
}

}  // namespace
}  // namespace skinslide

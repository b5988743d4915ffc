#include "mesh/patches.h"

#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "helpers/meshes.h"

namespace skinslide {
namespace {

FaceNamer names() {
  return [](Index f) { return "face " + std::to_string(f); };
}

std::string error_of(const PolyMesh& mesh, const std::vector<std::vector<Index>>& sel) {
  try {
    patch_components(mesh, sel, names());
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return "";
}

TEST(Patches, GridWithAHoleHasTwoLoopsStartingAtTheirSmallestVertex) {
  // 4x4 grid without the centre quads 5,6,9,10: an outer loop of 16 and a hole loop of 8.
  const PolyMesh mesh = test::quad_grid_with_holes(4, 4, {5, 6, 9, 10});
  const auto comps = patch_components(mesh, {test::all_faces(mesh)}, names());
  ASSERT_EQ(comps.size(), 1u);
  ASSERT_EQ(comps[0].loops.size(), 2u);
  const auto& outer = comps[0].loops[0];
  const auto& hole = comps[0].loops[1];
  EXPECT_EQ(outer.size(), 16u);
  EXPECT_EQ(hole.size(), 8u);
  EXPECT_EQ(outer.front(), 0);
  EXPECT_EQ(hole.front(), 6);
  // Walking direction = the direction the owning face traverses the edge: face 0 runs 0 -> 1.
  EXPECT_EQ(outer[1], 1);
  // Around the hole: face 4 = (5, 6, 11, 10) runs 6 -> 11, face 1 = (1, 2, 7, 6) runs 7 -> 6.
  EXPECT_EQ(hole[1], 11);
  EXPECT_EQ(comps[0].vertices.size(), 24u);
}

TEST(Patches, FacesTouchingAtAVertexAreSeparateComponents) {
  const PolyMesh mesh = test::quad_grid(2, 2);
  const auto comps = patch_components(mesh, {{0, 3}}, names());
  ASSERT_EQ(comps.size(), 2u);
  EXPECT_EQ(comps[0].faces, std::vector<Index>{0});
  EXPECT_EQ(comps[1].faces, std::vector<Index>{3});
}

TEST(Patches, SeparateSelectionsAreSeparatePatchesEvenWhenAdjacent) {
  const PolyMesh mesh = test::quad_grid(2, 1);
  const auto comps = patch_components(mesh, {{0}, {1}}, names());
  ASSERT_EQ(comps.size(), 2u);
  EXPECT_EQ(comps[0].selection, 0);
  EXPECT_EQ(comps[1].selection, 1);
}

TEST(Patches, RejectsAnEdgeInThreeFaces) {
  PolyMesh mesh = test::quad_grid(1, 1);
  mesh.positions.emplace_back(0.5, 0.5, 1);
  mesh.add_face({0, 1, 4});
  mesh.positions.emplace_back(0.5, 0.5, -1);
  mesh.add_face({1, 0, 5});
  const std::string msg = error_of(mesh, {test::all_faces(mesh)});
  EXPECT_NE(msg.find("edge (0, 1) is shared by 3 selected faces"), std::string::npos) << msg;
}

TEST(Patches, RejectsABowTieVertex) {
  // Two fans around vertex 0 ({0,1}, {2,3}) joined into one component through faces 4..6 that
  // avoid vertex 0: an hourglass at 0.
  PolyMesh mesh;
  for (int i = 0; i < 12; ++i) mesh.positions.emplace_back(i, i * i % 7, 0);
  mesh.add_face({0, 1, 2});
  mesh.add_face({0, 2, 3});
  mesh.add_face({0, 4, 5});
  mesh.add_face({0, 5, 6});
  mesh.add_face({3, 2, 10});
  mesh.add_face({5, 4, 11});
  mesh.add_face({3, 10, 11, 4});
  const std::string msg = error_of(mesh, {test::all_faces(mesh)});
  EXPECT_NE(msg.find("vertex 0 is non-manifold"), std::string::npos) << msg;
  EXPECT_NE(msg.find("2 separate fans"), std::string::npos) << msg;
  // Without the joining faces the two fans are separate components sharing a boundary vertex.
  EXPECT_EQ(error_of(mesh, {{0, 1, 2, 3}}), "");
}

TEST(Patches, RejectsInconsistentOrientation) {
  PolyMesh mesh = test::quad_grid(2, 1);
  PolyMesh flipped;
  flipped.positions = mesh.positions;
  flipped.add_face({0, 1, 4, 3});
  flipped.add_face({1, 4, 5, 2});  // traverses 1 -> 4 like face 0
  const std::string msg = error_of(flipped, {{0, 1}});
  EXPECT_NE(msg.find("not consistently oriented"), std::string::npos) << msg;
}

TEST(Patches, RejectsAClosedComponent) {
  PolyMesh cube;
  cube.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                    {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  cube.add_face({0, 3, 2, 1});
  cube.add_face({4, 5, 6, 7});
  cube.add_face({0, 1, 5, 4});
  cube.add_face({1, 2, 6, 5});
  cube.add_face({2, 3, 7, 6});
  cube.add_face({3, 0, 4, 7});
  const std::string msg = error_of(cube, {test::all_faces(cube)});
  EXPECT_NE(msg.find("no boundary"), std::string::npos) << msg;
  EXPECT_EQ(error_of(cube, {{0, 1, 2, 3, 4}}), "");
}

// A torus of n x m quads with one quad left out: one boundary loop, one handle (V - E + F = -1
// where a disk with one loop has 1). Neither method can chart it as a disk.
TEST(Patches, RejectsAComponentWithAHandle) {
  PolyMesh torus;
  const int n = 6, m = 4;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double a = 2 * M_PI * i / n, b = 2 * M_PI * j / m;
      torus.positions.push_back(
          Vec3((2 + std::cos(b)) * std::cos(a), (2 + std::cos(b)) * std::sin(a), std::sin(b)));
    }
  const auto id = [&](int i, int j) { return static_cast<Index>((i % n) * m + j % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j)
      torus.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  std::vector<Index> all_but_one;
  for (Index f = 1; f < torus.face_count(); ++f) all_but_one.push_back(f);
  const std::string msg = error_of(torus, {all_but_one});
  EXPECT_NE(msg.find("face 1 (23 faces) is not a disk with holes: it has 1 handle(s) "
                     "(V - E + F = -1 with 1 boundary loops)"),
            std::string::npos)
      << msg;
  // Cut across the handle as well (a ring of m faces out): a band, two loops, a disk with a hole.
  std::vector<Index> band;
  for (Index f = m; f < torus.face_count(); ++f) band.push_back(f);
  EXPECT_EQ(error_of(torus, {band}), "");
}

TEST(Patches, RejectsAFaceInTwoSelections) {
  const PolyMesh mesh = test::quad_grid(2, 2);
  const std::string msg = error_of(mesh, {{0, 1}, {1, 2}});
  EXPECT_NE(msg.find("face 1 is selected by patch 0 and by patch 1"), std::string::npos) << msg;
  // Named by their files when the caller names them (the patch components are numbered otherwise).
  const std::vector<std::string> files = {"left.txt", "right.txt"};
  try {
    patch_components(mesh, {{0, 1}, {1, 2}}, names(), [&](Index s) { return files[s]; });
    ADD_FAILURE() << "a face in two selections was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "face 1 is selected by left.txt and by right.txt; a face belongs to one patch");
  }
}

TEST(Patches, TubeBandHasTwoLoops) {
  const PolyMesh mesh = test::tube(8, 3, 3.0);
  const auto comps = patch_components(mesh, {test::all_faces(mesh)}, names());
  ASSERT_EQ(comps.size(), 1u);
  ASSERT_EQ(comps[0].loops.size(), 2u);
  EXPECT_EQ(comps[0].loops[0].front(), 0);
  EXPECT_EQ(comps[0].loops[1].front(), 24);
}

}  // namespace
}  // namespace skinslide

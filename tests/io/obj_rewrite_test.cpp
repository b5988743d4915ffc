#include "io/obj_rewrite.h"

#include <gtest/gtest.h>

namespace skinslide {

TEST(ObjRewrite, OnlyTheCoordinatesOfMovedVerticesChange) {
  const std::string text =
      "# c\r\nv  0 0 0\r\nv\t1  0.5\t0 1.0 # keep\r\nvt 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n";
  const ObjMesh obj = parse_obj("t.obj", text);
  Positions3 moved = obj.mesh.positions;
  EXPECT_EQ(rewrite_obj(obj.text, obj.mesh.positions, moved), text);  // nothing moved
  moved[1] = Vec3(0.1, -2, 1e-5);
  EXPECT_EQ(rewrite_obj(obj.text, obj.mesh.positions, moved),
            "# c\r\nv  0 0 0\r\nv\t0.1  -2\t1e-05 1.0 # keep\r\nvt 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n");
}

TEST(ObjRewrite, NumbersRoundTripExactly) {
  const ObjMesh obj = parse_obj("t.obj", "v 0 0 0\n");
  const Positions3 moved{Vec3(0.1 + 0.2, 1.0 / 3.0, -123456.789e-300)};
  const ObjMesh back = parse_obj("t.obj", rewrite_obj(obj.text, obj.mesh.positions, moved));
  EXPECT_EQ(back.mesh.positions[0], moved[0]);
}

}  // namespace skinslide

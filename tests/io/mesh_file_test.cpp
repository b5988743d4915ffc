#include "io/mesh_file.h"
#include "io/mesh_formats.h"

#include <gtest/gtest.h>

#include "core/error.h"
#include "helpers/meshes.h"
#include "io/atomic_write.h"

namespace skinslide {
namespace {

constexpr const char* kBind = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n# faces\nf 1 2 3\nf 1 3 4\n";

std::string input_error(const MeshFile& bind, const MeshFile& frame) {
  try {
    require_same_topology(bind, frame);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    return e.what();
  }
  return "";
}

TEST(MeshFile, AFrameMustHaveTheBindsVerticesAndFaces) {
  const std::string dir = test::temp_dir("mesh_file_topology");
  write_file_atomic(dir + "/bind.obj", kBind);
  write_file_atomic(dir + "/same.obj", "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\nf 1 2 3\nf 1 3 4\n");
  write_file_atomic(dir + "/other.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 4 3\n");
  write_file_atomic(dir + "/fewer.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  const MeshFile bind = read_mesh_file(dir + "/bind.obj");
  EXPECT_EQ(input_error(bind, read_mesh_file(dir + "/same.obj")), "");
  EXPECT_EQ(input_error(bind, read_mesh_file(dir + "/other.obj")),
            dir + "/other.obj:6: face 1 differs from the bind's (" + dir +
                "/bind.obj:7): a frame must have the bind's faces");
  EXPECT_EQ(input_error(bind, read_mesh_file(dir + "/fewer.obj")),
            dir + "/fewer.obj: has 3 vertices; the bind (" + dir +
                "/bind.obj) has 4: a frame must be the bind mesh deformed");
}

// Once checked, a frame's faces are freed; the frame is still written byte for byte as its file
// with only the moved vertex's coordinates changed.
TEST(MeshFile, AFrameWithoutItsFacesIsWrittenAsBefore) {
  const std::string dir = test::temp_dir("mesh_file_release");
  write_file_atomic(dir + "/frame.obj", kBind);
  MeshFile frame = read_mesh_file(dir + "/frame.obj");
  release_faces(frame);
  EXPECT_EQ(frame.mesh.face_count(), 0);
  EXPECT_TRUE(frame.face_lines.empty());
  EXPECT_EQ(frame.mesh.vertex_count(), 4);
  SlidVertices slid;
  slid.vertex = {2};
  slid.sample.resize(1);
  slid.position = {Vec3(0.5, 0.25, 2)};
  write_slid_mesh_file(frame, slid, dir + "/out.obj");
  EXPECT_EQ(read_file(dir + "/out.obj"),
            "v 0 0 0\nv 1 0 0\nv 0.5 0.25 2\nv 0 1 0\n# faces\nf 1 2 3\nf 1 3 4\n");
}

}  // namespace
}  // namespace skinslide

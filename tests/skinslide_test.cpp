// The embedding API (skinslide.h): arrays in and out give what the pipeline gives, errors carry
// their kinds, and frames slid from several threads at once give the same bits.
#include "skinslide.h"

#include <cmath>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "helpers/meshes.h"
#include "helpers/samples.h"

namespace skinslide {
namespace {

struct Arrays {
  std::vector<double> positions;
  std::vector<Index> face_vertices, face_sizes;
  Bind bind() const { return {positions, face_vertices, face_sizes}; }
};

Arrays arrays(const PolyMesh& mesh) {
  Arrays a;
  for (const Vec3& p : mesh.positions) a.positions.insert(a.positions.end(), {p.x(), p.y(), p.z()});
  a.face_vertices = mesh.face_vertices;
  for (Index f = 0; f < mesh.face_count(); ++f) a.face_sizes.push_back(mesh.face_size(f));
  return a;
}

std::vector<double> flat(const Positions3& points) {
  std::vector<double> out;
  for (const Vec3& p : points) out.insert(out.end(), {p.x(), p.y(), p.z()});
  return out;
}

ErrorKind kind_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.kind();
  }
  ADD_FAILURE() << "no error";
  return ErrorKind::Internal;
}

TEST(Api, ArraysGiveThePipelinesSlideForBothMethods) {
  const test::Sample c = test::load_sample("face");
  const Arrays a = arrays(c.bind);
  for (const SlideOptions& options :
       {SlideOptions{ElasticOptions{}}, SlideOptions{PaperOptions{}}}) {
    SCOPED_TRACE(method_name(options));
    const BindSetup api = set_up(a.bind(), {c.faces}, options);
    const BindSetup direct = bind_setup(c.bind, {c.faces}, options);
    for (const Positions3& frame : c.frames) {
      const std::vector<double> in = flat(frame);
      std::vector<double> out(in.size());
      const std::vector<PatchFrameReport> report = slide(api, in, out);
      EXPECT_EQ(out, flat(apply_slide(frame, slide_frame(direct, frame).slid)));
      ASSERT_EQ(report.size(), api.patches.size());
      EXPECT_GT(report[0].moved, 0);
    }
  }
}

TEST(Api, FramesSlidOnSeveralThreadsGiveTheSameBits) {
  const test::Sample c = test::load_sample("elbow");
  const BindSetup setup = set_up(arrays(c.bind).bind(), {c.faces});
  std::vector<std::vector<double>> in, serial, parallel;
  for (const Positions3& frame : c.frames) in.push_back(flat(frame));
  for (const auto& frame : in) {
    serial.emplace_back(frame.size());
    slide(setup, frame, serial.back());
  }
  parallel.assign(in.size(), {});
  std::vector<std::thread> threads;
  for (size_t f = 0; f < in.size(); ++f)
    threads.emplace_back([&, f] {
      parallel[f].resize(in[f].size());
      slide(setup, in[f], parallel[f]);
    });
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(parallel, serial);
}

TEST(Api, AVertexLeftWhereTheFrameHasItKeepsTheFramesBits) {
  // As the command's OBJ writer keeps the frame's text there: exporters write "-0.000000", and
  // the module gave +0 where the command gave -0 (found by tests/property, paper).
  const test::Sample c = test::load_sample("elbow");
  std::vector<double> frame = flat(c.bind.positions);
  int zeros = 0;
  for (double& x : frame)
    if (x == 0) {
      x = -0.0;
      ++zeros;
    }
  ASSERT_GT(zeros, 0);
  for (const SlideOptions& options :
       {SlideOptions{ElasticOptions{}}, SlideOptions{PaperOptions{}}}) {
    SCOPED_TRACE(method_name(options));
    SlideControls half;
    half.strength = 0.5;
    const BindSetup setup = set_up(arrays(c.bind).bind(), {c.faces}, options, half);
    std::vector<double> out(frame.size());
    slide(setup, frame, out);
    int kept = 0;
    for (size_t v = 0; v < frame.size(); v += 3) {
      if (out[v] != frame[v] || out[v + 1] != frame[v + 1] || out[v + 2] != frame[v + 2]) continue;
      ++kept;
      for (size_t k = v; k < v + 3; ++k)
        EXPECT_EQ(std::signbit(out[k]), std::signbit(frame[k])) << "vertex " << v / 3;
    }
    EXPECT_GT(kept, 0);
  }
}

TEST(Api, ErrorsCarryTheirKinds) {
  const PolyMesh mesh = test::quad_grid(4, 4);
  Arrays a = arrays(mesh);
  const std::vector<Index> all = test::all_faces(mesh);
  EXPECT_EQ(kind_of([&] { set_up(a.bind(), {{0, 99}}); }), ErrorKind::Input) << "face past the end";
  ElasticOptions e;
  e.rotation_fits = 0;
  EXPECT_EQ(kind_of([&] { set_up(a.bind(), {all}, e); }), ErrorKind::Usage);
  PaperOptions p;
  p.cg_tolerance = std::nan("");
  EXPECT_EQ(kind_of([&] { set_up(a.bind(), {all}, p); }), ErrorKind::Usage);
  SlideControls controls;
  controls.weight.assign(mesh.positions.size(), 2.0);
  EXPECT_EQ(kind_of([&] { set_up(a.bind(), {all}, {}, controls); }), ErrorKind::Usage);
  Arrays bad = a;
  bad.face_vertices[5] = 1000;
  EXPECT_EQ(kind_of([&] { set_up(bad.bind(), {all}); }), ErrorKind::Input) << "vertex past the end";
  bad = a;
  bad.face_sizes[0] = 2;
  EXPECT_EQ(kind_of([&] { set_up(bad.bind(), {all}); }), ErrorKind::Input) << "a two-corner face";
  const BindSetup setup = set_up(a.bind(), {all});
  std::vector<double> frame = a.positions, out(frame.size());
  std::vector<double> short_out(3);
  EXPECT_EQ(kind_of([&] { slide(setup, frame, short_out); }), ErrorKind::Input);
  frame[4] = INFINITY;
  EXPECT_EQ(kind_of([&] { slide(setup, frame, out); }), ErrorKind::Input);
}

TEST(Api, TrianglesNeedNoFaceSizes) {
  const PolyMesh grid = test::quad_grid(3, 3);
  Arrays tri;
  tri.positions = arrays(grid).positions;
  for (Index f = 0; f < grid.face_count(); ++f) {
    const Index* v = grid.face_begin(f);
    tri.face_vertices.insert(tri.face_vertices.end(), {v[0], v[1], v[2], v[0], v[2], v[3]});
  }
  std::vector<Index> faces(tri.face_vertices.size() / 3);
  for (size_t f = 0; f < faces.size(); ++f) faces[f] = static_cast<Index>(f);
  const BindSetup setup = set_up({tri.positions, tri.face_vertices, {}}, {faces});
  ASSERT_EQ(setup.patches.size(), 1u);
  EXPECT_EQ(setup.patches[0].triangles.size(), faces.size());
  EXPECT_EQ(setup.patches[0].free_vertices.size(), 4u) << "the inner 2x2 vertices of a 3x3 grid";
}

}  // namespace
}  // namespace skinslide

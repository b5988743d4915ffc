#include "pipeline/dumps.h"

#include <cmath>
#include <filesystem>
#include <numeric>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/version.h"
#include "dump/geometry_image.h"
#include "dump/slide_field.h"
#include "helpers/exr_read.h"
#include "helpers/nets.h"
#include "helpers/run.h"
#include "helpers/temp_dir.h"
#include "io/atomic_write.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

constexpr int kLookup = 64;
constexpr double kAreaTol = 1e-7;   // dump/coverage.h
constexpr double kFloatTol = 1e-5;  // P is stored as float; |P| ~ 2 here

// A paper's patch from a test net, with the net's corners as the square's.
Patch patch_from(const test::TestNet& g, Index first_id, Index id_step, int n, PaperMethod& paper) {
  Patch p;
  for (size_t k = 0; k < g.net.size(); ++k) p.vertices.push_back(first_id + id_step * Index(k));
  p.triangles = g.triangles;
  p.bars = g.bars;
  p.bind_net = g.net;
  p.free_vertices = g.interior;
  const Index m = n + 1;
  PaperSetup setup;
  setup.corners = {0, n, m * m - 1, m * n};
  paper.patches.push_back(setup);
  return p;
}

// Two patches (a bent 4x4 grid, a 6x6 grid with a hole) and a skipped one; the frame moves the
// free vertices of both nets by a smooth field and bends the 3D surface further.
struct Scene {
  test::TestNet grid = test::grid_net(4);
  test::TestNet holed = test::grid_net(6, 2, 2);
  BindSetup setup;
  Positions3 bind_positions, frame_positions;
  std::vector<PatchFrameReport> reports;

  Scene() {
    PaperMethod paper;
    setup.patches.push_back(patch_from(grid, 100, 2, 4, paper));
    setup.patches.push_back(patch_from(holed, 1000, 1, 6, paper));
    Patch skipped;
    skipped.skipped = true;
    skipped.vertices = {5, 6, 7};
    setup.patches.push_back(skipped);
    paper.patches.emplace_back();
    setup.method = paper;
    setup.vertex_count = 1100;
    bind_positions.assign(1100, Vec3::Zero());
    frame_positions.assign(1100, Vec3::Zero());
    for (const Patch& p : setup.patches) {
      PatchFrameReport r;
      r.method = PaperReport{};
      if (!p.skipped) {
        const Positions3 b = test::bent(p.bind_net);
        r.frame_net = p.bind_net;
        for (Index v : p.free_vertices) {
          const Vec2 u = p.bind_net[v];
          r.frame_net[v] += 0.03 * Vec2(std::sin(7 * u.x() + 2 * u.y()), std::cos(5 * u.y()));
        }
        for (size_t k = 0; k < p.vertices.size(); ++k) {
          bind_positions[p.vertices[k]] = b[k];
          frame_positions[p.vertices[k]] = Vec3(b[k].x(), b[k].y() * 1.2, b[k].z() * 1.5 + 0.1);
        }
        r.id_image = id_raster(r.frame_net, p.triangles, kLookup);
      }
      reports.push_back(r);
    }
  }

  Positions3 local(const Patch& p, const Positions3& all) const {
    Positions3 out;
    for (Index v : p.vertices) out.push_back(all[v]);
    return out;
  }

  void write(const std::string& dir, DumpOptions options = {}) const {
    options.id_image_size = kLookup;
    write_bind_dumps(dir, "in/bind.obj", setup, bind_positions, options);
    write_frame_dumps(dir, "frames/f0007.obj", setup, frame_positions, reports, options);
    write_previews(dir + "/preview", "frames/f0007.obj", setup, reports, options);
  }
};

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) names.push_back(fs::relative(e.path(), dir).string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(Dumps, FileNames) {
  EXPECT_EQ(dump_stem("frames/f0003.obj"), "f0003");
  EXPECT_EQ(dump_stem("a/b.c/arm.0012.obj"), "arm.0012");
  EXPECT_EQ(dump_path("out", "f0003", 2, "id.exr"), "out/f0003.patch002.id.exr");
  EXPECT_EQ(dump_path("out", "f0003", 1234, "png"), "out/f0003.patch1234.png");

  const Scene s;
  test::TempDir dir("dumps_names");
  s.write(dir.path().string());
  EXPECT_EQ(listing(dir.path()),
            (std::vector<std::string>{"bind.patch000.geom.exr", "bind.patch000.id.exr",
                                      "bind.patch001.geom.exr", "bind.patch001.id.exr",
                                      "f0007.patch000.geom.exr", "f0007.patch000.id.exr",
                                      "f0007.patch001.geom.exr", "f0007.patch001.id.exr",
                                      "preview/f0007.patch000.png", "preview/f0007.patch001.png"}));
}

TEST(Dumps, ChannelsTypesAndAttributes) {
  const Scene s;
  test::TempDir dir("dumps_channels");
  s.write(dir.path().string());
  const std::vector<Index> corner_ids[2] = {{100, 108, 148, 140}, {1000, 1006, 1048, 1042}};
  for (int k = 0; k < 2; ++k)
    for (const std::string stem : {"bind", "f0007"}) {
      const bool frame = stem != "bind";
      const test::ExrContents id = test::read_exr(dump_path(dir / "", stem, k, "id.exr"));
      const test::ExrContents geom = test::read_exr(dump_path(dir / "", stem, k, "geom.exr"));
      EXPECT_EQ(id.types, (std::map<std::string, Imf::PixelType>{{"id", Imf::UINT}}));
      std::map<std::string, Imf::PixelType> want = {
          {"P.X", Imf::FLOAT}, {"P.Y", Imf::FLOAT}, {"P.Z", Imf::FLOAT}, {"A", Imf::FLOAT}};
      if (frame) want.insert({{"slide.X", Imf::FLOAT}, {"slide.Y", Imf::FLOAT}});
      EXPECT_EQ(geom.types, want);
      for (const test::ExrContents* c : {&id, &geom}) {
        EXPECT_EQ(c->width, kLookup);
        EXPECT_EQ(c->height, kLookup);
        EXPECT_EQ(c->strings.at("skinslide.version"), version());
        EXPECT_EQ(c->strings.at("skinslide.source"), frame ? "frames/f0007.obj" : "in/bind.obj");
        EXPECT_EQ(c->strings.at("skinslide.net"), frame ? "frame" : "bind");
        EXPECT_EQ(c->ints.at("skinslide.patch"), k);
        EXPECT_EQ(c->ints.at("skinslide.resolution"), kLookup);
        EXPECT_EQ(c->ints.at("skinslide.corner00"), corner_ids[k][0]);
        EXPECT_EQ(c->ints.at("skinslide.corner10"), corner_ids[k][1]);
        EXPECT_EQ(c->ints.at("skinslide.corner11"), corner_ids[k][2]);
        EXPECT_EQ(c->ints.at("skinslide.corner01"), corner_ids[k][3]);
      }
      EXPECT_EQ(id.strings.at("skinslide.image"), "id");
      EXPECT_EQ(geom.strings.at("skinslide.image"), "geometry");
    }
}

// Read back, the images keep their promises: the frame's ID image is the one point location
// used; every vertex's pixel (or, for a vertex on a hole's edge, a neighbour: the candidates
// point location looks at) holds a triangle containing it; P there is within the surface's
// stretch times the distance to the pixel centre of the vertex's 3D position; coverage sums to
// the net's area; the slide field is slide_field()'s.
TEST(Dumps, ImagesMatchTheNetsTheyShow) {
  const Scene s;
  test::TempDir dir("dumps_properties");
  s.write(dir.path().string());
  for (int k = 0; k < 2; ++k) {
    const Patch& p = s.setup.patches[k];
    for (const std::string stem : {"bind", "f0007"}) {
      SCOPED_TRACE(stem + " patch " + std::to_string(k));
      const bool frame = stem != "bind";
      const Positions2& net = frame ? s.reports[k].frame_net : p.bind_net;
      const Positions3 points = s.local(p, frame ? s.frame_positions : s.bind_positions);
      const test::ExrContents id = test::read_exr(dump_path(dir / "", stem, k, "id.exr"));
      const test::ExrContents geom = test::read_exr(dump_path(dir / "", stem, k, "geom.exr"));
      const IdImage want_ids = frame ? s.reports[k].id_image : id_raster(net, p.triangles, kLookup);
      for (int j = 0; j < kLookup; ++j)
        for (int i = 0; i < kLookup; ++i) ASSERT_EQ(id.uint_at("id", i, j), want_ids.at(i, j));

      const double stretch = test::max_stretch(net, p.triangles, points);
      const std::vector<Index>& interior = p.free_vertices;
      for (size_t v = 0; v < net.size(); ++v) {
        const int i0 = std::min(kLookup - 1, int(std::floor(net[v].x() * kLookup)));
        const int j0 = std::min(kLookup - 1, int(std::floor(net[v].y() * kLookup)));
        const bool is_interior =
            std::find(interior.begin(), interior.end(), Index(v)) != interior.end();
        const int reach = is_interior ? 0 : 1;
        int found = 0;
        for (int j = std::max(0, j0 - reach); j <= std::min(kLookup - 1, j0 + reach); ++j)
          for (int i = std::max(0, i0 - reach); i <= std::min(kLookup - 1, i0 + reach); ++i) {
            const std::uint32_t t = id.uint_at("id", i, j);
            if (t == 0 || !test::contains(net, p.triangles[t - 1], net[v], 1e-12)) continue;
            ++found;
            const Vec2 c((i + 0.5) / kLookup, (j + 0.5) / kLookup);
            const Vec3 P(geom.float_at("P.X", i, j), geom.float_at("P.Y", i, j),
                         geom.float_at("P.Z", i, j));
            EXPECT_LE((P - points[v]).norm(), stretch * (c - net[v]).norm() + kFloatTol)
                << "vertex " << v << " pixel " << i << "," << j;
            EXPECT_LE((c - net[v]).norm(), (reach + 1) * std::sqrt(2.0) / kLookup);
          }
        EXPECT_GE(found, 1) << "vertex " << v << " at " << net[v].transpose();
      }

      const std::vector<float>& a = geom.floats.at("A");
      const double area = std::accumulate(a.begin(), a.end(), 0.0) / (kLookup * kLookup);
      const double want_area = k == 0 ? s.grid.area : s.holed.area;
      EXPECT_NEAR(area, want_area, kAreaTol);

      const GeometryImage g = geometry_image(net, p.triangles, points, kLookup);
      for (int j = 0; j < kLookup; ++j)
        for (int i = 0; i < kLookup; ++i) {
          const size_t n = size_t(j) * kLookup + i;
          ASSERT_EQ(geom.float_at("P.X", i, j), g.x[n]);
          ASSERT_EQ(geom.float_at("P.Z", i, j), g.z[n]);
          ASSERT_EQ(geom.float_at("A", i, j), g.coverage[n]);
        }
      if (frame) {
        const SlideField f = slide_field(p.bind_net, net, p.triangles, kLookup);
        float largest = 0;
        for (int j = 0; j < kLookup; ++j)
          for (int i = 0; i < kLookup; ++i) {
            const size_t n = size_t(j) * kLookup + i;
            ASSERT_EQ(geom.float_at("slide.X", i, j), f.x[n]);
            ASSERT_EQ(geom.float_at("slide.Y", i, j), f.y[n]);
            largest = std::max(largest, std::abs(f.x[n]));
          }
        EXPECT_GT(largest, 0.01f);  // the frame moved its free vertices by up to 0.03
      }
    }
  }
}

TEST(Dumps, GeometrySizeOption) {
  const Scene s;
  test::TempDir dir("dumps_geometry_size");
  DumpOptions options;
  options.geometry_size = 48;
  s.write(dir.path().string(), options);
  const test::ExrContents id = test::read_exr(dir / "bind.patch001.id.exr");
  const test::ExrContents geom = test::read_exr(dir / "bind.patch001.geom.exr");
  EXPECT_EQ(id.width, kLookup);
  EXPECT_EQ(geom.width, 48);
  EXPECT_EQ(geom.ints.at("skinslide.resolution"), 48);
  const std::vector<float>& a = geom.floats.at("A");
  EXPECT_NEAR(std::accumulate(a.begin(), a.end(), 0.0) / (48 * 48), s.holed.area, kAreaTol);
}

TEST(Dumps, SameInputsSameBytes) {
  const Scene s;
  test::TempDir one("dumps_bytes_1"), two("dumps_bytes_2");
  s.write(one.path().string());
  s.write(two.path().string());
  const std::vector<std::string> names = listing(one.path());
  ASSERT_EQ(names, listing(two.path()));
  for (const std::string& name : names)
    EXPECT_EQ(read_file(one / name), read_file(two / name)) << name;
}

TEST(Dumps, PreviewIsAPngOfTheRequestedSize) {
  const Scene s;
  test::TempDir dir("dumps_preview");
  DumpOptions options;
  options.preview_size = 200;
  s.write(dir.path().string(), options);
  const std::string png = read_file(dir / "preview/f0007.patch000.png");
  ASSERT_GE(png.size(), 24u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR: width and height, big-endian, at bytes 16..23.
  auto be32 = [&](size_t o) {
    return (std::uint32_t(std::uint8_t(png[o])) << 24) |
           (std::uint32_t(std::uint8_t(png[o + 1])) << 16) |
           (std::uint32_t(std::uint8_t(png[o + 2])) << 8) | std::uint32_t(std::uint8_t(png[o + 3]));
  };
  EXPECT_EQ(be32(16), 200u);
  EXPECT_EQ(be32(20), 200u);
}

TEST(Dumps, ExrheaderReadsADump) {
  const Scene s;
  test::TempDir dir("dumps_exrheader");
  s.write(dir.path().string());
  const test::RunResult r = test::run("exrheader '" + (dir / "f0007.patch001.geom.exr") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* want :
       {"P.X, 32-bit floating-point", "P.Y, 32-bit floating-point", "P.Z, 32-bit floating-point",
        "A, 32-bit floating-point", "slide.X, 32-bit floating-point",
        "slide.Y, 32-bit floating-point", "skinslide.corner11", "1048", "frames/f0007.obj"})
    EXPECT_NE(r.output.find(want), std::string::npos) << want << " not in:\n" << r.output;
}

TEST(Dumps, FrameWithoutItsIdImageIsAnInternalError) {
  Scene s;
  s.reports[0].id_image = IdImage{};
  test::TempDir dir("dumps_no_id");
  try {
    write_frame_dumps(dir.path().string(), "f.obj", s.setup, s.frame_positions, s.reports,
                      {.id_image_size = kLookup});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Internal);
    EXPECT_NE(std::string(e.what()).find("id_image_size"), std::string::npos) << e.what();
  }
}

TEST(Dumps, UnwritableFolderIsAnOutputError) {
  const Scene s;
  test::TempDir dir("dumps_unwritable");
  write_file_atomic(dir / "file", "x");
  try {
    write_bind_dumps(dir / "file/sub", "bind.obj", s.setup, s.bind_positions,
                     {.id_image_size = kLookup});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Output);
  }
}

TEST(Dumps, StemsThatWouldCollideAreRejected) {
  EXPECT_NO_THROW(check_dump_stems({"frames/f0001.obj", "frames/f0002.obj"}));
  for (const std::vector<std::string>& bad :
       {std::vector<std::string>{"frames/bind.obj"},
        std::vector<std::string>{"a/f0001.obj", "b/f0001.obj"},
        std::vector<std::string>{"f0001.obj", "f0001.glb"}}) {
    try {
      check_dump_stems(bad);
      FAIL() << bad.back();
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Usage);
      EXPECT_NE(std::string(e.what()).find(bad.back()), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace skinslide

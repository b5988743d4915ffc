#include "pipeline/dumps.h"

#include <cstdio>
#include <filesystem>
#include <map>
#include <system_error>

#include "core/check.h"
#include "core/error.h"
#include "core/version.h"
#include "dump/geometry_image.h"
#include "dump/preview.h"
#include "dump/slide_field.h"
#include "io/exr.h"
#include "io/png.h"

namespace skinslide {
namespace {

void make_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(ErrorKind::Output, dir + ": cannot create folder: " + ec.message());
}

// The attributes every dump carries (README "Dumps", header attributes).
void describe(ExrImage& image, const std::string& source, const BindSetup& setup, int index,
              const char* net, const char* kind) {
  image.string_attributes = {{"skinslide.version", version()},
                             {"skinslide.source", source},
                             {"skinslide.net", net},
                             {"skinslide.image", kind}};
  image.int_attributes = {{"skinslide.patch", index}, {"skinslide.resolution", image.width}};
  image.string_attributes.push_back(
      {"skinslide.method", method_name(method_options(setup.method))});
  const auto corners =
      square_corners(setup.method, static_cast<size_t>(index), setup.patches[index]);
  if (!corners) return;  // the elastic method's chart is a disk: no corners
  static const char* const kCornerNames[4] = {"skinslide.corner00", "skinslide.corner10",
                                              "skinslide.corner11", "skinslide.corner01"};
  for (int k = 0; k < 4; ++k)
    image.int_attributes.emplace_back(kCornerNames[k], corners->vertices[k]);
}

void write_id(const std::string& path, const IdImage& ids, const std::string& source,
              const BindSetup& setup, int index, const char* net) {
  ExrImage image;
  image.width = image.height = ids.size;
  image.uint_channels = {{"id", ids.ids}};
  describe(image, source, setup, index, net, "id");
  write_exr(path, image);
}

void write_geometry(const std::string& path, const GeometryImage& geometry, const SlideField* slide,
                    const std::string& source, const BindSetup& setup, int index, const char* net) {
  ExrImage image;
  image.width = image.height = geometry.size;
  image.float_channels = {
      {"P.X", geometry.x}, {"P.Y", geometry.y}, {"P.Z", geometry.z}, {"A", geometry.coverage}};
  if (slide) {
    image.float_channels.push_back({"slide.X", slide->x});
    image.float_channels.push_back({"slide.Y", slide->y});
  }
  describe(image, source, setup, index, net, "geometry");
  write_exr(path, image);
}

Positions3 local_points(const Patch& patch, const Positions3& positions) {
  Positions3 points(patch.vertices.size());
  for (size_t k = 0; k < patch.vertices.size(); ++k) {
    const Index v = patch.vertices[k];
    SKINSLIDE_CHECK(v >= 0 && static_cast<size_t>(v) < positions.size(), "patch vertex id");
    points[k] = positions[v];
  }
  return points;
}

bool has_net(const Patch& patch) {
  return !patch.skipped && !patch.bind_net.empty() &&
         patch.bind_net.size() == patch.vertices.size();
}

int geometry_size(const DumpOptions& options) {
  const int size = options.geometry_size > 0 ? options.geometry_size : options.id_image_size;
  SKINSLIDE_CHECK(size >= 1, "geometry image size");
  return size;
}

}  // namespace

std::string dump_stem(const std::string& mesh_path) {
  return std::filesystem::path(mesh_path).stem().string();
}

std::string dump_path(const std::string& dir, const std::string& stem, int patch,
                      const std::string& suffix) {
  char index[16];
  std::snprintf(index, sizeof index, "%03d", patch);
  return (std::filesystem::path(dir) / (stem + ".patch" + index + "." + suffix)).string();
}

void check_dump_stems(const std::vector<std::string>& frame_paths) {
  std::map<std::string, std::string> seen;
  for (const std::string& path : frame_paths) {
    const std::string stem = dump_stem(path);
    if (stem == "bind")
      throw Error(ErrorKind::Usage, path + ": its dumps would overwrite the bind's (" + stem +
                                        ".patch*); rename the frame");
    const auto [it, fresh] = seen.emplace(stem, path);
    if (!fresh)
      throw Error(ErrorKind::Usage, path + " and " + it->second +
                                        ": their dumps would have the same names (" + stem +
                                        ".patch*); rename one");
  }
}

void write_bind_dumps(const std::string& dump_dir, const std::string& bind_path,
                      const BindSetup& setup, const Positions3& bind_positions,
                      const DumpOptions& options) {
  make_dir(dump_dir);
  const int size = geometry_size(options);
  for (size_t k = 0; k < setup.patches.size(); ++k) {
    const Patch& patch = setup.patches[k];
    if (!has_net(patch)) continue;
    const int index = static_cast<int>(k);
    const IdImage ids = id_raster(patch.bind_net, patch.triangles, options.id_image_size);
    write_id(dump_path(dump_dir, "bind", index, "id.exr"), ids, bind_path, setup, index, "bind");
    const GeometryImage geometry =
        geometry_image(patch.bind_net, patch.triangles, local_points(patch, bind_positions), size);
    write_geometry(dump_path(dump_dir, "bind", index, "geom.exr"), geometry, nullptr, bind_path,
                   setup, index, "bind");
  }
}

void write_frame_dumps(const std::string& dump_dir, const std::string& frame_path,
                       const BindSetup& setup, const Positions3& frame_positions,
                       const std::vector<PatchFrameReport>& reports, const DumpOptions& options) {
  SKINSLIDE_CHECK(reports.size() == setup.patches.size(), "one report per patch");
  make_dir(dump_dir);
  const std::string stem = dump_stem(frame_path);
  const int size = geometry_size(options);
  for (size_t k = 0; k < setup.patches.size(); ++k) {
    const Patch& patch = setup.patches[k];
    const PatchFrameReport& report = reports[k];
    if (!has_net(patch) || report.frame_net.size() != patch.bind_net.size()) continue;
    const int index = static_cast<int>(k);
    SKINSLIDE_CHECK(report.id_image.size > 0,
                    "frame dumps need the ID image: slide_frame(..., {.id_image_size = N})");
    write_id(dump_path(dump_dir, stem, index, "id.exr"), report.id_image, frame_path, setup, index,
             "frame");
    // The paper's frame has a net of its own; the elastic method's frame lies over the chart.
    const Positions2& frame_net = report.frame_in_bind_net ? patch.bind_net : report.frame_net;
    const GeometryImage geometry =
        geometry_image(frame_net, patch.triangles, local_points(patch, frame_positions), size);
    const SlideField slide = slide_field(patch.bind_net, report.frame_net, patch.triangles, size);
    write_geometry(dump_path(dump_dir, stem, index, "geom.exr"), geometry, &slide, frame_path,
                   setup, index, "frame");
  }
}

void write_previews(const std::string& preview_dir, const std::string& frame_path,
                    const BindSetup& setup, const std::vector<PatchFrameReport>& reports,
                    const DumpOptions& options) {
  SKINSLIDE_CHECK(reports.size() == setup.patches.size(), "one report per patch");
  make_dir(preview_dir);
  const std::string stem = dump_stem(frame_path);
  for (size_t k = 0; k < setup.patches.size(); ++k) {
    const Patch& patch = setup.patches[k];
    const PatchFrameReport& report = reports[k];
    if (!has_net(patch) || report.frame_net.size() != patch.bind_net.size()) continue;
    const RgbImage image =
        preview_image(patch.bind_net, report.frame_net, patch.bars, patch.free_vertices,
                      options.preview_size, PreviewColors{}, report.frame_in_bind_net);
    write_png(dump_path(preview_dir, stem, static_cast<int>(k), "png"), image.width, image.height,
              image.rgb);
  }
}

}  // namespace skinslide

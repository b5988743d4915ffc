#include "compare/compare_outputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "core/error.h"
#include "core/file_extension.h"
#include "core/number_format.h"
#include "io/mesh_formats.h"
#include "io/obj_read.h"
#include "io/point_cache.h"

namespace skinslide {
namespace {

namespace fs = std::filesystem;

enum class OutputKind { Folder, Mesh, Cache };

// A folder's names that list without their frames are given this many, then "and N more".
constexpr std::size_t kNamesListed = 3;

bool is_mesh_name(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".obj" || ext == ".gltf" || ext == ".glb";
}

OutputKind output_kind(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw_input(path, 0, "no such file or folder");
  if (fs::is_directory(status)) return OutputKind::Folder;
  if (cache_format(path)) return OutputKind::Cache;
  if (is_mesh_name(path)) return OutputKind::Mesh;
  throw Error(ErrorKind::Usage, path +
                                    ": neither a folder, a mesh (.obj, .gltf, .glb) nor a point "
                                    "cache (.pc2, .mdd)");
}

// The frames a folder holds: its mesh and cache files by name (not its subfolders, a glTF's
// .bin, a report, nor a dot-file such as a write's temporary).
std::vector<std::string> frame_names(const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.' || !it->is_regular_file()) continue;
    if (is_mesh_name(name) || cache_format(name)) names.push_back(name);
  }
  if (ec) throw_input(folder, 0, "cannot be listed: " + ec.message());
  if (names.empty())
    throw_input(folder, 0, "holds no frame (no .obj, .gltf, .glb, .pc2 or .mdd file)");
  std::sort(names.begin(), names.end());
  return names;
}

std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size() && i < kNamesListed; ++i)
    text += (i ? ", " : "") + names[i];
  if (names.size() > kNamesListed)
    text += " and " + std::to_string(names.size() - kNamesListed) + " more";
  return text;
}

std::vector<std::string> missing_from(const std::vector<std::string>& names,
                                      const std::vector<std::string>& in) {
  std::vector<std::string> missing;
  std::set_difference(names.begin(), names.end(), in.begin(), in.end(),
                      std::back_inserter(missing));
  return missing;
}

std::string joined(const std::string& folder, const std::string& name) {
  return (fs::path(folder) / name).string();
}

// The names both folders hold. Without `common`, both hold the same names, else the counts and
// what each lacks; with it, what each lacks goes to `result`'s only_in_a/only_in_b.
std::vector<std::string> paired_frames(const std::string& a,
                                       const std::vector<std::string>& names_a,
                                       const std::string& b,
                                       const std::vector<std::string>& names_b, bool common,
                                       CompareResult& result) {
  const std::vector<std::string> not_in_b = missing_from(names_a, names_b);
  const std::vector<std::string> not_in_a = missing_from(names_b, names_a);
  if (not_in_b.empty() && not_in_a.empty()) return names_a;
  if (common) {
    for (const std::string& name : not_in_b) result.only_in_a.push_back(joined(a, name));
    for (const std::string& name : not_in_a) result.only_in_b.push_back(joined(b, name));
    std::vector<std::string> both;
    std::set_intersection(names_a.begin(), names_a.end(), names_b.begin(), names_b.end(),
                          std::back_inserter(both));
    if (both.empty())
      throw Error(ErrorKind::Input, a + " and " + b + " have no frame in common (" + a + ": " +
                                        listed(names_a) + "; " + b + ": " + listed(names_b) + ")");
    return both;
  }
  std::string what = a + " has " + std::to_string(names_a.size()) + " frames, " + b + " " +
                     std::to_string(names_b.size());
  if (!not_in_b.empty()) what += "; missing from " + b + ": " + listed(not_in_b);
  if (!not_in_a.empty()) what += "; missing from " + a + ": " + listed(not_in_a);
  throw Error(ErrorKind::Input, what + " (--common compares the frames both hold)");
}

// The 1-based line of OBJ vertex v's `v` statement.
long vertex_line(const ObjText& text, Index v) {
  const auto begin = text.bytes.begin();
  return 1 + std::count(begin, begin + static_cast<long>(text.coordinate_spans[v][0]), '\n');
}

// What every frame is compared with: the bind's diagonal and faces when it was given.
class Comparison {
 public:
  Comparison(const CompareOptions& options, CompareResult& result,
             const std::function<void(const ComparedFrame&)>& frame_done)
      : options_(options), result_(result), frame_done_(frame_done) {
    if (!options.bind.empty()) {
      bind_ = read_mesh_file(options.bind, options.mesh);
      result_.diagonal = diagonal_of(bind_->mesh.positions, options.bind);
      result_.diagonal_from = options.bind;
    }
  }

  void meshes(const std::string& a, const std::string& b);
  void caches(const std::string& a, const std::string& b);

 private:
  // The unit of `from`'s distances: the bind's diagonal, else that of `positions` (A's frame).
  double frame_diagonal(const Positions3& positions, const std::string& from) const;
  static double diagonal_of(const Positions3& positions, const std::string& from);
  void compare_samples(const CacheReader& ra, const CacheReader& rb, std::size_t ka,
                       std::size_t kb, const PolyMesh& faces);
  void require_bind_vertices(const std::string& path, std::size_t count) const;
  void add(ComparedFrame frame);

  const CompareOptions& options_;
  CompareResult& result_;
  const std::function<void(const ComparedFrame&)>& frame_done_;
  std::optional<MeshFile> bind_;
};

double Comparison::diagonal_of(const Positions3& positions, const std::string& from) {
  const double diagonal = bounding_box_diagonal(positions);
  if (!(diagonal > 0))
    throw_input(from, 0, "its bounding box is a single point: no diagonal to measure distances in");
  return diagonal;
}

double Comparison::frame_diagonal(const Positions3& positions, const std::string& from) const {
  return bind_ ? result_.diagonal : diagonal_of(positions, from);
}

void Comparison::require_bind_vertices(const std::string& path, std::size_t count) const {
  if (bind_ && count != bind_->mesh.positions.size())
    throw_input(path, 0,
                "has " + std::to_string(count) + " vertices; the bind (" + bind_->path + ") has " +
                    std::to_string(bind_->mesh.positions.size()));
}

void Comparison::add(ComparedFrame frame) {
  frame.differs = differs(frame.difference, options_.tolerance);
  if (frame_done_) frame_done_(frame);
  result_.frames.push_back(std::move(frame));
}

// A's faces against B's: the first that differs, or the counts.
void require_same_faces(const MeshFile& a, const MeshFile& b) {
  const PolyMesh& fa = a.mesh;
  const PolyMesh& fb = b.mesh;
  if (const Index f = first_differing_face(fa, fb); f >= 0)
    throw Error(ErrorKind::Input, b.where_face(f) + ": face " + std::to_string(f) +
                                      " differs from " + a.where_face(f) +
                                      ": the two are not one mesh");
  if (fa.face_count() != fb.face_count())
    throw_input(b.path, 0,
                "has " + std::to_string(fb.face_count()) + " faces; " + a.path + " has " +
                    std::to_string(fa.face_count()));
}

void Comparison::meshes(const std::string& a, const std::string& b) {
  const MeshFile fa = read_mesh_file(a, options_.mesh);
  const MeshFile fb = read_mesh_file(b, options_.mesh);
  if (fa.mesh.vertex_count() != fb.mesh.vertex_count())
    throw_input(b, 0,
                "has " + std::to_string(fb.mesh.vertex_count()) + " vertices; " + a + " has " +
                    std::to_string(fa.mesh.vertex_count()));
  require_same_faces(fa, fb);
  require_bind_vertices(a, fa.mesh.positions.size());
  ComparedFrame frame;
  frame.a = a;
  frame.b = b;
  frame.diagonal = frame_diagonal(fa.mesh.positions, a);
  frame.difference = frame_difference(fa.mesh.positions, fb.mesh.positions, fa.mesh,
                                      frame.diagonal, options_.tolerance);
  if (fa.obj && frame.difference.vertex >= 0)
    frame.vertex_at = a + ":" + std::to_string(vertex_line(*fa.obj, frame.difference.vertex));
  add(std::move(frame));
}

// "a.pc2 sample 3 (frame 4)"
std::string sample_name(const std::string& path, const CacheHeader& header, std::size_t k) {
  return path + " sample " + std::to_string(k) + " (frame " +
         std::to_string(sample_frame(header, k)) + ")";
}

// The caches hold points of one mesh in one format.
void require_same_points(const CacheReader& a, const CacheReader& b) {
  const CacheHeader& ha = a.header();
  const CacheHeader& hb = b.header();
  if (ha.format != hb.format)
    throw_input(b.path(), 0,
                std::string("is a ") + to_string(hb.format) + " cache, " + a.path() + " a " +
                    to_string(ha.format) + " one: compare caches of one format");
  if (ha.points != hb.points)
    throw_input(b.path(), 0,
                "has " + std::to_string(hb.points) + " points; " + a.path() + " has " +
                    std::to_string(ha.points));
}

// The caches hold the same frames, sample by sample.
void require_same_samples(const CacheReader& a, const CacheReader& b) {
  const CacheHeader& ha = a.header();
  const CacheHeader& hb = b.header();
  if (ha.samples != hb.samples)
    throw_input(b.path(), 0,
                "has " + std::to_string(hb.samples) + " samples; " + a.path() + " has " +
                    std::to_string(ha.samples));
  for (std::size_t k = 0; k < static_cast<std::size_t>(ha.samples); ++k) {
    const bool same_time = ha.format != CacheFormat::Mdd || ha.times[k] == hb.times[k];
    if (sample_frame(ha, k) == sample_frame(hb, k) && same_time) continue;
    throw_input(
        b.path(), 0,
        "sample " + std::to_string(k) + " is frame " + std::to_string(sample_frame(hb, k)) +
            (ha.format == CacheFormat::Mdd ? " at " + format_float(hb.times[k]) + " s" : "") +
            "; in " + a.path() + " frame " + std::to_string(sample_frame(ha, k)) +
            (ha.format == CacheFormat::Mdd ? " at " + format_float(ha.times[k]) + " s" : "") +
            ": the caches do not hold the same frames (--common compares the frames both "
            "hold)");
  }
}

// What pairs a sample with the other cache's: PC2 its frame number, MDD its time (an MDD's
// frame numbers are its sample indices, which a chunk starts again from 0).
std::string sample_key(const CacheHeader& header, std::size_t k) {
  return header.format == CacheFormat::Mdd ? format_float(header.times[k]) + " s"
                                           : std::to_string(sample_frame(header, k));
}

// The samples (index in A, index in B) both caches hold, in A's order; those of one only go to
// `result`'s only_in_a/only_in_b.
std::vector<std::pair<std::size_t, std::size_t>> common_samples(const CacheReader& a,
                                                                const CacheReader& b,
                                                                CompareResult& result) {
  std::map<std::string, std::size_t> in_b;
  const auto samples = [](const CacheReader& r) {
    return static_cast<std::size_t>(r.header().samples);
  };
  for (std::size_t k = 0; k < samples(b); ++k) in_b.emplace(sample_key(b.header(), k), k);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  std::set<std::size_t> paired_b;
  for (std::size_t k = 0; k < samples(a); ++k) {
    const auto it = in_b.find(sample_key(a.header(), k));
    if (it == in_b.end()) {
      result.only_in_a.push_back(sample_name(a.path(), a.header(), k));
      continue;
    }
    pairs.emplace_back(k, it->second);
    paired_b.insert(it->second);
  }
  for (std::size_t k = 0; k < samples(b); ++k)
    if (!paired_b.count(k)) result.only_in_b.push_back(sample_name(b.path(), b.header(), k));
  if (pairs.empty())
    throw_input(b.path(), 0, "holds no frame of " + a.path() + "'s: no sample in common");
  return pairs;
}

void Comparison::compare_samples(const CacheReader& ra, const CacheReader& rb, std::size_t ka,
                                 std::size_t kb, const PolyMesh& faces) {
  const Positions3 pa = sample_positions(ra.sample(ka));
  const Positions3 pb = sample_positions(rb.sample(kb));
  ComparedFrame frame;
  frame.a = sample_name(ra.path(), ra.header(), ka);
  frame.b = sample_name(rb.path(), rb.header(), kb);
  frame.diagonal = frame_diagonal(pa, frame.a);
  frame.difference = frame_difference(pa, pb, faces, frame.diagonal, options_.tolerance);
  add(std::move(frame));
}

void Comparison::caches(const std::string& a, const std::string& b) {
  const CacheReader ra(a);
  const CacheReader rb(b);
  require_same_points(ra, rb);
  if (!options_.common) require_same_samples(ra, rb);
  require_bind_vertices(a, static_cast<std::size_t>(ra.header().points));
  static const PolyMesh kNoFaces;
  const PolyMesh& faces = bind_ ? bind_->mesh : kNoFaces;
  if (!bind_) result_.faces_checked = false;
  if (options_.common) {
    for (const auto& [ka, kb] : common_samples(ra, rb, result_))
      compare_samples(ra, rb, ka, kb, faces);
    return;
  }
  for (std::size_t k = 0; k < static_cast<std::size_t>(ra.header().samples); ++k)
    compare_samples(ra, rb, k, k, faces);
}

}  // namespace

std::size_t CompareResult::differing() const {
  return static_cast<std::size_t>(std::count_if(frames.begin(), frames.end(),
                                                [](const ComparedFrame& f) { return f.differs; }));
}

long long CompareResult::largest() const {
  long long best = -1;
  for (std::size_t i = 0; i < frames.size(); ++i)
    if (best < 0 || frames[i].difference.max_distance > frames[best].difference.max_distance)
      best = static_cast<long long>(i);
  return best;
}

CompareResult compare_outputs(const std::string& a, const std::string& b,
                              const CompareOptions& options,
                              const std::function<void(const ComparedFrame&)>& frame_done) {
  if (!std::isfinite(options.tolerance) || options.tolerance < 0)
    throw Error(ErrorKind::Usage, "--tolerance " + format_double(options.tolerance) +
                                      ": a distance in diagonals, 0 or more");
  const OutputKind ka = output_kind(a);
  const OutputKind kb = output_kind(b);
  if (ka != kb)
    throw Error(ErrorKind::Usage, a + " and " + b +
                                      " are not alike: compare two folders, two meshes or two "
                                      "caches");
  CompareResult result;
  result.a = a;
  result.b = b;
  result.tolerance = options.tolerance;
  result.faces_checked = true;  // until a cache is compared without a bind
  Comparison comparison(options, result, frame_done);
  const auto compare_pair = [&](const std::string& fa, const std::string& fb) {
    if (cache_format(fa))
      comparison.caches(fa, fb);
    else
      comparison.meshes(fa, fb);
  };
  if (ka != OutputKind::Folder) {
    compare_pair(a, b);
    return result;
  }
  const std::vector<std::string> names_a = frame_names(a);
  const std::vector<std::string> names_b = frame_names(b);
  for (const std::string& name : paired_frames(a, names_a, b, names_b, options.common, result))
    compare_pair(joined(a, name), joined(b, name));
  return result;
}

}  // namespace skinslide

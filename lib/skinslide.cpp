#include "skinslide.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <numeric>
#include <optional>
#include <string>
#include <thread>

#include "core/number_format.h"
#include "pipeline/frame_window.h"

namespace skinslide {
namespace {

// Positions are handed on in place: a Vec3 is three doubles, with a double's alignment.
static_assert(sizeof(Vec3) == 3 * sizeof(double) && alignof(Vec3) == alignof(double));

std::span<const Vec3> as_points(std::span<const double> xyz) {
  return {reinterpret_cast<const Vec3*>(xyz.data()), xyz.size() / 3};
}

PolyMesh poly_mesh(const Bind& bind) {
  if (bind.positions.size() % 3 != 0)
    throw Error(ErrorKind::Input, "the bind has " + std::to_string(bind.positions.size()) +
                                      " coordinates, not 3 per vertex");
  PolyMesh mesh;
  const std::span<const Vec3> points = as_points(bind.positions);
  mesh.positions.assign(points.begin(), points.end());
  for (size_t v = 0; v < mesh.positions.size(); ++v)
    if (!mesh.positions[v].allFinite())
      throw Error(ErrorKind::Input, "bind vertex " + std::to_string(v) + " is not finite");
  const Index vertex_count = mesh.vertex_count();
  const bool triangles = bind.face_sizes.empty();
  if (triangles && bind.face_vertices.size() % 3 != 0)
    throw Error(ErrorKind::Input, "the faces have " + std::to_string(bind.face_vertices.size()) +
                                      " vertex ids, not 3 per triangle");
  const size_t face_count = triangles ? bind.face_vertices.size() / 3 : bind.face_sizes.size();
  size_t at = 0;
  std::vector<Index> face;
  for (size_t f = 0; f < face_count; ++f) {
    const Index size = triangles ? 3 : bind.face_sizes[f];
    if (size < 3 || at + static_cast<size_t>(size) > bind.face_vertices.size())
      throw Error(ErrorKind::Input, "face " + std::to_string(f) + " has " + std::to_string(size) +
                                        " corners" +
                                        (size < 3 ? "" : ", past the end of the face list"));
    face.assign(bind.face_vertices.begin() + at, bind.face_vertices.begin() + at + size);
    for (Index v : face)
      if (v < 0 || v >= vertex_count)
        throw Error(ErrorKind::Input, "face " + std::to_string(f) + ": vertex " +
                                          std::to_string(v) + " is out of range (the bind has " +
                                          std::to_string(vertex_count) + " vertices)");
    mesh.add_face(face);
    at += static_cast<size_t>(size);
  }
  if (at != bind.face_vertices.size())
    throw Error(ErrorKind::Input, "the face sizes add up to " + std::to_string(at) +
                                      " corners; the face list has " +
                                      std::to_string(bind.face_vertices.size()));
  return mesh;
}

std::vector<std::vector<Index>> selections(const std::vector<std::vector<Index>>& patches,
                                           Index face_count) {
  std::vector<std::vector<Index>> out;
  for (size_t s = 0; s < patches.size(); ++s) {
    std::vector<Index> faces = patches[s];
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    if (faces.empty()) throw Error(ErrorKind::Input, "patch " + std::to_string(s) + " is empty");
    if (faces.front() < 0 || faces.back() >= face_count)
      throw Error(ErrorKind::Input,
                  "patch " + std::to_string(s) + ": face " +
                      std::to_string(faces.front() < 0 ? faces.front() : faces.back()) +
                      " is out of range (the bind has " + std::to_string(face_count) + " faces)");
    out.push_back(std::move(faces));
  }
  return out;
}

void check_span(std::span<const double> xyz, Index vertex_count, const char* what) {
  if (xyz.size() != 3 * static_cast<size_t>(vertex_count))
    throw Error(ErrorKind::Input, std::string(what) + " has " + std::to_string(xyz.size()) +
                                      " coordinates; the bind has " + std::to_string(vertex_count) +
                                      " vertices (x y z each)");
}

// A frame and its output: #V x 3 each, the frame finite.
void check_frame(const BindSetup& setup, std::span<const double> frame, std::span<const double> out,
                 const char* frame_name, const char* out_name) {
  check_span(frame, setup.vertex_count, frame_name);
  check_span(out, setup.vertex_count, out_name);
  for (size_t k = 0; k < frame.size(); ++k)
    if (!std::isfinite(frame[k]))
      throw Error(ErrorKind::Input,
                  std::string(frame_name) + ": vertex " + std::to_string(k / 3) + " is not finite");
}

std::string frame_name(size_t k) { return "frame " + std::to_string(k); }

// slide_sequence's arguments: the window's range, method and ends, one output a frame, each frame
// and output as slide() checks them.
void check_sequence(const BindSetup& setup, std::span<const std::span<const double>> frames,
                    std::span<const std::span<double>> outs, int window, WindowEnds ends) {
  if (window < 0 || window > kMaxWindow)
    throw Error(ErrorKind::Usage, "window " + std::to_string(window) + " is out of its range [0, " +
                                      std::to_string(kMaxWindow) + "]");
  if (window == 0 && ends == WindowEnds::Cycle)
    throw Error(ErrorKind::Usage, "cycle ends say where a window's frames end: give a window too");
  if (window > 0 && !std::holds_alternative<ElasticMethod>(setup.method))
    throw Error(ErrorKind::Usage, "a window is the elastic method's; this set-up slides by the " +
                                      method_name(method_options(setup.method)) + " method");
  if (frames.size() != outs.size())
    throw Error(ErrorKind::Input, std::to_string(frames.size()) + " frames and " +
                                      std::to_string(outs.size()) + " outputs");
  for (size_t k = 0; k < frames.size(); ++k)
    check_frame(setup, frames[k], outs[k], frame_name(k).c_str(),
                ("output " + std::to_string(k)).c_str());
}

// A slid frame written into `out`: the frame, with every slid vertex moved. Returns its reports.
std::vector<PatchFrameReport> written(FrameResult result, std::span<const double> frame,
                                      std::span<double> out) {
  std::copy(frame.begin(), frame.end(), out.begin());
  for (size_t k = 0; k < result.slid.vertex.size(); ++k) {
    const Vec3& p = result.slid.position[k];
    double* xyz = out.data() + 3 * static_cast<size_t>(result.slid.vertex[k]);
    // A vertex the slide left where the frame has it keeps the frame's bits (a -0 stays -0), as
    // the command's OBJ writer keeps its text: the module gives the command's bits.
    if (p.x() == xyz[0] && p.y() == xyz[1] && p.z() == xyz[2]) continue;
    xyz[0] = p.x();
    xyz[1] = p.y();
    xyz[2] = p.z();
  }
  for (PatchFrameReport& r : result.patches) r.frame_net = {};  // the nets are dumps' business
  return std::move(result.patches);
}

}  // namespace

void check_options(const SlideOptions& options) {
  std::visit(
      [](const auto& o) {
        using Options = std::decay_t<decltype(o)>;
        check_ranges(option_table<Options>(), o);
      },
      options);
}

BindSetup set_up(const Bind& bind, const std::vector<std::vector<Index>>& patches,
                 const SlideOptions& options, const SlideControls& controls, unsigned threads) {
  check_options(options);
  const PolyMesh mesh = poly_mesh(bind);
  return bind_setup(mesh, selections(patches, mesh.face_count()), options, controls, {}, threads);
}

std::vector<PatchFrameReport> slide(const BindSetup& setup, std::span<const double> frame,
                                    std::span<double> out, bool edge_spread) {
  check_frame(setup, frame, out, "the frame", "the output");
  return written(slide_frame(setup, as_points(frame), {.edge_spread = edge_spread}), frame, out);
}

std::vector<std::vector<PatchFrameReport>> slide_sequence(
    const BindSetup& setup, std::span<const std::span<const double>> frames,
    std::span<const std::span<double>> outs, int window, bool edge_spread, unsigned threads,
    WindowEnds ends) {
  check_sequence(setup, frames, outs, window, ends);
  const size_t count = frames.size();
  std::vector<size_t> all(count);
  std::iota(all.begin(), all.end(), size_t{0});
  std::optional<RelaxationStore> store;
  WindowPlan plan = ordered_window_plan(window, count);
  plan.cycle = ends == WindowEnds::Cycle;
  if (window > 0)
    store.emplace(std::move(plan), all, [&](size_t k) {
      return labelled(frame_name(k), [&] { return relax_frame(setup, as_points(frames[k])); });
    });
  std::vector<std::vector<PatchFrameReport>> reports(count);
  std::vector<std::exception_ptr> errors(count);
  const FrameExtras extras{.edge_spread = edge_spread};
  const auto slide_one = [&](size_t k) {
    try {
      std::optional<WindowedFrame> mean;
      std::vector<RelaxationStore::Member> members;
      if (store) {
        members = store->window(k);
        rethrow_window_error(members, k, frame_name(k));  // relaxations' errors are labelled
        mean = windowed_frame(members, k);
      }
      reports[k] = labelled(frame_name(k), [&] {
        return written(slide_frame(setup, as_points(frames[k]), extras, mean ? &*mean : nullptr),
                       frames[k], outs[k]);
      });
    } catch (...) {
      errors[k] = std::current_exception();
    }
    if (store) store->done(k);
  };
  std::atomic<size_t> next{0};
  const auto worker = [&] {
    for (size_t k; (k = next++) < count;) slide_one(k);
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < std::min<size_t>(std::max(threads, 1u), count); ++t)
    pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)  // the first in the sequence, whatever the threads
    if (e) std::rethrow_exception(e);
  return reports;
}

}  // namespace skinslide

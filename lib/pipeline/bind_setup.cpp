#include "pipeline/bind_setup.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <string>
#include <thread>

#include "core/check.h"
#include "core/error.h"
#include "mesh/measures.h"
#include "mesh/outer_loop.h"

namespace skinslide {
namespace {

Positions3 gather(const Positions3& positions, const std::vector<Index>& ids) {
  Positions3 out(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) out[i] = positions[ids[i]];
  return out;
}

double diagonal(const Positions3& points) {
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

// What the controls ask of one patch; mesh vertex ids.
struct PatchChoice {
  Index outer_vertex = -1;  ///< a vertex on the chosen outer loop; -1 = automatic
  std::string outer_source;
  bool has_corners = false;
  std::array<Index, 4> corners{};
  std::string corners_source;
};

std::string corners_text(const std::array<Index, 4>& c) {
  return "--corners " + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," +
         std::to_string(c[2]) + "," + std::to_string(c[3]);
}

int loop_of(const PatchComponent& comp, Index v) {
  for (size_t l = 0; l < comp.loops.size(); ++l)
    if (std::find(comp.loops[l].begin(), comp.loops[l].end(), v) != comp.loops[l].end())
      return static_cast<int>(l);
  return -1;
}

void check_vertex(const std::string& option, Index v, Index vertex_count) {
  if (v < 0 || v >= vertex_count)
    throw Error(ErrorKind::Usage, option + ": vertex " + std::to_string(v) +
                                      " is out of range (the bind has " +
                                      std::to_string(vertex_count) + " vertices, numbered 0 to " +
                                      std::to_string(vertex_count - 1) + ")");
}

// Resolves the corner and outer-loop choices to the patches whose loops they name. A choice
// names a loop, not a patch number: patch order is an implementation detail a TD never sees,
// while a vertex id can be read off the rig. A loop shared by two patches serves both.
std::vector<PatchChoice> patch_choices(const std::vector<PatchComponent>& comps,
                                       const SlideControls& controls, Index vertex_count) {
  std::vector<PatchChoice> choices(comps.size());
  auto conflict = [](size_t c, const std::string& a, const std::string& b) {
    return Error(ErrorKind::Usage, "patch " + std::to_string(c) + ": " + a + " and " + b +
                                       " choose different outer loops or corners for it");
  };
  for (Index v : controls.outer_loop_vertices) {
    const std::string source = "--outer-loop-vertex " + std::to_string(v);
    check_vertex(source, v, vertex_count);
    bool used = false;
    for (size_t c = 0; c < comps.size(); ++c) {
      const int l = loop_of(comps[c], v);
      if (l < 0) continue;
      used = true;
      PatchChoice& ch = choices[c];
      if (ch.outer_vertex >= 0 && loop_of(comps[c], ch.outer_vertex) != l)
        throw conflict(c, ch.outer_source, source);
      ch.outer_vertex = v;
      ch.outer_source = source;
    }
    if (!used)
      throw Error(ErrorKind::Usage, source + ": vertex " + std::to_string(v) +
                                        " is not on a boundary loop of any patch");
  }
  for (const auto& q : controls.corners) {
    const std::string source = corners_text(q);
    for (Index v : q) check_vertex(source, v, vertex_count);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < i; ++j)
        if (q[i] == q[j])
          throw Error(ErrorKind::Usage,
                      source + ": vertex " + std::to_string(q[i]) + " is named twice");
    bool used = false;
    Index stray = q[0];
    for (size_t c = 0; c < comps.size(); ++c) {
      const int l = loop_of(comps[c], q[0]);
      if (l < 0) continue;
      const auto& loop = comps[c].loops[l];
      bool all = true;
      for (Index v : q)
        if (std::find(loop.begin(), loop.end(), v) == loop.end()) {
          stray = v;
          all = false;
          break;
        }
      if (!all) continue;
      used = true;
      PatchChoice& ch = choices[c];
      if (ch.has_corners) throw conflict(c, ch.corners_source, source);
      if (ch.outer_vertex >= 0 && loop_of(comps[c], ch.outer_vertex) != l)
        throw conflict(c, ch.outer_source, source);
      ch.has_corners = true;
      ch.corners = q;
      ch.corners_source = source;
      if (ch.outer_vertex < 0) {
        ch.outer_vertex = q[0];
        ch.outer_source = source;
      }
    }
    if (!used)
      throw Error(
          ErrorKind::Usage,
          source + ": vertex " + std::to_string(stray) +
              (stray == q[0] ? std::string(" is not on a boundary loop of any patch")
                             : " is not on the boundary loop through vertex " +
                                   std::to_string(q[0]) + "; the four corners go on one loop"));
  }
  return choices;
}

// Mesh vertex -> patch vertex, for one patch at a time: a dense table (one lookup per face corner
// is the hot path of the set-up) whose entries are reset when the patch is done.
class LocalIds {
 public:
  explicit LocalIds(Index vertex_count) : local_(vertex_count, -1) {}
  struct Scope {
    LocalIds& ids;
    const std::vector<Index>& vertices;
    Scope(LocalIds& i, const std::vector<Index>& v) : ids(i), vertices(v) {
      for (size_t k = 0; k < v.size(); ++k) ids.local_[v[k]] = static_cast<Index>(k);
    }
    ~Scope() {
      for (Index v : vertices) ids.local_[v] = -1;
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    Index operator()(Index v) const {
      const Index l = v >= 0 && v < static_cast<Index>(ids.local_.size()) ? ids.local_[v] : -1;
      SKINSLIDE_CHECK(l >= 0, "patch vertex");
      return l;
    }
  };

 private:
  std::vector<Index> local_;
};

// Patch `index` of the bind: its shared part, then the method's set-up of it (in `method`).
Patch patch_net(const PolyMesh& bind, const PatchComponent& comp, std::size_t index,
                MethodSetup& method, const PatchChoice& choice, const std::vector<char>& pinned,
                const std::vector<double>& weight, LocalIds& local_ids, bool spare_thread) {
  Patch patch;
  patch.selection = comp.selection;
  patch.faces = comp.faces;
  patch.vertices = comp.vertices;
  // comp outlives the patch's return (which may move patch.vertices away first).
  const LocalIds::Scope local(local_ids, comp.vertices);
  for (Index f : patch.faces) {
    const Index* fv = bind.face_begin(f);
    const Index m = bind.face_size(f);
    for (Index k = 0; k < m; ++k) {
      const Index a = local(fv[k]), b = local(fv[(k + 1) % m]);
      patch.bars.push_back({std::min(a, b), std::max(a, b)});
    }
    // Polygons are triangulated only for location and interpolation, as the fan (v0, vi, vi+1).
    for (Index k = 0; k + 2 < m; ++k) {
      patch.triangles.push_back({local(fv[0]), local(fv[k + 1]), local(fv[k + 2])});
      patch.triangle_face.push_back(f);
      patch.triangle_fan.push_back(k);
    }
  }
  std::sort(patch.bars.begin(), patch.bars.end());
  patch.bars.erase(std::unique(patch.bars.begin(), patch.bars.end()), patch.bars.end());

  const Positions3 points = gather(bind.positions, patch.vertices);
  require_computable_span(points, patch.vertices);
  patch.bind_diagonal = diagonal(points);
  std::vector<double> lengths;
  std::vector<Index> starts;
  std::vector<char> on_loop(patch.vertices.size(), 0);
  for (const auto& mesh_loop : comp.loops) {
    std::vector<Index> loop;
    for (Index v : mesh_loop) {
      loop.push_back(local(v));
      on_loop[loop.back()] = 1;
    }
    lengths.push_back(loop_length(gather(points, loop)));
    starts.push_back(loop.front());
    patch.loops.push_back(std::move(loop));
  }
  patch.outer_loop = outer_loop(lengths, starts);
  if (choice.outer_vertex >= 0) {
    patch.outer_loop = loop_of(comp, choice.outer_vertex);
    patch.outer_loop_chosen = true;
  }
  for (Index v = 0; v < static_cast<Index>(patch.vertices.size()); ++v) {
    if (on_loop[v]) continue;
    if (!pinned.empty() && pinned[patch.vertices[v]]) {
      patch.pinned.push_back(v);
    } else {
      patch.free_vertices.push_back(v);
    }
  }
  // Every patch's bars are measured, a skipped one's too: the report's spreads read them.
  patch.bind_lengths = bar_lengths(points, patch.bars);
  patch.skipped = patch.free_vertices.empty();
  if (patch.skipped) return patch;  // nothing to move: no unwrap needed, whatever the loops
  CornerChoice corners;
  if (choice.has_corners) corners = {true, choice.corners, choice.corners_source};
  set_up_patch(method, index, patch, points, weight, corners, spare_thread);
  return patch;
}

}  // namespace

BindSetup bind_setup(const PolyMesh& bind, const std::vector<std::vector<Index>>& selections,
                     const SlideOptions& options, const FaceNamer& name_face) {
  return bind_setup(bind, selections, options, SlideControls{}, name_face);
}

BindSetup bind_setup(const PolyMesh& bind, const std::vector<std::vector<Index>>& selections,
                     const SlideOptions& options, const SlideControls& controls,
                     const FaceNamer& name_face, unsigned threads,
                     const SelectionNamer& name_selection) {
  std::visit([](const auto& o) { check_rules(option_table<std::decay_t<decltype(o)>>(), o); },
             options);
  const FaceNamer namer =
      name_face ? name_face : [](Index f) { return "face " + std::to_string(f); };
  BindSetup setup;
  setup.vertex_count = bind.vertex_count();
  setup.bind_positions = bind.positions;
  const Index nv = setup.vertex_count;

  if (!controls.weight.empty() && static_cast<Index>(controls.weight.size()) != nv)
    throw Error(ErrorKind::Usage, "there are " + std::to_string(controls.weight.size()) +
                                      " slide weights; the bind has " + std::to_string(nv) +
                                      " vertices");
  if (!(controls.strength >= 0) || !std::isfinite(controls.strength))
    throw Error(ErrorKind::Usage, "--strength must be a finite number >= 0");
  for (size_t v = 0; v < controls.weight.size(); ++v)
    if (!(controls.weight[v] >= 0 && controls.weight[v] <= 1))
      throw Error(ErrorKind::Usage, "vertex " + std::to_string(v) + ": slide weight " +
                                        std::to_string(controls.weight[v]) + " is outside [0, 1]");
  if (!controls.weight.empty() || controls.strength < 1) {
    setup.weight.assign(nv, 1.0);
    for (Index v = 0; v < nv; ++v) {
      const double w = controls.weight.empty() ? 1.0 : controls.weight[v];
      setup.weight[v] = std::clamp(w * controls.strength, 0.0, 1.0);
    }
  }
  std::vector<char> pinned;
  if (!controls.pins.empty()) {
    pinned.assign(nv, 0);
    for (Index v : controls.pins) {
      check_vertex("--pin", v, nv);
      pinned[v] = 1;
    }
  }

  const std::vector<PatchComponent> comps =
      patch_components(bind, selections, namer, name_selection);
  const std::vector<PatchChoice> choices = patch_choices(comps, controls, nv);
  // Patches are independent: each is set up into its own slot, by as many threads as asked, and
  // the first failing patch in order decides the error, as in a serial run.
  std::vector<Patch> nets(comps.size());
  setup.method = method_setup(options, comps.size());
  std::vector<std::exception_ptr> failed(comps.size());
  std::atomic<size_t> next{0};
  // With at least two threads a patch, each patch's set-up runs two things at once.
  const bool spare_thread = threads >= 2 * comps.size();
  auto work = [&] {
    LocalIds local_ids(nv);
    for (size_t c; (c = next++) < comps.size();) {
      try {
        nets[c] = patch_net(bind, comps[c], c, setup.method, choices[c], pinned, setup.weight,
                            local_ids, spare_thread);
      } catch (const Error& e) {
        failed[c] = std::make_exception_ptr(Error(
            e.kind(), "patch " + std::to_string(c) + " (" + namer(comps[c].faces.front()) + ", " +
                          std::to_string(comps[c].faces.size()) + " faces): " + e.what()));
      } catch (...) {
        failed[c] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> helpers;
  for (size_t t = 1; t < std::min<size_t>(std::max(threads, 1u), comps.size()); ++t)
    helpers.emplace_back(work);
  work();
  for (std::thread& t : helpers) t.join();
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  setup.patches = std::move(nets);
  if (!pinned.empty()) {
    Index distinct = 0, used = 0;
    for (char p : pinned) distinct += p;
    for (const Patch& p : setup.patches) used += static_cast<Index>(p.pinned.size());
    setup.pins_ignored = distinct - used;
  }
  return setup;
}

}  // namespace skinslide

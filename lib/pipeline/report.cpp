#include "pipeline/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/version.h"
#include "io/number_format.h"
#include "unwrap/bar_net.h"

namespace skinslide {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x",
                        static_cast<unsigned>(static_cast<unsigned char>(c)));
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// JSON has no NaN or infinity; a non-finite number (never expected) is written as null.
std::string number(double x) { return std::isfinite(x) ? format_double(x) : "null"; }
std::string number(long long x) { return std::to_string(x); }
std::string boolean(bool b) { return b ? "true" : "false"; }

// A JSON object written member by member, in the order given.
class Object {
 public:
  explicit Object(int indent) : indent_(indent) {}
  Object& add(const std::string& key, const std::string& json) {
    members_.push_back(std::string(indent_ + 2, ' ') + quoted(key) + ": " + json);
    return *this;
  }
  std::string str() const {
    if (members_.empty()) return "{}";
    std::string out = "{\n";
    for (size_t i = 0; i < members_.size(); ++i)
      out += members_[i] + (i + 1 < members_.size() ? ",\n" : "\n");
    return out + std::string(indent_, ' ') + "}";
  }

 private:
  int indent_;
  std::vector<std::string> members_;
};

std::string array(const std::vector<std::string>& items, int indent) {
  if (items.empty()) return "[]";
  std::string out = "[\n";
  for (size_t i = 0; i < items.size(); ++i)
    out += std::string(indent + 2, ' ') + items[i] + (i + 1 < items.size() ? ",\n" : "\n");
  return out + std::string(indent, ' ') + "]";
}

std::string inline_array(const std::vector<std::string>& items) {
  std::string out = "[";
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i];
  return out + "]";
}

// What --frame-solver auto chose for the patch, in the option's words.
std::string solver_name(const PatchNet& p) {
  if (p.skipped || !p.solver) return "none";
  switch (p.solver->method()) {
    case FrameNetMethod::Cholesky:
      return "cholesky";
    case FrameNetMethod::Cg:
      return "cg";
    case FrameNetMethod::Multigrid:
      return "multigrid";
  }
  return "?";
}

}  // namespace

std::string report_json(const BindSetup& setup, const RunReport& run) {
  const SlideOptions& o = setup.options;
  Object root(0);
  root.add("skinslide", quoted(version()));
  root.add("bind", quoted(run.bind));
  std::vector<std::string> files;
  for (const std::string& f : run.patch_files) files.push_back(quoted(f));
  root.add("patch_files", inline_array(files));
  const bool elastic = o.method == SlideMethod::Elastic;
  if (elastic)
    root.add("options",
             Object(2)
                 .add("method", quoted(to_string(o.method)))
                 .add("rotation_fits", number(static_cast<long long>(o.elastic.rotation_fits)))
                 .add("max_iterations", number(static_cast<long long>(o.elastic.max_iterations)))
                 .add("tolerance", number(o.elastic.tolerance))
                 .str());
  else
    root.add("options",
             Object(2)
                 .add("method", quoted(to_string(o.method)))
                 .add("density", quoted(to_string(o.density)))
                 .add("holes", quoted(to_string(o.holes)))
                 .add("q_floor", number(o.q_floor))
                 .add("frame_solver", quoted(to_string(o.frame_solver)))
                 .add("cg_tolerance", number(o.cg_tolerance))
                 .add("cg_max_iterations", number(static_cast<long long>(o.cg_max_iterations)))
                 .add("locate", quoted(to_string(o.locate)))
                 .add("lookup_size", number(static_cast<long long>(o.lookup_size)))
                 .str());
  root.add("controls",
           Object(2)
               .add("weights", run.weights.empty() ? "null" : quoted(run.weights))
               .add("strength", number(run.strength))
               .add("pins", run.pins.empty() ? "null" : quoted(run.pins))
               .add("pins_requested", number(static_cast<long long>(run.pins_requested)))
               .add("pins_ignored", number(static_cast<long long>(setup.pins_ignored)))
               .str());
  std::vector<std::string> patches;
  for (const PatchNet& p : setup.patches) {
    std::vector<std::string> corners;
    if (!p.skipped)
      for (Index c : p.corners) corners.push_back(number(static_cast<long long>(p.vertices[c])));
    if (elastic) {
      patches.push_back(
          Object(4)
              .add("faces", number(static_cast<long long>(p.faces.size())))
              .add("vertices", number(static_cast<long long>(p.vertices.size())))
              .add("free", number(static_cast<long long>(p.free_vertices.size())))
              .add("pinned", number(static_cast<long long>(p.pinned.size())))
              .add("moving",
                   number(static_cast<long long>(p.elastic ? p.elastic->movable.size() : 0)))
              .add("loops", number(static_cast<long long>(p.loops.size())))
              .add("outer_loop_start",
                   number(static_cast<long long>(p.vertices[p.loops[p.outer_loop].front()])))
              .add("outer_loop_chosen", boolean(p.outer_loop_chosen))
              .add("skipped", boolean(p.skipped))
              .add("chart_weights", quoted(!p.elastic                         ? "none"
                                           : p.elastic->chart.uniform_weights ? "uniform"
                                                                              : "mean value"))
              .str());
      continue;
    }
    patches.push_back(Object(4)
                          .add("faces", number(static_cast<long long>(p.faces.size())))
                          .add("vertices", number(static_cast<long long>(p.vertices.size())))
                          .add("free", number(static_cast<long long>(p.free_vertices.size())))
                          .add("pinned", number(static_cast<long long>(p.pinned.size())))
                          .add("loops", number(static_cast<long long>(p.loops.size())))
                          .add("outer_loop_start", number(static_cast<long long>(
                                                       p.vertices[p.loops[p.outer_loop].front()])))
                          .add("outer_loop_chosen", boolean(p.outer_loop_chosen))
                          .add("corners", inline_array(corners))
                          .add("corners_chosen", boolean(p.corners_chosen))
                          .add("skipped", boolean(p.skipped))
                          .add("bind_net_flips", number(static_cast<long long>(p.bind_net_flips)))
                          .add("frame_solver", quoted(solver_name(p)))
                          .str());
  }
  root.add("patches", array(patches, 2));

  long long moved = 0, iterations = 0, direct = 0, fallbacks = 0, flips = 0, held = 0;
  double max_slide = 0;
  double read = 0, solve = 0, locate = 0, transfer = 0, write = 0;
  std::vector<std::string> frames;
  for (const ReportFrame& f : run.frames) {
    std::vector<std::string> fp;
    for (const PatchFrameReport& r : f.patches) {
      // Each method's own figures, then the slide's, which both have.
      Object patch(8);
      if (elastic) {
        patch.add("energy_before", number(r.energy_before))
            .add("energy_after", number(r.energy_after))
            .add("iterations", number(static_cast<long long>(r.iterations)))
            .add("stop", quoted(r.stop.empty() ? "skipped" : r.stop))
            .add("held", number(static_cast<long long>(r.held)))
            .add("flips", number(static_cast<long long>(r.slid_flips)));
        iterations += r.iterations;
        held += r.held;
        flips += r.slid_flips;
      } else {
        patch.add("cg_iterations", number(static_cast<long long>(r.cg_iterations)))
            .add("cg_residual", number(r.cg_residual))
            .add("direct_solve", boolean(r.direct_solve))
            .add("located_in_image", number(static_cast<long long>(r.located_in_image)))
            .add("located_fallback", number(static_cast<long long>(r.located_fallback)))
            .add("frame_net_flips", number(static_cast<long long>(r.frame_net_flips)));
        iterations += r.cg_iterations;
        direct += r.direct_solve;
        fallbacks += r.located_fallback;
        flips += r.frame_net_flips;
        locate += r.locate_seconds;
      }
      patch.add("moved", number(static_cast<long long>(r.moved)))
          .add("max_slide", number(r.max_slide))
          .add("mean_slide", number(r.mean_slide))
          .add("spread_frame", number(r.spread_frame))
          .add("spread_slid", number(r.spread_slid));
      fp.push_back(patch.str());
      moved += r.moved;
      max_slide = std::max(max_slide, r.max_slide);
      solve += r.solve_seconds;
      transfer += r.transfer_seconds;
    }
    read += f.read_seconds;
    write += f.write_seconds;
    frames.push_back(Object(4)
                         .add("path", quoted(f.path))
                         .add("output", quoted(f.output))
                         .add("patches", array(fp, 6))
                         .str());
  }
  root.add("frames", array(frames, 2));
  if (elastic)
    root.add("totals", Object(2)
                           .add("frames", number(static_cast<long long>(run.frames.size())))
                           .add("moved", number(moved))
                           .add("iterations", number(iterations))
                           .add("held", number(held))
                           .add("flips", number(flips))
                           .add("max_slide", number(max_slide))
                           .str());
  else
    root.add("totals", Object(2)
                           .add("frames", number(static_cast<long long>(run.frames.size())))
                           .add("moved", number(moved))
                           .add("cg_iterations", number(iterations))
                           .add("direct_solves", number(direct))
                           .add("fallbacks", number(fallbacks))
                           .add("frame_net_flips", number(flips))
                           .add("max_slide", number(max_slide))
                           .str());
  if (run.timings)
    root.add("timings", Object(2)
                            .add("bind_setup", number(run.bind_seconds))
                            .add("read", number(read))
                            .add("solve", number(solve))
                            .add("locate", number(locate))
                            .add("transfer", number(transfer))
                            .add("write", number(write))
                            .add("wall", number(run.wall_seconds))
                            .str());
  return root.str() + "\n";
}

}  // namespace skinslide

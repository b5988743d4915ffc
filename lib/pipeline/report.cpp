#include "pipeline/report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <type_traits>
#include <variant>

#include "core/version.h"
#include "io/atomic_write.h"
#include "core/json_text.h"
#include "core/number_format.h"
#include "pipeline/log_lines.h"

namespace skinslide {
namespace {

// JSON has no NaN or infinity; a non-finite number (never expected) is written as null.
std::string number(double x) { return std::isfinite(x) ? format_double(x) : "null"; }
std::string number(long long x) { return std::to_string(x); }
std::string boolean(bool b) { return b ? "true" : "false"; }

// A JSON object written member by member, in the order given.
class Object {
 public:
  explicit Object(int indent) : indent_(indent) {}
  Object& add(const std::string& key, const std::string& json) {
    members_.push_back(std::string(indent_ + 2, ' ') + json_string(key) + ": " + json);
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

std::string json(const FigureValue& value) {
  return std::visit(
      [](const auto& v) -> std::string {
        using Value = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<Value, long long> || std::is_same_v<Value, double>)
          return number(v);
        else if constexpr (std::is_same_v<Value, bool>)
          return boolean(v);
        else if constexpr (std::is_same_v<Value, std::string>)
          return json_string(v);
        else {
          std::vector<std::string> items;
          for (long long x : v) items.push_back(number(x));
          return inline_array(items);
        }
      },
      value);
}

Object& add(Object& object, const Figures& figures) {
  for (const Figure& f : figures) object.add(f.key, json(f.value));
  return object;
}

std::string controls_json(const BindSetup& setup, const RunReport& run) {
  return Object(2)
      .add("weights", run.weights.empty() ? "null" : json_string(run.weights))
      .add("strength", number(run.strength))
      .add("pins", run.pins.empty() ? "null" : json_string(run.pins))
      .add("pins_requested", number(static_cast<long long>(run.pins_requested)))
      .add("pins_ignored", number(static_cast<long long>(setup.pins_ignored)))
      .str();
}

std::string patches_json(const BindSetup& setup) {
  std::vector<std::string> patches;
  for (size_t p = 0; p < setup.patches.size(); ++p) {
    Object patch(4);
    patches.push_back(add(patch, patch_figures(setup.method, p, setup.patches[p])).str());
  }
  return array(patches, 2);
}

// What the frames' figures add up to, and the timings summed over them.
struct FrameSums {
  long long moved = 0;
  double max_slide = 0;
  MethodTotals totals;  ///< the method's, over every patch of every frame
  double read = 0, solve = 0, locate = 0, transfer = 0, write = 0;
};

// One frame's entry: per patch the method's figures, then the slide's, which both have.
std::string frame_json(const ReportFrame& f, FrameSums& sums) {
  std::vector<std::string> patches;
  for (const PatchFrameReport& r : f.patches) {
    Object patch(8);
    patches.push_back(add(patch, frame_figures(r)).str());
    sums.moved += r.moved;
    sums.max_slide = std::max(sums.max_slide, r.max_slide);
    add_to_totals(sums.totals, r.method);
    sums.solve += r.solve_seconds;
    sums.locate += r.locate_seconds;
    sums.transfer += r.transfer_seconds;
  }
  sums.read += f.read_seconds;
  sums.write += f.write_seconds;
  return Object(4)
      .add("path", json_string(f.path))
      .add("output", json_string(f.output))
      .add("patches", array(patches, 6))
      .str();
}

std::string timings_json(const RunReport& run, const FrameSums& sums) {
  return Object(2)
      .add("bind_setup", number(run.bind_seconds))
      .add("read", number(sums.read))
      .add("solve", number(sums.solve))
      .add("locate", number(sums.locate))
      .add("transfer", number(sums.transfer))
      .add("write", number(sums.write))
      .add("wall", number(run.wall_seconds))
      .str();
}

}  // namespace

std::string report_json(const BindSetup& setup, const RunReport& run) {
  Object root(0);
  root.add("skinslide", json_string(version()));
  root.add("bind", json_string(run.bind));
  std::vector<std::string> files;
  for (const std::string& f : run.patch_files) files.push_back(json_string(f));
  root.add("patch_files", inline_array(files));
  Object options(2);
  Figures option_list = option_figures(setup.method);
  if (std::holds_alternative<ElasticMethod>(setup.method)) {
    RunOptions window;
    window.window = run.window;
    window.window_ends = run.window_ends;
    option_list.push_back(option_figure(window_option(), window));
    option_list.push_back(option_figure(window_ends_option(), window));
  }
  root.add("options", add(options, option_list).str());
  root.add("controls", controls_json(setup, run));
  root.add("patches", patches_json(setup));
  FrameSums sums;
  sums.totals = method_totals(setup.method);
  std::vector<std::string> frames;
  for (const ReportFrame& f : run.frames) frames.push_back(frame_json(f, sums));
  root.add("frames", array(frames, 2));
  Object totals(2);
  totals.add("frames", number(static_cast<long long>(run.frames.size())))
      .add("moved", number(sums.moved));
  add(totals, total_figures(sums.totals)).add("max_slide", number(sums.max_slide));
  if (run.window > 0) {  // frames whose window's mean costs them ten points (log_lines.h)
    long long costly = 0;
    for (const ReportFrame& f : run.frames) costly += window_costly(setup, f.patches) ? 1 : 0;
    totals.add("window_costly", number(costly));
  }
  root.add("totals", totals.str());
  if (run.timings) root.add("timings", timings_json(run, sums));
  return root.str() + "\n";
}

void record_frame(ReportFrame& record, const std::string& source, const std::string& out_path,
                  double read_seconds, double write_seconds,
                  std::vector<PatchFrameReport> patches) {
  record.path = source;
  record.output = out_path;
  record.read_seconds = read_seconds;
  record.write_seconds = write_seconds;
  record.patches = std::move(patches);
  for (PatchFrameReport& r : record.patches) {
    r.frame_net = {};
    r.id_image = {};
  }
}

void write_run_report(const RunOptions& o, const BindSetup& setup, double wall_seconds,
                      RunReport& report) {
  report.bind = o.bind;
  report.patch_files = o.patches;
  report.window = o.window;
  report.window_ends = o.window_ends;
  report.timings = o.report_timings;
  report.wall_seconds = wall_seconds;
  std::erase_if(report.frames, [](const ReportFrame& r) { return r.output.empty(); });
  write_file_atomic(o.report, report_json(setup, report));
  const std::filesystem::path report_folder = std::filesystem::path(o.report).parent_path();
  sync_folder(report_folder.empty() ? "." : report_folder.string());
}

}  // namespace skinslide

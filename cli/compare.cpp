#include "compare.h"

#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "compare/compare_outputs.h"
#include "compare/compare_report.h"
#include "core/error.h"
#include "exit_status.h"
#include "help_format.h"
#include "io/atomic_write.h"
#include "core/number_format.h"

namespace skinslide {
namespace {

constexpr int kDifferent = 1;  // like diff and cmp: 0 the same, 1 different
// --common names this many of the frames it left out on each side, then "and N more".
constexpr std::size_t kLeftOutListed = 5;

struct CompareCli {
  std::string a, b, report;
  CompareOptions options;
  bool quiet = false, verbose = false;
};

const char* kDescription =
    "skinslide compare: compares two slid outputs as meshes, frame by frame: two folders of "
    "frames (OBJ, glTF, GLB files and PC2/MDD caches, paired by file name), two mesh files or "
    "two caches. Per frame: the largest vertex distance in bounding-box diagonals (the bind's "
    "with --bind, else the frame's own in A) and the faces turned over between A and B.\n"
    "Exit 0: the same within --tolerance; 1: different; 2: usage; 3: unreadable or mismatched "
    "inputs (a frame on one side only, two meshes' frames paired, other counts); 4: the report "
    "cannot be written.";

void add_options(CLI::App& app, CompareCli& c) {
  app.add_option("A", c.a, "First output: a folder of frames, a mesh file or a cache")->required();
  app.add_option("B", c.b, "Second output, of the same kind as A")->required();
  app.add_option("--tolerance", c.options.tolerance,
                 "Frames differ when a vertex moved farther than T bounding-box diagonals, or a "
                 "face turned over (the default: far above a float's last bit, far below a "
                 "pixel)")
      ->type_name("T")
      ->default_str(format_double(kDefaultCompareTolerance))
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--bind", c.options.bind,
                 "The bind mesh: its diagonal is the unit of distance (default: each frame's "
                 "own, A's), and its faces are the caches' (else a cache's faces are not "
                 "checked)")
      ->type_name("FILE");
  app.add_option("--mesh", c.options.mesh.mesh, "Which mesh of a glTF holding several")
      ->type_name("NAME|INDEX");
  app.add_flag("--common", c.options.common,
               "Compare only the frames both hold (a farm chunk against the whole shot): a "
               "folder's by file name, a cache's samples by frame number (MDD: time); says which "
               "it left out");
  app.add_option("--report", c.report, "Write the comparison as JSON (every frame, the totals)")
      ->type_name("FILE.json");
  app.add_flag("-q,--quiet", c.quiet, "Errors only");
  app.add_flag("-v,--verbose", c.verbose, "A line for every frame, not only the differing ones");
}

std::string frame_line(const ComparedFrame& f) {
  const FrameDifference& d = f.difference;
  std::string line = std::string("skinslide compare: ") + (f.differs ? "differs: " : "same: ") +
                     f.a + ": largest distance " + log_number(d.max_distance) + " of the diagonal";
  if (d.vertex >= 0)
    line += ", vertex " + std::to_string(d.vertex) +
            (f.vertex_at.empty() ? "" : " (" + f.vertex_at + ")");
  if (d.turned_faces > 0)
    line += "; " + std::to_string(d.turned_faces) + " faces turned over, the first face " +
            std::to_string(d.first_turned_face);
  return line;
}

// "1 only in a/ (a/f.0005.obj)": what --common left out of one side.
std::string left_out(const std::vector<std::string>& names, const std::string& side) {
  std::string text = std::to_string(names.size()) + " only in " + side;
  for (std::size_t i = 0; i < names.size() && i < kLeftOutListed; ++i)
    text += (i ? ", " : " (") + names[i];
  if (names.size() > kLeftOutListed)
    text += " and " + std::to_string(names.size() - kLeftOutListed) + " more";
  return text + (names.empty() ? "" : ")");
}

// With --common: how many frames both held, and which it left out.
std::string common_line(const CompareResult& r) {
  return "skinslide compare: --common: " + std::to_string(r.frames.size()) +
         " frames in both compared; left out " + left_out(r.only_in_a, r.a) + ", " +
         left_out(r.only_in_b, r.b);
}

std::string summary_line(const CompareResult& r) {
  const std::size_t differing = r.differing();
  std::string line =
      "skinslide compare: " + std::to_string(r.frames.size()) + " frames, " +
      (differing == 0 ? std::string("the same") : std::to_string(differing) + " differ") +
      " (tolerance " + log_number(r.tolerance) +
      (r.diagonal_from.empty()
           ? std::string(" of each frame's own diagonal, A's")
           : " of the diagonal " + log_number(r.diagonal) + ", " + r.diagonal_from + "'s") +
      ")";
  const long long k = r.largest();
  if (k >= 0) {
    const ComparedFrame& f = r.frames[static_cast<std::size_t>(k)];
    line += ": largest distance " + log_number(f.difference.max_distance);
    if (f.difference.vertex >= 0)
      line += " at " + f.a + " vertex " + std::to_string(f.difference.vertex);
  }
  if (!r.faces_checked) line += "; faces not compared (a cache has none: --bind BIND gives them)";
  return line;
}

int compare_and_print(const CompareCli& c) {
  const CompareResult result = compare_outputs(c.a, c.b, c.options, [&](const ComparedFrame& f) {
    if (!c.quiet && (f.differs || c.verbose)) std::fprintf(stderr, "%s\n", frame_line(f).c_str());
  });
  if (!c.report.empty()) write_file_atomic(c.report, compare_report_json(result));
  if (!c.quiet && c.options.common) std::fprintf(stderr, "%s\n", common_line(result).c_str());
  if (!c.quiet) std::fprintf(stderr, "%s\n", summary_line(result).c_str());
  return result.differing() == 0 ? 0 : kDifferent;
}

}  // namespace

int run_compare(int argc, char** argv) {
  CompareCli c;
  CLI::App app{kDescription, "skinslide compare"};
  cli::use_help_format(app);
  add_options(app, c);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return cli::parse_error_exit(app, e, "skinslide compare");
  }
  return cli::exit_status("skinslide compare", [&] { return compare_and_print(c); });
}

}  // namespace skinslide

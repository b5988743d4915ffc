// `skinslide compare --report FILE.json`: the comparison as JSON, for CI to keep or read.
#pragma once

#include <string>

#include "compare/compare_outputs.h"

namespace skinslide {

/// The result as JSON text (UTF-8, 2-space indent, final newline), keys in this order:
/// { "skinslide": version, "a", "b", "tolerance", "diagonal" and "diagonal_from" (the bind's, or
///   null when each frame's distances are in its own diagonal), "faces_checked",
///   "frames": [{"a", "b", "diagonal", "max_distance" (in diagonals), "vertex" (-1: none moved),
///   "turned_faces", "first_turned_face" (-1: none), "differs"}], "only_in_a", "only_in_b" (the
///   frames --common left out), "differing_frames",
///   "largest": {"frame" (index into "frames"), "max_distance"} or null, "same" }
/// Numbers as the shortest text that reads back to the same double; no timings: two
/// comparisons of the same inputs give the same bytes.
std::string compare_report_json(const CompareResult& result);

}  // namespace skinslide

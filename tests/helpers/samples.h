// The shipped sample cases (data/) and geometric checks on them, shared by pipeline tests.
#pragma once

#include <string>
#include <vector>

#include "mesh/poly_mesh.h"
#include "pipeline/bind_setup.h"
#include "pipeline/slide_frame.h"

namespace skinslide::test {

struct Sample {
  PolyMesh bind;
  std::vector<Index> faces;        ///< data/<name>/patch.txt
  std::vector<Positions3> frames;  ///< data/<name>/frames/*.obj in name order
};

/// The elastic method's search (--solver search) with its default options: the tests of its
/// rounds, holds, escalation and blend.
inline ElasticOptions search_options() {
  ElasticOptions o;
  o.solver = ElasticSolver::Search;
  return o;
}

/// The paper's method with its default options.
inline SlideOptions paper_options() { return PaperOptions{}; }

/// A set-up's method data, for the method the test set it up with.
inline const PaperMethod& paper(const BindSetup& s) { return std::get<PaperMethod>(s.method); }
inline const ElasticMethod& elastic(const BindSetup& s) {
  return std::get<ElasticMethod>(s.method);
}

/// A patch's report of a frame, for the method the test slid it with.
inline const PaperReport& paper(const PatchFrameReport& r) {
  return std::get<PaperReport>(r.method);
}
inline const ElasticReport& elastic(const PatchFrameReport& r) {
  return std::get<ElasticReport>(r.method);
}

/// Loads data/<name> ("elbow" or "face").
Sample load_sample(const std::string& name);

/// Bounding-box diagonal of the points.
double diagonal(const Positions3& points);

/// Exact distance from p to the 3D triangle abc, also when abc is degenerate (a segment or a
/// point).
double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Distance from x to the nearest triangle of the patch, with the patch's vertices at `frame`.
double distance_to_patch(const Patch& patch, const Positions3& frame, const Vec3& x);

/// std of log(L / L_bind) over the patch's bars: how unevenly the patch is stretched (the measure
/// of README "Choosing the defaults"), computed here independently of the library's report.
double edge_log_spread(const Patch& patch, const Positions3& bind, const Positions3& x);

}  // namespace skinslide::test

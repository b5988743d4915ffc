#include "helpers/samples.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "helpers/meshes.h"
#include "io/obj_read.h"
#include "io/patch_file.h"

namespace skinslide::test {

Sample load_sample(const std::string& name) {
  namespace fs = std::filesystem;
  Sample c;
  const std::string dir = source_path("data/" + name);
  c.bind = read_obj(dir + "/bind.obj").mesh;
  c.faces = selected_faces(read_patch(dir + "/patch.txt"), c.bind.face_count());
  std::vector<std::string> paths;
  for (const auto& e : fs::directory_iterator(dir + "/frames")) paths.push_back(e.path().string());
  std::sort(paths.begin(), paths.end());
  for (const auto& p : paths) c.frames.push_back(read_obj(p).mesh.positions);
  return c;
}

double diagonal(const Positions3& p) {
  Vec3 lo = p[0], hi = p[0];
  for (const Vec3& x : p) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return (hi - lo).norm();
}

namespace {
// Ericson, Real-Time Collision Detection 5.1.5; divides by the area, so not finite on a
// degenerate triangle.
double ericson_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double den = 1 / (va + vb + vc);
  return (p - (a + ab * vb * den + ac * vc * den)).norm();
}
}  // namespace

double point_triangle_distance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const double d = ericson_distance(p, a, b, c);
  if (std::isfinite(d)) return d;
  // A degenerate triangle (a segment or a point): the nearest of its edges.
  auto segment = [&](const Vec3& u, const Vec3& v) {
    const double l2 = (v - u).squaredNorm();
    const double t = l2 > 0 ? std::clamp((p - u).dot(v - u) / l2, 0.0, 1.0) : 0.0;
    return (p - (u + t * (v - u))).norm();
  };
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

double distance_to_patch(const Patch& patch, const Positions3& frame, const Vec3& x) {
  double best = INFINITY;
  for (const Triangle& t : patch.triangles)
    best = std::min(
        best, point_triangle_distance(x, frame[patch.vertices[t[0]]], frame[patch.vertices[t[1]]],
                                      frame[patch.vertices[t[2]]]));
  return best;
}

double edge_log_spread(const Patch& patch, const Positions3& bind, const Positions3& x) {
  std::vector<double> r;
  for (const auto& [a, b] : patch.bars) {
    const Index u = patch.vertices[a], v = patch.vertices[b];
    r.push_back(std::log((x[u] - x[v]).norm() / (bind[u] - bind[v]).norm()));
  }
  double mean = 0, var = 0;
  for (double v : r) mean += v;
  mean /= static_cast<double>(r.size());
  for (double v : r) var += (v - mean) * (v - mean);
  return std::sqrt(var / static_cast<double>(r.size()));
}

}  // namespace skinslide::test

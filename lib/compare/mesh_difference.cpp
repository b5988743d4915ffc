#include "compare/mesh_difference.h"

#include <algorithm>

#include <Eigen/Geometry>

#include "core/check.h"

namespace skinslide {
namespace {

// Newell's normal of face f: the sum of its edges' cross products, twice its vector area (a
// triangle's cross product), defined for a polygon that is not planar. Taken about the face's
// first corner: about the origin, a mesh far from it would lose the normal to cancellation.
Vec3 face_normal(const PolyMesh& faces, const Positions3& p, Index f) {
  const Index* v = faces.face_begin(f);
  const Index n = faces.face_size(f);
  const Vec3& o = p[v[0]];
  Vec3 normal = Vec3::Zero();
  for (Index i = 1; i + 1 < n; ++i) normal += (p[v[i]] - o).cross(p[v[i + 1]] - o);
  return normal;
}

double longest_edge(const PolyMesh& faces, const Positions3& p, Index f) {
  const Index* v = faces.face_begin(f);
  const Index n = faces.face_size(f);
  double longest = 0;
  for (Index i = 0; i < n; ++i) longest = std::max(longest, (p[v[(i + 1) % n]] - p[v[i]]).norm());
  return longest;
}

// Twice the face's area over its longest edge: a triangle's smallest height.
double thickness(const Vec3& normal, double longest) {
  return longest > 0 ? normal.norm() / longest : 0;
}

}  // namespace

double bounding_box_diagonal(const Positions3& positions) {
  if (positions.empty()) return 0;
  Vec3 lo = positions.front(), hi = positions.front();
  for (const Vec3& p : positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

FrameDifference frame_difference(const Positions3& a, const Positions3& b, const PolyMesh& faces,
                                 double diagonal, double tolerance) {
  SKINSLIDE_CHECK(a.size() == b.size(), "frames of different vertex counts compared");
  SKINSLIDE_CHECK(diagonal > 0, "a diagonal of zero length");
  FrameDifference d;
  double largest = 0;
  for (size_t v = 0; v < a.size(); ++v) {
    const double distance = (a[v] - b[v]).norm();
    if (distance > largest) {
      largest = distance;
      d.vertex = static_cast<Index>(v);
    }
  }
  d.max_distance = largest / diagonal;
  const double thin = tolerance * diagonal;
  for (Index f = 0; f < faces.face_count(); ++f) {
    const Vec3 na = face_normal(faces, a, f);
    const Vec3 nb = face_normal(faces, b, f);
    if (na.dot(nb) >= 0) continue;
    if (thickness(na, longest_edge(faces, a, f)) <= thin ||
        thickness(nb, longest_edge(faces, b, f)) <= thin)
      continue;
    if (d.turned_faces++ == 0) d.first_turned_face = f;
  }
  return d;
}

bool differs(const FrameDifference& d, double tolerance) {
  return d.max_distance > tolerance || d.turned_faces > 0;
}

}  // namespace skinslide

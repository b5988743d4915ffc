// The vertices a slide moved and where each landed on the frame's surface: a fan triangle of a
// mesh face and barycentric weights on its corners, the 3D point interpolated there (Yang & Zhang
// 2010, section III.F, equation (4): P' = a*VA + b*VB + c*VC). Mesh vocabulary, below both
// methods and every file format: io/ writes a slid frame from it.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"
#include "mesh/poly_mesh.h"

namespace skinslide {

/// Where a slid vertex landed on the frame's surface: a fan triangle of one mesh face and
/// barycentric weights on its corners. The fan triangle k of face f has corners at slots
/// (0, k+1, k+2) of the face's vertex list; `corner` holds those slots, `weight` sums to 1.
struct SurfaceSample {
  Index face = -1;
  std::array<Index, 3> corner{0, 1, 2};
  std::array<double, 3> weight{1.0, 0.0, 0.0};
};

/// The vertices a slide moved, ascending by vertex id, with where each landed.
struct SlidVertices {
  std::vector<Index> vertex;          ///< mesh vertex ids, ascending
  std::vector<SurfaceSample> sample;  ///< one per entry of `vertex`
  Positions3 position;                ///< output 3D position, one per entry of `vertex`; with a
                                      ///< slide weight w < 1 it lies between the frame position
                                      ///< and `sample`'s point, off the surface
};

/// The 3D point of `sample` on `mesh` (positions from `positions`, faces from `mesh`).
/// Throws Numeric when the result is not finite.
Vec3 surface_point(const PolyMesh& mesh, const Positions3& positions, const SurfaceSample& sample);

/// Copy of `frame` with every vertex of `slid` moved to its slid position.
Positions3 apply_slide(const Positions3& frame, const SlidVertices& slid);

}  // namespace skinslide

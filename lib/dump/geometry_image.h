// The geometry image of a net: the 3D surface over the unit square, sampled per texel.
#pragma once

#include <vector>

#include "core/types.h"
#include "locate/id_raster.h"

namespace skinslide {

/// Float planes of a size x size image over the unit square, each stored at [j*size + i] with
/// row 0 = v = 0 (as IdImage; the EXR writer flips them).
struct GeometryImage {
  int size = 0;
  std::vector<float> x, y, z;   ///< P: the 3D point at the texel centre; 0 where uncovered
  std::vector<float> coverage;  ///< A: fraction of the texel covered by the net, in [0, 1]
};

/// Samples the 3D surface carried by a 2D net. P at texel (i, j) is the point of `points` (3D,
/// one per net vertex, mesh units) interpolated with the barycentric weights of the texel centre
/// ((i + 0.5)/size, (j + 0.5)/size) in the net triangle id_raster() assigns to that pixel (see
/// texel_samples()); texels whose centre no triangle covers (holes, partly covered border
/// texels) get P = (0, 0, 0), so A > 0 with P = 0 can happen along a hole's edge. A is
/// coverage_image(): exact area fractions, sum(A) / size^2 = the net's area within 1e-7.
/// \param net 2D position of every net vertex (#n); triangles index it
/// \param points 3D position of every net vertex (#n)
/// \pre size >= 1; points.size() == net.size()
GeometryImage geometry_image(const Positions2& net, const std::vector<Triangle>& triangles,
                             const Positions3& points, int size);

}  // namespace skinslide

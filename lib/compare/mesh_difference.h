// How far two versions of one mesh frame are apart as meshes (`skinslide compare`): the largest
// vertex distance in units of a bounding-box diagonal, and the faces that face opposite ways.
// Plain arrays in, a plain struct out; nothing is read or printed here (compare/compare_outputs.h
// reads the files).
#pragma once

#include "core/types.h"
#include "mesh/poly_mesh.h"

namespace skinslide {

/// The default `skinslide compare --tolerance`, in bounding-box diagonals (README "Tests"): a
/// double's last bit is about 1e-16 of a coordinate and a float32's (point caches) 6e-8, so two
/// builds whose numbers differ in their last bits stay far below it (a float32 coordinate up to
/// 16 diagonals from the origin); and 1e-6 of a 2 m character is 2 micrometres, a thousandth of
/// what a 4K close-up shows in a pixel. A real change (an option, a solver, a patch) moves
/// vertices by 1e-4 and more.
constexpr double kDefaultCompareTolerance = 1e-6;

/// The length of the diagonal of `positions`' axis-aligned bounding box (0 for no vertex).
double bounding_box_diagonal(const Positions3& positions);

/// How frame B differs from frame A.
struct FrameDifference {
  double max_distance = 0;       ///< largest |a_v - b_v| over the vertices, in diagonals
  Index vertex = -1;             ///< the first vertex at that distance; -1: every vertex the same
  Index turned_faces = 0;        ///< faces whose orientation differs (below)
  Index first_turned_face = -1;  ///< the first of them; -1: none
};

/// Compares two positions of one mesh, vertex by vertex and face by face.
/// \param a, b #V positions each, the same vertex order.
/// \param faces the faces both share (only its face lists are read); none: no face is checked.
/// \param diagonal the length distances are measured in (above 0): the bind's bounding-box
///        diagonal.
/// \param tolerance in diagonals: a face counts as turned when its normal in B points against
///        its normal in A (negative dot product; polygon normals by Newell's sum) and it is
///        thicker than `tolerance` in both (twice its area over its longest edge: a triangle's
///        smallest height). A sliver thinner than that has no orientation at that scale: moving
///        its corners by less than the tolerance can turn it.
/// \pre a.size() == b.size(); every face's vertex ids below a.size(); diagonal > 0.
FrameDifference frame_difference(const Positions3& a, const Positions3& b, const PolyMesh& faces,
                                 double diagonal, double tolerance);

/// True when B is not A within `tolerance` (in diagonals): a vertex farther than it, or a face
/// turned.
bool differs(const FrameDifference& d, double tolerance);

}  // namespace skinslide

// Vocabulary types shared by every module: points, index aliases, Eigen sparse aliases.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace skinslide {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;

/// Vertex, face and triangle indices: 0-based, in file order unless a header says otherwise.
using Index = std::int32_t;

/// A triangle as three vertex (node) ids.
using Triangle = std::array<Index, 3>;

using SparseMatrix = Eigen::SparseMatrix<double>;
using Triplet = Eigen::Triplet<double>;

/// Positions of a mesh's vertices, one entry a vertex (#V).
using Positions3 = std::vector<Vec3>;
/// 2D net positions, one entry a vertex of a patch (#patch vertices).
using Positions2 = std::vector<Vec2>;

}  // namespace skinslide
